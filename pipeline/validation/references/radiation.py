"""References of the radiation checks (tests/radiation/, the radiation writer): the efficiencies of SPEC 5
worked out by hand (the arithmetic written out with literal numbers, not by calling the formulas under test),
a flat disc wheel and a synthetic section with one mode shape, the modal velocity of one mode from its time
history (an independent route to the sound power of a force history), and the built C20's radiation set-up."""
from __future__ import annotations

import json

import numpy as np

from geometry.wheel import surface_radii, wheel_segments
from solvers.constants import thesis_contact_point
from solvers.radiation import surfaces as SF
from solvers.radiation.force_power import build_model
from solvers.radiation.surfaces import radiation_surfaces, surface_nodes

from pipeline.store.paths import ROOT
from pipeline.validation.references import node_average as NA

PI = np.pi


# ---------------------------------------------------------------- from test_efficiency.py

# ---------------------------------------------------------------- axial
# (n, f, hand value).  kappa = 1.9 + 1.015 n - 0.0189 n^2;  f_ca = 343 kappa / (2 pi 0.39),
# 2 pi 0.39 = 2.4504423;  sigma_a = 1 / (1 + (f_ca / f)^(2n + 4))
AXIAL_HAND = [
    # n = 0: kappa = 1.9, f_ca = 651.7 / 2.4504423 = 265.951991 Hz, (265.951991/200)^4 = 3.126747
    (0, 200.0, 1.9, 265.951991, 1 / (1 + (265.951991 / 200.0) ** 4), 0.24232151),
    # n = 1: kappa = 1.9 + 1.015 - 0.0189 = 2.8961, f_ca = 993.3623 / 2.4504423 = 405.380821 Hz
    (1, 500.0, 2.8961, 405.380821, 1 / (1 + (405.380821 / 500.0) ** 6), 0.77880001),
    # n = 2: kappa = 1.9 + 2.03 - 0.0756 = 3.8544, f_ca = 1322.0592 / 2.4504423 = 539.518607 Hz
    (2, 400.0, 3.8544, 539.518607, 1 / (1 + (539.518607 / 400.0) ** 8), 0.083654227),
    # n = 5: kappa = 1.9 + 5.075 - 0.4725 = 6.5025, f_ca = 2230.3575 / 2.4504423 = 910.185695 Hz
    (5, 800.0, 6.5025, 910.185695, 1 / (1 + (910.185695 / 800.0) ** 14), 0.14105963),
    # n = 8: kappa = 1.9 + 8.12 - 1.2096 = 8.8104, f_ca = 3021.9672 / 2.4504423 = 1233.233379 Hz
    (8, 1000.0, 8.8104, 1233.233379, 1 / (1 + (1233.233379 / 1000.0) ** 20), 0.014879352),
]


# ---------------------------------------------------------------- radial
# f_r1 = 120 n / 0.9636241, f_r2 = 800 / 0.9636241 = 830.199235, f_r3 = (280 + 150 n) / 0.9636241
GAMMA = 0.4


RADIAL_HAND = [
    # n = 0, f = 200 < f_r3(0) = 290.569732: Gamma / (1 + (830.199235/200)^2) = 0.4 / 18.231 = 0.021940928
    (0, 200.0, 0.4 / (1 + (830.199235 / 200.0) ** 2), 0.021940928),
    # n = 0, f = 500 > f_r3(0): Gamma = 1: 1 / (1 + (830.199235/500)^2) = 0.266175266
    (0, 500.0, 1 / (1 + (830.199235 / 500.0) ** 2), 0.266175266),
    # n = 1, f = 100 < f_r3(1) = 446.232089; f_r1 = 124.529885
    (1, 100.0, 0.4 / (1 + (124.529885 / 100.0) ** 2) / (1 + (830.199235 / 100.0) ** 2), 0.0022426851),
    # n = 2, f = 400 < f_r3(2) = 601.894445; f_r1 = 249.059770
    (2, 400.0, 0.4 / (1 + (249.059770 / 400.0) ** 4) / (1 + (830.199235 / 400.0) ** 2), 0.065515057),
    # n = 3, f = 1500 > f_r3(3) = 757.556802: Gamma = 1; f_r1 = 373.589656
    (3, 1500.0, 1 / (1 + (373.589656 / 1500.0) ** 6) / (1 + (830.199235 / 1500.0) ** 2), 0.76532374),
]

