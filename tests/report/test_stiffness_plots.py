"""``geargen stiffness`` on the robot joint: the printed summary, the JSON, and the three PNGs; the
plots of a type 1 design; how the command picks up the synthesis error budget."""

import dataclasses
import json
import sys
import types
from pathlib import Path

import numpy as np
import pytest

from geargen.cli import main
from geargen.commands import stiffness as cmd
from geargen.core.stiffness import stiffness_summary
from geargen.design.assembly import design_from_dict, load_design
from geargen.report.stiffness import (format_summary, preload_band_figure, preload_diagram_figure,
                                      torque_deflection_figure, write_stiffness_plots)

ROBOT = Path(__file__).resolve().parents[2] / "assemblies" / "robot_joint.toml"
IN = 25.4



def _summary(design, travels=None):
    """The stiffness summary as the commands compute it: from-geometry components sized by the
    resolved drive's placed shafts (geargen.model.analysis)."""
    from geargen.drives.resolver import resolve
    from geargen.model.analysis import placed_components
    return stiffness_summary(design, travels, components=placed_components(design, resolve(design)))

def _assert_real_png(path: Path):
    """A PNG that decodes, is a sensible size and carries a drawing, not a blank canvas."""
    import matplotlib.image as mpimg

    assert path.is_file() and path.stat().st_size > 15_000, path
    img = mpimg.imread(path)
    assert img.ndim == 3 and img.shape[0] >= 400 and img.shape[1] >= 600
    rgb = img[..., :3]
    ink = np.mean(np.any(rgb < 0.9, axis=-1))
    assert 0.02 < ink < 0.6, f"{path.name}: {ink:.3f} of the pixels are drawn"
    packed = (rgb * 255).astype(np.uint32) @ np.array([65536, 256, 1], dtype=np.uint32)
    assert len(np.unique(packed)) > 30  # lines in several colours, text, grid, shading


def test_robot_joint_command_prints_summary_writes_plots_and_json(tmp_path, capsys, monkeypatch):
    budget = {"sum": 0.0121648 * IN, "rss": 0.0068853 * IN, "mean": 0.00952505 * IN}
    import geargen.model.analysis as analysis
    monkeypatch.setattr(analysis, "loop_error_travels", lambda layout: (budget, "test budget"))
    out, js = tmp_path / "plots", tmp_path / "summary.json"
    assert main(["stiffness", str(ROBOT), "--out", str(out), "--json", str(js)]) == 0
    text = capsys.readouterr().out

    summary = _summary(load_design(ROBOT), budget)
    d = summary.drive
    for needle in ("path 1 = path 2", "k_D (Eq. 5", "k_L (Eq. 6)", "k3, preload spring", "Preload variation",
                   "test budget", "Blade flexures", "Compression springs", "No warnings."):
        assert needle in text, needle
    assert f"{d.k1 * 1e-3:.6g}" in text  # path stiffness, N·m/rad
    assert f"{d.drive_stiffness * 1e-3:.6g} N·m/rad" in text
    assert f"{d.preload * 1e-3:.4g} N·m from springs" in text
    for v in summary.variations:
        assert f"{v.low * 1e-3:.4g} .. {v.high * 1e-3:<7.4g} N·m" in text

    data = json.loads(js.read_text())
    assert data["k1_Nm_per_rad"] == pytest.approx(d.k1 * 1e-3, rel=1e-12)
    assert data["k3_Nm_per_rad"] == pytest.approx(d.k3 * 1e-3, rel=1e-12)
    assert data["preload_Nm"] == pytest.approx(d.preload * 1e-3, rel=1e-12)
    assert data["loop"]["stiffness_Nm_per_rad"] == pytest.approx(d.loop_stiffness * 1e-3, rel=1e-12)
    assert [v["label"] for v in data["preload_variation"]] == ["sum", "rss", "mean"]
    assert data["headline_budget"] == "mean" and data["loop_error_source"] == "test budget"

    names = {"preload_diagram", "torque_deflection", "preload_band"}
    assert set(data["plots"]) == names
    for name in names:
        _assert_real_png(out / f"robot_joint_{name}.png")


