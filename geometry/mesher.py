"""Gmsh meshing of a cross-section given as named boundary segments.

Each segment's polyline becomes Gmsh lines in a physical curve group of the
segment's name; the enclosed region becomes physical surface 1.  The physical
tags are numbered in first-appearance order and returned, so the solvers can
address boundaries by name.
"""
from __future__ import annotations

import numpy as np

from geometry.outline import Segment


def mesh_section(segments: list[Segment], path: str, order: int = 1, verbose: bool = False) -> dict[str, int]:
    """Mesh the closed outline with triangles and write it to ``path`` (.msh).

    Returns {name: physical curve tag}.  The surface has physical tag 1.
    The caller is responsible for atomic placement (write to a temp path).
    """
    import gmsh  # lazy: brings in gmsh

    gmsh.initialize()  # gmsh 4.8 has no isInitialized(): one session per call
    try:
        gmsh.option.setNumber("General.Terminal", 1 if verbose else 0)
        gmsh.model.add("section")
        geo = gmsh.model.geo
        point_tags: list[int] = []
        point_xy: list[np.ndarray] = []
        seg_of_line: list[str] = []
        line_tags: list[int] = []

        def add_point(xy, size):
            # reuse the previous point when the polylines join
            for tag, q in zip(point_tags[-1:] + point_tags[:1], point_xy[-1:] + point_xy[:1]):
                if np.linalg.norm(q - xy) < 1e-12:
                    return tag
            tag = geo.addPoint(float(xy[0]), float(xy[1]), 0.0, size)
            point_tags.append(tag)
            point_xy.append(np.asarray(xy, float))
            return tag

        prev = None
        for seg in segments:
            size = seg.size or 0.01
            for k, xy in enumerate(seg.points):
                if k == 0 and prev is not None:
                    continue
                tag = add_point(xy, size)
                if prev is not None and tag != prev:
                    line_tags.append(geo.addLine(prev, tag))
                    seg_of_line.append(seg.name)
                prev = tag
        first = point_tags[0]
        if prev != first:
            line_tags.append(geo.addLine(prev, first))
            seg_of_line.append(segments[-1].name)
        loop = geo.addCurveLoop(line_tags)
        surf = geo.addPlaneSurface([loop])
        geo.synchronize()
        names: dict[str, int] = {}
        for name in seg_of_line:
            names.setdefault(name, len(names) + 1)
        for name, tag in names.items():
            lines = [lt for lt, nm in zip(line_tags, seg_of_line) if nm == name]
            gmsh.model.addPhysicalGroup(1, lines, tag)
            gmsh.model.setPhysicalName(1, tag, name)
        gmsh.model.addPhysicalGroup(2, [surf], 1)
        gmsh.model.setPhysicalName(2, 1, "section")
        gmsh.option.setNumber("Mesh.Algorithm", 6)
        gmsh.option.setNumber("Mesh.CharacteristicLengthExtendFromBoundary", 1)
        gmsh.model.mesh.generate(2)
        if order > 1:
            gmsh.model.mesh.setOrder(order)
        gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
        gmsh.write(path)
        return names
    finally:
        gmsh.finalize()


def read_msh(path: str, gdim: int = 2):
    """Read a .msh file into dolfinx: (mesh, cell_tags, facet_tags).

    (dolfinx 0.5.2's gmshio.read_from_msh has a bug, so open the file in a
    Gmsh session and convert the model.)"""
    import gmsh  # lazy: brings in gmsh
    from dolfinx.io import gmshio  # lazy: brings in dolfinx (and PETSc's signal handlers)
    from mpi4py import MPI  # lazy: brings in mpi4py (and PETSc's signal handlers)

    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.open(str(path))
        return gmshio.model_to_mesh(gmsh.model, MPI.COMM_SELF, 0, gdim=gdim)
    finally:
        gmsh.finalize()