# ---------------------------------------------------------------- from test_surfaces.py

# Flat disc wheel in (r, Z): hub r <= 0.10, web 0.10..0.33 of constant thickness 0.02
# (Z = -0.01..0.01), rectangular tyre 0.33..0.40 of width 0.10 (Z = -0.05..0.05).
RADII = {"r": 0.40, "w": 0.10, "w_web": 0.03, "r_in": 0.33, "r_hub": 0.10}  # w_web: a deliberately different "mean"


def flat_disc_segments():
    return {
        "hub_inboard": np.array([[0.05, -0.04], [0.10, -0.04]]),
        "hub_outer": [np.array([[0.10, -0.04], [0.10, -0.01]]), np.array([[0.10, 0.01], [0.10, 0.04]])],
        "web_gauge": np.array([[0.10, -0.01], [0.20, -0.01], [0.33, -0.01]]),
        "tyre_inner": [np.array([[0.33, -0.01], [0.33, -0.05]]), np.array([[0.33, 0.05], [0.33, 0.01]])],
        "flange_back": np.array([[0.33, -0.05], [0.43, -0.05]]),
        "flange": np.array([[0.43, -0.05], [0.40, -0.03]]),
        "tread": np.array([[0.40, -0.03], [0.40, 0.05]]),
        "field_face": np.array([[0.40, 0.05], [0.33, 0.05]]),
        "web_field": np.array([[0.33, 0.01], [0.25, 0.01], [0.10, 0.01]]),
        "hub_outboard": np.array([[0.10, 0.04], [0.05, 0.04]]),
    }

# ---------------------------------------------------------------- from test_power.py

# synthetic section nodes (r, Z): 0 contact (tread), 1-4 web, 5 tyre side face, 6 tyre inner
PTS = np.array([[0.40, 0.0], [0.12, -0.01], [0.18, 0.01], [0.25, -0.01], [0.30, 0.01], [0.36, 0.05],
                [0.33, -0.03]])


BND = {"tread": [0], "web_gauge": [1, 3], "web_field": [2, 4], "field_face": [5], "tyre_inner": [6]}


# one mode shape (U_r, U_z, U_phi) per node
SHAPE = np.array([[0.3, 1.0, 0.1], [0.0, 0.05, 0.0], [0.0, 0.2, 0.0], [0.02, 0.5, 0.0], [0.05, 0.8, 0.0],
                  [0.1, 0.9, 0.0], [0.25, 0.7, 0.0]])


def setup(n=2, f_r=1000.0, m_r=20.0, zeta=1e-4, extra=None):
    modes = {"f_hz": np.array([f_r]), "n": np.array([n]), "cls": np.array(["a"]), "kind": np.array(["flexible"]),
             "modal_mass": np.array([m_r]), "shapes": SHAPE[None].copy(), "zeta_suspension": np.array([np.nan])}
    if extra is not None:
        for k, v in extra.items():
            modes[k] = np.concatenate([modes[k], v])
    s = radiation_surfaces(RADII, flat_disc_segments())
    return modes, s, surface_nodes(PTS, BND, s), zeta

# ---------------------------------------------------------------- from test_forces.py

DT = 36e-6  # SPEC 6


N = 13889  # 0.5 s, the simulation's final stretch


# flat disc wheel, by hand (tests/radiation/test_surfaces.py): annulus areas, both faces (m^2)
S_A_HAND = np.array([0.09303041, 0.13457798, 0.17612554, 0.21767310, 0.32107077])


S_R_HAND = 0.41720350  # 2 pi [0.40 * 0.10 + 0.33 (0.10 - 0.02)]


GAMMA_HAND = 0.45256964


