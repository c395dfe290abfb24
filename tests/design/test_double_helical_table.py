"""Double-helical gears in design tables and on the command line: the centre gap read in the design's
unit, refused for other kinds and outside [0, face width); the gear data gains the gap and the hands."""

import math

import pytest

from geargen.cli import main
from geargen.families.registry import read_gear
from geargen.errors import DesignError


def table(**kw):
    return {"kind": "double_helical", "teeth": 24, "module_mm": 2.0, "pressure_angle_deg": 20,
            "helix_angle_deg": 30, "hand": "left", "face_width_mm": 40.0, "centre_gap_mm": 8.0} | kw


def test_table_reads_the_gap_and_halves():
    spec = read_gear(table())
    assert spec.kind == "double_helical" and spec.centre_gap == 8.0
    assert spec.half_face_width == 16.0 and spec.half_hands == ("left", "right")
    inch = read_gear(_drop_none(table(module_mm=None, diametral_pitch_per_in=12, face_width_mm=None,
                                            face_width_in=2.0, centre_gap_mm=None, centre_gap_in=0.25)))
    assert inch.centre_gap == pytest.approx(0.25 * 25.4)
    assert read_gear(_drop_none(table(centre_gap_mm=None))).centre_gap == 0.0  # default: herringbone apex


def _drop_none(d):
    return {k: v for k, v in d.items() if v is not None}


@pytest.mark.parametrize("changes, key", [
    ({"centre_gap_mm": 40.0}, "gear.centre_gap_mm"),                      # not below the face width
    ({"centre_gap_mm": -1.0}, "gear.centre_gap_mm"),                      # negative
    ({"kind": "external"}, "gear.centre_gap_mm"),                         # only double_helical has one
    ({"helix_angle_deg": 0, "centre_gap_mm": None}, "gear.helix_angle_deg"),  # a double_helical needs a helix
])
def test_table_refusals_name_the_key(changes, key):
    with pytest.raises(DesignError) as err:
        read_gear(_drop_none(table(**changes)))
    assert err.value.field == key


def test_option_refused_for_an_external_gear(capsys):
    rc = main(["gear", "--teeth", "20", "--module", "1", "--face-width", "10", "--helix-angle", "20",
               "--centre-gap", "2"])
    assert rc == 2
    assert "--centre-gap" in capsys.readouterr().err


def test_gear_data_gains_gap_and_hands():
    from geargen.model.gear_data import gear_data
    from geargen.profile.tooth import tooth_profile
    spec = read_gear(_drop_none(table(module_mm=None, diametral_pitch_per_in=12, face_width_mm=None,
                                            face_width_in=2.0, centre_gap_mm=None, centre_gap_in=0.25)))
    data = gear_data(spec, tooth_profile(spec))
    assert data["double_helical"] == {"centre_gap": pytest.approx(0.25), "half_face_width": pytest.approx(0.875),
                                      "half_hands": ["left", "right"]}
    assert data["face_width"] == pytest.approx(2.0) and math.isclose(data["helix_angle_deg"], 30)
