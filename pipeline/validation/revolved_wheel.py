"""Validation of the Fourier-harmonic solver against a full 3D model.

The C20 wheel cross-section (mount 'clamped': wheel alone, bore clamped) is
revolved 360 degrees about the axle axis with the Gmsh OCC kernel and meshed
with tetrahedra; a P2 dolfinx elasticity model gives the lowest modes by
SLEPc shift-invert (MUMPS).  solvers.wheel.axisym.HarmonicSolver is run on EXACTLY
the same outline (a simplified version of the C20 outline: each named
polyline is thinned by Douglas-Peucker to 0.75 mm, so the 3D model has no
sub-millimetre edges that would force a fine mesh) with a fine 2D mesh.

For n = 0..3 the harmonic solver's lowest two modes are compared with the 3D
modes nearest in frequency: one 3D mode for n = 0, a degenerate pair
(cos n phi / sin n phi) for n >= 1.  The pairing is confirmed by shape: the
harmonic mode is expanded into 3D (both orientations) and the fraction of
each 3D mode lying in that subspace (mass-weighted, "subspace MAC") is
reported.  The 3D run is repeated on 3 mesh sizes to show convergence.

``study()`` runs it once per code and wheel file (a JSON cache, build/validation/wheel_3d.json, keyed by the
code ``run_study`` reaches and the C20's file): the writer (``pipeline.validation.writers.wheel_3d``,
docs/validation/22_wheel_3d.md) and the test asserting its criteria (tests/validation/test_wheel_3d.py) share
the run.
"""
from __future__ import annotations

import os
import resource
import tempfile
import time
import tomllib
from dataclasses import dataclass, field
import fcntl
import hashlib
import json

import numpy as np

from geometry.outline import Segment

from pipeline.store.paths import ROOT
from geometry.wheel import wheel_segments
from geometry.mesher import mesh_section, read_msh
from solvers.wheel.axisym import HarmonicSolver
from solvers.wheel.eigen import shift_invert
from pipeline.store import paths
from pipeline.store.atomic import save_text
from pipeline.validation.cached import plain
from pipeline.store.code_hash import code_key
N_MAX = 3  # harmonics compared
N_MODES = 2  # per harmonic
TOL = 0.02  # relative frequency agreement required (finest 3D mesh)
SIMPLIFY_TOL = 0.00075  # m, Douglas-Peucker tolerance of the outline
SIZE_2D = 0.003  # m, element size of the harmonic reference mesh (P2)
SIZES_3D = (0.030, 0.024, 0.017)  # m, 3D element sizes, coarse -> fine
GEOM_ORDER = 2  # 3D geometry: 1 straight-sided (faceted) tets, 2 curved


# ----------------------------------------------------------------------------
# geometry
# ----------------------------------------------------------------------------
def c20_params() -> dict:
    with open(ROOT / "geometry" / "wheels" / "c20.toml", "rb") as f:
        p = tomllib.load(f)
    p["mount"]["type"] = "clamped"
    return p


def _douglas_peucker(pts: np.ndarray, tol: float) -> np.ndarray:
    if len(pts) <= 2:
        return pts
    a, b = pts[0], pts[-1]
    d = b - a
    L = np.linalg.norm(d)
    rel = pts - a
    dist = np.abs(d[0] * rel[:, 1] - d[1] * rel[:, 0]) / L if L > 0 else np.linalg.norm(rel, axis=1)
    i = int(np.argmax(dist))
    if dist[i] <= tol:
        return np.array([a, b])
    left = _douglas_peucker(pts[: i + 1], tol)
    right = _douglas_peucker(pts[i:], tol)
    return np.vstack([left[:-1], right])


def simplified_segments(tol: float = SIMPLIFY_TOL) -> list[Segment]:
    """C20 clamped outline with each segment's polyline thinned (end points
    kept, so the segments still join)."""
    return [Segment(s.name, _douglas_peucker(np.asarray(s.points, float), tol), s.size)
            for s in wheel_segments(c20_params())]


def outline_polygon(segs: list[Segment]) -> np.ndarray:
    return np.vstack([s.points[:-1] for s in segs])


# ----------------------------------------------------------------------------
# harmonic (2D) reference
# ----------------------------------------------------------------------------
def harmonic_solver(segs: list[Segment], size: float, E, nu, rho):
    segs = [Segment(s.name, s.points, size) for s in segs]
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "section.msh")
        names = mesh_section(segs, path)
        mesh, _, ft = read_msh(path, gdim=2)
    return HarmonicSolver(mesh, ft, E, nu, rho, degree=2, clamped=(names["bore"],))


