"""The part that is cut is the part that is drawn (issue 27, must show): every gear of every shipped
design that builds, its exported STEP and DXF measured on their own sections, lies inside its own
drawing's span and over-pins (balls) limits, and the drawing's numbers are the gear JSON's.

STEP: the placed part read back (``BuiltAssemblies.step``), moved back into its own frame by the
inverse of the manifest's placement and cut at the middle of its face (:func:`geargen.cad.measure.section`).
DXF: its outline entities (arcs, cubic splines, evaluated by ezdxf) as a section at z = 0. Both are
measured by :func:`geargen.cad.measure.span_on_section` and :func:`over_balls_on_section` with k and
the pin (ball) diameter the gear JSON states, and compared with the JSON's limits, which are
:func:`geargen.core.allowance.span_limits` and :func:`over_pins_limits` of the drive's allowance
(checked here too). The drawing's text (SVG) is read back and its numbers compared with the JSON's.
"""

import json
import math
import re

import numpy as np
import pytest

from geargen.cad.assembly import location
from geargen.cad.measure import Section, over_balls_on_section, section, span_on_section
from geargen.core.allowance import over_pins_limits, span_limits
from geargen.design.assembly import load_design
from geargen.design.gear import GearSpec
from geargen.drives.resolver import resolve
from geargen.model.allowance import drive_allowances
from geargen.profile.tooth import tooth_profile
from geargen.report.drawing import DATA_BLOCK
from geargen.units import LENGTH_SUFFIXES
from tests.conftest import ASSEMBLY_DESIGNS
from tests.drawing_support import cell_texts, table_rows

pytestmark = pytest.mark.slow

#: the shipped designs that build (assemblies/dual_motor.toml is a [dual_motor] study, no drive)
BUILDABLE = [name for name in ASSEMBLY_DESIGNS if name != "gears_only"]

#: the toothed parts that get no tooth-thickness allowance, and why: the rack states none (a rack's
#: thickness is its own family's data), and the rack pinion's only mesh is with the rack; the ring's
#: planet-ring mesh is checked on the placed outlines (its spaces are widened for the sun-planet backlash)
WITHOUT_ALLOWANCE = {"rack_drive": {"rack", "pinion"}, "planetary_dual_pinion": {"ring"}}

#: the exported solid's flanks lie within 0.02 um of the involute and the section is solved to ~1e-15 mm,
#: the DXF's splines within 0.01 um: measured and nominal (the JSON's, of the model's gear) agree to 0.1 um
AGREE_MM = 1e-4


class DxfCurve:
    """One outline entity of a DXF as a section curve (``point(t)``, mm): an ARC by its angle, a
    SPLINE by its own parameter."""

    def __init__(self, entity, scale: float):
        self.scale = scale
        if entity.dxftype() == "ARC":
            self.arc = (np.array(entity.dxf.center)[:2], entity.dxf.radius)
            a0, a1 = math.radians(entity.dxf.start_angle), math.radians(entity.dxf.end_angle)
            self.t0, self.t1 = a0, a1 if a1 > a0 else a1 + 2 * math.pi  # DXF arcs run counter-clockwise
        else:
            self.arc = None
            self.tool = entity.construction_tool()
            knots = self.tool.knots()
            self.t0, self.t1 = knots[0], knots[-1]

    def point(self, t: float):
        t = min(max(float(t), self.t0), self.t1)
        if self.arc is not None:
            (cx, cy), r = self.arc
            return np.array([cx + r * math.cos(t), cy + r * math.sin(t)]) * self.scale
        p = self.tool.point(t)
        return np.array([p.x, p.y]) * self.scale


def dxf_section(path, unit: str, samples: int = 64) -> Section:
    """The DXF's ``GEAR_OUTLINE`` layer as the section at z = 0 (mm)."""
    import ezdxf
    curves, points, index, params = [], [], [], []
    for entity in ezdxf.readfile(path).modelspace():
        if entity.dxf.layer != "GEAR_OUTLINE":
            continue
        curve = DxfCurve(entity, LENGTH_SUFFIXES[unit])
        t = np.linspace(curve.t0, curve.t1, samples)
        points.append(np.array([curve.point(x) for x in t]))
        params.append(t)
        index.append(np.full(samples, len(curves)))
        curves.append(curve)
    return Section(0.0, curves, np.concatenate(points), np.concatenate(index), np.concatenate(params))


def printed_equal(text: str, values: list[float]) -> None:
    """The numbers printed in ``text`` are ``values`` rounded as printed (half a unit of the last digit)."""
    printed = re.findall(r"[-+]?\d+\.\d+", text)
    assert len(printed) >= len(values), text
    for p, v in zip(printed, values):
        decimals = len(p.split(".")[1])
        assert abs(float(p) - v) <= 0.5 * 10 ** -decimals + 1e-12, (text, values)


