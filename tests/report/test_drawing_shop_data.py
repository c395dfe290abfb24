"""The drawing's shop data read back from the SVG (and the PDF's text) equals the gear JSON's, from
the design-file keys of a gear table (geargen.design.gear, geargen.model.gear_data, geargen.report.drawing)."""

import math
import subprocess

import pytest

from geargen.core.allowance import series_allowance
from geargen.design.gear import gear_from_table
from geargen.errors import DesignError
from geargen.model.gear_data import gear_data
from geargen.profile.tooth import tooth_profile
from geargen.report.drawing import BLANK_BLOCK, DATA_BLOCK, FULL_VIEW, RUNOUT_SYMBOL, SECTION_VIEW, write_drawing
from tests.drawing_support import cell_texts, table_rows, tolerance_frames

TABLE = {"teeth": 40, "module_mm": 1.0, "pressure_angle_deg": 20, "face_width_mm": 12.0, "bore_diameter_mm": 20.0,
         "part_number": "GG-40-001", "revision": "B", "material": "42CrMo4 (1.7225)",
         "heat_treatment": "quenched and tempered", "hardness_HRC": 30, "flank_roughness_Ra_um": 0.8,
         "bore_fit": "H7", "tip_diameter_tolerance": "h9", "face_width_upper_deviation_mm": 0.0,
         "face_width_lower_deviation_mm": -0.05, "thickness_allowance_series": "cd26", "accuracy_grade": 6}


@pytest.fixture(scope="module")
def drawn(tmp_path_factory):
    spec = gear_from_table(TABLE, "gears.wheel", "wheel")
    profile = tooth_profile(spec, warn=False)
    data = gear_data(spec, profile, series_allowance(spec))
    folder = tmp_path_factory.mktemp("shop")
    files = write_drawing(data, profile, folder, spec.name, "gear wheel from test", "design.toml", "0.0")
    return spec, data, files


def test_the_json_carries_the_design_keys_and_the_standards_numbers(drawn):
    spec, data, _ = drawn
    assert data["part_number"] == "GG-40-001" and data["revision"] == "B"
    assert data["material"] == {"material": "42CrMo4 (1.7225)", "heat_treatment": "quenched and tempered",
                                "hardness": {"value": 30, "unit": "HRC"}, "source": "the gear table"}
    assert data["flank_roughness_Ra_um"] == pytest.approx(0.8, abs=1e-12)
    # ISO 286-2: 20 H7 = 0 / +21 um
    assert data["bore"]["code"] == "H7" and (data["bore"]["lower_deviation_um"], data["bore"]["upper_deviation_um"]) == (0, 21)
    assert data["bore"]["limits"] == pytest.approx([20.0, 20.021], abs=1e-12)
    # d_a = (40 + 2) mm = 42 mm, h9 above 30 up to 50: IT9 = 62 um
    tip = data["tip_diameter_tolerance"]
    assert tip["nominal"] == pytest.approx(42.0, abs=1e-9) and tip["limits"] == pytest.approx([41.938, 42.0], abs=1e-9)
    face = data["face_width_tolerance"]
    assert face["code"] is None and face["limits"] == pytest.approx([11.95, 12.0], abs=1e-12)
    # DIN 3967 cd26 at d = 40 mm (10 < d <= 50): A_sne = -54 um, T_s = 50 um
    allowance = data["thickness_allowance"]
    assert (allowance["upper_um"], allowance["lower_um"]) == pytest.approx((-54.0, -104.0), abs=1e-9)
    assert allowance["method"].startswith("DIN 3967:1978-08 cd26")
    assert data["span"]["limits"] and data["over_pins"]["limits"]
    # span limits: W_k moves by E_sn cos(alpha_n) (the module docstring of geargen.core.allowance)
    w = data["span"]["span_normal"]
    c = math.cos(math.radians(20))
    assert data["span"]["limits"] == pytest.approx([w - 0.104 * c, w - 0.054 * c], abs=1e-9)
    # geargen's rule for the axial runout of face B, stated as its own (no standard's number):
    # 0.2 (d_f / b) F_beta
    geo = data["datum_tolerances"]
    assert geo["face_axial_runout_formula"] == "0.2 (d_f / b) F_βT"
    assert geo["face_axial_runout_rule"].startswith("geargen's convention, not a value of a standard")
    assert geo["face_axial_runout_um"] == pytest.approx(0.2 * 2 * data["root_radius"] / 12.0
                                                        * data["accuracy"]["helix_total_um"], rel=1e-12)


