"""Waveguide finite elements (SAFE / WFE) of the rail cross-section, dolfinx + SLEPc.

SPEC 3.2.  The rail (steel) and the rail pad (an elastic layer under the
foot, clamped at its underside on rigid ground) are meshed in the (y, z)
cross-section; along the rail the displacement is a wave

    u(x, y, z, t) = U(y, z) exp(i (w t - k x)).

Strains (engineering shears, Voigt order xx, yy, zz, yz, xy, xz):

    e_xx = -i k U_x     e_yy = U_y,y    e_zz = U_z,z    g_yz = U_y,z + U_z,y
    g_xy = U_x,y - i k U_y              g_xz = U_x,z - i k U_z

The axial component is scaled by the imaginary unit,

    U_x = -i W        (W real for real k; physical u_x = Re{-i W e^{i(wt-kx)}}),

which turns every strain into a real vector times a common phase:
e_xx = -k W and (g_xy, g_xz) = -i (W,y + k U_y, W,z + k U_z); the factor -i
of the two axial shears cancels in the energy because the isotropic D does
not couple them with the in-plane strains.  With the real strain vector
e(k) = e0 + k e1,

    e0 = (0, U_y,y, U_z,z, U_y,z + U_z,y, W,y, W,z),   e1 = (-W, 0, 0, 0, U_y, U_z),

the stiffness is K(k) = K0 + k K1 + k^2 K2 with the REAL SYMMETRIC matrices

    K0 = int e0' D e0,   K1 = int (e0' D e1 + e1' D e0),   K2 = int e1' D e1,
    M  = int rho (W^2 + U_y^2 + U_z^2),

so for real k the dispersion relation is the real symmetric generalized
eigenproblem (K0 + k K1 + k^2 K2) phi = w^2 M phi (SLEPc, shift-invert,
MUMPS).  The physical matrices are T K(k) T^H with T = diag(-i, 1, 1): the
in-plane (y, z) block is untouched, so forces and responses in y and z
need no conversion.  K1 couples W only with (U_y, U_z), while K0, K2 and M
are block diagonal in (W | U_y, U_z); the spectrum is even in k
(K(-k) = S K(k) S with S = diag(-1, 1, 1)).  ``solvers.rail.response``
exploits both facts.

Symmetry.  The rail is symmetric about y = 0, the mesh covers y >= 0 and the
two wave families are solved separately:

    'sym'  (vertical bending, extension, symmetric foot/web modes):  U_y = 0 on y = 0
    'anti' (lateral bending, torsion, web bending, antisymmetric foot): W = U_z = 0 on y = 0

A full-section field is the sum of the two; for a unit load at a point P
(y > 0 or on the axis), the full-section receptance is
G(P, P) = (G_sym + G_anti) / 2, each G from the half model loaded at P.

Materials.  Steel: E, nu, rho, loss factor eta_s.  Pad: an isotropic
elastic layer with Poisson ratio nu_p whose Young's modulus is calibrated
so that the vertical stiffness per unit rail length of the layer under a
rigid foot equals the given k_pad (N/m^2); the matrices are stored split
into their lambda- and mu-parts per region, K = lam K^lam + mu K^mu, so the
pad (or the steel) can be changed without re-assembly.  Loss factors enter
the forced response as complex moduli (``solvers.rail.response``).

Pad density.  The layer smears discrete pads (stiffness s_p every sleeper
spacing) along the rail, so its modulus is ~20x lower than a real pad's;
with a realistic rubber density (~1200 kg/m^3) the layer would have its
own thickness/shear resonances at 1-2 kHz, which real pads do not have
(and ~90 spurious waves below 7 kHz).  The pad mass (~0.1-0.3 kg/m) is
negligible for the rail, so the parameter files use rho_pad = 10 kg/m^3,
which moves the layer resonances above ~15 kHz.
"""
# The public names of the waveguide model; the code lives in ``solvers.rail.wfe``: assembly (matrices,
# materials, pad calibration), family (one wave family, real-k waves), section (torsion and
# shear centre), waves (wave types and dispersion branches).
from solvers.rail.wfe.assembly import FACETS, PAD_TAG, RAIL_TAG, Assembled, assemble, lame, material_moduli, pad_calibration
from solvers.rail.wfe.family import Family, eig_real_k, family  # noqa: F401
from solvers.rail.wfe.section import torsion_properties  # noqa: F401
from solvers.rail.wfe.waves import LABELS, classify, dispersion, region_masks  # noqa: F401
