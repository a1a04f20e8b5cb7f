"""Every fragment of docs/validation/ and the writer that makes it, in the order ``make validate`` starts
them (the slowest first, so that two cores finish together).  ``in_validate=False``: a study too long
for ``make validate`` (hours of curve-stage runs, boundary-element solves), run by hand with its own
command; its fragment is assembled as last written.  tests/validation/test_writers.py checks that every
fragment has exactly one writer and that every module exists."""
from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Writer:
    name: str
    module: str                      # run as ``python -m <module> <args>``
    fragments: tuple[str, ...]       # docs/validation/<fragment>
    in_validate: bool = True
    args: tuple[str, ...] = ()


W = "pipeline.validation.writers."
WRITERS = (
    Writer("field_statistics", "pipeline.validation.field_statistics_doc", ("96_field_statistics.md",)),
    Writer("wheel_3d", W + "wheel_3d", ("22_wheel_3d.md",)),
    Writer("limit_cycle", "pipeline.validation.limit_cycle_runs", ("68_limit_cycle.md",)),
    Writer("interaction", W + "interaction", ("60_interaction.md",)),
    Writer("line", "pipeline.validation.line_doc", ("94_line.md",)),
    Writer("wheel_modes", W + "wheel_modes", ("20_wheel_plates.md", "21_c20_modes.md")),
    Writer("rail", W + "rail", ("40_rail.md",)),
    Writer("radiation", W + "radiation", ("70_radiation.md",)),
    Writer("studies", W + "studies", ("80_studies.md",)),
    Writer("reference_behaviour", W + "reference_behaviour", ("81_reference_behaviour.md",)),
    Writer("stability", W + "stability", ("66_stability.md", "66_stability_falling.md")),
    Writer("diagnosis", W + "diagnosis", ("65_fidelity_diagnosis.md",)),
    Writer("falling_friction", W + "falling_friction", ("67_falling_friction.md", "67_falling_friction_kalker.md")),
    Writer("two_points", W + "two_points", ("34_two_points.md",)),
    Writer("greens", W + "greens", ("50_greens.md",)),
    Writer("contact", W + "contact", ("30_contact.md",)),
    Writer("contact_positions", W + "contact_positions", ("31_contact_positions.md",)),
    Writer("friction_values", W + "friction_values", ("32_friction_values.md",)),
    Writer("contact_peer", W + "contact_peer", ("33_contact_peer.md",)),
    Writer("calibration", W + "calibration", ("23_calibration.md",)),
    Writer("fast_paths", W + "fast_paths", ("52_fast_paths.md",)),
    Writer("rail_surface", W + "rail_surface", ("53_any_rail_point.md",)),
    Writer("listening", W + "listening", ("75_listening.md",)),
    Writer("passby_exports", W + "passby_exports", ("76_passby_exports.md",)),
    Writer("mitigation", W + "mitigation", ("93_mitigation.md",)),
    Writer("curving", W + "curving", ("90_curving.md",)),
    Writer("bem_spheres", W + "bem_spheres", ("71_bem_spheres.md",)),
    Writer("profiles", "pipeline.validation.profiles_doc", ("15_profiles.md",)),
    Writer("rolling_cnossos", "pipeline.validation.rolling_cnossos_doc", ("95_rolling_cnossos.md",)),
    # by hand: `python -m pipeline.study.radius`, `python -m pipeline.validation.field`,
    # `python -m pipeline.validation.bem_check` (docs/reference.md, "Tests, validation, benchmarks")
    Writer("radius", "pipeline.study.radius", ("91_verdict.md",), in_validate=False),
    Writer("field", "pipeline.validation.field", ("92_field.md",), in_validate=False),
    Writer("bem_wheel", "pipeline.validation.bem_check", ("72_bem_wheel.md",), in_validate=False),
)