def test_the_sheet_reads_back_the_jsons_values(drawn):
    _, data, files = drawn
    cells = cell_texts(files["svg"])
    blank = table_rows(cells, BLANK_BLOCK)
    main = table_rows(cells, DATA_BLOCK)
    lo, hi = data["bore"]["limits"]
    assert blank["Bore"] == f"20.0000 mm H7: {hi:.4f} / {lo:.4f} mm (max / min)"
    lo, hi = data["tip_diameter_tolerance"]["limits"]
    assert blank["Tip diameter"] == f"h9 (ISO 286-1): {hi:.4f} / {lo:.4f} mm (max / min)"
    lo, hi = data["face_width_tolerance"]["limits"]
    assert blank["Face width"] == f"by deviation: {hi:.4f} / {lo:.4f} mm (max / min)"
    assert blank["Material"] == data["material"]["material"]
    assert blank["Heat treatment"] == data["material"]["heat_treatment"]
    assert blank["Surface hardness"] == "30 HRC"
    assert blank["Flank roughness"] == "0.8 µm"
    assert blank["Datum A"] == "bore axis"
    t_b = data["datum_tolerances"]["face_axial_runout_um"]
    assert blank["Axial runout of B"] == f"{t_b * 1e-3:.4f} mm ({t_b:.1f} µm) to A; geargen's rule 0.2 (d_f / b) F_βT"
    assert blank["Datum B"] == data["datums"]["B"] == "face at z = b"
    assert main["Tooth thickness allowance, upper"] == "-0.0540 mm (-54.0 µm)"
    assert main["Tooth thickness allowance, lower"] == "-0.1040 mm (-104.0 µm)"
    assert main["Allowance method"].startswith("DIN 3967:1978-08 cd26 (Tables 1 and 2)")
    lo, hi = data["span"]["limits"]
    assert main["Span limits"] == f"{hi:.4f} / {lo:.4f} mm (max / min)"
    assert main["Pin diameter"] == f"{data['over_pins']['diameter']:.4f} mm"
    assert blank["Pin series"] == data["over_pins"]["series"]
    assert main["Runout tolerance"].endswith(", to datum A")
    chord = data["chordal_tooth"]
    assert main["Chordal tooth thickness / height"] == f"{chord['thickness_normal']:.4f} / {chord['height']:.4f} mm"
    lo, hi = chord["limits"]
    assert main["Chordal thickness limits"] == f"{hi:.4f} / {lo:.4f} mm (max / min)"
    # spur m 1 z 40 x 0: s = pi/2 mm, s_c = d sin(s/d) = 1.5704 mm, h_c = m + (d/2)(1 - cos(s/d)) = 1.0154 mm
    assert f"{40 * math.sin(math.pi / 2 / 40):.4f} / {1 + 20 * (1 - math.cos(math.pi / 2 / 40)):.4f} mm" \
        == main["Chordal tooth thickness / height"]
    title = {" ".join(t) for c, t in cells.items() if c[1] < 51}
    assert "Part number GG-40-001" in title and "Revision B" in title


def test_the_pdf_text_holds_the_same_values(drawn, poppler):
    _, data, files = drawn
    text = subprocess.run([poppler["pdftotext"], str(files["pdf"]), "-"], capture_output=True, text=True,
                          check=True, timeout=120).stdout
    compact = "".join(text.split())
    lo, hi = data["bore"]["limits"]
    for value in (f"{hi:.4f}/{lo:.4f}mm", "GG-40-001", "42CrMo4(1.7225)", "30HRC", "-0.1040mm(-104.0µm)",
                  f"{data['over_pins']['dimension']:.4f}mm"):
        assert value in compact, value


