"""The engineer's nouns as typed, immutable objects (issue 34): a curve, the vehicle that runs
through it (its bogie and its train), a wheel's steady-curving operating point and a resolved
friction law.  They are built once from the input files (``pipeline.config.curve_inputs``: the
schemas of ``pipeline.config.curve_schemas``) and passed in memory between the layers:

    Curve (its Vehicle, FrictionLaw) -> steady curving (``pipeline.curve.curving``)
      -> one WheelOperatingPoint per wheel of the leading bogie
      -> one ResolvedCase per wheel (``pipeline.config.case``) -> the stages.

Units: a field named with its unit (``radius_m``, ``cant_mm``, ``speed_kmh``) holds the file's
engineering value; the properties without a unit suffix are SI (m, m/s, N), as the solvers take
them.  The objects are picklable (a line study sends its curves to Dask workers).
"""
from __future__ import annotations

from dataclasses import dataclass, field, fields
from pathlib import Path

#: the wheels of the leading bogie: axle 1 leads, o/i the outer/inner rail
WHEELS = ("a1o", "a1i", "a2o", "a2i")


@dataclass(frozen=True)
class FrictionLaw:
    """A resolved ``[friction]`` table, resolved once where its file is read
    (``pipeline.caches.friction_curves.resolve_friction``).

    law: the registry's name ('coulomb', ...: ``solvers.contact.friction_laws.LAWS``); params:
    {name: value} in the registry's units; preset: the friction-modifier preset it came from, or
    None; mu: the coefficient (-) -- the Coulomb law's ``mu``, for another law its coefficient at
    zero slip speed (CONTACT's fstat) -- a field, set here, never read back from a curve's label."""
    law: str = "coulomb"
    params: dict = field(default_factory=dict)
    preset: str | None = None
    mu: float | None = None

    def __post_init__(self):
        if self.mu is None:
            object.__setattr__(self, "mu", self._coefficient())

    @classmethod
    def coulomb(cls, mu: float) -> "FrictionLaw":
        return cls("coulomb", {"mu": float(mu)})

    @classmethod
    def of(cls, name: str, params: dict, preset: str | None = None) -> "FrictionLaw":
        return cls(name, {k: float(v) for k, v in sorted(params.items())}, preset)

    def _coefficient(self) -> float:
        if self.law == "coulomb":
            return float(self.params["mu"])
        return float(self.solver_law().mu_static)

    @property
    def name(self) -> str:
        return self.law

    @property
    def coulomb_mu(self) -> float | None:
        """The Coulomb coefficient, None for another law (the what-ifs over mu scale Coulomb curves)."""
        return self.mu if self.law == "coulomb" else None

    @property
    def label(self) -> str:
        """The name of its friction curve in contact.npz and the curve cache."""
        from solvers.timeloop.inputs import curve_label  # lazy: brings in numba, rocket_fft, scipy

        return curve_label(self)

    def solver_law(self):
        """The solver's argument: the float mu for the Coulomb law, else the registry's law object."""
        if self.law == "coulomb":
            return float(dict(self.params)["mu"])
        from solvers.contact.friction_laws import get_friction_law  # lazy: brings in numba, rocket_fft, scipy

        return get_friction_law(self.law, **dict(self.params))

    @property
    def text(self) -> str:
        """For people: ``mu = 0.35`` (Coulomb), else the law with its parameters (and preset)."""
        if self.law == "coulomb":
            return f"mu = {dict(self.params)['mu']:g}"
        return self.label + (f" (preset {self.preset})" if self.preset else "")

    def config(self) -> dict:
        """JSON-able form, for configuration hashes (without ``mu``: it follows from the rest)."""
        return {"law": self.law, "params": dict(self.params), "preset": self.preset}

    def table(self) -> dict:
        """The ``[friction]`` table of a case file that resolves to this law."""
        if self.preset is not None:
            return {"preset": self.preset}
        return {"law": self.law, **dict(self.params)}


@dataclass(frozen=True)
class Bogie:
    """The leading bogie (vehicle file's [bogie], [wheelset], [primary], [secondary]): two
    wheelsets of the wheel ``wheel`` (geometry/wheels/<wheel>.toml), wheels ``WHEELS``."""
    wheel: str                        # geometry/wheels/<wheel>.toml
    wheel_profile: str | None         # geometry/profiles/<name>.csv, None: the wheel file's
    wheelbase_m: float                # between the two axles
    back_to_back_mm: float            # between the wheels' flange back faces
    wheelset_mass_kg: float
    wheelset_yaw_inertia_kgm2: float  # recorded, not used by the quasi-static equilibrium
    primary_kx_MN_per_m: float        # longitudinal, per axle box
    primary_ky_MN_per_m: float        # lateral, per axle box
    box_half_spacing_m: float         # wheelset centre to the axle-box springs, laterally
    secondary_yaw_kNm_per_rad: float  # bogie to car body

    @property
    def wheels(self) -> tuple[str, ...]:
        return WHEELS

    @property
    def semi_wheelbase(self) -> float:
        """m"""
        return 0.5 * self.wheelbase_m


@dataclass(frozen=True)
class Train:
    """The vehicle's axles along the track (vehicle file's [bogie] and [train]): ``cars`` identical
    cars of two bogies, ``car_length_m`` apart (a bogie to the same bogie of the next car)."""
    bogie_spacing_m: float            # between the car's bogie centres
    wheelbase_m: float                # of each bogie
    cars: int = 1
    car_length_m: float | None = None  # None: one car

    @property
    def axle_positions_m(self) -> tuple[float, ...]:
        """x of the train's axles from the leading one (m, positive backward), car by car."""
        s, a, L = self.bogie_spacing_m, self.wheelbase_m, self.car_length_m or 0.0
        return tuple(k * L + x for k in range(self.cars) for x in (0.0, a, s, s + a))

