"""CONTACT (E.A.H. Vollebregt's open-source CONTACT, github.com/eve70a/CONTACT, commit d431cdb of
2025-07-23, "$Revision: 2707$", built with gfortran outside this repository) as the peer of the
project's contact solvers: its printed results with every input stated, and the project's
numbers on the same inputs.  Used by test_falling_friction.py and test_two_patch.py.

Creep curves (module 3, steady rolling T=3, prescribed normal force N=1, Hertzian geometry
IPOTCN=-3): semi-axes AA = 8 mm, BB = 4 mm (CONTACT's curvatures A1 = 0.8464e-3, B1 = 2.406e-3
/mm), FN = 82 kN, GG = 82000 MPa and POISS = 0.28 for both bodies, 44 x 44 elements over 1.1
times the ellipse (dx = 0.4 mm, dy = 0.2 mm), CHI = 0, DQ = 0.4 mm, VELOC = 30000 mm/s.
Friction: the falling laws below with MEMDST = 0 (no friction memory: the instantaneous law),
MEM_S0 = 1 mm/s, and two with the friction memory MEMDST = 0.003 mm (CONTACT's tractcurv value); G = 4 with INISLP = 1 (slip velocity from below), OMGSLP = 1, EPS = 1e-8,
MAXIN = 1000; I = 0 (every case from scratch).  Creepages c = CREEP: lateral CETA = -c,
longitudinal CKSI = +c, each without spin and with CPHI = 6.25e-4 rad/mm (0.625 /m).
CONTACT's printed FX/FSTAT/FN, FY/FSTAT/FN, MZ [N mm] and the number of adhesion elements
('final element division: A') per case.

Transient rolling (T=2) with the L4 law over 40 steps: see CONTACT_TRANSIENT below.

Two patches (module 3, normal problem only, N=1, IPOTCN=3, IBASE=2): 44 x 64 elements of
0.5 x 0.5 mm centred on the origin (XC1 = -10.75, YC1 = -15.75 mm), undeformed distance
h = p(y) + x^2 / (2 RM) with the profile p(y) given at the element centres, two lobes
p(y) = min((y - yl)^2 / (2 rl), (y - yr)^2 / (2 rr) + dz); GG = 80769.23 MPa, POISS = 0.3
(E = 210 GPa).  The patch forces are CONTACT's element pressures PN (its .mat output, 6
digits) summed over y < 0 and y > 0 times dx dy.
"""
from __future__ import annotations

import numpy as np

from solvers.contact.friction_laws import get_friction_law
from solvers.contact.norm import approach_for_load
from solvers.contact.tang import tang_steady, tang_transient
from pipeline.validation.references.contact import grid

G28, NU28 = 82e9, 0.28
E28 = 2 * G28 * (1 + NU28)
FN = 82e3
V = 30.0                                  # VELOC 30000 mm/s
M = 44
DX, DY = 2 * 1.1 * 8e-3 / M, 2 * 1.1 * 4e-3 / M
SPIN = 0.625                              # CPHI 6.25e-4 rad/mm in 1/m
CREEP = (0.0005, 0.001, 0.002, 0.003, 0.005, 0.01, 0.02, 0.04)
SETS = (("lateral", 0, -1, 0.0), ("longitudinal", 1, 0, 0.0),
        ("lateral + spin", 0, -1, SPIN), ("longitudinal + spin", 1, 0, SPIN))

LAWS = {   # CONTACT L-digit: the law in the registry's names (CONTACT's own parameters)
    "L4 exponential": ("exponential", dict(fkin=0.14, fexp1=0.19, sabsh1=1250.0)),
    "L3 rational": ("rational", dict(fkin=0.2, frat1=0.1, sabsh1=200.0, frat2=0.05, sabsh2=500.0)),
    "L2 linear": ("linear", dict(fkin=0.2, flin1=0.1, sabsh1=300.0)),
    "L4 with memory": ("exponential", dict(fkin=0.14, fexp1=0.19, sabsh1=1250.0, memdst=0.003, mem_s0=1.0)),
    "L4 steep, memory": ("exponential", dict(fkin=0.1, fexp1=0.25, sabsh1=20.0, memdst=0.003, mem_s0=1.0)),
}

