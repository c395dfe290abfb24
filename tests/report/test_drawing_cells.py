"""Every text of the gear drawing stays inside its cell (geargen.report.drawing).

Each text drawn in a table (data block, blank table, title block) carries its cell in its SVG group
id (``cell-<n>-x0_y0_x1_y1``, sheet mm, y up). Two independent measurements of the drawn text:

- the sheet's record: each text's box as laid out by the drawing font's advance widths, ascent and
  descent (what the layout wrapped against);
- headless Chromium: the SVG opened in a page whose script maps each text's getBBox through its
  getCTM into the sheet and writes the boxes into the DOM (--dump-dom); Chromium lays the text out
  with its own font engine, so a wrap that fits only the sheet's own metrics is caught here.

The sheets: a metric helical pinion with every drawing key given and the accuracy grade the error
budget chose (the longest accuracy-grade text), an inch spur gear with only its teeth, and a gear whose
part number, revision, material and heat treatment are each at its length limit in the widest letter.
"""

import html
import json
import math
import re
import subprocess
from pathlib import Path

import pytest

from geargen.design.gear import GearSpec, Hub, ShopData
from geargen.model.gear_data import gear_data
from geargen.profile.tooth import tooth_profile
from geargen.report.drawing import MM_PER_PT, SHEET_MM, draw_gear, parse_cell_gid, write_drawing
from tests.drawing_support import cell_texts, table_rows

#: a text may reach this far (mm) past its cell's line: half the thinnest rule (0.18 mm) drawn on it
SLACK_MM = 0.09


def _full():
    spec = GearSpec(teeth=21, module=0.79375, pressure_angle=math.radians(20), face_width=12.7,
                    helix_angle=math.radians(20), hand="left", profile_shift=0.2,
                    hub=Hub(bore_diameter=6.0, keyway_width=2.0, keyway_depth=1.0), name="pinion_21",
                    shop=ShopData(part_number="GG-2026-0021-PINION-LONG-NUMBER", revision="C",
                                  material="42CrMo4 (1.7225), ISO 683-2",
                                  heat_treatment="quenched and tempered, nitrided",
                                  hardness=(650.0, "HV"), flank_roughness_Ra=0.4e-3, bore_fit="H7",
                                  tip_diameter_class="h9", face_width_deviations=(0.0, -0.05)))
    profile = tooth_profile(spec, warn=False)
    data = gear_data(spec, profile)
    # the accuracy block as the error budget gives it (its longest label)
    data["accuracy"] = {"standard": "ISO 1328-1:2013", "grade": 6, "single_pitch_um": 5.5, "cumulative_pitch_um": 16.0,
                        "profile_total_um": 6.5, "helix_total_um": 9.0, "runout_um": 13.0,
                        "grade_source": "the coarsest grade within the design's error budget"}
    data["mating_gears"] = [{"name": "cluster_large", "teeth": 112, "centre_distance": 52.3456,
                             "centre_distance_tolerance": [-0.005, 0.005]}]
    return spec, profile, data


def _bare():
    spec = GearSpec(teeth=112, module=25.4 / 32, pressure_angle=math.radians(20), face_width=6.35,
                    hub=Hub(bore_diameter=10.0), name="gear_112", length_unit="in")
    profile = tooth_profile(spec, warn=False)
    return spec, profile, gear_data(spec, profile)


def _longest():
    """Every designer's text of the drawing at its length limit, in the widest letter."""
    from geargen.design.gear import DRAWN_TEXT_MAX, gear_from_table
    spec = gear_from_table({"teeth": 40, "module_mm": 1.0, "pressure_angle_deg": 20, "face_width_mm": 12.0,
                            "bore_diameter_mm": 20.0, "bore_fit": "H7",
                            **{key: "—" * n for key, n in DRAWN_TEXT_MAX.items()}}, "gears.wheel", "wheel")
    profile = tooth_profile(spec, warn=False)
    return spec, profile, gear_data(spec, profile)


SOURCE = "gear x from " + "/a/long/path" * 10 + "/design.toml [gear]"


@pytest.mark.parametrize("make", [_full, _bare, _longest])
def test_recorded_text_boxes_lie_inside_their_cells(make):
    spec, profile, data = make()
    sheet = draw_gear(data, profile, SOURCE, "/a/long/path/design.toml", "0.0")
    checked, outside = 0, []
    for text, box, gid in sheet.text_boxes():  # sheet mm, y up from the sheet's bottom
        cell = parse_cell_gid(gid)
        if cell is None:
            continue
        checked += 1
        if not (box[0] >= cell[0] - SLACK_MM and box[2] <= cell[2] + SLACK_MM
                and box[1] >= cell[1] - SLACK_MM and box[3] <= cell[3] + SLACK_MM):
            outside.append((text, [round(v, 2) for v in box], cell))
    assert checked > 100  # the data block, blank table and title block
    assert not outside, outside


