"""ZA worm and generated wheel geometry (geargen.families.worm.geometry) against a published example and an
independent envelope computation."""

import math

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from geargen.families.worm.geometry import space_width_at_radius, wheel_angle, wheel_section, worm_geometry
from geargen.families.worm.spec import WormGearSet, WormWheelSpec, worm_set_from_table
from geargen.errors import DesignError, GeometryError


def khk_set(**changes):
    """KHK Gear Technical Reference, section 4.5 'Worm gear pair', Table 4.17 (axial module system):
    m_x = 3, alpha_n = 20 deg, z1 = 2 (double thread), z2 = 30, d1 = 44, x2 = 0, right hand."""
    kw = dict(axial_module=3.0, starts=2, wheel_teeth=30, worm_reference_diameter=44.0,
              pressure_angle=math.radians(20), worm_face_length=60.0, wheel_face_width=28.0)
    kw.update(changes)
    return WormGearSet(**kw)


def test_khk_table_4_17_dimensions():
    # KHK Table 4.17 results: gamma = 7.76517 deg, alpha_x = 20.17024 deg, d2 = 90, a = 67,
    # d_a1 = 50, d_a2 (throat) = 96, r_i (throat radius) = 19, d_f1 = 36.5, d_f2 = 82.5,
    # wheel outside diameter 99; lead = pi m z1 = 18.84956
    g = worm_geometry(khk_set())
    assert math.degrees(g.lead_angle) == pytest.approx(7.76517, abs=5e-6)
    assert math.degrees(g.axial_pressure_angle) == pytest.approx(20.17024, abs=5e-6)
    assert g.lead == pytest.approx(18.84956, abs=5e-6)
    assert (g.wheel_reference_diameter, g.centre_distance) == pytest.approx((90.0, 67.0))
    assert (g.worm_tip_diameter, g.throat_diameter, g.throat_radius) == pytest.approx((50.0, 96.0, 19.0))
    assert (g.worm_root_diameter, g.wheel_root_diameter, g.wheel_outside_diameter) == pytest.approx((36.5, 82.5, 99.0))


def test_mid_plane_space_is_the_worm_thread_as_a_rack():
    # in the wheel's mid plane the worm's axial section is a straight-sided rack rolling on the
    # wheel reference circle: the space width there is the thread thickness p_x / 2, plus the backlash
    sec = wheel_section(khk_set(), z=0.0, n_flank=4000)
    assert space_width_at_radius(sec, 45.0) == pytest.approx(math.pi * 3 / 2, abs=1e-7)
    j = 0.05
    thinned = wheel_section(khk_set(backlash=j), z=0.0, n_flank=4000)
    # the flank is turned by j / d2 each side: arc j at the reference circle
    assert space_width_at_radius(thinned, 45.0) - space_width_at_radius(sec, 45.0) == pytest.approx(j, abs=1e-9)
    # a worm thinned for the backlash does not change the wheel: the wheel is cut by the nominal hob
    worm_thinned = wheel_section(khk_set(backlash=j, backlash_on="worm"), z=0.0, n_flank=4000)
    assert space_width_at_radius(worm_thinned, 45.0) == pytest.approx(math.pi * 3 / 2, abs=1e-7)
    # the root circle is the hob tip: d_f2 / 2
    assert sec.root_radius == pytest.approx(41.25)
    assert np.hypot(*sec.trochoid[1][-1]) == pytest.approx(41.25, abs=1e-9)


