"""Shared CAD fixtures: the issue's two bench gears, built once per session."""

import math
import warnings

import pytest

from geargen.design.gear import GearSpec, Hub
from geargen.profile.tooth import UndercutWarning

DP32 = 25.4 / 32
DEG = math.pi / 180


def make_spec(teeth, module=DP32, helix=0.0, face=5.0, **kw):
    kw.setdefault("pressure_angle", 20 * DEG)
    return GearSpec(teeth=teeth, module=module, helix_angle=helix * DEG, face_width=face, **kw)


@pytest.fixture(name="make_spec", scope="session")
def make_spec_fixture():
    """``make_spec(teeth, module=32 DP, helix=deg, face=mm, **GearSpec fields)``."""
    return make_spec


@pytest.fixture(scope="session")
def spur112():
    """112-tooth 32 DP spur gear, 6.35 mm face, 10 mm bore (the issue's bench gear), inch design."""
    from geargen.cad.gear_solid import build_gear
    spec = make_spec(112, face=6.35, hub=Hub(bore_diameter=10.0), name="output", length_unit="in")
    return build_gear(spec)


@pytest.fixture(scope="session")
def helical21():
    """21-tooth 32 DP 20 deg right-hand helical pinion, 12.7 mm face (the issue's bench gear)."""
    from geargen.cad.gear_solid import build_gear
    return build_gear(make_spec(21, helix=20, face=12.7, name="pinion"))


@pytest.fixture
def quiet_undercut():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UndercutWarning)
        yield
