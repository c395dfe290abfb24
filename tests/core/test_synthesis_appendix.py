"""Every number of the paper's Appendix, from assemblies/robot_joint.toml, through `geargen synth`.

The golden cells (tests/data/appendix_golden.toml) are compared two ways, both through the code
users run: the command's text table must show the printed string in the right row, and the
command's JSON must hold a number that rounds half-up (ties away from zero) to the printed
string at the printed decimals -- e.g. nominal N = 35.17014955 must print 35.1701, not 35.1702.
"""

from __future__ import annotations

import contextlib
import io
import json
import math
import tomllib
from decimal import ROUND_HALF_UP, Decimal
from pathlib import Path

import pytest

from geargen.cli import main
from geargen.commands.synth import compute
from geargen.design.assembly import load_design

ROOT = Path(__file__).resolve().parents[2]
ROBOT = ROOT / "assemblies" / "robot_joint.toml"
DATA = ROOT / "tests" / "data"
GOLDEN = tomllib.loads((DATA / "appendix_golden.toml").read_text())["row"]


def half_up(value: float, printed: str) -> str:
    """``value`` rounded half-up to as many decimals as ``printed`` has."""
    decimals = len(printed.split(".")[1]) if "." in printed else 0
    q = Decimal(value).quantize(Decimal(1).scaleb(-decimals), rounding=ROUND_HALF_UP)
    return f"{abs(q) if q == 0 else q:.{decimals}f}"


def lookup(data, path: str):
    for part in path.split("."):
        data = data[int(part)] if isinstance(data, list) else data[part]
    return data


@pytest.fixture(scope="module")
def cli_output(tmp_path_factory):
    out = tmp_path_factory.mktemp("synth") / "robot_joint.json"
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        assert main(["synth", str(ROBOT), "--json", str(out)]) == 0
    return buf.getvalue(), json.loads(out.read_text())


def test_golden_file_covers_every_appendix_number():
    # 11 rows of four gear cells; 12 two-cell rows (Sum/RSS/mean, six mesh rows, A1 and A2 in rad and deg,
    # minimum-backlash A1); 11 single cells (A1, A2, N, error, x1, y1, x2, y2, C1, x1, Δx1)
    cells = [c for row in GOLDEN for c in row["printed"]]
    assert len(cells) == 11 * 4 + 12 * 2 + 11
    assert all(len(r["printed"]) == len(r["json"]) for r in GOLDEN)


@pytest.mark.parametrize("row", GOLDEN, ids=lambda r: f"{r['label'] or r['unit']}")
def test_json_reproduces_appendix_to_printed_decimals(cli_output, row):
    _, data = cli_output
    for path, printed in zip(row["json"], row["printed"]):
        assert half_up(lookup(data, path), printed) == printed, path


def test_text_table_prints_every_appendix_cell_in_its_row(cli_output):
    text, _ = cli_output
    lines = text.splitlines()
    at = 0
    for row in GOLDEN:
        for k in range(at, len(lines)):
            line = lines[k]
            if line[:20].strip() == row["label"] and line[20:36].strip() == row["unit"]:
                assert line[36:].split()[: len(row["printed"])] == row["printed"], line
                at = k + 1
                break
        else:
            pytest.fail(f"row {row['label']!r} {row['unit']!r} not found after line {at}")


def test_json_follows_the_contract_example(cli_output):
    """Every key of the contract's example is there, each number equal at the example's decimals."""
    _, data = cli_output
    example = json.loads((DATA / "synthesis_contract_example.json").read_text(), parse_float=Decimal)

    def walk(expected, got, where):
        if isinstance(expected, dict):
            assert isinstance(got, dict), where
            for k, v in expected.items():
                assert k in got, f"{where}.{k} missing"
                walk(v, got[k], f"{where}.{k}")
        elif isinstance(expected, list):
            assert isinstance(got, list) and len(got) == len(expected), where
            for i, (e, g) in enumerate(zip(expected, got)):
                walk(e, g, f"{where}.{i}")
        elif isinstance(expected, str):
            assert got == expected, where
        elif isinstance(expected, int):
            assert got == expected and isinstance(got, int), where
        else:
            assert half_up(got, str(expected)) == str(expected), where

    walk(example, data, "")
    assert data["length_unit"] == "in"
    assert data["centres"]["gear1"][1] == 0.0 and data["centres"]["gear4"] == [0.0, 0.0]


def test_numbers_are_computed_not_echoed():
    """The JSON and the in-memory result agree, and the knife-edge N keeps its margins (appendix-notes §5)."""
    run = compute(load_design(ROBOT))
    s = run.synthesis
    assert s.nominal_teeth_count == pytest.approx(35.17014955, abs=2e-9)
    assert s.increments == 70 and s.teeth_count == 35
    assert abs(s.eq7_residual) < 1e-12
    # Eq. 8 with the sheet's signs puts the input on the symmetry line
    assert s.y1 == pytest.approx(-s.y2, abs=1e-12)
    assert math.degrees(s.A1) == pytest.approx(-69.4939, abs=5e-5)
    assert run.budget.factors[3] == pytest.approx(1.7762, abs=5e-5)  # the gear-4 rule, appendix-notes §4


def test_json_to_standard_output_is_pure_json(capsys):
    assert main(["synth", str(ROBOT), "--json", "-"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["solved"]["N"] == 35 and data["schema"] == "geargen.synth/1"