@pytest.mark.parametrize("z", [0.0, 6.0, -9.0, 12.5])
@pytest.mark.parametrize("hand", ["right", "left"])
def test_wheel_flank_is_the_envelope_of_the_moving_worm(z, hand):
    """Independent of the meshing equation: each worm flank point's path through the wheel plane z,
    over the worm angle, must touch the wheel flank (the path's farthest reach into the tooth is 0)
    and no point of the worm may cross it (brute-force maximisation over the worm angle)."""
    s = khk_set(hand=hand)
    g = worm_geometry(s)
    sec = wheel_section(s, g, z, n_flank=3000)
    p = s.hand_sign * g.lead / (2 * math.pi)
    for side in (1, -1):
        f = sec.flank[side]
        radius = np.hypot(f[:, 0], f[:, 1])
        angle = np.arctan2(f[:, 0], f[:, 1])

        def flank_angle(R):
            return np.interp(-R, -radius, angle)  # radius falls along the flank

        for r in np.linspace(sec.worm_radii[5], sec.worm_radii[-5], 7):
            theta = math.pi - math.asin(z / r)
            y = g.centre_distance + r * math.cos(theta)
            offset = side * (g.hob_axial_thickness / 2 - (r - 22.0) * math.tan(g.axial_pressure_angle))

            def reach(phi1):  # how far (arc, mm) the worm point lies beyond the wheel flank, into the tooth
                x = p * (theta - math.pi - phi1) + offset
                phi2 = float(wheel_angle(s, g, phi1))
                c, sn = math.cos(phi2), math.sin(phi2)
                xw, yw = c * x + sn * y, -sn * x + c * y
                R = math.hypot(xw, yw)
                if not radius[-1] <= R <= radius[0]:  # above the rim or below the flank: no tooth to enter
                    return -1.0
                return side * (math.atan2(xw, yw) - flank_angle(R)) * R

            grid = np.linspace(-12.0, 12.0, 4001)  # off the mid plane contact runs far along the worm
            values = np.array([reach(v) for v in grid])
            k = int(np.argmax(values))
            best = minimize_scalar(lambda v: -reach(v), bounds=(grid[max(k - 1, 0)], grid[min(k + 1, 4000)]),
                                   method="bounded", options={"xatol": 1e-12})
            # the flank is read by linear interpolation between 3000 points (chord sag ~0.1 um, always
            # on the tooth side): the path touches it within 0.2 um and never enters the tooth
            assert -0.2e-3 < -best.fun <= 1e-9


def test_undercut_is_tagged():
    # a 20-deg ZA worm on a 10-tooth wheel: the envelope folds back near the wheel root
    s = khk_set(wheel_teeth=10, pressure_angle=math.radians(10), worm_reference_diameter=60.0, wheel_face_width=10.0)
    with pytest.raises(GeometryError) as info:
        wheel_section(s, z=0.0)
    assert info.value.kind == "wheel_undercut"


def test_table_reader_and_validation():
    spec = worm_set_from_table({"kind": "worm_wheel", "module_mm": 3, "starts": 2, "wheel_teeth": 30,
                                "diameter_quotient": 44 / 3, "pressure_angle_deg": 20, "worm_face_length_mm": 60,
                                "wheel_face_width_mm": 28, "backlash_mm": 0.05})
    assert isinstance(spec, WormWheelSpec) and spec.set.worm_reference_diameter == pytest.approx(44.0)
    with pytest.raises(DesignError) as info:
        worm_set_from_table({"kind": "worm", "module_mm": 3, "starts": 2, "wheel_teeth": 30, "diameter_quotient": 15,
                             "pressure_angle_deg": 20, "worm_face_length_mm": 60, "wheel_face_width_mm": 80})
    assert info.value.field == "gear.wheel_face_width_mm"
    # an axial pressure angle reads back to the normal one: tan alpha_n = tan alpha_x cos gamma
    axial = worm_set_from_table({"kind": "worm", "module_mm": 3, "starts": 2, "wheel_teeth": 30,
                                 "worm_reference_diameter_mm": 44, "pressure_angle_deg": 20.17024,
                                 "pressure_angle_system": "axial", "worm_face_length_mm": 60,
                                 "wheel_face_width_mm": 28})
    assert math.degrees(axial.set.pressure_angle) == pytest.approx(20.0, abs=1e-5)


@pytest.mark.parametrize("tolerance", [4e-10, 1e-6])
def test_helix_spline_stays_on_the_circle_over_many_turns(tolerance):
    """The helix B-spline (geargen.families.worm.geometry.helix_spline) over 60 turns, evaluated independently
    (scipy's BSpline on its knots and poles) at 200,000 parameters: within its stated error and the
    tolerance of (cos t, sin t) at the same t; its Greville abscissae reproduce t (a helix's z)."""
    from scipy.interpolate import BSpline

    from geargen.families.worm.geometry import helix_spline

    t0, t1 = -2.0, 2.0 + 120 * math.pi
    h = helix_spline(t0, t1, tolerance)
    assert h.knots[h.degree] == pytest.approx(t0) and h.knots[-h.degree - 1] >= t1
    t = np.linspace(t0, t1, 200_001)
    xy = BSpline(h.knots, h.poles, h.degree)(t)
    err = np.hypot(xy[:, 0] - np.cos(t), xy[:, 1] - np.sin(t)).max()
    # the stated error is measured on one span; every span is the same (uniform, poles on a circle),
    # so the 60 turns' error is it to rounding (1e-12 of the unit circle)
    assert err <= h.max_error + 1e-12 and h.max_error <= tolerance
    assert np.abs(BSpline(h.knots, h.greville, h.degree)(t) - t).max() < 1e-9  # t up to 379: 1e-9 is rounding
