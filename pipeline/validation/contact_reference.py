"""An independent source of the standard profiles: the S1002 wheel and the
UIC60 (60E1) rail files that CONTACT ships, as check points and as the rail's
arc geometry, for ``pipeline.validation.profiles_doc`` and
tests/profiles/test_standard_profiles_contact.py.

Source: E.A.H. Vollebregt, CONTACT (Vtech CMCC / TU Delft), github.com/eve70a/CONTACT
at commit ``CONTACT_COMMIT``, Apache License 2.0, files ``testbank/profiles/
MBench_S1002_v3.prw`` and ``MBench_UIC60_v3.prr`` (identical copies in examples/
and perfc_test/): SIMPACK profile files, "S1002 wheel profile v3" and "UIC60
rail profile v3 for Manchester Contact Benchmark" (Shackleton & Iwnicki,
Vehicle System Dynamics 46, 2008), lengths in mm (units.len.f = 1000).  The
files are not copied here; what is kept are numbers quoted from them:

* ``S1002_POINTS``: every 8th (y, z) point of the wheel file, as printed, from
  the flange back at y = 61.87 to the field side at y = -60 (file: y + toward
  the flange, from the tape circle; z = r - r0, + toward the flange; its
  ``mirror.y = 1`` makes y + toward the field side, this project's convention).
* ``UIC60_POINTS``: every 10th point of the rail file and every 3rd of its
  gauge face 11-26 mm below the crown, as printed (file frame: z + down; the
  head "already canted", 1:40 toward -y, the gauge side; "reference point not
  SIMPACK standard").
* ``UIC60_FRAME``: the rail centre line and crown top in that frame once the
  cant is turned back (found here: the head is then symmetric about the centre
  line to 1e-6 mm), and ``UIC60_ARCS``: R300 / R80 / R13 arcs and the 1:20 head
  side, least-squares circles and line through all 495 points of the file
  (largest residual 0.5 um).
"""
from __future__ import annotations

import numpy as np

CONTACT_COMMIT = "d431cdbd125084c79bd59df83b4ac4c63c570ac9"
CONTACT_FILES = ("testbank/profiles/MBench_S1002_v3.prw", "testbank/profiles/MBench_UIC60_v3.prr")
UIC60_CANT = 1 / 40  # the file's head is turned by atan(1/40) toward its gauge side (-y)
UIC60_FRAME = (-7.491702, 0.093557)  # (y, z) mm of the centre line / crown top, file frame turned back, z up
# (y, z) mm of the arc centres (crown top frame, z up), radii; the head side |y| = SIDE[0] - SIDE[1] z
UIC60_ARCS = {"R300": ((0.0, -300.0), 300.0), "R80": ((7.700, -80.134794), 80.0),
              "R13": ((23.01622, -14.908972), 13.0)}
UIC60_SIDE = (35.287013, 0.05)

S1002_POINTS = (  # (y, z) mm as printed in MBench_S1002_v3.prw
    (61.8651880, 25.8422150),
    (58.7662130, 27.3936670),
    (55.6672370, 27.9814350),
    (52.5682610, 27.7510270),
    (49.4692850, 26.6503480),
    (46.3703090, 24.6921700),
    (43.2713330, 21.7309640),
    (41.9579210, 19.9895890),
    (41.4084820, 19.1248620),
    (41.0586590, 18.5179830),
    (40.7470620, 17.9321140),
    (40.1516290, 16.6575510),
    (39.2431570, 14.2430200),
    (37.9929270, 10.9525210),
    (36.4608110, 8.4500950),
    (34.7139080, 6.6125274),
    (32.7692890, 5.2170012),
    (30.6421400, 4.1708523),
    (28.3471440, 3.3725450),
    (25.8968750, 2.7162302),
    (23.3014080, 2.1580232),
    (20.5686660, 1.6835016),
    (17.7051080, 1.2801375),
    (14.7165000, 0.9379210),
    (11.6087010, 0.6494553),
    (8.3885139, 0.4094554),
    (5.0647127, 0.2140044),
    (1.6493546, 0.0597801),
    (-1.8406501, -0.0566893),
    (-5.3819445, -0.1398074),
    (-8.9436670, -0.1957811),
    (-12.4877670, -0.2334264),
    (-15.9715290, -0.2644154),
    (-19.3526300, -0.3023438),
    (-22.5960200, -0.3604606),
    (-25.6810540, -0.4488383),
    (-28.6073410, -0.5723356),
    (-31.4119480, -0.7310073),
    (-34.2010260, -0.9157448),
    (-36.9901040, -1.1016833),
    (-39.7791830, -1.2876219),
    (-42.5682610, -1.4735604),
    (-45.3573390, -1.6594990),
    (-48.1464170, -1.8454375),
    (-50.9354960, -2.0313761),
    (-53.7245740, -2.2173146),
    (-56.5136520, -2.4032532),
    (-59.3027300, -2.5891917),
    (-60.0000000, -2.6356764),
)