# nodes of PTS on the surfaces (by radius): annuli q = 1..5 <- nodes 1, 2, 3, 4, 5; radial <- nodes 0, 6
AXIAL_NODES = [[1], [2], [3], [4], [5]]


RADIAL_NODES = [0, 6]


def sigma_by_hand(n, f):
    """SPEC 5 with r = 0.40, c0 = 343 written out (not the module's functions)."""
    kap = 1.9 + 1.015 * n - 0.0189 * n * n
    fca = 343.0 * kap / (2 * PI * 0.40)
    sa = 1 / (1 + (fca / f) ** (2 * n + 4))
    s = (0.40 / 0.42) ** 0.5
    fr1, fr2, fr3 = 120.0 * n / s, 800.0 / s, (280.0 + 150.0 * n) / s
    g = GAMMA_HAND if f < fr3 else 1.0
    sr = g / (1 + (fr2 / f) ** 2) * (1.0 if n == 0 else 1 / (1 + (fr1 / f) ** (2 * n)))
    return sa, sr


def one_mode_model(n, f_r, m_r, zeta):
    modes = {"f_hz": np.array([f_r]), "n": np.array([n]), "m": np.array([0]), "cls": np.array(["a"]),
             "modal_mass": np.array([m_r]), "shapes": SHAPE[None].copy()}
    s = SF.radiation_surfaces(RADII, flat_disc_segments())
    nodes = SF.surface_nodes(PTS, BND, s)
    phi = np.array([[SHAPE[0, 1], SHAPE[0, 0]]])  # contact at node 0: (U_z, U_r)
    return build_model(modes, s, nodes, phi, [zeta]), modes


def modal_velocity_reference(n, f_r, m_r, zeta, A2, A3, theta):
    """rho c0 [sigma_a sum_q S_aq <v_aq^2> + sigma_r S_r <v_r^2>] from the time-domain modal velocity."""
    w = 2 * PI * f_r
    u2, u3 = SHAPE[0, 1], SHAPE[0, 0]
    # one period, finely sampled (the time mean of a periodic signal), and the circumference
    t = np.arange(400) / 400 / f_r
    P = u2 * A2 * np.cos(w * t) + u3 * A3 * np.cos(w * t + theta)  # modal force (oscillating part)
    qdot = P / (2 * zeta * m_r * w)  # steady state at resonance
    phi = np.arange(360) * 2 * PI / 360
    ang = np.cos(n * phi)

    def ms(node, comp):  # space-time mean square of the velocity component at a node
        v = SHAPE[node, comp] * qdot[:, None] * ang[None, :]
        return np.mean(v**2)

    v2a = np.array([np.mean([ms(i, 1) for i in nodes]) for nodes in AXIAL_NODES])  # axial: U_z
    v2r = np.mean([ms(i, 0) for i in RADIAL_NODES])  # radial: U_r
    sa, sr = sigma_by_hand(n, f_r)
    return 1.21 * 343.0 * (sa * S_A_HAND @ v2a + sr * S_R_HAND * v2r)

# ---------------------------------------------------------------- from test_c20.py

ART = ROOT / "build" / "wheels" / "c20" / "modes.npz"


Y_DEFAULT = thesis_contact_point(-0.015)[0]  # the default case's y^W (m)


def load_c20(path=ART):
    """(modes dict, wheel parameters, surfaces, surface nodes, contact node at the default case's
    y^W = +32 mm: thesis [4.1] field-positive, solvers.constants)."""
    d = dict(np.load(path, allow_pickle=False))
    p = json.loads(str(d["__provenance__"]))["config"]  # the resolved configuration the artifact was built from
    s = SF.radiation_surfaces(surface_radii(p), wheel_segments(p))
    bnd = {k[len("boundary_"):]: d[k] for k in d if k.startswith("boundary_")}
    nodes = SF.surface_nodes(d["points"], bnd, s)
    c = NA.contact_node(d["points"], bnd, Y_DEFAULT, p["axle"]["rolling_circle_z"])
    return d, p, s, nodes, c
