"""Backlash and interference of a worm and its wheel at a centre distance, measured on the exact
surfaces: the worm's ZA thread (closed form) and the wheel's generated flanks (the envelope
sections of :func:`geargen.core.worm.wheel_section`).

With the worm held (angle 0), each flank point of the worm's thread in a wheel transverse plane
is at some angle from the wheel flank facing it (at its radius); the smallest such angle over the
thread, over the planes across the face, is how far the wheel turns that way before touching.
The two sides' sum is the wheel's free rotation, reported as an arc at the wheel reference
circle (the backlash as designed, ``WormGearSet.backlash``). A negative side is interference.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import CubicSpline
from scipy.optimize import minimize_scalar

from geargen.core.worm import flank_axial_offset, wheel_section, worm_geometry
from geargen.design.worm import WormGearSet


@dataclass(frozen=True)
class WormPairCheck:
    """``free_rotation`` (rad) of the wheel per side (+1: toward +X at the mesh), ``backlash`` (mm,
    arc at the wheel reference circle), ``interference`` (a side below -``tolerance``), the plane
    of first contact per side and the centre distance checked (mm)."""

    free_rotation: dict
    backlash: float
    interference: bool
    contact_plane: dict
    centre_distance: float

    def to_dict(self) -> dict:
        return {"backlash_mm": self.backlash, "interference": self.interference,
                "free_rotation_rad": {str(k): v for k, v in self.free_rotation.items()},
                "contact_plane_mm": {str(k): v for k, v in self.contact_plane.items()},
                "centre_distance_mm": self.centre_distance}


def worm_pair_check(s: WormGearSet, centre_distance_error: float = 0.0, planes: int = 9,
                    samples: int = 200, tolerance: float = 1e-7) -> WormPairCheck:
    """The pair at its design centre distance plus ``centre_distance_error`` (mm, the worm moved away
    from the wheel). ``planes`` wheel transverse planes across 95 % of the face (1: the mid plane), ``samples`` worm
    radii per plane from root to tip, each side's smallest gap refined by a bounded search."""
    g = worm_geometry(s)
    a = g.centre_distance + centre_distance_error
    r2 = g.wheel_reference_diameter / 2
    p = s.hand_sign * g.screw_parameter
    rf, ra = g.worm_root_diameter / 2, g.worm_tip_diameter / 2
    half = 0.95 * s.wheel_face_width / 2
    best = {1: (math.inf, None), -1: (math.inf, None)}
    for z in (np.linspace(-half, half, planes) if planes > 1 else [0.0]):  # one plane: the mid plane
        sec = wheel_section(s, g, float(z), n_flank=400)
        r_tip = min(g.wheel_outside_diameter / 2, g.centre_distance - math.sqrt(g.throat_radius ** 2 - z * z))
        for side in (1, -1):
            f = sec.flank[side]
            radius = np.hypot(f[:, 0], f[:, 1])[::-1]  # increasing
            angle = np.arctan2(f[:, 0], f[:, 1])[::-1]
            flank_angle = CubicSpline(radius, angle)
            r_lo_wheel = radius[0]

            def gap(r):  # wheel turn (rad) toward ``side`` until the worm point at radius r touches
                th = math.pi - math.asin(z / r)
                x = p * (th - math.pi) + float(flank_axial_offset(g, side, r))
                y = a + r * math.cos(th)
                R = math.hypot(x, y)
                if not r_lo_wheel <= R <= r_tip:
                    return math.inf  # off the wheel's flank: nothing to touch
                return side * (float(flank_angle(R)) - math.atan2(x, y))

            lo = max(rf, abs(z) * 1.0001)
            if lo >= ra:
                continue
            rs = np.linspace(lo, ra, samples)
            values = np.array([gap(r) for r in rs])
            if not np.isfinite(values).any():
                continue
            k = int(np.argmin(values))
            res = minimize_scalar(gap, bounds=(rs[max(k - 1, 0)], rs[min(k + 1, samples - 1)]), method="bounded",
                                  options={"xatol": 1e-10})
            value = min(res.fun, values[k])
            if value < best[side][0]:
                best[side] = (value, float(z))
    rotation = {side: best[side][0] for side in (1, -1)}
    return WormPairCheck(free_rotation=rotation, backlash=(rotation[1] + rotation[-1]) * r2,
                         interference=min(rotation.values()) * r2 < -tolerance,
                         contact_plane={side: best[side][1] for side in (1, -1)}, centre_distance=a)


__all__ = ["WormPairCheck", "worm_pair_check"]