# ----------------------------------------------------------------------------
# 3D model
# ----------------------------------------------------------------------------
def revolved_mesh(segs: list[Segment], h: float, geom_order: int = GEOM_ORDER):
    """Revolve the outline (x = r, z = Z, in the x-z plane) 360 degrees about
    the z axis (OCC), tetrahedral mesh of size h.  Returns (mesh, facet_tags,
    bore_tag)."""
    import gmsh  # lazy: brings in gmsh
    from dolfinx.io import gmshio  # lazy: brings in dolfinx (and PETSc's signal handlers)
    from mpi4py import MPI  # lazy: brings in mpi4py (and PETSc's signal handlers)

    poly = outline_polygon(segs)
    bore = next(s for s in segs if s.name == "bore").points
    r_b, z0, z1 = float(bore[0, 0]), float(bore[:, 1].min()), float(bore[:, 1].max())
    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add("wheel3d")
        occ = gmsh.model.occ
        pts = [occ.addPoint(float(r), 0.0, float(z), h) for r, z in poly]
        lines = [occ.addLine(pts[i], pts[(i + 1) % len(pts)]) for i in range(len(pts))]
        surf = occ.addPlaneSurface([occ.addCurveLoop(lines)])
        occ.revolve([(2, surf)], 0, 0, 0, 0, 0, 1, 2 * np.pi)
        occ.synchronize()
        vols = gmsh.model.getEntities(3)
        assert len(vols) == 1, vols
        eps = 1e-6
        bore_surfs = [t for _, t in gmsh.model.getEntitiesInBoundingBox(
            -r_b - eps, -r_b - eps, z0 - eps, r_b + eps, r_b + eps, z1 + eps, 2)]
        assert bore_surfs, "bore surface not found"
        gmsh.model.addPhysicalGroup(3, [vols[0][1]], 1)
        gmsh.model.addPhysicalGroup(2, bore_surfs, 1)
        gmsh.option.setNumber("Mesh.MeshSizeMax", h)
        gmsh.option.setNumber("Mesh.MeshSizeMin", 0.2 * h)
        gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 1)
        gmsh.option.setNumber("Mesh.Algorithm", 6)
        gmsh.option.setNumber("Mesh.Algorithm3D", 1)
        gmsh.model.mesh.generate(3)
        if geom_order > 1:
            gmsh.model.mesh.setOrder(geom_order)  # curved tets on the surfaces of revolution
        mesh, _, ft = gmshio.model_to_mesh(gmsh.model, MPI.COMM_SELF, 0, gdim=3)
    finally:
        gmsh.finalize()
    return mesh, ft, 1


@dataclass
class Solid3D:
    mesh: object
    V: object
    M: object  # PETSc mass matrix without constraints (for projections)
    freqs: np.ndarray
    vecs: np.ndarray  # (nmodes, ndofs), M-normalised
    ndofs: int
    t_mesh: float
    t_solve: float
    ncells: int


def solve_3d(segs, h, E, nu, rho, nev, tol=1e-9) -> Solid3D:
    import ufl  # lazy: brings in ufl (and PETSc's signal handlers)
    from dolfinx import fem  # lazy: brings in dolfinx (and PETSc's signal handlers)
    from dolfinx.fem.petsc import assemble_matrix  # lazy: brings in dolfinx (and PETSc's signal handlers)
    from petsc4py import PETSc  # lazy: brings in petsc4py (and PETSc's signal handlers)

    t0 = time.perf_counter()
    mesh, ft, bore_tag = revolved_mesh(segs, h)
    t_mesh = time.perf_counter() - t0
    t0 = time.perf_counter()
    V = fem.FunctionSpace(mesh, ufl.VectorElement("Lagrange", mesh.ufl_cell(), 2))
    lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    mu = E / (2 * (1 + nu))
    u, v = ufl.TrialFunction(V), ufl.TestFunction(V)

    def eps(w):
        return ufl.sym(ufl.grad(w))

    k_form = fem.form((lam * ufl.tr(eps(u)) * ufl.tr(eps(v)) + 2 * mu * ufl.inner(eps(u), eps(v))) * ufl.dx)
    m_form = fem.form(rho * ufl.inner(u, v) * ufl.dx)
    fdim = mesh.topology.dim - 1
    dofs = fem.locate_dofs_topological(V, fdim, ft.find(bore_tag))
    bc = fem.dirichletbc(np.zeros(3, dtype=PETSc.ScalarType), dofs, V)
    K = assemble_matrix(k_form, bcs=[bc], diagonal=1.0)
    K.assemble()
    Mb = assemble_matrix(m_form, bcs=[bc], diagonal=0.0)
    Mb.assemble()
    M = assemble_matrix(m_form)
    M.assemble()


    eps_ = shift_invert(K, Mb, nev, -(2 * np.pi * 5.0) ** 2, tol, 200, mesh.comm)
    nconv = eps_.getConverged()
    assert nconv >= nev, (nconv, nev)
    vr, _ = K.createVecs()
    freqs, vecs = [], []
    mv = M.createVecLeft()
    for i in range(nconv):
        lam_i = eps_.getEigenpair(i, vr).real
        M.mult(vr, mv)
        vecs.append(vr.array / np.sqrt(vr.dot(mv)))
        freqs.append(np.sqrt(max(lam_i, 0.0)) / (2 * np.pi))
    order = np.argsort(freqs)
    eps_.destroy()
    K.destroy()
    Mb.destroy()
    t_solve = time.perf_counter() - t0
    return Solid3D(mesh, V, M, np.array(freqs)[order], np.array(vecs)[order],
                   V.dofmap.index_map.size_local * V.dofmap.index_map_bs, t_mesh, t_solve,
                   mesh.topology.index_map(3).size_local)


