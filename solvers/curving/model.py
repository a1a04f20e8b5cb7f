"""The quasi-static equations of steady curving: one wheelset on its two rails, the leading
bogie's two wheelsets on their primary suspension and the frame (Boocock 1969; Wickens,
*Fundamentals of Rail Vehicle Dynamics*, 2003, the steady curving of the two-axle vehicle and
bogie), with the contact geometry of the actual profiles (``wheelrail``), the creep forces of
``creep`` and flange contact as a unilateral constraint (``solve``).

Track frame: x forward (travel), y outward (toward the outer rail), z down; the curve's centre
is at y = -R.  A wheelset at x_i (+a leading, -a trailing, from the bogie centre) has lateral
shift y (outward) from the track centre line, yaw psi (angle of attack: + when its wheels head
outward, toward the outer rail; measured from the local radial position) and rolling speed
omega = (1 + eps) V / r0.  Each wheel j (side s = +1 outer, -1 inner) touches its rail at one
or two points at distance l = l_w + y^W from the wheelset centre (l_w: rolling circle), with
rolling radius r = r0 + z_W(y^W) and contact angle delta.  The kinematics of the rigid
wheelset turning with the curve (yaw rate V / R) give the creepages of the rail relative to
the wheel in each contact's frame (1 travel, 2 toward that rail's field side, 3 into the rail):

    gamma_1 = (1 + eps) r / r0 - (1 + (y + s l) / R)
    gamma_2 = s psi cos(delta)
    phi     = (1 + eps) sin(delta) / r0 + s cos(delta) / R

(an under-radial leading wheelset, psi > 0, has gamma_2 < 0 on its inner wheel, as the
default case).  The contact force on the wheel is -(F1 e1 + F2 e2 + N e3) with e1 = x,
e2 = (0, s cos d, -sin d), e3 = (0, s sin d, cos d), acting at (0, s l, r) from the wheelset
centre.

Per wheelset five equations (lateral force, vertical force, roll moment, the torque about the
axle and the yaw moment) in five unknowns: y (or, in flange contact, the flange's normal force,
y then being the flange shift), psi, eps and the two tread normal forces.  The primary
suspension (per wheelset: lateral 2 k_y, yaw 2 k_x b^2) ties each wheelset to the frame, whose
lateral position y_b and yaw psi_b (outward) close the system with the frame's lateral force
and yaw moment.  The sprung mass per wheelset (axle load / g less the wheelset) loads the axle
boxes with its weight and the load transfer m_s a_unc (h_cg - r0) / b of the cant deficiency's
lateral acceleration a_unc = V^2 / R cos(phi_t) - g sin(phi_t) (phi_t the cant angle), and
pulls the frame outward with 2 m_s a_unc.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from solvers.curving.creep import CreepLaw, creep_forces
from solvers.curving.wheelrail import zone_point

G_ACC = 9.81


@dataclass(frozen=True)
class Vehicle:
    """The leading bogie (SI units).  semi_wheelbase a (m); bogie_spacing (m, between bogie
    centres); wheel_load Q0 (N, static, per wheel); wheelset_mass (kg); kx, ky (N/m per axle box,
    longitudinal and lateral primary stiffness); box_half_spacing b (m); secondary_yaw (N m/rad,
    bogie to car body); cg_height (m, sprung mass above the rail); r0 (m); rolling_circle l_w (m,
    from the wheelset centre: half back-to-back plus the wheel's flange-back offset)."""

    semi_wheelbase: float
    bogie_spacing: float
    wheel_load: float
    wheelset_mass: float
    kx: float
    ky: float
    box_half_spacing: float
    secondary_yaw: float
    cg_height: float
    r0: float
    rolling_circle: float


@dataclass(frozen=True)
class Track:
    """The curve (SI): radius R (m), cant (m), speed V (m/s), rail_centre b_r (m, half distance
    between the rail centre lines), c (m, each wheel's rolling circle over its rail centre with
    the wheelset centred, + field side: l_w - b_r), tractive force per axle (N, + traction)."""

    radius: float
    cant: float
    speed: float
    rail_centre: float
    c: float
    tractive_force: float = 0.0

    @property
    def cant_angle(self) -> float:
        return math.asin(self.cant / (2.0 * self.rail_centre))

    def unbalanced(self) -> tuple[float, float]:
        """(a_unc lateral outward, g_n normal) in the track plane, m/s^2."""
        ac, p = self.speed ** 2 / self.radius, self.cant_angle
        return ac * math.cos(p) - G_ACC * math.sin(p), G_ACC * math.cos(p) + ac * math.sin(p)


@dataclass(frozen=True)
class Profiles:
    """The wheel profile (``geometry.profiles.Profile``), the rail in the track frame
    (``geometry.contact_point.TrackRail``) and the wheel's flange edge y^W (``flange_edge``)."""

    wheel: object
    rail: object
    edge: float


@dataclass(frozen=True)
class ContactResult:
    """One contact point's geometry, creepages and forces (N on the rail, contact frame)."""

    side: int
    point: object
    r: float
    l: float
    gamma_1: float
    gamma_2: float
    spin: float
    N: float
    F1: float
    F2: float
    a: float
    b: float

    def force_on_wheel(self) -> tuple[float, float, float]:
        """(fx, fy, fz) in the track frame."""
        d, s = self.point.angle, self.side
        return (-self.F1, -(self.F2 * s * math.cos(d) + self.N * s * math.sin(d)),
                -(-self.F2 * math.sin(d) + self.N * math.cos(d)))


_CONTACTS: dict = {}
_CONTACTS_MAX = 20000


def wheel_contacts(prof: Profiles, veh: Vehicle, trk: Track, law: CreepLaw, side: int, y: float, psi: float,
                   eps: float, loads: dict) -> list[ContactResult]:
    """``_wheel_contacts`` memoised per (profiles, vehicle, track, law: by identity, held while cached) and
    its numbers: a Jacobian column of another unknown (the other wheelset's, the frame's) leaves a wheel's
    contacts as they were.  The same results (a pure function of its arguments); a fresh list each call."""
    key = (id(prof), id(veh), id(trk), id(law), side, float(y), float(psi), float(eps),
           tuple((k, float(v)) for k, v in loads.items()))
    hit = _CONTACTS.get(key)
    if hit is None or hit[0] is not prof or hit[1] is not veh or hit[2] is not trk or hit[3] is not law:
        if len(_CONTACTS) >= _CONTACTS_MAX:
            _CONTACTS.clear()
        hit = _CONTACTS[key] = (prof, veh, trk, law, _wheel_contacts(prof, veh, trk, law, side, y, psi, eps, loads))
    return list(hit[4])


def _wheel_contacts(prof: Profiles, veh: Vehicle, trk: Track, law: CreepLaw, side: int, y: float, psi: float,
                    eps: float, loads: dict) -> list[ContactResult]:
    """The contacts of one wheel (side +1 outer, -1 inner) of a wheelset at shift y, yaw psi,
    spin eps; loads: {'tread': N, 'flange': N or absent}."""
    out = []
    for zone, N in loads.items():
        zone, near = (zone, None) if isinstance(zone, str) else zone  # ("tread", y^W): one of two tread points
        p = zone_point(prof.wheel, prof.rail, trk.c + side * y, zone, prof.edge, near)
        if p is None:
            raise ValueError(f"the {zone} of the {'outer' if side > 0 else 'inner'} wheel does not face its rail "
                             f"(wheelset shift {1e3 * y:+.2f} mm)")
        d = p.angle
        r = veh.r0 + p.z_wheel
        l = veh.rolling_circle + p.y_wheel
        g1 = (1.0 + eps) * r / veh.r0 - (1.0 + (y + side * l) / trk.radius)
        g2 = side * psi * math.cos(d)
        phi = (1.0 + eps) * math.sin(d) / veh.r0 + side * math.cos(d) / trk.radius
        A = 0.5 * math.cos(d) / r
        pa = creep_forces(law, N, A, max(p.B, 1e-3 * A), g1, g2, phi)
        out.append(ContactResult(side, p, r, l, g1, g2, phi, N, pa.F1, pa.F2, pa.a, pa.b))
    return out


def box_loads(veh: Vehicle, trk: Track) -> tuple[float, float]:
    """(P_o, P_i): the vertical forces (N, down) of the outer and inner axle boxes on a wheelset."""
    a_unc, g_n = trk.unbalanced()
    m_s = 2.0 * veh.wheel_load / G_ACC - veh.wheelset_mass
    dP = m_s * a_unc * (veh.cg_height - veh.r0) / (2.0 * veh.box_half_spacing)
    return 0.5 * m_s * g_n + dP, 0.5 * m_s * g_n - dP


def wheelset_residual(contacts: list[ContactResult], veh: Vehicle, trk: Track, F_susp: float,
                      M_susp: float) -> tuple[float, float, float, float, float]:
    """(lateral force, vertical force, roll moment, axle torque, yaw moment) on a wheelset (N,
    N m), zero at equilibrium; F_susp, M_susp: the primary suspension's lateral force and yaw
    moment on it."""
    a_unc, g_n = trk.unbalanced()
    P_o, P_i = box_loads(veh, trk)
    b = veh.box_half_spacing
    Fy = F_susp + veh.wheelset_mass * a_unc
    Fz = P_o + P_i + veh.wheelset_mass * g_n
    Mx = b * (P_o - P_i)
    My = -trk.tractive_force * veh.r0
    Mz = M_susp
    for c in contacts:
        fx, fy, fz = c.force_on_wheel()
        yj = c.side * c.l
        Fy += fy
        Fz += fz
        Mx += yj * fz - c.r * fy
        My += c.r * fx
        Mz += -yj * fx
    return Fy, Fz, Mx, My, Mz
