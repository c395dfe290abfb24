"""Fixtures of the mesh-check tests (helpers live in checks_support.py)."""

from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def robot_joint():
    from geargen.design.assembly import load_design

    return load_design(ROOT / "assemblies" / "robot_joint.toml")