def _artist(fig, gid, ax_index=0):
    ax = fig.axes[ax_index]
    found = [a for a in ax.lines + ax.collections if a.get_gid() == gid]
    assert len(found) == 1, f"no single artist {gid!r}"
    return found[0]


def test_what_the_figures_draw_is_the_model():
    budget = {"sum": 0.0121648 * IN, "rss": 0.0068853 * IN, "mean": 0.00952505 * IN}
    s = _summary(load_design(ROBOT), budget)
    d = s.drive
    # preload diagram: the two path lines cross at the preload point, with the paths' rates
    fig = preload_diagram_figure(s)
    x1, y1 = (np.asarray(a) for a in _artist(fig, "path1").get_data())
    x2, y2 = (np.asarray(a) for a in _artist(fig, "path2").get_data())
    assert np.interp(0.0, x1, y1) == pytest.approx(d.preload * 1e-3, rel=1e-9)
    assert np.interp(0.0, x2, y2) == pytest.approx(d.preload * 1e-3, rel=1e-9)
    g1, g2 = d.path_force_rates
    small = 0.5 * d.unloading_rotations[1] * 1e6
    assert (np.interp(small, x1, y1) - np.interp(-small, x1, y1)) / (2 * small * 1e-6) == pytest.approx(g1 * 1e-3, rel=1e-6)
    assert (np.interp(-small, x2, y2) - np.interp(small, x2, y2)) / (2 * small * 1e-6) == pytest.approx(g2 * 1e-3, rel=1e-6)
    # the drive-load bar spans exactly the maximum drive torque between the lines
    (seg,) = _artist(fig, "drive_load").get_segments()
    assert abs(seg[1][1] - seg[0][1]) == pytest.approx(s.max_output_torque * 1e-3, rel=1e-9)
    assert seg[0][0] * 1e-6 == pytest.approx(float(d.rotation(s.max_output_torque)), rel=1e-9)
    # torque-deflection: the drawn curve is the piecewise law, in both panels
    fig = torque_deflection_figure(s)
    for i in (0, 1):
        rot, torque = (np.asarray(a) for a in _artist(fig, "drive", i).get_data())
        assert np.allclose(torque * 1e3, d.torque(rot * 1e-6), rtol=1e-9, atol=1e-9)
    # preload band: slope k_L * 2 lambda against carriage travel (in inches: the robot joint's unit);
    # each budget's band ends on the line
    fig = preload_band_figure(s)
    xs, ps = (np.asarray(a) for a in _artist(fig, "preload").get_data())
    slope = (ps[-1] - ps[0]) * 1e3 / ((xs[-1] - xs[0]) * IN)
    assert slope == pytest.approx(s.loop_stiffness * 2 * s.lever, rel=1e-9)
    for v in s.variations:
        bx, by = (np.asarray(a) for a in _artist(fig, f"band_{v.label}").get_data())
        assert by * 1e3 == pytest.approx([v.low, v.high], rel=1e-12)
        assert bx * IN == pytest.approx([-v.carriage_travel / 2, v.carriage_travel / 2], rel=1e-12)


def test_json_to_standard_output_keeps_it_parseable(tmp_path, capsys, monkeypatch):
    import geargen.model.analysis as analysis
    monkeypatch.setattr(analysis, "loop_error_travels", lambda layout: (None, "design"))
    assert main(["stiffness", str(ROBOT), "--json", "-", "--no-plots"]) == 0
    captured = capsys.readouterr()
    data = json.loads(captured.out)
    assert data["preload_variation"][0]["label"] == "design" and "plots" not in data
    assert "k_D (Eq. 5" in captured.err