@dataclass(frozen=True)
class Vehicle:
    """A vehicle file (``geometry/vehicles/<name>.toml`` or a user's), validated.  ``data``: the
    validated file (provenance)."""
    name: str
    description: str
    source: Path
    bogie: Bogie
    train: Train
    wheel_load_N: float               # static vertical load per wheel (from wheel_load_kN or axle_load_kN)
    cg_height_m: float                # sprung mass's centre of gravity above the top of rail
    data: dict = field(repr=False, compare=False, default_factory=dict)

    @property
    def wheel(self) -> str:
        return self.bogie.wheel


@dataclass(frozen=True)
class Curve:
    """A curve file (``pipeline/curves/<name>.toml`` or a user's), validated, with its vehicle and
    friction resolved.  ``name`` is the file's stem (its results: build/curves/<name>/);
    ``data``: the validated file (provenance)."""
    name: str
    description: str
    source: Path
    vehicle: Vehicle
    rail: str                         # geometry/rails/<rail>.toml
    rail_profile: str | None          # geometry/profiles/<name>.csv, None: the rail file's
    radius_m: float                   # track centre line
    cant_mm: float
    gauge_mm: float
    gauge_widening_mm: float
    speed_kmh: float
    friction: FrictionLaw
    traction_force_kN: float          # per axle of the leading bogie (+ traction, - braking)
    data: dict = field(repr=False, compare=False, default_factory=dict)

    @property
    def radius(self) -> float:
        """m"""
        return float(self.radius_m)

    @property
    def cant(self) -> float:
        """m"""
        return 1e-3 * float(self.cant_mm)

    @property
    def gauge(self) -> float:
        """m, with the widening"""
        return 1e-3 * (float(self.gauge_mm) + float(self.gauge_widening_mm))

    @property
    def speed(self) -> float:
        """m/s"""
        return float(self.speed_kmh) / 3.6

    @property
    def wheel(self) -> str:
        return self.vehicle.wheel

    @property
    def wheelbase(self) -> float:
        """m"""
        return float(self.vehicle.bogie.wheelbase_m)

    @property
    def sources(self) -> tuple[str, str]:
        return str(self.source), str(self.vehicle.source)


@dataclass(frozen=True)
class WheelOperatingPoint:
    """One wheel of the leading bogie in steady curving (``pipeline.curve.curving.solve_curve``).

    SI, angles in rad; sign conventions of SPEC 2: track lateral y + toward the outer rail,
    dy_wr + toward the field side of that wheel's rail, creepages in the contact frame (1 along
    the travel, 2 toward that rail's field side)."""
    wheel: str                  # a1o, a1i, a2o, a2i
    axle: int                   # 1 leading, 2 trailing
    side: str                   # 'outer' / 'inner'
    dy_wr: float                # m, wheelset offset at this wheel (+ field side)
    rolling_circle_y: float     # m, c: the rolling circle over the rail centre
    angle_of_attack: float      # rad, the wheelset's yaw (+ under-radial)
    gamma_x: float              # -, longitudinal creepage of the tread contact
    gamma_y: float              # -, lateral creepage
    spin: float                 # 1/m
    y_wheel: float              # m, contact point on the wheel (y^W)
    y_rail: float               # m, on the rail head (y^R)
    contact_angle: float        # rad
    rolling_radius: float       # m
    wheel_load: float           # N, vertical force of all its contacts on the rail
    lateral_force: float        # N, toward the field side
    normal_load: float          # N, the tread contact's normal force (the case's preload)
    F1: float                   # N, tread creep forces on the rail
    F2: float                   # N
    creep_use: float            # |F| / (mu N)
    patch_a: float              # m, Hertz semi-axes
    patch_b: float              # m
    contact_points: int         # 1, or 2 with flange contact
    nadal: float                # Y/Q of the flange contact, NaN without
    nadal_limit: float
    flange_y_wheel: float       # m
    flange_y_rail: float        # m
    flange_angle: float         # rad
    flange_load: float          # N
    speed: float                # m/s
    mu: float                   # the curve's friction coefficient
    friction_law: str
    wheel_file: str             # geometry/wheels/<wheel_file>.toml
    rail_file: str
    wheel_profile: str | None
    rail_profile: str | None

    def case_fields(self) -> dict:
        """The keys of an ordinary case file (``pipeline.config.input_schemas.CASE``) this wheel fixes;
        the caller adds name, time and listener."""
        contact = {"dy_wr": self.dy_wr, "rolling_circle_y": self.rolling_circle_y}
        contact.update({k: v for k, v in (("wheel_profile", self.wheel_profile), ("rail_profile", self.rail_profile))
                        if v})
        # another law: the curve's own [friction] table stands (its parameters or preset; issue 33), no mu
        friction = {"mu": self.mu} if self.friction_law == "coulomb" else {}
        return {"wheel": self.wheel_file, "rail": self.rail_file, "contact": contact, "friction": friction,
                "kinematics": {"gamma_y": self.gamma_y, "gamma_x": self.gamma_x, "speed": self.speed},
                "loading": {"preload": self.normal_load}}


OPERATING_FIELDS = [f.name for f in fields(WheelOperatingPoint)]
