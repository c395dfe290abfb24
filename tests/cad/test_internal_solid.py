"""Internal gear solids: one valid closed solid, volume against the rim disc less the exact hole,
flanks on the exact involute on transverse sections (spur and helical), STEP export."""

from __future__ import annotations

import math

import numpy as np
import pytest

from geargen.cad.families import build_part
from geargen.cad.gear_solid import check_solid, solid_volume
from geargen.cad.measure import flank_deviation
from geargen.families.internal.spec import InternalGearSpec

pytestmark = pytest.mark.slow


def ring(**kw):
    base = dict(teeth=40, module=1.0, pressure_angle=math.radians(20), face_width=6.0, profile_shift=0.5)
    return InternalGearSpec(**{**base, **kw})


@pytest.fixture(scope="module")
def spur_ring():
    return build_part(ring(), check=True)


@pytest.fixture(scope="module")
def helical_ring():
    return build_part(ring(helix_angle=math.radians(20), hand="left", rim_diameter=52.0), check=True)


def expected_volume(spec, profile):
    """pi R_rim^2 b less the hole: the exact inner outline's area (Green's theorem on the analytic
    segments) times the face width."""
    return (math.pi * (spec.rim_diameter / 2) ** 2 - profile.hole_area()) * spec.face_width


@pytest.mark.parametrize("which", ["spur_ring", "helical_ring"])
def test_ring_solid_is_valid_with_exact_volume_and_flanks(which, request):
    solid = request.getfixturevalue(which)
    spec, profile = solid.spec, solid.profile
    assert check_solid(solid.shape) is None
    assert solid_volume(solid.shape) == pytest.approx(expected_volume(spec, profile), rel=1e-6)
    for z in np.linspace(0.1, 0.9, 3) * spec.face_width:
        dev = flank_deviation(solid.shape, profile.flank_frame(), z, samples_per_face=48)
        assert dev.flanks == 2 * spec.teeth  # every flank of every space was sampled
        assert dev.max_abs <= 1e-4  # 0.1 um, the bound (the splines hold 2 nm)


def test_ring_step_export(spur_ring, tmp_path):
    from geargen.cad.export import export_step, read_step
    record = export_step(spur_ring, tmp_path / "ring.step")
    assert record.path.exists()
    back = read_step(record.path)
    assert check_solid(back.shape) is None
    assert solid_volume(back.shape) == pytest.approx(solid_volume(spur_ring.shape), rel=1e-6)


def test_gear_command_writes_a_ring(tmp_path):
    """``geargen gear --kind internal`` writes STEP, STL and the ring's gear data."""
    import json

    from geargen.cli import main
    out = tmp_path / "ring"
    assert main(["gear", "--kind", "internal", "--teeth", "30", "--module", "1", "--profile-shift", "0.5",
                 "--face-width", "3", "--rim-diameter", "40", "--out", str(out)]) == 0
    data = json.loads((out / "internal_30.json").read_text())
    assert {"internal_30.step", "internal_30.stl"} <= set(data["files"])
    assert data["kind"] == "internal" and data["rim_diameter"] == 40.0
    assert data["tip_radius"] == pytest.approx(15 - (1 - 0.5))  # r - m (h_a* - x)
    assert data["between_pins"]["dimension"] > 0
    assert main(["gear", "--kind", "internal", "--teeth", "30", "--module", "1", "--face-width", "3",
                 "--bore", "5", "--out", str(tmp_path / "bad")]) != 0


def test_gear_design_file_of_a_ring(tmp_path):
    """``[gear] kind = "internal"`` in a gear design file: the same table keys as an external gear."""
    import json

    from geargen.cli import main
    design = tmp_path / "ring.toml"
    design.write_text('[gear]\nkind = "internal"\nteeth = 36\nmodule_mm = 0.5\npressure_angle_deg = 20\n'
                      'helix_angle_deg = 12\nhand = "left"\nprofile_shift = 0.4\nface_width_mm = 2\n'
                      'rim_diameter_mm = 24\n')
    assert main(["gear", str(design), "--out", str(tmp_path / "out"), "--no-stl"]) == 0
    data = json.loads((tmp_path / "out" / "ring.json").read_text())
    assert data["kind"] == "internal" and data["hand"] == "left" and data["rim_diameter"] == 24.0
    assert "between_pins" not in data  # a helical ring: between-balls is not implemented