def check_drawing(folder, data: dict, unit: str) -> None:
    """The drawing's allowance, thinning, span and over-pins numbers are the gear JSON's."""
    # the data block's rows read by their cells (a label may wrap to two lines)
    rows = table_rows(cell_texts(folder / "drawings" / f"{data['name']}-drawing.svg"), DATA_BLOCK)
    allowance = data["thickness_allowance"]
    k = LENGTH_SUFFIXES[unit]
    for side in ("upper", "lower"):
        um = allowance[f"{side}_um"]
        # a metric sheet prints the um beside the mm; an inch sheet inches only
        printed_equal(rows[f"Tooth thickness allowance, {side}"], [um * 1e-3 / k, um] if unit == "mm" else [um * 1e-3 / k])
    printed_equal(rows["Thinning in the model (circumferential)"], [data["thinning_circumferential"]])
    span = data["span"]
    if span:
        printed_equal(rows[f"Span over k = {span['teeth_spanned']} teeth"], [span["span_normal"]])
        printed_equal(rows["Span limits"], span["limits"][::-1])  # printed max / min
    pins = data["over_pins"]
    kind = pins["kind"]
    printed_equal(rows[f"{kind[:-1].capitalize()} diameter"], [pins["diameter"]])
    printed_equal(rows[f"Dimension over {kind}"], [pins["dimension"]])
    printed_equal(rows[f"Over-{kind} limits"], pins["limits"][::-1])


def measure(shape, cut, spec: GearSpec, data: dict, z: float) -> dict[str, float]:
    """Span (normal) and size over pins (balls) measured on ``cut`` (mm), with the JSON's k and
    diameter; both contacts on the involute."""
    profile = tooth_profile(spec, warn=False)
    k = LENGTH_SUFFIXES[spec.length_unit]
    out = {}
    if data["span"]:
        s = span_on_section(shape, profile, data["span"]["teeth_spanned"], z, cut=cut)
        assert s.on_involute
        out["span"] = s.normal
    b = over_balls_on_section(shape, profile, data["over_pins"]["diameter"] * k, z, cut=cut)
    assert b.on_involute
    out["over_pins"] = b.size
    return out


@pytest.mark.parametrize("name", BUILDABLE)
def test_exported_gears_measure_inside_their_drawings_limits(name, built_assemblies):
    folder = built_assemblies[name]
    layout = resolve(load_design(ASSEMBLY_DESIGNS[name]))
    unit = layout.design.length_unit
    k = LENGTH_SUFFIXES[unit]
    allowances = drive_allowances(layout, strict=False)
    matrices = {part: np.array(v["placement_matrix_mm"])
                for part, v in json.loads((folder / "manifest.json").read_text())["parts"].items()}
    without, drawn, report = set(), set(), []
    for placed in layout.gears:
        for spec in placed.gears:
            data = json.loads((folder / "drawings" / f"{spec.name}.json").read_text())
            if not isinstance(spec, GearSpec) or data.get("thickness_allowance") is None:
                # a rack is measured by its own sheet (tests/report/test_family_sheets.py)
                without.add(spec.name)
                continue
            assert spec.name in allowances
            limits = {key: np.array(data[key]["limits"]) * k for key in ("span", "over_pins") if data[key]}
            nominal = {key: data[key]["span_normal" if key == "span" else "dimension"] * k for key in limits}
            # the JSON's limits are the allowance's (the JSON's k and pin diameter, the modelled gear)
            if "span" in limits:
                assert limits["span"] == pytest.approx(
                    span_limits(spec, allowances[spec.name], data["span"]["teeth_spanned"]), abs=1e-9)
            assert limits["over_pins"] == pytest.approx(
                over_pins_limits(spec, allowances[spec.name], data["over_pins"]["diameter"] * k), abs=1e-9)
            cuts = []
            if spec.name not in drawn:  # one drawing and DXF per gear (two clusters share theirs)
                drawn.add(spec.name)
                check_drawing(folder, data, unit)
                cuts.append(("DXF", None, dxf_section(folder / "drawings" / f"{spec.name}.dxf", unit), 0.0))
            # the placed part back in its own frame, cut at the middle of this gear's face
            own = built_assemblies.step(name, placed.name).shape.Moved(location(np.linalg.inv(matrices[placed.name])))
            z = placed.face_z(spec)[0] - placed.z + spec.face_width / 2
            cuts.append(("STEP", own, section(own, z, 128), z))
            for source, shape, cut, z_cut in cuts:
                got = measure(shape, cut, spec, data, z_cut)
                for key, value in got.items():
                    lo, hi = limits[key]
                    report.append(f"{placed.name} {source} {key} {value / k:.6f} in [{lo / k:.6f}, {hi / k:.6f}]")
                    assert lo <= value <= hi, report[-1]
                    assert value == pytest.approx(nominal[key], abs=AGREE_MM), report[-1]
    assert without == WITHOUT_ALLOWANCE.get(name, set())
    assert drawn, "no gear measured"
