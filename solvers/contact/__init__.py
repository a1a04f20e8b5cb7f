"""Rolling contact (SPEC 4): half-space influence coefficients, Kalker's NORM and TANG,
regularized friction curves and the tangential contact compliance.

Conventions (SPEC 2): grid axis 0 = x, rolling direction (the contact moves towards
+x), axis 1 = y, lateral (towards the field side); dx = v dt.  Pressures and
tractions act on the rail, u = u(rail) - u(wheel), slip = rail relative to wheel,
so F2 = -c^2 G C22 gamma_y in the linear range.  All functions take arrays on the
grid (any gap: Hertzian or from real profiles) and SI units.
"""
from solvers.contact.compliance import compliance_table, contact_compliance, table_compliance
from solvers.contact.friction import RFCurve, mu_rf, rf_curve
from solvers.contact.friction_laws import LAWS, PRESETS, FrictionLaw, get_friction_law, mu_of
from solvers.contact.influence import boussinesq, cerruti, dense_matrix, normal_kernel, tangential_kernels
from solvers.contact.norm import NormalContact, NormTable, approach_for_load, norm, norm_table, table_force, table_midpoint_error, table_pressure
from solvers.contact.tang import TangentialContact, rigid_slip, tang_steady, tang_transient

__all__ = [
    "boussinesq", "cerruti", "normal_kernel", "tangential_kernels", "dense_matrix",
    "NormalContact", "NormTable", "norm", "approach_for_load", "norm_table", "table_force", "table_pressure",
    "table_midpoint_error",
    "TangentialContact", "tang_steady", "tang_transient", "rigid_slip",
    "RFCurve", "rf_curve", "mu_rf",
    "FrictionLaw", "get_friction_law", "LAWS", "PRESETS", "mu_of",
    "contact_compliance", "compliance_table", "table_compliance",
]
