"""``geargen new KIND FILE.toml [--units in]`` (issues 11, 26): a commented starter design, metric
or inch, that loads, checks and builds; every key commented with its meaning and unit from the
schema; an existing file is never overwritten (exit status 3), and the file appears whole or not
at all.

The numbers the starters' comments claim (spring rate and force, blade stiffness and stress,
the split pinion's preload band) are recomputed here from closed forms and compared with the
stiffness model. The builds are slow (5-20 s each) and run once per kind.
"""

import json
import math
import os
import re
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

from geargen.cli import main
from geargen.commands import new as new_command
from geargen.core.stiffness import stiffness_summary
from geargen.design.assembly import load_design
from geargen.design.schema import key_comment
from geargen.commands.new import STARTERS
from geargen.design.starters import starter_data as data_of, starter_text as text_of
from geargen.design.validate import key_schema

ROOT = Path(__file__).resolve().parents[1]
KINDS = sorted(STARTERS)
#: every starter: (kind, length unit)
VARIANTS = [(kind, units) for kind in KINDS for units in sorted(STARTERS[kind])]


def starter_data(kind: str, name: str, units: str = "mm") -> dict:
    return data_of(STARTERS[kind][units], name)


def starter_text(kind: str, name: str, units: str = "mm") -> str:
    return text_of(STARTERS[kind][units], name)


def _env() -> dict:
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT)] + [p for p in [env.get("PYTHONPATH")] if p])
    env.pop("GEARGEN_DEBUG", None)
    return env


def _new(tmp_path: Path, kind: str, capsys, name: str = "starter") -> Path:
    path = tmp_path / f"{name}.toml"
    assert main(["new", kind, str(path)]) == 0
    assert str(path) in capsys.readouterr().out
    return path


@pytest.fixture(scope="module")
def starters(tmp_path_factory) -> dict:
    """Each starter written once by the command: by kind (metric) and by (kind, units)."""
    folder = tmp_path_factory.mktemp("starters")
    out = {}
    for kind, units in VARIANTS:
        path = folder / f"my_{kind}_{units}.toml"
        assert main(["new", kind, str(path), "--units", units]) == 0
        out[kind, units] = path
        if units == "mm":
            out[kind] = path
    return out


# ------------------------------------------------------------------ what is written

@pytest.mark.parametrize("kind, units", VARIANTS)
def test_starter_reads_back_as_its_data_and_loads(kind, units, starters):
    path = starters[kind, units]
    assert tomllib.loads(path.read_text()) == starter_data(kind, f"my_{kind}_{units}", units)
    design = load_design(path)
    assert design.name == f"my_{kind}_{units}"
    assert design.length_unit == units
    assert design.defaulted == ()  # a starter gives all its hardware
    # metric: module 1 mm; inch: a whole diametral pitch (the robot joint's 32, the split pinion's 20)
    modules = {g.module if units == "mm" else round(25.4 / g.module, 9) for g in design.gears.values()}
    assert modules == ({1.0} if units == "mm" else {32.0} if kind == "dual_pinion" else {20.0})
    assert all(g.length_unit == units for g in design.gears.values())
    if units == "in":
        assert f"`geargen new {kind} --units in`" in path.read_text()


@pytest.mark.parametrize("kind, units", VARIANTS)
def test_every_key_is_commented_with_its_meaning_and_unit(kind, units, starters):
    lines = starters[kind, units].read_text().splitlines()
    data = starter_data(kind, "x", units)
    table: tuple[str, ...] = ()
    seen = 0
    for i, line in enumerate(lines):
        if line.startswith("["):
            table = tuple(line.strip("[]").split("."))
            continue
        m = re.match(r"^([A-Za-z0-9_]+) = ", line)
        if not m:
            continue
        key = m.group(1)
        schema = key_schema(data, table + (key,))
        assert schema is not None and schema.help
        # the comment follows on the line (continued below it), or stands just above a long value
        if " # " in line:
            comment = [line.split(" # ", 1)[1]]
            j = i + 1
            while j < len(lines) and re.match(r"^ {20,}# ", lines[j]):  # continued in its column
                comment.append(lines[j].strip()[2:])
                j += 1
        else:
            j = i - 1
            comment = []
            while lines[j].startswith("# "):
                comment.insert(0, lines[j][2:])
                j -= 1
        text = " ".join(comment)
        assert key_comment(schema, key) in text, f"{'.'.join(table + (key,))}: {text!r}"
        suffix = key[len(schema.name) + 1:]
        if suffix:
            assert text.endswith(f"[{suffix}]")
        seen += 1
    assert seen == sum(1 for _ in _leaves(data))


