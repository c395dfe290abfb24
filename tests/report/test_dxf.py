"""geargen's DXF writer (geargen.report.dxf) writes, byte for byte, the file ezdxf writes.

The reference is tools/dxf_frame.py's ``ezdxf_bytes``: the same outline and bore entities added with
ezdxf's own calls (add_arc, add_spline, add_circle, add_line) to ezdxf's new R2010 document and written
by ezdxf's tag writer. Compared for a metric helical gear with a keyway (ARC and LINEs on the bore), an
inch spur gear with a plain bore (CIRCLE) and a gear without a bore, so that every
entity kind, both units and the handles after the entities are covered. The stored frame must be the one
the pinned ezdxf writes today (else tools/dxf_frame.py regenerates it).
"""

import importlib.util
import math
from pathlib import Path

import pytest

from geargen.design.gear import GearSpec, Hub
from geargen.profile.tooth import tooth_profile
from geargen.report.dxf import FRAME_PATH, write_profile_dxf

ROOT = Path(__file__).resolve().parents[2]


def _load(path: Path):
    spec = importlib.util.spec_from_file_location(path.stem, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


reference = _load(ROOT / "tools" / "dxf_frame.py")

SPECS = {
    "metric helical, keyway": GearSpec(teeth=21, module=0.79375, pressure_angle=math.radians(20), face_width=12.7,
                                       helix_angle=math.radians(20), hand="left", profile_shift=0.2,
                                       hub=Hub(bore_diameter=6.0, keyway_width=2.0, keyway_depth=1.0), name="pinion_21"),
    "inch spur, plain bore": GearSpec(teeth=112, module=25.4 / 32, pressure_angle=math.radians(20), face_width=6.35,
                                      hub=Hub(bore_diameter=10.0), name="gear_112", length_unit="in"),
    "no bore": GearSpec(teeth=9, module=1.0, pressure_angle=math.radians(20), face_width=5.0, name="small"),
}


@pytest.mark.parametrize("name", SPECS)
def test_the_writer_writes_ezdxfs_bytes(name, tmp_path):
    import ezdxf

    profile = tooth_profile(SPECS[name], warn=False)
    record = write_profile_dxf(profile, tmp_path / "g.dxf")
    ours = record.path.read_bytes()
    header = ezdxf.readfile(record.path).header  # the GUIDs (their rule: tests/test_reproducible_build.py)
    guids = [reference.uuid.UUID(header[key].strip("{}")) for key in ("$FINGERPRINTGUID", "$VERSIONGUID")]
    theirs = reference.ezdxf_bytes(profile, *guids)
    assert ours == theirs
    assert record.bytes == len(theirs)


def test_the_stored_frame_is_what_the_pinned_ezdxf_writes():
    assert FRAME_PATH.read_text(encoding="utf-8") == reference.frame("mm") == reference.frame("in")
