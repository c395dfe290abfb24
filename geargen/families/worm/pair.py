"""Backlash and interference of a worm and its wheel at a centre distance, measured on the exact
surfaces: the worm's ZA thread (closed form) and the wheel's generated flanks (the envelope
sections of :func:`geargen.families.worm.geometry.wheel_section`).

With the worm held, each flank point of the worm's threads in a wheel transverse plane is at some
angle from the wheel flank facing it (at its radius); the smallest such angle over every engaged
thread, every phase of the mesh and the planes across the face is how far the wheel turns that
way before touching. The threads and phases are one family: the worm turned by phi1 moves its
thread by -p phi1 along X and the wheel's space by the same arc, and the next thread is p_x further
on facing the next space, so a shift u of the thread along X with the wheel space turned u / r2
covers them all (u over the wheel's rim). At the design centre distance the surfaces are
conjugate and every phase gives the same play; off it, another thread or phase touches first
(a solid measurement found 5 um less than the one-thread check gave, 0.05 mm off the distance).
The two sides' sum is the wheel's free rotation, reported as an arc at the wheel reference
circle (the backlash as designed, ``WormGearSet.backlash``). A negative side is interference.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import CubicSpline
from scipy.optimize import minimize_scalar

from geargen.families.worm.geometry import flank_axial_offset, wheel_section, worm_geometry
from geargen.families.worm.spec import WormGearSet


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
                    samples: int = 200, shifts_per_pitch: int = 12, tolerance: float = 1e-7) -> WormPairCheck:
    """The pair at its design centre distance plus ``centre_distance_error`` (mm, the worm moved away
    from the wheel). ``planes`` wheel transverse planes across 95 % of the face (1: the mid plane), ``samples`` worm
    radii per plane from root to tip, ``shifts_per_pitch`` thread shifts u per axial pitch over the
    wheel's rim (every thread and phase, see the module docstring); each side's smallest gap
    refined by a bounded search in r and in u."""
    g = worm_geometry(s)
    a = g.centre_distance + centre_distance_error
    r2 = g.wheel_reference_diameter / 2
    p = s.hand_sign * g.screw_parameter
    rf, ra = g.worm_root_diameter / 2, g.worm_tip_diameter / 2
    half = 0.95 * s.wheel_face_width / 2
    r_out = g.wheel_outside_diameter / 2
    count = 2 * int(math.ceil(r_out / g.axial_pitch * shifts_per_pitch)) + 1
    shifts = np.linspace(-r_out, r_out, count)
    best = {1: (math.inf, None), -1: (math.inf, None)}
    for z in (np.linspace(-half, half, planes) if planes > 1 else [0.0]):  # one plane: the mid plane
        sec = wheel_section(s, g, float(z), n_flank=400)
        r_tip = min(r_out, g.centre_distance - math.sqrt(g.throat_radius ** 2 - z * z))
        for side in (1, -1):
            f = sec.flank[side]
            radius = np.hypot(f[:, 0], f[:, 1])[::-1]  # increasing
            angle = np.arctan2(f[:, 0], f[:, 1])[::-1]
            flank_angle = CubicSpline(radius, angle)
            r_lo_wheel = radius[0]

            def gap(r, u):  # wheel turn (rad) toward ``side`` until the worm point at radius r, shift u touches
                r, u = np.broadcast_arrays(np.asarray(r, float), np.asarray(u, float))
                th = math.pi - np.arcsin(z / r)
                x = p * (th - math.pi) + flank_axial_offset(g, side, r) + u
                y = a + r * np.cos(th)
                big_r = np.hypot(x, y)
                on = (big_r >= r_lo_wheel) & (big_r <= r_tip)  # elsewhere: off the wheel's flank, nothing to touch
                out = np.full(big_r.shape, np.inf)
                out[on] = side * (flank_angle(big_r[on]) + u[on] / r2 - np.arctan2(x[on], y[on]))
                return out

            lo = max(rf, abs(z) * 1.0001)
            if lo >= ra:
                continue
            rs = np.linspace(lo, ra, samples)
            values = gap(rs[:, None], shifts[None, :])
            if not np.isfinite(values).any():
                continue
            i, j = np.unravel_index(int(np.argmin(values)), values.shape)
            r_range = (rs[max(i - 1, 0)], rs[min(i + 1, samples - 1)])
            u_range = (shifts[max(j - 1, 0)], shifts[min(j + 1, count - 1)])

            def smallest_over_r(u):
                # 1 rad stands for "off the flank" (inf would upset the parabolic steps)
                res = minimize_scalar(lambda r: min(float(gap(r, u)), 1.0), bounds=r_range, method="bounded",
                                      options={"xatol": 1e-10})
                return res.fun

            res = minimize_scalar(smallest_over_r, bounds=u_range, method="bounded", options={"xatol": 1e-9})
            value = min(res.fun, values[i, j])
            if value < best[side][0]:
                best[side] = (value, float(z))
    rotation = {side: best[side][0] for side in (1, -1)}
    return WormPairCheck(free_rotation=rotation, backlash=(rotation[1] + rotation[-1]) * r2,
                         interference=min(rotation.values()) * r2 < -tolerance,
                         contact_plane={side: best[side][1] for side in (1, -1)}, centre_distance=a)


__all__ = ["WormPairCheck", "worm_pair_check"]