def test_bad_drawing_keys_name_the_key():
    from geargen.model.gear_data import check_shop_keys
    with pytest.raises(DesignError) as exc:
        check_shop_keys(gear_from_table({**TABLE, "bore_diameter_mm": 0.0}, "gears.wheel", "wheel"))
    assert exc.value.field == "gears.wheel.bore_fit"
    with pytest.raises(DesignError) as exc:
        check_shop_keys(gear_from_table({**TABLE, "bore_fit": "G7"}, "gears.wheel", "wheel"))
    assert exc.value.field == "gears.wheel.bore_fit" and "H7" in exc.value.allowed
    with pytest.raises(DesignError) as exc:
        check_shop_keys(gear_from_table({**TABLE, "thickness_allowance_series": "cd31"}, "gears.wheel", "wheel"))
    assert exc.value.field == "gears.wheel.thickness_allowance_series"
    with pytest.raises(DesignError) as exc:
        gear_from_table({**TABLE, "hardness_HV": 300}, "gears.wheel", "wheel")
    assert exc.value.field == "gears.wheel.hardness_HRC"


def test_the_datum_letters_stand_in_the_axial_section(drawn):
    """A and B are drawn in the axial section, each in its frame (ISO 5459): A above the gear in line
    with the bore's diameter dimension (left of the part), B right of the face at z = b, where the
    tables' tolerances "to datum A" and the blank table's datum rows refer."""
    spec, data, files = drawn
    cells = cell_texts(files["svg"])
    # the runout frames' datum compartments (their symbol's cell 6 mm to the value's left) name A too
    cited = {c for c, t in cells.items() if t == ["A"] and any(s[1] == c[1] and s[3] == c[3] and s[0] < c[0]
                                                              and cells[s] == [RUNOUT_SYMBOL] for s in cells)}
    letters = {t[0]: c for c, t in cells.items() if t in (["A"], ["B"]) and c not in cited
               and SECTION_VIEW[0] <= c[0] and c[2] <= SECTION_VIEW[2] + 5.0 and SECTION_VIEW[1] <= c[1]}
    assert set(letters) == {"A", "B"}
    a, b = letters["A"], letters["B"]
    # both frames 5 mm squares (DATUM_FRAME_MM) at one height above the tip; A left of B by more
    # than the face width drawn (B stands right of the face, A left of the hub and bore)
    for c in (a, b):
        assert c[2] - c[0] == pytest.approx(5.0, abs=1e-3) and c[3] - c[1] == pytest.approx(5.0, abs=1e-3)
    assert a[1] == pytest.approx(b[1], abs=1e-3)
    assert b[0] - a[2] > 0


@pytest.mark.parametrize("teeth", [40, 60])
def test_the_runout_frames_carry_the_jsons_tolerances(teeth, tmp_path):
    """ISO 1101 frames in the axial section (40 teeth: room below it) or beside it below the
    transverse section (60 teeth: the 2:1 section reaches the face width's text within 7 mm of the
    view's bottom): circular runout of the teeth (F_rT) and of face B (t_B), both to datum A, their
    values in mm to 4 decimals equal to the JSON's um."""
    spec = gear_from_table({**TABLE, "teeth": teeth}, "gears.wheel", "wheel")
    profile = tooth_profile(spec, warn=False)
    data = gear_data(spec, profile, series_allowance(spec))
    files = write_drawing(data, profile, tmp_path, spec.name, "gear wheel from test", "design.toml", "0.0")
    frames = tolerance_frames(cell_texts(files["svg"]), RUNOUT_SYMBOL)
    geo = data["datum_tolerances"]
    assert geo["radial_runout_um"] == data["accuracy"]["runout_um"]
    # the sheet gives mm to 4 decimals: 0.05 um of rounding
    values = sorted((float(v) * 1e3, d) for _, v, d in frames)
    expected = sorted((geo[k], "A") for k in ("radial_runout_um", "face_axial_runout_um"))
    assert [d for _, d in values] == ["A", "A"]
    assert [v for v, _ in values] == pytest.approx([v for v, _ in expected], abs=0.05 + 1e-9)
    in_section = [SECTION_VIEW[0] <= c[0] and c[1] >= SECTION_VIEW[1] for c, _, _ in frames]
    assert in_section == ([True, True] if teeth == 40 else [False, False])
    for c, _, _ in frames:  # every frame inside the views' area, above the blank table
        assert c[1] > BLANK_BLOCK[3] and FULL_VIEW[0] <= c[0]