_PAGE = """<!DOCTYPE html><html><head><meta charset="utf-8"></head><body style="margin:0">{svg}
<pre id="boxes"></pre><script>
const root = document.querySelector("svg");
const out = [];
for (const t of root.querySelectorAll("text")) {{
  const g = t.closest("[id^='cell-']");
  if (!g) continue;
  const b = t.getBBox(), r = root.getCTM().inverse().multiply(t.getCTM());
  const pts = [[b.x, b.y], [b.x + b.width, b.y], [b.x, b.y + b.height], [b.x + b.width, b.y + b.height]]
    .map(([x, y]) => [r.a * x + r.c * y + r.e, r.b * x + r.d * y + r.f]);
  const xs = pts.map(p => p[0]), ys = pts.map(p => p[1]);
  out.push({{text: t.textContent, id: g.id, x0: Math.min(...xs), y0: Math.min(...ys), x1: Math.max(...xs),
            y1: Math.max(...ys)}});
}}
document.getElementById("boxes").textContent = JSON.stringify(out);
</script></body></html>"""


def _boxes_in_chromium(chromium, svg_path: Path, tmp_path: Path) -> list[dict]:
    svg = svg_path.read_text(encoding="utf-8")
    page = tmp_path / "cells.html"
    page.write_text(_PAGE.format(svg=svg[svg.index("<svg"):]), encoding="utf-8")
    cmd = [chromium, "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-extensions",
           "--disable-background-networking", "--disable-component-update", "--disable-sync",
           f"--user-data-dir={tmp_path / 'profile'}", "--virtual-time-budget=5000", "--dump-dom", page.resolve().as_uri()]
    done = subprocess.run(cmd, capture_output=True, text=True, timeout=120)
    found = re.search(r'<pre id="boxes">(.*?)</pre>', done.stdout, re.S)
    assert found and found.group(1), done.stderr[-2000:]
    return json.loads(html.unescape(found.group(1)))


@pytest.mark.parametrize("make", [_full, _bare, _longest])
def test_in_chromium_every_text_lies_inside_its_cell(make, chromium, tmp_path):
    spec, profile, data = make()
    files = write_drawing(data, profile, tmp_path, spec.name, SOURCE, "/a/long/path/design.toml", "0.0")
    boxes = _boxes_in_chromium(chromium, Path(files["svg"]), tmp_path)
    assert len(boxes) > 100
    outside = []
    for b in boxes:
        x0, y0, x1, y1 = parse_cell_gid(b["id"])
        # the SVG's user unit is the point, y down from the sheet's top; cells are mm, y up
        left, right = b["x0"] * MM_PER_PT, b["x1"] * MM_PER_PT
        bottom, top = SHEET_MM[1] - b["y1"] * MM_PER_PT, SHEET_MM[1] - b["y0"] * MM_PER_PT
        if not (left >= x0 - SLACK_MM and right <= x1 + SLACK_MM and bottom >= y0 - SLACK_MM and top <= y1 + SLACK_MM):
            outside.append((b["text"], round(left - x0, 2), round(x1 - right, 2), round(bottom - y0, 2),
                            round(y1 - top, 2)))
    assert not outside, outside


def test_the_chordal_tooth_stays_on_a_gear_with_three_mates(tmp_path):
    """The full pinion's data block keeps its chordal tooth rows with three mates (before: they gave
    way on a full block; the gear JSON kept them). Read back from the SVG's cells, the rows are the
    JSON's chordal tooth, and every mate's centre distance is there too."""
    from geargen.report.drawing import DATA_BLOCK, format_limits, format_number
    from geargen.core.allowance import ThicknessAllowance
    spec, profile, full = _full()
    # with an allowance: every row the block can have (limits of span, over balls and chordal tooth)
    allowance = ThicknessAllowance(-0.02, -0.045, "entered (--thickness-allowance)", "--thickness-allowance")
    data = gear_data(spec, profile, allowance)
    data["accuracy"] = full["accuracy"]
    data["mating_gears"] = [dict(full["mating_gears"][0], name=f"mate_{i}") for i in range(3)]
    chord = data["chordal_tooth"]
    assert chord["limits"]
    files = write_drawing(data, profile, tmp_path, spec.name, SOURCE, "/a/long/path/design.toml", "0.0")
    rows = table_rows(cell_texts(files["svg"]), DATA_BLOCK)
    u = data["length_unit"]
    assert rows["Chordal tooth thickness / height"] == \
        f"{format_number(chord['thickness_normal'], u)} / {format_number(chord['height'], u)} {u}"
    assert rows["Chordal thickness limits"] == format_limits(chord["limits"], u)
    assert all(f"Centre distance to mate_{i}" in rows for i in range(3))
    assert "Over-balls limits" in rows or "Over-pins limits" in rows