def _leaves(node):
    for value in node.values():
        if isinstance(value, dict):
            yield from _leaves(value)
        else:
            yield value


@pytest.mark.parametrize("kind, units", VARIANTS)
def test_starter_passes_geargen_check(kind, units, starters, capsys):
    assert main(["check", str(starters[kind, units]), "--json", "-"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result["ok"] and not result["failures"]


def test_dual_pinion_check_numbers_its_comments_quote(starters, capsys):
    assert main(["check", str(starters["dual_pinion"]), "--json", "-"]) == 0
    tolerances = {t["mesh"]: t for t in json.loads(capsys.readouterr().out)["tolerances"]}
    # "(geargen check: 0.05 mm worst case)" of mesh 1; "(geargen check: 0.12 mm worst case)" travel
    assert tolerances["mesh1_a"]["worst_case_min_backlash"] == pytest.approx(0.05, abs=0.005)
    assert tolerances["mesh1_a"]["carriage_travel"] == pytest.approx(0.12, abs=0.005)
    assert tolerances["mesh1_a"]["carriage_travel"] < starter_data("dual_pinion", "x")["flexures"]["travel_mm"]


def test_dual_pinion_preload_hardware_matches_closed_forms(starters):
    data = starter_data("dual_pinion", "x")
    s = stiffness_summary(load_design(starters["dual_pinion"]))
    sp, fl = data["springs"], data["flexures"]
    g, d, mean, coils = sp["shear_modulus_GPa"] * 1e3, sp["wire_diameter_mm"], sp["mean_coil_diameter_mm"], sp["active_coils"]
    rate = g * d ** 4 / (8 * mean ** 3 * coils)  # "2.97 N/mm each"
    assert rate == pytest.approx(2.974, abs=5e-4)
    assert s.spring.rate == pytest.approx(rate, rel=1e-9)
    force = sp["count"] * rate * (sp["free_length_mm"] - sp["installed_length_mm"])  # "2 x 31 N = 62 N"
    assert force == pytest.approx(62.45, abs=0.01)
    assert s.carriage_force == pytest.approx(force, rel=1e-9)
    e, t, length, width = fl["elastic_modulus_GPa"] * 1e3, fl["thickness_mm"], fl["length_mm"], fl["width_mm"]
    blades = fl["count"] * 12 * e * (width * t ** 3 / 12) / length ** 3  # "3 x 12 E I / L^3 = 7.45 N/mm"
    assert blades == pytest.approx(7.452, abs=1e-3)
    assert s.flexure.stiffness_along == pytest.approx(blades, rel=1e-6)
    stress = 3 * e * t * fl["travel_mm"] / length ** 2  # "124 MPa at the clamps"
    assert stress == pytest.approx(124.2, abs=0.05)
    assert s.flexure.stress_at_travel == pytest.approx(stress, rel=1e-6)
    # "about 4 N·m against the 3.5 N·m (half the maximum load)"
    assert s.required_preload == pytest.approx(3500.0)
    assert s.preload_ok and s.drive.preload == pytest.approx(4000.0, rel=0.05)
    assert not s.warnings


def test_split_pinion_preload_band_matches_closed_forms(starters):
    """The band the starter's comment claims, from closed forms on the heights the [parts] keys give:
    meshes (Eq. 1), the shafts in torsion, each pinion on its shaft and supports (a beam on elastic
    supports by superposition; the compliant pinion's lower support is the collar on the hollow
    shaft's overhung end)."""
    from geargen.drives.resolver import resolve
    from geargen.model.analysis import stiffness

    data = starter_data("split_pinion", "x")
    design = load_design(starters["split_pinion"])
    s, _ = stiffness(design, resolve(design))
    comp, parts, gears = data["stiffness"]["components"], data["parts"], data["gears"]
    g, e = 79.3e3, 207e3
    base_radius = 96 * 1.0 / 2 * math.cos(math.radians(20))
    pinion_base = 24 * 1.0 / 2 * math.cos(math.radians(20))
    ratio = 4.0
    kb = comp["stiff_support"]["stiffness_N_per_um"] * 1e3

    def polar(d, bore=0.0):
        return math.pi * (d ** 4 - bore ** 4) / 32

    def mesh(width):  # Eq. 1: E w / 11 along the line of action, at the output's base radius
        return e * width / 11 * base_radius ** 2

    def series(*k):
        return 1 / sum(1 / x for x in k)

    # heights (mm): the stiff pinion's face from 0, the gap, the compliant pinion; the output spans both
    gap = parts["bearing_clearance_mm"]
    w_stiff, w_compl = gears["pinion_stiff"]["face_width_mm"], gears["pinion_compliant"]["face_width_mm"]
    z_compl0 = w_stiff + data["layout"]["pinion_axial_gap_mm"]
    z_top = max(z_compl0 + w_compl, gears["output"]["face_width_mm"]) + gap
    upper = -gap - parts["bearing_width_mm"] / 2  # the pair's bearing centres
    lower = upper - parts["bearing_spacing_mm"]
    z_hollow0 = w_stiff - parts["hollow_shaft_length_mm"]
    collar = z_hollow0 - parts["collar_width_mm"] / 2
    outboard = z_top + parts["compliant_bearing_width_mm"] / 2
    d_in = gears["pinion_compliant"]["bore_diameter_mm"]
    d_h, bore_h = parts["hollow_shaft_outer_diameter_mm"], d_in + 2 * gap
    ei_h = e * math.pi * (d_h ** 4 - bore_h ** 4) / 64
    ei_in = e * math.pi * d_in ** 4 / 64

    def overhung(ei, span, c, k1, k2):  # c beyond the support at span: beam plus both supports' levers
        return c * c * (span + c) / (3 * ei) + ((c / span) ** 2) / k1 + (((span + c) / span) ** 2) / k2

    span_h = upper - lower
    stiff_support = 1 / overhung(ei_h, span_h, w_stiff / 2 - upper, kb, kb)
    collar_k = 1 / overhung(ei_h, span_h, lower - collar, kb, kb)  # overhung below the lower bearing
    a, b = z_compl0 + w_compl / 2 - collar, outboard - (z_compl0 + w_compl / 2)
    L = a + b
    compl_support = 1 / (a * a * b * b / (3 * ei_in * L) + (b / L) ** 2 / collar_k + (a / L) ** 2 / kb)

    def at_output(linear):  # a linear stiffness at the pinion's base radius, referred to the output
        return linear * pinion_base ** 2 * ratio ** 2

    # the hollow shaft twists from its lower end (the drive) to the stiff pinion's mid-face
    path1 = series(mesh(w_stiff), g * polar(d_h, bore_h) / (w_stiff / 2 - z_hollow0) * ratio ** 2,
                   at_output(stiff_support))
    twist = z_compl0 - z_hollow0  # collar face to the compliant pinion's face
    assert twist == pytest.approx(60.0)  # the starter's comment
    path2 = series(mesh(w_compl), g * polar(d_in) / twist * ratio ** 2, at_output(compl_support))
    loop = series(path1, path2)  # Eq. 3
    assert s.loop_stiffness == pytest.approx(loop, rel=1e-6)
    band = loop * data["preload"]["loop_error_rotation_urad"] * 1e-6
    preload = data["preload"]["preload_Nm"] * 1e3
    # "geargen stiffness shows the band: 8.5 to 9.5 N·m (12 %)"
    assert (preload - band / 2, preload + band / 2) == pytest.approx((8.452e3, 9.548e3), abs=1.0)
    assert (s.headline.low, s.headline.high) == pytest.approx((preload - band / 2, preload + band / 2), rel=1e-9)
    assert s.preload_ok and not s.warnings


@pytest.mark.slow
@pytest.mark.parametrize("kind, units", VARIANTS)
def test_starter_builds(kind, units, tmp_path):
    path = tmp_path / f"{kind}.toml"
    cli = [sys.executable, "-m", "geargen.cli"]
    subprocess.run(cli + ["new", kind, str(path), "--units", units], env=_env(), check=True, capture_output=True)
    run = subprocess.run(cli + ["build", str(path), "--out", str(tmp_path / "out"), "--quiet"], env=_env(),
                         capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr
    manifest = json.loads((tmp_path / "out" / "manifest.json").read_text())
    assert manifest["generator"] == "geargen build"
    assert "**Status: PASS**" in (tmp_path / "out" / "report.md").read_text()
    gears = set(starter_data(kind, kind, units)["gears"])
    assert all(any(f.startswith(g) and f.endswith(".step") for f in manifest["files"]) for g in gears)


# ------------------------------------------------------------------ never a lost file

def test_an_existing_file_is_refused_and_left_alone(tmp_path, capsys):
    path = tmp_path / "mine.toml"
    path.write_text("# my notes\n")
    assert main(["new", "dual_pinion", str(path)]) == 3
    err = capsys.readouterr().err
    assert f"geargen new: error: {path}: exists" in err and "Traceback" not in err
    assert path.read_text() == "# my notes\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["mine.toml"]


def test_a_folder_of_that_name_is_refused(tmp_path, capsys):
    (tmp_path / "d.toml").mkdir()
    assert main(["new", "split_pinion", str(tmp_path / "d.toml")]) == 3
    assert "exists" in capsys.readouterr().err


def test_a_file_appearing_while_writing_is_not_replaced(tmp_path, monkeypatch, capsys):
    path = tmp_path / "race.toml"

    def link(src, dst):  # another process creates the file between the check and the link
        Path(dst).write_text("theirs\n")
        raise FileExistsError(17, "File exists", str(dst))

    monkeypatch.setattr(new_command.os, "link", link)
    assert main(["new", "dual_pinion", str(path)]) == 3
    assert path.read_text() == "theirs\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["race.toml"]  # no temporary file left
    assert "exists" in capsys.readouterr().err


def test_missing_folders_are_created_and_no_temporary_is_left(tmp_path, capsys):
    path = _new(tmp_path / "a" / "b", "split_pinion", capsys)
    assert sorted(p.name for p in path.parent.iterdir()) == ["starter.toml"]
    assert path.read_text() == starter_text("split_pinion", "starter")
    assert (path.stat().st_mode & 0o777) == (0o666 & ~_umask())


def _umask() -> int:
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


@pytest.mark.skipif(hasattr(os, "geteuid") and os.geteuid() == 0, reason="root writes anywhere")
def test_an_unwritable_folder_is_an_environment_problem(tmp_path, capsys):
    folder = tmp_path / "ro"
    folder.mkdir()
    folder.chmod(0o555)
    try:
        assert main(["new", "dual_pinion", str(folder / "x.toml")]) == 3
    finally:
        folder.chmod(0o755)
    assert "cannot write" in capsys.readouterr().err
    assert list(folder.iterdir()) == []


def test_a_refused_temporary_file_is_an_environment_problem(tmp_path, monkeypatch, capsys):
    def refuse(**kw):
        raise PermissionError(13, "Permission denied")

    monkeypatch.setattr(new_command.tempfile, "mkstemp", refuse)
    assert main(["new", "dual_pinion", str(tmp_path / "x.toml")]) == 3
    assert f"{tmp_path / 'x.toml'}: cannot write in {tmp_path}: Permission denied" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("file, text", [
    ("joint.txt", "FILE: 'joint.txt' is not a .toml file name"),
    (".toml", "FILE: '.toml' is not a .toml file name"),
])
def test_a_file_name_that_is_not_a_design_file_is_bad_input(tmp_path, capsys, monkeypatch, file, text):
    monkeypatch.chdir(tmp_path)
    assert main(["new", "dual_pinion", file]) == 2
    assert text in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


def test_an_unknown_kind_is_bad_input(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(SystemExit) as info:
        main(["new", "planetary", "x.toml"])
    assert info.value.code == 2
    assert "invalid choice: 'planetary'" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


def test_the_command_is_listed_in_help(capsys):
    with pytest.raises(SystemExit):
        main(["--help"])
    assert "new" in capsys.readouterr().out