# ----------------------------------------------------------------------------
# harmonic mode -> 3D field, subspace MAC
# ----------------------------------------------------------------------------
def _section_sampler(hs, xyz):
    """Returns f(shape) giving (U_r, U_z, U_phi) at the (r, z) of the 3D dof
    points xyz, from a P1 nodal shape of the harmonic solver."""
    from dolfinx import fem, geometry  # lazy: brings in dolfinx (and PETSc's signal handlers)
    from scipy.spatial import cKDTree  # lazy: brings in scipy

    r = np.hypot(xyz[:, 0], xyz[:, 1])
    q = np.column_stack([r, xyz[:, 2], np.zeros_like(r)])
    mesh2 = hs.mesh
    tree = geometry.BoundingBoxTree(mesh2, 2)
    cand = geometry.compute_collisions(tree, q)
    coll = geometry.compute_colliding_cells(mesh2, cand, q)
    inside = np.array([len(coll.links(i)) > 0 for i in range(len(q))])
    cells = np.array([coll.links(i)[0] for i in np.nonzero(inside)[0]], dtype=np.int32)
    # P2 dof points on chords of curved 3D faces may lie a fraction of a mm
    # outside the section: take the nearest section node there
    near = cKDTree(hs.points).query(q[~inside, :2])[1]
    f1 = fem.Function(hs.P1)

    def sample(shape):
        out = np.empty((len(q), 3))
        f1.x.array[:] = shape.reshape(-1)
        out[inside] = f1.eval(q[inside], cells)
        out[~inside] = shape[near]
        return out

    return sample


def harmonic_basis(sample, shape, n, xyz):
    """3D displacement fields (ndofs,) of harmonic mode `shape` (P1 nodal
    (U_r, U_z, U_phi)): [cos-orientation, sin-orientation] for n >= 1."""
    U = sample(shape)
    phi = np.arctan2(xyz[:, 1], xyz[:, 0])
    c, s = np.cos(phi), np.sin(phi)
    out = []
    if n == 0:
        pairs = [(np.ones_like(phi), np.ones_like(phi))]  # u_phi = U_phi (torsion)
    else:
        pairs = [(np.cos(n * phi), np.sin(n * phi)), (np.sin(n * phi), -np.cos(n * phi))]
    for fa, fb in pairs:
        ur, uz, up = U[:, 0] * fa, U[:, 1] * fa, U[:, 2] * fb
        out.append(np.column_stack([ur * c - up * s, ur * s + up * c, uz]).reshape(-1))
    return out


def subspace_fraction(M, basis, vecs):
    """Fraction (0..1) of each M-normalised vector lying in span(basis)."""

    x = M.createVecRight()
    y = M.createVecLeft()
    Mb = []
    for b in basis:
        x.array[:] = b
        M.mult(x, y)
        Mb.append(y.array.copy())
    B = np.array(basis)
    G = np.array(Mb) @ B.T  # Gram matrix
    P = vecs @ np.array(Mb).T  # (nvec, nbasis)
    return np.einsum("ij,jk,ik->i", P, np.linalg.inv(G), P)


# ----------------------------------------------------------------------------
# study
# ----------------------------------------------------------------------------
@dataclass
class Study:
    harmonic: dict  # n -> freqs (lowest N_MODES), fine 2D mesh
    harmonic_coarse: dict  # n -> freqs at 2 x SIZE_2D
    h2d_dofs: int
    kinds: dict  # n -> dominant component per mode
    runs: list = field(default_factory=list)  # per 3D size: dict


