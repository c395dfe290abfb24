"""Each mesh's backlash range from the thickness allowances (geargen.checks.allowance): the route's range
measured by path 1 on the thinnest and thickest pairs equals the analytic range and the design's, and the
check's verdict fails when they disagree or leave the design range."""

import math
from pathlib import Path

import pytest
from checks_support import gear, inch_gear, theory_normal_backlash

from geargen.checks import allowance as check_allowance
from geargen.checks.allowance import AGREEMENT_TOLERANCE, backlash_ranges, measured_backlash_range
from geargen.checks.verdict import verify
from geargen.core.allowance import BacklashRoute, allowances_for_backlash, mesh_backlash_range, thickest, thinnest
from geargen.core.geometry import GearPair
from geargen.design.assembly import design_from_dict, load_design
from geargen.drives.resolver import resolve
from geargen.errors import DesignError

ROOT = Path(__file__).resolve().parents[2]
UM = 1e-3

PAIRS = {
    "spur inch 32 DP 21/112": (inch_gear(21, x=0.1), inch_gear(112)),
    "helical metric 20/61": (gear(20, 2.0, beta_deg=15, hand="right", x=0.3), gear(61, 2.0, beta_deg=15, hand="left")),
}


@pytest.mark.parametrize("pair", list(PAIRS))
@pytest.mark.parametrize("f_a", [0.0, 0.02])
def test_route_range_measured_on_the_extreme_pairs(pair, f_a):
    g1, g2 = PAIRS[pair]
    a = GearPair(g1, g2).standard_centre_distance + 0.05
    b_min, b_max = 0.06, 0.14
    a1, a2 = allowances_for_backlash(g1, g2, BacklashRoute(b_min, b_max, a, f_a))
    measured = measured_backlash_range(g1, a1, g2, a2, a, f_a)
    analytic = mesh_backlash_range(g1, a1, g2, a2, a, f_a)
    # path 1 resolves the play to ~1e-9 mm (its stated accuracy), the route meets the range exactly
    assert measured == pytest.approx(analytic, abs=1e-9)
    assert measured == pytest.approx((b_min, b_max), abs=1e-9)
    # independent: involute theory's normal backlash (checks_support, from the tight-mesh working angle)
    # over cos(alpha_t) cos(beta_b) is the circumferential backlash at the reference circle
    c = math.cos(g1.transverse_pressure_angle) * math.cos(g1.base_helix_angle)
    theory = (theory_normal_backlash(thickest(g1, a1), thickest(g2, a2), a - f_a) / c,
              theory_normal_backlash(thinnest(g1, a1), thinnest(g2, a2), a + f_a) / c)
    assert measured == pytest.approx(theory, abs=1e-9)


@pytest.mark.parametrize("name", ["split_pinion", "c_axis", "robot_joint"])
def test_shipped_designs_get_allowances_and_their_range(name):
    """No design file edited: every mesh with a range gets allowances, and with the design's own
    centre-distance tolerance (none given: 0) the range is the design's."""
    layout = resolve(load_design(ROOT / "assemblies" / f"{name}.toml"))
    records, failures = backlash_ranges(layout)
    assert not failures
    assert {r["mesh"] for r in records} == {m.name for m in layout.meshes if m.engaged}
    for r in records:
        assert r["measured"] == pytest.approx(r["analytic"], abs=1e-9)
        assert r["analytic"] == pytest.approx(r["design"], abs=1e-9)
        assert r["ok"]


SPLIT = ROOT / "assemblies" / "split_pinion.toml"


def _split_pinion(**changes):
    import tomllib
    data = tomllib.loads(SPLIT.read_text())
    for section, values in changes.items():
        for key, v in values.items():
            data[section] = data.get(section, {})
            if isinstance(v, dict):
                data[section][key] = {**data[section].get(key, {}), **v}
            else:
                data[section][key] = v
    return design_from_dict(data, SPLIT)


def test_check_reports_the_range_in_the_design_unit_with_the_tolerance():
    design = _split_pinion(checks={"centre_distance_tolerance_um": 10, "tolerances": False})
    result = verify(resolve(design))
    assert result.ok, [f.message for f in result.all_failures]
    d = result.to_dict()
    rec = d["backlash_range"][0]
    assert rec["centre_distance_tolerance"] == pytest.approx(0.010)
    assert rec["analytic"] == pytest.approx([0.05, 0.10], abs=1e-9)
    assert rec["measured"] == pytest.approx([0.05, 0.10], abs=1e-9)


