"""Helpers of the mesh-check tests: gears, and the backlash of involute theory."""

import math
import warnings

from geargen.core.involute import involute, inverse_involute
from geargen.design.gear import GearSpec
from geargen.units import MM_PER_IN

DEG = math.pi / 180

warnings.filterwarnings("ignore", message="undercut")


def gear(teeth, module=2.0, alpha_deg=20.0, beta_deg=0.0, hand="right", x=0.0, thinning=0.0, name=None, **kw):
    """A GearSpec in the normal system (mm, deg)."""
    return GearSpec(teeth=teeth, module=module, pressure_angle=alpha_deg * DEG, helix_angle=beta_deg * DEG,
                    hand=hand, profile_shift=x, thinning=thinning, face_width=kw.pop("face_width", 10.0),
                    name=name or f"z{teeth}", **kw)


def inch_gear(teeth, diametral_pitch=32, alpha_deg=20.0, **kw):
    return gear(teeth, MM_PER_IN / diametral_pitch, alpha_deg, **kw)


def tight_working_angle(g1, g2):
    """Transverse working pressure angle of the zero-backlash mesh of the unthinned gears:
    inv(alpha_wt0) = inv(alpha_t) + 2 tan(alpha_n) (x1 + x2) / (z1 + z2)."""
    return inverse_involute(involute(g1.transverse_pressure_angle)
                            + 2 * math.tan(g1.pressure_angle) * (g1.profile_shift + g2.profile_shift)
                            / (g1.teeth + g2.teeth))


def tight_centre_distance(g1, g2):
    return (g1.base_radius + g2.base_radius) / math.cos(tight_working_angle(g1, g2))


def theory_normal_backlash(g1, g2, centre_distance):
    """(z1+z2) m_n cos(alpha_n) (inv alpha_wt' - inv alpha_wt0) plus the thinning of both gears
    as normal backlash, (s1 + s2) cos(alpha_t) cos(beta_b)."""
    a_w = math.acos((g1.base_radius + g2.base_radius) / centre_distance)
    geometric = ((g1.teeth + g2.teeth) * g1.module * math.cos(g1.pressure_angle)
                 * (involute(a_w) - involute(tight_working_angle(g1, g2))))
    allowance = (g1.thinning + g2.thinning) * math.cos(g1.transverse_pressure_angle) * math.cos(g1.base_helix_angle)
    return geometric + allowance
