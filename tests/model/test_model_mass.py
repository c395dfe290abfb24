"""Mass properties from the parts' own geometry (geargen.model.mass) against the kernel's
integration of the built solids (an independent method: OCCT's Gauss integration over the B-rep)."""

import math
import warnings

import pytest

from geargen.cad.families import build_part
from geargen.cad.gear_solid import build_cluster
from geargen.cad.mass import mass_properties
from geargen.design.cluster import ClusterSpec
from geargen.design.gear import GearSpec, Hub
from geargen.families.double_helical.spec import DoubleHelicalGearSpec
from geargen.families.internal.spec import InternalGearSpec
from geargen.model.mass import cluster_mass, gear_mass
from geargen.profile.tooth import UndercutWarning

pytestmark = pytest.mark.slow

DEG = math.pi / 180


@pytest.fixture(name="quiet_undercut")
def quiet_undercut_fixture():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UndercutWarning)
        yield


def spec(teeth, spec_class=GearSpec, **kw):
    base = dict(teeth=teeth, module=1.0, pressure_angle=20 * DEG, face_width=6.0, name="g")
    base.update(kw)
    return spec_class(**base)


CASES = {
    "spur with keyway and hub": spec(23, hub=Hub(bore_diameter=8.0, keyway_width=3.0, keyway_depth=1.4,
                                                 hub_diameter=14.0, hub_length=5.0)),
    "undercut pinion": spec(11, module=0.8, hub=Hub(bore_diameter=3.0)),
    "shifted helical": spec(31, helix_angle=25 * DEG, profile_shift=0.3, hub=Hub(bore_diameter=10.0)),
    "double helical with a gap": spec(40, DoubleHelicalGearSpec, helix_angle=30 * DEG, face_width=20.0,
                                      centre_gap=4.0, hub=Hub(bore_diameter=12.0)),
    "internal ring": spec(60, InternalGearSpec),
}


@pytest.mark.parametrize("name", CASES)
def test_gear_mass_matches_the_solid(name, quiet_undercut):
    gear = CASES[name]
    kernel = mass_properties(build_part(gear).shape, eps=1e-7)
    model = gear_mass(gear)
    assert model.volume == pytest.approx(kernel.volume, rel=2e-5)
    assert model.axial_moment == pytest.approx(kernel.axial_moment, rel=2e-5)
    assert model.centre[2] == pytest.approx(kernel.centre[2], abs=1e-4)


def test_cluster_mass_matches_the_solid(quiet_undercut):
    large = spec(48, face_width=4.7625, hub=Hub(bore_diameter=6.35, keyway_width=2.0, keyway_depth=1.0,
                                               hub_diameter=10.0, hub_length=3.0))
    small = spec(17, face_width=7.9375, hub=Hub(bore_diameter=6.35, keyway_width=2.0, keyway_depth=1.0,
                                              hub_diameter=9.0, hub_length=2.0))
    cluster = ClusterSpec(large, small, axial_gap=1.5, relative_phase=0.05, name="cluster")
    kernel = mass_properties(build_cluster(cluster).shape, eps=1e-7)
    model = cluster_mass(cluster)
    assert model.volume == pytest.approx(kernel.volume, rel=2e-5)
    assert model.axial_moment == pytest.approx(kernel.axial_moment, rel=2e-5)
    assert model.centre[2] == pytest.approx(kernel.centre[2], abs=1e-4)


@pytest.mark.parametrize("back", ["spherical", "flat"])
def test_bevel_axial_moment_matches_the_solid(back):
    from geargen.families.bevel.solid import build_bevel
    from geargen.families.bevel.geometry import bevel_axial_moment, bevel_volume
    from geargen.families.registry import read_gear
    gear = read_gear({"kind": "bevel", "teeth": 15, "mate_teeth": 30, "diametral_pitch_per_in": 32,
                            "face_width_in": 0.15, "bore_diameter_in": 0.1})
    kernel = mass_properties(build_bevel(gear, back=back).shape, eps=1e-3)  # converged to 1e-10 already
    assert bevel_volume(gear, back) == pytest.approx(kernel.volume, rel=1e-7)
    assert bevel_axial_moment(gear, back) == pytest.approx(kernel.axial_moment, rel=1e-7)


@pytest.mark.parametrize("bore, slot", [(8.5, 1.5), (8.5, 12.0), (0.0, 3.0)])
def test_split_collar_closed_form_matches_the_solid(bore, slot):
    """The slot crossing the bore's side (narrow), wider than the bore, and a solid collar."""
    from geargen.cad import parts as P
    from geargen.model.bodies import mass_properties as body_mass, split_collar
    kernel = mass_properties(P.split_collar(bore, 30.0, 10.0, slot), eps=1e-7)
    model = body_mass(split_collar(bore, 30.0, 10.0, slot))
    assert model.volume == pytest.approx(kernel.volume, rel=1e-9)
    assert model.axial_moment == pytest.approx(kernel.axial_moment, rel=1e-9)
    assert model.centre == pytest.approx(kernel.centre, abs=1e-7)