def test_type1_plots_and_summary(tmp_path):
    design = design_from_dict({
        "name": "split",
        "drive": {"type": "type1", "preload": "frictional_interface"},
        "gear_defaults": {"module_mm": 1.0, "pressure_angle_deg": 20},
        "gears": {"outer": {"teeth": 20, "face_width_mm": 12}, "inner": {"teeth": 20, "face_width_mm": 6},
                  "out_a": {"teeth": 80, "face_width_mm": 12}, "out_b": {"teeth": 80, "face_width_mm": 6}},
        "stiffness": {"train": "custom", "components": {
            "mesh_outer": {"kind": "mesh", "gears": ["outer", "out_a"], "ratio": 1.0, "scope": "path1"},
            "mesh_inner": {"kind": "mesh", "gears": ["inner", "out_b"], "ratio": 1.0, "scope": "path2"},
            "inner_shaft": {"kind": "shaft_torsion", "ratio": 4.0, "diameter_mm": 4, "length_mm": 60,
                            "scope": "path2"}}},
        "preload": {"max_output_torque_Nm": 20.0, "preload_Nm": 21.0, "loop_error_rotation_urad": 300.0,
                    "path_backlash_urad": 150.0}})
    s = stiffness_summary(design)
    text = format_summary(s)
    assert "k_D (Eq. 2" in text and "k_L (Eq. 3)" in text and "the loaded path alone" in text
    assert "path 1" in text and "path 2" in text and "path 1 = path 2" not in text
    written = write_stiffness_plots(s, tmp_path)
    assert set(written) == {"preload_diagram", "torque_deflection", "preload_band"}
    for p in written.values():
        _assert_real_png(p)


def test_no_loop_error_means_no_band_plot(tmp_path):
    design = load_design(ROBOT)
    sections = dict(design.sections)
    sections["preload"] = {k: v for k, v in sections["preload"].items() if not k.startswith("loop_error")}
    gears = {n: {"teeth": g.teeth, "diametral_pitch_per_in": 32, "pressure_angle_deg": 20,
                 "face_width_mm": g.face_width, "bore_diameter_mm": g.hub.bore_diameter} for n, g in design.gears.items()}
    bare = design_from_dict({"name": "rj", "length_unit": "in", "drive": {"type": "type2", "preload": "radial"},
                             "gears": gears, **sections})
    s = _summary(bare)
    assert s.variations == ()
    assert set(write_stiffness_plots(s, tmp_path)) == {"preload_diagram", "torque_deflection"}
    assert "no loop error given" in format_summary(s)


# --- where the loop error comes from ---------------------------------------------------------------

def test_loop_error_falls_back_to_preload_section_without_synthesis():
    design = load_design(ROBOT)
    bare = dataclasses.replace(design, sections={k: v for k, v in design.sections.items()
                                                 if k not in ("synthesis", "layout")})
    from geargen.model import is_drive
    from geargen.model.analysis import loop_error_travels
    assert not is_drive(bare)  # no [layout] either: nothing to resolve, the [preload] loop error stands
    travels, note = loop_error_travels(None)
    assert travels is None and "[preload]" in note


def test_synthesis_budget_is_the_appendix_travel():
    from geargen.drives.resolver import resolve
    from geargen.model.analysis import loop_error_travels
    travels, note = loop_error_travels(resolve(load_design(ROBOT)))
    assert "synthesis error budget" in note
    # the Appendix's Sum and RSS of the carriage travel, in inches
    assert travels["sum"] / IN == pytest.approx(0.0122, abs=5e-5)
    assert travels["rss"] / IN == pytest.approx(0.0069, abs=5e-5)
    assert travels["mean"] == pytest.approx((travels["sum"] + travels["rss"]) / 2, rel=1e-12)


def test_stiffness_ratio_names_the_equations_of_its_drive_type():
    """Eq. 4 is the type 1 ratio (Eq. 2 / Eq. 3); a type 2 drive's is Eq. 5 / Eq. 6 (it printed
    "Eq. 4 for type 1" beside the type 2 number)."""
    text = format_summary(_summary(load_design(ROBOT)))
    line = next(x for x in text.splitlines() if "k_D / k_L" in x)
    assert "(Eq. 5 / Eq. 6)" in line and "Eq. 4" not in line
