"""The one gear-family registry (geargen/families/registry.py): every family registered provides the
GearFamily interface, under the kind its specs carry, and any family's table is read through it."""

from __future__ import annotations

import inspect

import pytest

from geargen.errors import DesignError
from geargen.families.family import GearFamily
from geargen.families.registry import FAMILIES, family_of, read_gear

#: one small table per family, the kind's own keys (values from the families' own tests)
TABLES = {
    "external": {"teeth": 20, "module_mm": 2, "pressure_angle_deg": 20, "face_width_mm": 10},
    "internal": {"kind": "internal", "teeth": 60, "module_mm": 1, "pressure_angle_deg": 20, "face_width_mm": 8},
    "double_helical": {"kind": "double_helical", "teeth": 30, "module_mm": 2, "pressure_angle_deg": 20,
                       "helix_angle_deg": 25, "face_width_mm": 30, "centre_gap_mm": 6},
    "rack": {"kind": "rack", "module_mm": 2, "teeth": 30, "face_width_mm": 20},
    "bevel": {"kind": "bevel", "teeth": 20, "mate_teeth": 40, "module_mm": 3, "face_width_mm": 22},
    "worm": {"kind": "worm", "module_mm": 3, "starts": 2, "wheel_teeth": 30, "worm_reference_diameter_mm": 44,
             "worm_face_length_mm": 30, "wheel_face_width_mm": 28},
    "worm_wheel": {"kind": "worm_wheel", "module_mm": 3, "starts": 2, "wheel_teeth": 30,
                   "worm_reference_diameter_mm": 44, "worm_face_length_mm": 30, "wheel_face_width_mm": 28},
}


def test_the_seven_families_are_registered_under_their_kind():
    assert set(FAMILIES) == set(TABLES)
    assert all(family.KIND == kind for kind, family in FAMILIES.items())


@pytest.mark.parametrize("kind", sorted(TABLES))
def test_each_family_provides_the_interface(kind):
    """Every member GearFamily declares, the functions with the parameters it names."""
    family = FAMILIES[kind]
    for name, member in inspect.getmembers(GearFamily):
        if name.startswith("_"):
            continue
        assert hasattr(family, name), f"{kind} has no {name}"
        if inspect.isfunction(member):
            wanted = list(inspect.signature(member).parameters)[1:]  # without self
            assert list(inspect.signature(getattr(family, name)).parameters) == wanted, (kind, name)
    for name in GearFamily.__annotations__:
        assert hasattr(family, name), f"{kind} has no {name}"


@pytest.mark.parametrize("kind", sorted(TABLES))
def test_a_table_reads_to_a_spec_of_its_family(kind):
    spec = read_gear(TABLES[kind], where=f"gears.{kind}", name=kind)
    assert spec.kind == kind and family_of(spec) is FAMILIES[kind]
    assert FAMILIES[kind].FIELDS  # validate and the reference read the same keys


def test_a_kind_no_family_has_is_refused_naming_the_key():
    with pytest.raises(DesignError) as e:
        read_gear({"kind": "hypoid", "teeth": 20, "module_mm": 2, "face_width_mm": 10}, where="gears.g")
    assert e.value.field == "gears.g.kind"


def test_every_family_folder_is_registered_by_its_one_line():
    """A folder with a ``family.py`` is a family: its import line in the registry is all that
    registers it (FAMILIES collects the imported family modules), so a folder without the line, or a
    line without the folder, fails here."""
    from pathlib import Path

    import geargen.families as package
    folders = {p.parent.name for p in Path(package.__file__).parent.glob("*/family.py")}
    assert folders == set(FAMILIES) == set(TABLES)
    registry = (Path(package.__file__).parent / "registry.py").read_text()
    lines = [line for line in registry.splitlines() if line.startswith("from geargen.families.") and " import family as " in line]
    assert len(lines) == len(FAMILIES)  # one line each
