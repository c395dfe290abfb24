"""bench/bench_families.py compares like with like: each peer builds the case geargen builds.

The peers' side (bench/peers/make_peer_family.py) runs in another venv and cannot import the
cases, so their numbers are kept in step by hand; this test reads both files (no kernel, no
peer library: both import their CAD libraries lazily) and holds every peer's parameters to the
geargen table of the same case.
"""

import importlib.util
import math
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _load(path: Path):
    spec = importlib.util.spec_from_file_location(path.stem, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[path.stem] = module  # dataclasses look their module up there
    spec.loader.exec_module(module)
    return module


bench = _load(ROOT / "bench" / "bench_families.py")
peers = _load(ROOT / "bench" / "peers" / "make_peer_family.py")

# peer parameter -> the design-table keys that give it (first found wins)
TABLE_KEYS = {"teeth": ("teeth", "wheel_teeth"), "mate_teeth": ("mate_teeth",),
              "face": ("face_width_mm", "wheel_face_width_mm"), "length": ("length_mm", "worm_face_length_mm"),
              "helix_deg": ("helix_angle_deg",), "starts": ("starts",), "q": ("diameter_quotient",),
              "wheel_teeth": ("wheel_teeth",)}
# peer parameters a table does not state: the peer's own switches or its pair's data
PEER_ONLY = {"herringbone", "shaft_deg"}


def table_value(table: dict, name: str):
    if name == "module":
        if "module_mm" in table:
            return table["module_mm"]
        return 25.4 / table["diametral_pitch_per_in"]  # DP: teeth per inch of pitch diameter
    if name == "helix_deg":
        return table.get("helix_angle_deg", 0.0)
    for key in TABLE_KEYS[name]:
        if key in table:
            return table[key]
    raise KeyError(name)


def test_the_same_cases_and_peers_on_both_sides():
    ours = {(c.name, p) for c in bench.CASES for p in c.peers}
    theirs = {(case, p) for case, by_peer in peers.PEERS.items() for p in by_peer}
    assert ours == theirs


@pytest.mark.parametrize("case", [c for c in bench.CASES if c.peers], ids=lambda c: c.name)
def test_peers_build_the_case_geargen_builds(case):
    for peer, (_, params) in peers.PEERS[case.name].items():
        for name, value in params.items():
            if name in PEER_ONLY:
                continue
            assert math.isclose(value, table_value(case.table, name), rel_tol=1e-12), (peer, name)
        # and every dimension the table states reaches the peer (none silently left at its default)
        # a worm-gear set's table states both parts; each part's peer takes its own part's dimensions
        stated_names = {"worm": ("module", "length", "starts", "q"),
                        "worm_wheel": ("teeth", "module", "face", "starts", "q")}.get(
            case.table.get("kind"), ("teeth", "mate_teeth", "module", "face", "length", "starts", "q"))
        for name in stated_names:
            try:
                table_value(case.table, name)
            except KeyError:
                continue
            stated = name in params or (name == "teeth" and "wheel_teeth" in params)
            assert stated, (peer, name)
    if case.table.get("kind") == "double_helical":  # a peer's herringbone has no gap: the gap-0 case only
        assert "centre_gap_mm" not in case.table
        assert all(params.get("herringbone") for _, params in peers.PEERS[case.name].values())
