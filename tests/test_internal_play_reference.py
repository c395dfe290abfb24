"""The internal pair's free play on the exact outlines (geargen.families.internal.pair.free_play)
after issue 28 (the bisection reads only the pinion points that can reach the ring's tip circle
within its bracket) against the code it replaced, kept here as the reference: the same play to the
last bit, at several mesh phases of a published pair, a thinned pair and the shipped planetary
drive's planet-ring meshes."""

import math
from pathlib import Path

import numpy as np
import pytest

from geargen.errors import GeargenError
from geargen.families.internal.geometry import internal_pair_geometry
from geargen.families.internal.pair import InternalPlay, RingMaterial, _max_depth, free_play, pinion_points
from geargen.profile.internal import internal_profile
from geargen.profile.tooth import tooth_profile

from test_internal import pair_parts, pinion, ring

ASSEMBLIES = Path(__file__).resolve().parents[1] / "assemblies"


def reference_free_play(pair, pinion, ring, phase=0.0, step=None, material=None):
    """geargen before issue 28: every pinion point read at every bisection step."""
    step = step or 1e-3 * pair.pinion.module
    material = material or RingMaterial(ring)
    pts = pinion_points(pinion, step)
    z1, z2, a = pair.pinion.teeth, pair.ring.teeth, pair.centre_distance
    from geargen.families.internal.pair import placed_points
    reach = np.hypot(*placed_points(pts, (a, 0.0), phase).T)
    pts = pts[reach > ring.tip_radius - pinion.tip_radius * pinion.pitch_angle]
    if _max_depth(material, pts, a, z1, z2, phase, 0.0) >= 0:
        raise GeargenError(f"the pinion overlaps the ring at mesh position {phase!r} rad")
    limits = []
    for sign in (1.0, -1.0):
        lo, hi = 0.0, 0.0
        stride = 0.01 * pinion.pitch_angle
        while True:
            hi += stride
            if _max_depth(material, pts, a, z1, z2, phase, sign * hi) >= 0:
                break
            lo = hi
            if hi > pinion.pitch_angle:
                raise GeargenError("no contact within one pitch")
        for _ in range(80):
            mid = 0.5 * (lo + hi)
            if hi - lo < 1e-13:
                break
            if _max_depth(material, pts, a, z1, z2, phase, sign * mid) >= 0:
                hi = mid
            else:
                lo = mid
        limits.append(0.5 * (lo + hi))
    return InternalPlay(phase, limits[0], limits[1], pair.pinion.base_radius * (limits[0] + limits[1]))


def _cases():
    zero = internal_pair_geometry(pinion(30), ring(40, 0.5)).centre_distance
    yield "30/40", pair_parts(30, 0.0, 40, 0.5, centre_distance=zero - 0.02)
    zero = internal_pair_geometry(pinion(17, 0.3, 2.0), ring(61, 0.0, 2.0)).centre_distance
    yield "17/61 m2", pair_parts(17, 0.3, 61, 0.0, m=2.0, centre_distance=zero - 0.05)
    # the shipped planetary drive's stage, at its planet's carrier radius (as its verdict reads it)
    from geargen.design.assembly import load_design
    from geargen.drives.resolver import resolve
    layout = resolve(load_design(ASSEMBLIES / "planetary_dual_pinion.toml"))
    planets = [g for g in layout.gears if "planetary_planet" in g.roles]
    ring_part = next(g for g in layout.gears if g.spec.kind == "internal")
    sun = next(g for g in layout.gears if g.group == planets[0].group and "planetary_sun" in g.roles)
    a = math.dist(planets[0].centre, sun.centre)
    planet, ring_spec = planets[0].spec, ring_part.spec
    yield "planetary", (internal_pair_geometry(planet, ring_spec, a), tooth_profile(planet, warn=False),
                        internal_profile(ring_spec))


@pytest.mark.parametrize("label, parts", list(_cases()), ids=lambda v: v if isinstance(v, str) else "")
def test_free_play_as_before(label, parts):
    g, p1, p2 = parts
    material = RingMaterial(p2)
    for phase in np.linspace(0.0, 2 * math.pi / g.pinion.teeth, 5, endpoint=False):
        got = free_play(g, p1, p2, float(phase), material=material)
        want = reference_free_play(g, p1, p2, float(phase), material=material)
        assert got == want


@pytest.mark.parametrize("label, parts", list(_cases()), ids=lambda v: v if isinstance(v, str) else "")
def test_ring_half_angle_on_the_involute_as_the_masked_reading(label, parts):
    """RingMaterial.half_angle of radii all on the ring's involute (read at once) gives the bits the
    masked reading gives them when one radius off the involute (on the fillet) sends it that way."""
    _, _, p2 = parts
    material = RingMaterial(p2)
    ring = material.ring
    radii = np.linspace(ring.base_radius, ring.form_radius, 997)
    at_once = material.half_angle(radii)
    masked = material.half_angle(np.append(radii, 0.5 * (ring.form_radius + ring.root_radius)))
    assert at_once.tobytes() == masked[:-1].tobytes()