# CONTACT's printed (FX/FSTAT/FN, FY/FSTAT/FN, MZ [N mm], adhesion elements), SETS x CREEP in order
CONTACT_CREEP = {
    "L4 exponential": [
        (0.0, 0.2282, -15250.0, 1118), (0.0, 0.4193, -22780.0, 964), (0.0, 0.6996, -22500.0, 670), (0.0, 0.8648, -12800.0, 402), (0.0, 0.9541, 432.5, 20), (0.0, 0.9126, 1154.0, 0), (0.0, 0.8378, 1125.0, 0), (0.0, 0.7207, 757.5, 0),
        (-0.2376, 0.0, 0.0, 1116), (-0.4357, 0.0, 0.0, 948), (-0.7223, 0.0, 0.0, 632), (-0.8844, 0.0, 0.0, 354), (-0.9546, 0.0, 0.0, 0), (-0.9126, 0.0, 0.0, 0), (-0.8377, 0.0, 0.0, 0), (-0.7206, 0.0, 0.0, 0),
        (0.0, -0.6128, -46550.0, 474), (0.0, -0.4366, -55610.0, 616), (0.0, -0.09864, -66230.0, 666), (0.0, 0.1923, -66240.0, 614), (0.0, 0.6107, -46560.0, 414), (0.0, 0.9019, -3654.0, 0), (0.0, 0.8366, 221.9, 0), (0.0, 0.7209, 841.0, 0),
        (-0.154, -0.7414, -40020.0, 197), (-0.3025, -0.7203, -39280.0, 164), (-0.5588, -0.6303, -37390.0, 39), (-0.7225, -0.4897, -35680.0, 0), (-0.8517, -0.2754, -30030.0, 0), (-0.8872, -0.08693, -17740.0, 0), (-0.8317, -0.0215, -8500.0, 0), (-0.7193, -0.004676, -3609.0, 0),
    ],
    "L3 rational": [
        (0.0, 0.2154, -15280.0, 1124), (0.0, 0.3949, -22610.0, 980), (0.0, 0.6551, -21480.0, 680), (0.0, 0.8032, -10920.0, 418), (0.0, 0.8699, 2945.0, 24), (0.0, 0.7931, 2161.0, 0), (0.0, 0.7026, 972.2, 0), (0.0, 0.6336, 223.2, 0),
        (-0.2243, 0.0, 0.0, 1118), (-0.4107, 0.0, 0.0, 952), (-0.6771, 0.0, 0.0, 638), (-0.8226, 0.0, 0.0, 356), (-0.8703, 0.0, 0.0, 0), (-0.7929, 0.0, 0.0, 0), (-0.7024, 0.0, 0.0, 0), (-0.6336, 0.0, 0.0, 0),
        (0.0, -0.5845, -46500.0, 544), (0.0, -0.416, -55560.0, 650), (0.0, -0.09781, -65510.0, 680), (0.0, 0.1729, -64550.0, 624), (0.0, 0.5539, -43110.0, 418), (0.0, 0.7893, -748.7, 0), (0.0, 0.7039, 340.1, 0), (0.0, 0.634, -273.7, 0),
        (-0.1457, -0.7149, -39630.0, 294), (-0.286, -0.6947, -39000.0, 258), (-0.5261, -0.6077, -37600.0, 116), (-0.6732, -0.4664, -35940.0, 0), (-0.7734, -0.2506, -29210.0, 0), (-0.7702, -0.07232, -16240.0, 0), (-0.6975, -0.0163, -7557.0, 0), (-0.6326, -0.003661, -3511.0, 0),
    ],
    "L2 linear": [
        (0.0, 0.2487, -14770.0, 1110), (0.0, 0.4517, -21090.0, 934), (0.0, 0.7337, -18050.0, 600), (0.0, 0.8796, -7302.0, 318), (0.0, 0.9169, 1899.0, 0), (0.0, 0.8338, 2320.0, 0), (0.0, 0.6775, 1012.0, 0), (0.0, 0.6667, -66.53, 0),
        (-0.259, 0.0, 0.0, 1094), (-0.4692, 0.0, 0.0, 910), (-0.7565, 0.0, 0.0, 560), (-0.897, 0.0, 0.0, 260), (-0.917, 0.0, 0.0, 0), (-0.8339, 0.0, 0.0, 0), (-0.6768, 0.0, 0.0, 0), (-0.6667, 0.0, 0.0, 0),
        (0.0, -0.642, -46340.0, 260), (0.0, -0.4699, -53600.0, 514), (0.0, -0.1153, -62520.0, 612), (0.0, 0.1873, -60670.0, 566), (0.0, 0.6058, -38160.0, 376), (0.0, 0.8227, 302.4, 0), (0.0, 0.6914, 880.3, 0), (0.0, 0.6664, -894.9, 0),
        (-0.1567, -0.7331, -39680.0, 3), (-0.3069, -0.7063, -38510.0, 2), (-0.5603, -0.6011, -35390.0, 0), (-0.7132, -0.4543, -33180.0, 0), (-0.8193, -0.2442, -26850.0, 0), (-0.8091, -0.07066, -14530.0, 0), (-0.6742, -0.01361, -6200.0, 0), (-0.6656, -0.003399, -3258.0, 0),
    ],
    "L4 with memory": [
        (0.0, 0.2285, -15300.0, 1118), (0.0, 0.4201, -22950.0, 968), (0.0, 0.7018, -22780.0, 672), (0.0, 0.868, -13020.0, 416), (0.0, 0.9587, 600.1, 20), (0.0, 0.915, 1316.0, 0), (0.0, 0.8389, 1228.0, 0), (0.0, 0.7213, 829.0, 0),
        (-0.2378, 0.0, 0.0, 1116), (-0.4365, 0.0, 0.0, 948), (-0.7244, 0.0, 0.0, 632), (-0.8877, 0.0, 0.0, 354), (-0.9591, 0.0, 0.0, 0), (-0.9148, 0.0, 0.0, 0), (-0.8388, 0.0, 0.0, 0), (-0.7212, 0.0, 0.0, 0),
        (0.0, -0.6137, -46610.0, 478), (0.0, -0.4368, -55760.0, 618), (0.0, -0.09793, -66500.0, 666), (0.0, 0.1938, -66590.0, 616), (0.0, 0.6135, -46890.0, 416), (0.0, 0.9063, -3434.0, 0), (0.0, 0.8386, 355.9, 0), (0.0, 0.7217, 920.4, 0),
        (-0.1545, -0.7437, -40020.0, 199), (-0.3035, -0.7228, -39280.0, 172), (-0.5609, -0.6335, -37420.0, 44), (-0.7253, -0.4931, -35780.0, 0), (-0.8547, -0.2774, -30150.0, 0), (-0.8892, -0.08752, -17810.0, 0), (-0.8328, -0.02165, -8523.0, 0), (-0.7198, -0.004721, -3617.0, 0),
    ],
    "L4 steep, memory": [
        (0.0, 0.2123, -14470.0, 1116), (0.0, 0.3597, -14840.0, 924), (0.0, 0.4488, 5169.0, 478), (0.0, 0.3979, 12100.0, 136), (0.0, 0.3158, 4198.0, 0), (0.0, 0.2929, 1179.0, 0), (0.0, 0.2883, 435.0, 0), (0.0, 0.2868, 178.5, 0),
        (-0.2213, 0.0, 0.0, 1114), (-0.3739, 0.0, 0.0, 896), (-0.4549, 0.0, 0.0, 408), (-0.3947, 0.0, 0.0, 70), (-0.3143, 0.0, 0.0, 0), (-0.2928, 0.0, 0.0, 0), (-0.2883, 0.0, 0.0, 0), (-0.2868, 0.0, 0.0, 0),
        (0.0, -0.3679, -42110.0, 64), (0.0, -0.4131, -46720.0, 526), (0.0, -0.1477, -49090.0, 592), (0.0, 0.06239, -40050.0, 528), (0.0, 0.2921, -11390.0, 302), (0.0, 0.3004, 910.4, 0), (0.0, 0.2887, -245.6, 0), (0.0, 0.2868, -208.2, 0),
        (-0.0718, -0.3289, -31240.0, 15), (-0.1395, -0.3078, -28750.0, 12), (-0.2423, -0.2211, -21810.0, 3), (-0.2726, -0.1177, -17950.0, 0), (-0.2784, -0.0448, -12650.0, 0), (-0.2848, -0.01242, -6656.0, 0), (-0.2864, -0.003399, -3322.0, 0), (-0.2863, -0.000987, -1652.0, 0),
    ],
}


