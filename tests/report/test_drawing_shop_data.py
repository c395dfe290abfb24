"""The drawing's shop data read back from the SVG (and the PDF's text) equals the gear JSON's, from
the design-file keys of a gear table (geargen.design.gear, geargen.model.gear_data, geargen.report.drawing)."""

import math
import subprocess
import xml.etree.ElementTree as ET

import pytest

from geargen.core.allowance import series_allowance
from geargen.design.gear import gear_from_table
from geargen.errors import DesignError
from geargen.model.gear_data import gear_data
from geargen.profile.tooth import tooth_profile
from geargen.report.drawing import BLANK_BLOCK, DATA_BLOCK, parse_cell_gid, write_drawing

SVG = "{http://www.w3.org/2000/svg}"

TABLE = {"teeth": 40, "module_mm": 1.0, "pressure_angle_deg": 20, "face_width_mm": 12.0, "bore_diameter_mm": 20.0,
         "part_number": "GG-40-001", "revision": "B", "material": "42CrMo4 (1.7225)",
         "heat_treatment": "quenched and tempered", "hardness_HRC": 30, "flank_roughness_Ra_um": 0.8,
         "bore_fit": "H7", "tip_diameter_tolerance": "h9", "face_width_upper_deviation_mm": 0.0,
         "face_width_lower_deviation_mm": -0.05, "thickness_allowance_series": "cd26", "accuracy_grade": 6}


def cell_texts(svg_path):
    """{cell (x0, y0, x1, y1) mm: [its texts, top to bottom]} of the SVG."""
    out = {}
    for g in ET.parse(svg_path).getroot().iter(f"{SVG}g"):
        cell = parse_cell_gid(g.get("id"))
        if cell is not None:
            out.setdefault(cell, []).extend("".join(t.itertext()) for t in g.iter(f"{SVG}text"))
    return out


def table_rows(cells, box):
    """{name: value} of a table in ``box``: the cells in it grouped by row, first column the name,
    last the value, wrapped lines joined with spaces."""
    rows = {}
    inside = {c: t for c, t in cells.items() if box[0] - 1e-3 <= c[0] and c[2] <= box[2] + 1e-3
              and box[1] - 1e-3 <= c[1] and c[3] <= box[3] + 1e-3}
    for c, texts in inside.items():
        if abs(c[0] - box[0]) < 1e-3:
            value = next((" ".join(t) for cc, t in inside.items() if abs(cc[2] - box[2]) < 1e-3 and cc[1] == c[1]
                          and cc[3] == c[3]), "")
            rows[" ".join(texts)] = value
    return rows


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
    # ISO/TR 10064-3 axial runout of face B: 0.2 (d_f / b) F_beta
    geo = data["datum_tolerances"]
    assert geo["face_axial_runout_um"] == pytest.approx(0.2 * 2 * data["root_radius"] / 12.0
                                                        * data["accuracy"]["helix_total_um"], rel=1e-12)


def test_the_sheet_reads_back_the_jsons_values(drawn):
    _, data, files = drawn
    cells = cell_texts(files["svg"])
    blank = table_rows(cells, BLANK_BLOCK)
    main = table_rows(cells, DATA_BLOCK)
    assert blank["Bore"] == "20.0000 mm H7"
    lo, hi = data["bore"]["limits"]
    assert blank["Bore limits"] == f"{hi:.4f} / {lo:.4f} mm (max / min)"
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
    assert blank["Axial runout of B"] == f"{t_b * 1e-3:.4f} mm ({t_b:.1f} µm), to datum A"
    assert main["Tooth thickness allowance, upper"] == "-0.0540 mm (-54.0 µm)"
    assert main["Tooth thickness allowance, lower"] == "-0.1040 mm (-104.0 µm)"
    assert main["Allowance method"].startswith("DIN 3967:1978-08 cd26 (Tables 1 and 2)")
    lo, hi = data["span"]["limits"]
    assert main["Span limits"] == f"{hi:.4f} / {lo:.4f} mm (max / min)"
    assert main["Pin diameter"] == f"{data['over_pins']['diameter']:.4f} mm"
    assert blank["Pin series"] == data["over_pins"]["series"]
    assert main["Runout tolerance"].endswith(", to datum A")
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