def run_study(sizes=SIZES_3D, verbose=True) -> Study:
    segs = simplified_segments()
    p = c20_params()
    E, nu, rho = (p["material"][k] for k in ("E", "nu", "rho"))
    hs = harmonic_solver(segs, SIZE_2D, E, nu, rho)
    hs_c = harmonic_solver(segs, 2 * SIZE_2D, E, nu, rho)
    harm, harm_c, shapes, kinds = {}, {}, {}, {}
    fmax = 3000.0
    for n in range(N_MAX + 1):
        res = hs.solve(n, fmax)
        harm[n] = res.freqs_hz[:N_MODES]
        shapes[n] = res.shapes[:N_MODES]
        # dominant displacement component of each mode
        kinds[n] = [("radial", "axial", "circumf.")[int(np.argmax(np.abs(sh).max(axis=0)))] for sh in shapes[n]]
        harm_c[n] = hs_c.solve(n, fmax).freqs_hz[:N_MODES]
    f_top = max(f[-1] for f in harm.values())
    # how many 3D modes lie below 1.1 f_top: count over all harmonics
    count, n = 0, 0
    while True:
        fn = hs_c.solve(n, 1.1 * f_top).freqs_hz
        if len(fn) == 0 and n > N_MAX:
            break
        count += len(fn) * (1 if n == 0 else 2)
        n += 1
    nev = count + 4
    study = Study(harm, harm_c, 3 * hs.V.dofmap.index_map.size_local, kinds)
    if verbose:
        print(f"\nharmonic reference: {study.h2d_dofs} dofs; 3D modes below {1.1 * f_top:.0f} Hz: {count}, nev = {nev}")
        for n in harm:
            print(f"  n={n}: {np.round(harm[n], 2)}  (2x coarser: {np.round(harm_c[n], 2)})")
    for h in sizes:
        sol = solve_3d(segs, h, E, nu, rho, nev)
        xyz = sol.V.tabulate_dof_coordinates()
        sample = _section_sampler(hs, xyz)
        rows = []
        for n in range(N_MAX + 1):
            k = 1 if n == 0 else 2
            for m, fh in enumerate(harm[n]):
                idx = np.sort(np.argsort(np.abs(sol.freqs - fh))[:k])
                basis = harmonic_basis(sample, shapes[n][m], n, xyz)
                mac = subspace_fraction(sol.M, basis, sol.vecs[idx])
                # best-matching 3D modes by shape alone, for the record
                frac_all = subspace_fraction(sol.M, basis, sol.vecs)
                best = np.sort(np.argsort(-frac_all)[:k])
                rows.append(dict(n=n, m=m, f_h=fh, idx=idx, f_3d=sol.freqs[idx],
                                 err=sol.freqs[idx] / fh - 1.0, mac=mac, shape_match=bool(np.all(best == idx))))
        peak_gb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024**2
        run = dict(h=h, ndofs=sol.ndofs, ncells=sol.ncells, t_mesh=sol.t_mesh, t_solve=sol.t_solve,
                   peak_gb=peak_gb, rows=rows, nconv=len(sol.freqs), freqs=sol.freqs)
        study.runs.append(run)
        if verbose:
            print(f"3D h={h * 1000:.0f} mm: {sol.ncells} tets, {sol.ndofs} dofs, mesh {sol.t_mesh:.1f} s, "
                  f"assemble+solve {sol.t_solve:.1f} s, peak RSS {peak_gb:.2f} GB")
            for r in rows:
                print(f"  n={r['n']} m={r['m']} harm {r['f_h']:9.2f}  3D {np.round(r['f_3d'], 2)} "
                      f"err% {np.round(100 * r['err'], 3)}  MAC {np.round(r['mac'], 3)} shape-match {r['shape_match']}")
        del sol, sample
    return study


def _intkeys(d: dict) -> dict:
    return {int(k): v for k, v in d.items()}


def study(sizes=SIZES_3D) -> Study:
    """``run_study(sizes)``, read from build/validation/wheel_3d.json when its key (the code ``run_study`` reaches,
    the C20's wheel file, the sizes) is the current one; run and stored otherwise (one run at a time: a lock)."""
    key = {"code": code_key("pipeline.validation.revolved_wheel:run_study"), "sizes": list(sizes),
           "wheel": hashlib.sha256((ROOT / "geometry" / "wheels" / "c20.toml").read_bytes()).hexdigest()[:16]}
    path = paths.build() / "validation" / "wheel_3d.json"
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path.with_suffix(".lock"), "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if path.exists():
            d = json.loads(path.read_text())
            if d.get("key") == key:
                s = d["study"]
                return Study(_intkeys(s["harmonic"]), _intkeys(s["harmonic_coarse"]), s["h2d_dofs"],
                             _intkeys(s["kinds"]), s["runs"])
        st = run_study(sizes, verbose=False)
        save_text(json.dumps({"key": key, "study": plain(st.__dict__)}), path)
        return st