def hertz_contact():
    """The creep cases' NORM solution (X, Y, pressures) on CONTACT's grid."""
    X, Y = grid(M, M, DX, DY)
    _, ns = approach_for_load(FN, 0.8464 * X**2 + 2.406 * Y**2, DX, DY, E28, NU28)
    return X, Y, ns


def creep_curves(name, contact=None):
    """The project's steady TANG on the CONTACT cases of law `name`: array (32, 4) of (F1/(fstat FN),
    F2/(fstat FN), Mz [N mm], stick elements), SETS x CREEP in CONTACT's order, each case from
    scratch (CONTACT's I = 0, INISLP = 1)."""
    X, Y, ns = contact or hertz_contact()
    law = get_friction_law(LAWS[name][0], **LAWS[name][1])
    scale = law.mu_static * ns.F3
    out = []
    for _, ix, iy, spin in SETS:
        for c in CREEP:
            sol = tang_steady(ns.p, DX, DY, V, law, gamma_x=c * ix, gamma_y=c * iy, spin=spin, E=E28, nu=NU28,
                              full_output=False)
            assert sol.converged
            mz = float((X * sol.p2 - Y * sol.p1).sum() * DX * DY * 1e3)
            out.append((sol.F1 / scale, sol.F2 / scale, mz, int(sol.stick.sum())))
    return np.array(out)