def test_entered_allowances_that_leave_the_range_fail_the_check():
    # 0.05 to 0.10 mm asks for 25 to 50 um per gear (20/80 teeth, m 1.5, standard centres); 10 to 20 um
    # on the pinions and the output gives 0.04 mm at most of summed thinning: below the minimum
    entered = {"thickness_upper_deviation_um": -10, "thickness_lower_deviation_um": -20}
    design = _split_pinion(gears={"pinion_stiff": entered, "pinion_compliant": entered, "output": entered},
                           checks={"tolerances": False})
    result = verify(resolve(design))
    kinds = [f.kind for f in result.failures]
    assert kinds.count("allowance_range_outside_design") == 2
    rec = result.backlash_range[0]
    # spur, unshifted, standard centres: backlash = summed circumferential thinning = 2 x 10 and 2 x 20 um
    assert rec["analytic"] == pytest.approx([2 * 10 * UM, 2 * 20 * UM], abs=1e-9)


def test_a_disagreement_between_analytic_and_measured_fails(monkeypatch):
    real = check_allowance.measured_backlash_range
    monkeypatch.setattr(check_allowance, "measured_backlash_range",
                        lambda *a, **k: tuple(v + 2 * AGREEMENT_TOLERANCE for v in real(*a, **k)))
    layout = resolve(_split_pinion(checks={"tolerances": False}))
    _, failures = backlash_ranges(layout)
    assert [f.kind for f in failures] == ["allowance_range_disagrees"] * 2


def test_a_tolerance_that_eats_the_range_is_reported_naming_the_key():
    # the model's gears are made within their allowances: with none to be had the drive is refused
    with pytest.raises(DesignError) as err:
        resolve(_split_pinion(checks={"centre_distance_tolerance_mm": 0.1, "tolerances": False}))
    assert err.value.field == "layout.circumferential_backlash_max_mm"
    assert "checks.centre_distance_tolerance_mm" in err.value.allowed
    # teeth as designed are placed, and the check reports it
    design = _split_pinion(checks={"centre_distance_tolerance_mm": 0.1, "tolerances": False},
                           layout={"model_tooth_thickness": "as_designed"})
    result = verify(resolve(design))
    f = [f for f in result.failures if f.kind == "allowance_range_outside_design"]
    assert f and "layout.circumferential_backlash_max_mm" in f[0].message
    assert "checks.centre_distance_tolerance_mm" in f[0].message


@pytest.mark.slow
def test_route_range_measured_on_the_thickest_and_thinnest_solids():
    """The range the allowances promise, measured on generated solids: the thickest pair (upper
    deviations) built and sectioned at a - f_a, the thinnest (lower) at a + f_a, through the
    checker's solid-section path (path 2: cad.measure sections of the B-rep, chords refined to
    0.05 um) at the same mesh positions as the analytic sweep."""
    import numpy as np

    from geargen.cad.gear_solid import build_gear
    from geargen.checks.mesh2d import CheckSettings, MeshSetup, mesh_positions
    from geargen.checks.solids import check_mesh_sections, sections_from_shape

    g1, g2 = gear(18, 1.0, name="p", face_width=4.0), gear(29, 1.0, name="w", face_width=4.0)
    a, f_a = GearPair(g1, g2).standard_centre_distance + 0.03, 0.01
    a1, a2 = allowances_for_backlash(g1, g2, BacklashRoute(0.05, 0.12, a, f_a))
    analytic = mesh_backlash_range(g1, a1, g2, a2, a, f_a)
    measured = []
    for pick, centre, extreme in ((thickest, a - f_a, np.nanmin), (thinnest, a + f_a, np.nanmax)):
        p, w = pick(g1, a1), pick(g2, a2)
        setup = MeshSetup.centred(p, w, centre, "solids")
        planes = np.array([2.0])
        secs = [sections_from_shape(g, build_gear(g).shape, planes, samples_per_face=48) for g in (p, w)]
        check = check_mesh_sections(setup, secs[0], secs[1], CheckSettings(steps_per_tooth=4),
                                    mesh_positions(setup, 4))
        measured.append(float(extreme(check.sweep.angular_backlash)) * p.reference_radius)
    # the solids' flanks lie within 0.02 um of the involute and the section chords within 0.05 um:
    # the measured range is the promised one to 0.1 um (found: 0.018 and 0.034 um), and so the design's
    assert measured == pytest.approx(analytic, abs=1e-4)
    assert measured == pytest.approx((0.05, 0.12), abs=1e-4)