UIC60_POINTS = (  # (y, z) mm as printed in MBench_UIC60_v3.prr
    (-43.7048980, 38.5107260),
    (-43.7046900, 38.5024140),
    (-43.7028640, 38.4292670),
    (-43.6963080, 38.1667140),
    (-43.6802580, 37.5239270),
    (-43.6483900, 36.2476150),
    (-43.5929460, 34.0270810),
    (-43.5048910, 30.5004480),
    (-43.4041890, 26.4673540),
    (-43.3740920, 25.2619660),
    (-43.3582440, 24.6272350),
    (-43.3073610, 22.5893830),
    (-43.2512290, 20.3412920),
    (-43.1895300, 17.8702660),
    (-43.1218190, 15.1684590),
    (-43.0080770, 13.8106430),
    (-42.8679360, 12.9853600),
    (-42.8172730, 12.7473880),
    (-42.7104420, 12.3044150),
    (-42.2110050, 10.7770020),
    (-41.4169910, 9.1264297),
    (-40.4151480, 7.6248431),
    (-39.1825330, 6.2449216),
    (-37.6963710, 5.0034021),
    (-35.9350390, 3.9422659),
    (-33.8786430, 3.1260143),
    (-31.5124480, 2.5231803),
    (-28.8289790, 1.9400944),
    (-25.8189390, 1.3995600),
    (-22.4766520, 0.9371498),
    (-18.8005420, 0.5931302),
    (-14.7945390, 0.3653135),
    (-10.4688810, 0.1829261),
    (-5.8725241, 0.0575997),
    (-1.4504537, 0.0035352),
    (2.6581070, 0.0117233),
    (6.4443153, 0.1232364),
    (9.9040297, 0.3820059),
    (13.0354810, 0.7470406),
    (15.8412890, 1.1811412),
    (18.3282190, 1.6518593),
    (20.5103620, 2.2715944),
    (22.4056510, 3.1735515),
    (24.0298100, 4.2865984),
    (25.4015350, 5.5611066),
    (26.5420460, 6.9707748),
    (27.4748650, 8.5245345),
    (28.2267130, 10.3235280),
    (28.8471760, 13.3692340),
    (29.4558870, 21.4718860),
    (29.8930940, 27.2940260),
    (30.1924040, 31.2798440),
    (30.3850800, 33.8456430),
    (30.4992740, 35.3663320),
    (30.5594640, 36.1678540),
    (30.5859550, 36.5206300),
    (30.5944800, 36.6341600),
    (30.5958840, 36.6528520),
    (30.5959120, 36.6532250),
)


def s1002_contact() -> tuple[np.ndarray, np.ndarray]:
    """CONTACT's S1002 check points (y, z) in m, this project's wheel convention."""
    p = np.array(S1002_POINTS)
    y, z = -p[:, 0], p[:, 1]  # the file's mirror.y
    order = np.argsort(y)
    return 1e-3 * y[order], 1e-3 * z[order]


def uic60_contact_points() -> tuple[np.ndarray, np.ndarray]:
    """CONTACT's UIC60 check points (y, z) in m, rail convention (y from the centre
    line + field side, z up from the crown top): the file's cant turned back."""
    p = np.array(UIC60_POINTS)
    y, z = p[:, 0], -p[:, 1]
    a = -np.arctan(UIC60_CANT)
    Y, Z = y * np.cos(a) - z * np.sin(a), y * np.sin(a) + z * np.cos(a)
    return 1e-3 * (Y - UIC60_FRAME[0]), 1e-3 * (Z - UIC60_FRAME[1])


def uic60_contact_curve(depth_mm: float = 25.0, ds_mm: float = 0.02) -> tuple[np.ndarray, np.ndarray]:
    """The UIC60 head of ``UIC60_ARCS`` (y, z) in m, gauge side to field side, down
    to ``depth_mm`` below the crown top, every ~ds_mm of arc length: the crown,
    shoulder and corner arcs from tangent point to tangent point, then the side."""
    (c1, r1), (c2, r2), (c3, r3) = (UIC60_ARCS[k] for k in ("R300", "R80", "R13"))
    c1, c2, c3 = (np.array(c) for c in (c1, c2, c3))
    t12 = c1 + r1 * (c2 - c1) / np.linalg.norm(c2 - c1)  # internal tangency of two arcs
    t23 = c2 + r2 * (c3 - c2) / np.linalg.norm(c3 - c2)
    n = np.array([1.0, UIC60_SIDE[1]]) / np.hypot(1.0, UIC60_SIDE[1])  # outward normal of the side
    t3s = c3 + r3 * n
    ang = lambda c, p: np.arctan2(p[0] - c[0], p[1] - c[1])  # noqa: E731  (from the vertical)
    pts = [np.zeros((1, 2))]
    for c, r, p0, p1 in ((c1, r1, np.array([0.0, 0.0]), t12), (c2, r2, t12, t23), (c3, r3, t23, t3s)):
        th = np.linspace(ang(c, p0), ang(c, p1), max(2, int(np.ceil(r * (ang(c, p1) - ang(c, p0)) / ds_mm)) + 1))[1:]
        pts.append(c + r * np.column_stack([np.sin(th), np.cos(th)]))
    zs = np.arange(t3s[1], -depth_mm, -ds_mm)[1:]
    pts.append(np.column_stack([UIC60_SIDE[0] - UIC60_SIDE[1] * zs, zs]))
    half = np.vstack(pts)
    y = np.r_[-half[:0:-1, 0], half[:, 0]]
    z = np.r_[half[:0:-1, 1], half[:, 1]]
    return 1e-3 * y, 1e-3 * z