# ---------------------------------------------------------------------------------------------
# two patches
# ---------------------------------------------------------------------------------------------

E30, NU30 = 210e9, 0.3
PATCH_GRID = (44, 64, 0.5e-3)             # MX, MY, dx = dy [m]
GEOMETRIES = {   # lobe centres yl, yr [mm], lateral radii rl, rr [mm], dz [mm] (right lobe lower), RM [mm]
    "two tread lobes": dict(yl=-4.0, rl=50.0, yr=4.0, rr=80.0, dz=0.005, rm=390.0),
    "tread + flange-like lobe": dict(yl=-5.0, rl=100.0, yr=5.0, rr=15.0, dz=0.010, rm=460.0),
}
# CONTACT: (geometry, FN [N]) -> (patch y < 0 [N], patch y > 0 [N], contact elements, approach [mm])
CONTACT_TWO_PATCH = {
        ("two tread lobes", 30e3): (16053.75, 13946.26, 148, 4.492e-2),
        ("two tread lobes", 65e3): (33319.47, 31680.54, 256, 7.552e-2),
        ("tread + flange-like lobe", 30e3): (20908.17, 9091.838, 152, 4.516e-2),
        ("tread + flange-like lobe", 65e3): (43297.65, 21702.35, 246, 7.507e-2),
}


def two_lobe_gap(geometry):
    """(X, Y, h) [m] of a two-lobe geometry on the patch grid: h = p(y) + x^2 / (2 RM)."""
    nx, ny, d = PATCH_GRID
    q = GEOMETRIES[geometry]
    X, Y = grid(nx, ny, d, d)
    ym = 1e3 * Y
    p = np.minimum((ym - q["yl"]) ** 2 / (2 * q["rl"]), (ym - q["yr"]) ** 2 / (2 * q["rr"]) + q["dz"])
    return X, Y, 1e-3 * p + X**2 / (2e-3 * q["rm"])


def patch_forces(geometry, F3):
    """The project's NORM at total load F3: (force on y < 0, force on y > 0, elements, approach [m])."""
    X, Y, h = two_lobe_gap(geometry)
    d = PATCH_GRID[2]
    xi, ns = approach_for_load(F3, h, d, d, E30, NU30)
    left = float(ns.p[Y < 0].sum() * d * d)
    right = float(ns.p[Y > 0].sum() * d * d)
    return left, right, int(ns.contact.sum()), float(xi)


# ---------------------------------------------------------------------------------------------
# transient rolling with falling friction
# ---------------------------------------------------------------------------------------------

# CONTACT module 3, transient rolling in contact-fixed coordinates (T=2), the creep cases' Hertzian
# contact, grid, material and L4 law (FKIN 0.14, FEXP1 0.19, SABSH1 1250 mm/s, MEMDST 0), G=4 with
# INISLP = 0 (the previous case's slip velocity), one case per time step DQ = dx = 0.4 mm: step 1
# a new sequence (P=2: no previous tractions), steps 2-40 P=0; steps 1-20 CETA = -0.002, steps
# 21-40 CKSI = 0.001, CETA = -0.006, CPHI = 6.25e-4 rad/mm.
TRANSIENT_LAW = "L4 exponential"
TRANSIENT_STEPS = 40


