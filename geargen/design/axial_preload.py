"""The gear tables of an axial-preload drive (``[layout] kind = "axial_preload"``) checked
against each other: what the placement (:mod:`geargen.model.axial_drive`) relies on.

The two pinions sit on one shaft and the two output gears on another, so each pair turns
together: the same teeth (or the meshes would run at two ratios), the same normal module,
pressure angle and helix angle (so one axial slide turns both meshes by the same arc), opposite
hands (so the slide turns them in opposite senses: that is the preload), and each output gear of
the hand opposite to its pinion (an external helical pair).
"""

from __future__ import annotations

import math
from typing import Any

from geargen.errors import DesignError

ROLES = ("pinion_left", "pinion_right", "output_right", "output_left")
HAND_OF_ROLE = {"pinion_left": "left", "pinion_right": "right", "output_right": "right", "output_left": "left"}


def _same(name_a: str, a, name_b: str, b, attr: str, label: str, unit: str = "") -> None:
    va, vb = getattr(a, attr), getattr(b, attr)
    if not math.isclose(va, vb, rel_tol=1e-12, abs_tol=1e-12):
        shown = (lambda v: f"{math.degrees(v):.6g} deg") if unit == "deg" else (lambda v: f"{v:.6g}")
        raise DesignError(f"gears.{name_b}.{label}", f"{shown(vb)}, but gears.{name_a} has {shown(va)}: the axial "
                          "preload turns both meshes by one slide", shown(va))


def check_axial_gears(design, v: dict[str, Any]) -> None:
    """The rules of the module docstring on the gear tables named by ``[layout]`` (``v``)."""
    gears = {}
    for role in ROLES:
        name = v[role]
        if name not in design.gears:
            key = f"layout.{role}" if role in (design.section("layout") or {}) else f"gears.{name}"
            raise DesignError(key, f"no gear named {name!r} in the design", ", ".join(design.gears))
        spec = design.gears[name]
        if spec.kind != "external" or not spec.helix_angle > 0:
            raise DesignError(f"gears.{name}.helix_angle_deg", f"gears.{name} is {'a spur' if spec.kind == 'external' else spec.kind} "
                              "gear: the axial preload slides helical gears", "a helical external gear, helix_angle_deg > 0")
        if spec.hand != HAND_OF_ROLE[role]:
            raise DesignError(f"gears.{name}.hand", f"{spec.hand!r}: layout.{role} must be {HAND_OF_ROLE[role]}-hand",
                              repr(HAND_OF_ROLE[role]))
        gears[role] = spec
    pl = gears["pinion_left"]
    for role in ROLES[1:]:
        g = gears[role]
        _same(pl.name, pl, g.name, g, "module", "module")
        _same(pl.name, pl, g.name, g, "pressure_angle", "pressure_angle_deg", "deg")
        _same(pl.name, pl, g.name, g, "helix_angle", "helix_angle_deg", "deg")
    for a, b in (("pinion_left", "pinion_right"), ("output_right", "output_left")):
        if gears[a].teeth != gears[b].teeth:
            raise DesignError(f"gears.{gears[b].name}.teeth", f"{gears[b].teeth} teeth, but gears.{gears[a].name} has "
                              f"{gears[a].teeth}: the two turn together on one shaft", f"{gears[a].teeth}")


__all__ = ["ROLES", "HAND_OF_ROLE", "check_axial_gears"]