def transient_kinematics(k):
    """(gamma_x, gamma_y, spin [1/m]) of step k (0-based)."""
    return (0.0, -0.002, 0.0) if k < 20 else (0.001, -0.006, SPIN)


CONTACT_TRANSIENT = [
        (0.0, 0.03366, 0.0, 1240), (0.0, 0.06649, -125.1, 1226), (0.0, 0.09846, -363.9, 1200), (0.0, 0.1296, -711.6, 1192), (0.0, 0.1598, -1170.0, 1174),
        (0.0, 0.1894, -1740.0, 1164), (0.0, 0.218, -2389.0, 1138), (0.0, 0.2457, -3104.0, 1128), (0.0, 0.2726, -3905.0, 1118), (0.0, 0.2986, -4780.0, 1092),
        (0.0, 0.3238, -5691.0, 1080), (0.0, 0.348, -6651.0, 1064), (0.0, 0.3714, -7660.0, 1048), (0.0, 0.3939, -8699.0, 1038), (0.0, 0.4155, -9740.0, 1018),
        (0.0, 0.4362, -10810.0, 1000), (0.0, 0.456, -11890.0, 992), (0.0, 0.4748, -12930.0, 972), (0.0, 0.4928, -13980.0, 958), (0.0, 0.5098, -15010.0, 940),
        (-0.01466, 0.5654, -21310.0, 841), (-0.02825, 0.6108, -25970.0, 756), (-0.04077, 0.6458, -29060.0, 669), (-0.05228, 0.6716, -30940.0, 597), (-0.06282, 0.689, -31890.0, 535),
        (-0.07255, 0.7015, -32470.0, 485), (-0.0816, 0.7108, -32860.0, 448), (-0.08999, 0.7172, -33070.0, 416), (-0.09779, 0.7217, -33210.0, 392), (-0.1051, 0.7247, -33260.0, 375),
        (-0.1119, 0.7268, -33280.0, 357), (-0.1182, 0.7278, -33240.0, 346), (-0.1242, 0.7288, -33220.0, 338), (-0.1298, 0.7292, -33160.0, 329), (-0.135, 0.7296, -33100.0, 324),
        (-0.14, 0.73, -33040.0, 321), (-0.1447, 0.7305, -32980.0, 321), (-0.1491, 0.7312, -32920.0, 321), (-0.1532, 0.7318, -32850.0, 318), (-0.1571, 0.7323, -32790.0, 316),
]


def transient_run(law_or_mu, contact=None):
    """The project's transient TANG over CONTACT's 40 steps: array (40, 4) as creep_curves (forces
    normalised by the law's mu(0) FN)."""
    X, Y, ns = contact or hertz_contact()
    law = law_or_mu
    if isinstance(law_or_mu, str):
        law = get_friction_law(LAWS[law_or_mu][0], **LAWS[law_or_mu][1])
    scale = (law if isinstance(law, float) else law.mu_static) * ns.F3
    st, out = None, []
    for k in range(TRANSIENT_STEPS):
        gx, gy, sp = transient_kinematics(k)
        st = tang_transient(ns.p, DX, DY, V, law, gamma_x=gx, gamma_y=gy, spin=sp, state=st, E=E28, nu=NU28)
        assert st.converged
        mz = float((X * st.p2 - Y * st.p1).sum() * DX * DY * 1e3)
        out.append((st.F1 / scale, st.F2 / scale, mz, int(st.stick.sum())))
    return np.array(out)


def deviations(ours, ref):
    """Per case: the largest force component's deviation relative to the creep force |(FX, FY)|
    (CONTACT's, normalised by fstat FN), and |Mz - Mz_CONTACT| relative to the curve's largest
    |Mz| (the moment passes through zero along the curves)."""
    ref = np.asarray(ref)
    force = np.abs(ours[:, :2] - ref[:, :2]).max(axis=1) / np.hypot(ref[:, 0], ref[:, 1])
    mz_scale = np.repeat([np.abs(ref[k:k + len(CREEP), 2]).max() for k in range(0, len(ref), len(CREEP))],
                         len(CREEP))
    mz = np.abs(ours[:, 2] - ref[:, 2]) / np.maximum(mz_scale, 1.0)
    return force, mz
