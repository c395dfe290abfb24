"""geargen from Python, for CadQuery users: a gear, a pair or a whole assembly as CadQuery objects.

    from geargen import api
    gear = api.gear(teeth=21, module=1, pressure_angle=20, face_width=5, bore=6)   # cadquery.Solid
    pair = api.pair(teeth=(12, 24), module=3, face_width=10)                      # cadquery.Assembly
    joint = api.assembly("assemblies/robot_joint.toml")                           # cadquery.Assembly

The objects are ordinary CadQuery objects: show them in CQ-editor or ocp_vscode, combine them
with your own parts (booleans, ``cq.Workplane(...).add(gear)``), export them with
``cadquery.exporters``. They are built by the same steps as ``geargen gear`` and ``geargen build``
(:mod:`geargen.pipeline`) and validated the same way: bad input raises
:class:`geargen.errors.DesignError` naming the keyword argument (``face_width``), or the design
file's key, and the allowed range.

Units: inputs are in the design's length unit (mm with ``module``, inches with
``diametral_pitch``; an assembly's ``length_unit``); angles in degrees. The returned geometry is
always in **mm**, as CadQuery and its STEP exporter assume, whatever the design's unit.

This module does not import CadQuery itself (the kernel stays behind :mod:`geargen.cad`); the
first call imports it (about a second).
"""

from __future__ import annotations

import argparse
import re
from pathlib import Path
from typing import Sequence

from geargen.errors import DesignError


def _keyword_errors(fn, *args):
    """``fn(*args)``, its errors naming the keyword argument (``face_width``) instead of the
    command's option (``--face-width``)."""
    try:
        return fn(*args)
    except DesignError as exc:
        if not exc.field.startswith("--"):
            raise
        raise DesignError(_keyword(exc.field), _OPTION.sub(lambda m: _keyword(m[0]), exc.problem),
                          exc.allowed and _OPTION.sub(lambda m: _keyword(m[0]), exc.allowed)) from None


#: a command-line option in a message (``--face-width-mm``), not a negative number
_OPTION = re.compile(r"--[a-z][a-z-]*")


def _keyword(option: str) -> str:
    return option[2:].replace("-", "_")


def gear(teeth: int | None = None, *, module: float | None = None, diametral_pitch: float | None = None,
         pressure_angle: float | None = None, face_width: float | None = None, helix_angle: float | None = None,
         hand: str | None = None, pitch_system: str | None = None, profile_shift: float | None = None,
         bore: float | None = None, thinning: float | None = None, name: str | None = None,
         design: str | Path | None = None, gear: str | None = None):
    """One gear as a :class:`cadquery.Solid` (mm), as ``geargen gear`` builds it: axis on z, the
    toothed face from z = 0 to the face width, tooth 0 centred on +x, the bore through it.

    Give the gear's options, as ``geargen gear`` takes them (lengths in the pitch system's unit:
    mm with ``module``, inches with ``diametral_pitch``; angles in degrees; ``pitch_system`` and
    ``profile_shift`` as there), or a ``design`` file with a ``[gear]`` table, or an assembly
    file with ``gear="NAME"`` (built as the assembly builds it, thinning included), not both.
    """
    from geargen.cad.cq_objects import shape
    from geargen.cad.gear_solid import build_gear
    from geargen.commands import gear as command

    given = {"teeth": teeth, "module": module, "diametral_pitch": diametral_pitch, "pressure_angle": pressure_angle,
             "face_width": face_width, "helix_angle": helix_angle, "hand": hand, "pitch_system": pitch_system,
             "profile_shift": profile_shift, "bore": bore, "thinning": thinning, "name": name,
             "design": None if design is None else str(design), "gear": gear}
    if module is not None and diametral_pitch is not None:
        raise DesignError("module", "given with diametral_pitch", "one of module or diametral_pitch")
    # every gear option of the command, unset unless given
    args = argparse.Namespace(**(command.unset_options() | given))
    spec, _ = _keyword_errors(command.spec_from_args, args)
    return shape(build_gear(spec, check=True).shape)


def pair(teeth: Sequence[int], *, module: float | None = None, diametral_pitch: float | None = None,
         face_width: float, pressure_angle: float = 20.0, helix_angle: float = 0.0, hand: str | None = None,
         profile_shift: Sequence[float] | None = None, centre_distance: float | None = None,
         thinning: Sequence[float] | None = None):
    """Two gears in mesh as a :class:`cadquery.Assembly` (mm): gear 1 (the pinion, ``"gear 1"``) at
    the origin, gear 2 (``"gear 2"``) on +x at the operating centre distance, both axes on z, the
    faces from z = 0 to ``face_width``, gear 1 turned so that its teeth sit centred in gear 2's
    gaps (the backlash split evenly between the flanks).

    The options are those of ``geargen pair`` (lengths in the pitch system's unit): the operating
    centre distance is ``centre_distance``, or the working centre distance of the shifts (zero
    backlash without ``thinning``); with ``centre_distance`` and no ``profile_shift`` the shifts are
    the recommended split of the sum it needs, as ``geargen pair`` reports them.
    """
    from dataclasses import replace

    from geargen.cad.assembly import PlacedPart, transform
    from geargen.cad.cq_objects import assembly
    from geargen.cad.gear_solid import build_gear
    from geargen.commands import pair as command
    from geargen.core.synthesis import mate_rotation
    from geargen.report.pair import pair_data
    from geargen.units import to_mm

    if face_width is None:
        raise DesignError("face_width", "missing: a gear solid needs its face width", "> 0")
    given = {"teeth": list(teeth) if isinstance(teeth, (list, tuple)) else teeth, "module": module,
             "diametral_pitch": diametral_pitch, "face_width": face_width, "pressure_angle": pressure_angle,
             "helix_angle": helix_angle, "hand": hand, "centre_distance": centre_distance,
             "profile_shift": None if profile_shift is None else list(profile_shift),
             "thinning": None if thinning is None else list(thinning),
             # geargen pair's options a CAD pair does not take: the standard basic rack, no stiffness inputs
             "dedendum_coefficient": None, "elastic_modulus": None, "load": None}
    if not isinstance(teeth, (list, tuple)) or len(teeth) != 2:
        raise DesignError("teeth", f"{teeth!r} is not two tooth counts", "(Z1, Z2)")
    if (module is None) == (diametral_pitch is None):
        raise DesignError("module", "give exactly one of module or diametral_pitch", "module (mm) or diametral_pitch (1/in)")
    args = argparse.Namespace(**given)
    gear1, gear2, unit = _keyword_errors(command.gears_from_args, args)
    operating = _keyword_errors(command.check_centre_distance, args, gear1, gear2, unit)
    source = "given" if profile_shift is not None else "default" if operating is None else "centre_distance"
    data = pair_data(gear1, gear2, shift_source=source, centre_distance=operating)
    gear1, gear2 = (replace(g, profile_shift=x) for g, x in zip((gear1, gear2), data["profile_shift"]))
    distance = to_mm(data["centre_distance"]["operating"], unit)
    # gear 2's tooth 0 on +x, away from gear 1; gear 1's tooth centred in the gap facing it
    rotation1 = float(mate_rotation(0.0, 0.0, gear1.teeth, gear2.teeth, 0.0, 0))
    parts = [PlacedPart(g.name, build_gear(g, check=True).shape, transform((x, 0.0, 0.0), (0, 0, 1), angle),
                        "gears", kind)
             for g, x, angle, kind in ((gear1, 0.0, rotation1, "gear_input"), (gear2, distance, 0.0, "gear_output"))]
    return assembly(f"pair_{gear1.teeth}_{gear2.teeth}", parts)


def assembly(design: str | Path, position: str | None = None):
    """The assembly of ``design`` (a design file) as a :class:`cadquery.Assembly` (mm): every part
    of ``geargen build`` (gears and the other parts), named, coloured and placed as in its
    ``assembly.step`` (root named after the design, one ``<group>_assembly`` per group).
    ``position`` is ``geargen build``'s ``--position`` (``"engaged"``, ``"disengaged"``; default
    the design's). No mesh checks are run and nothing is written: ``geargen build`` does that.
    """
    from geargen import pipeline
    from geargen.cad.cq_objects import assembly as cq_assembly

    loaded = pipeline.load(design)
    layout = _keyword_errors(pipeline.place, loaded, position)
    gears = pipeline.gear_solids(layout)
    parts = pipeline.other_parts(layout, gears, pipeline.stiffness(layout))
    return cq_assembly(loaded.name, parts.parts)


__all__ = ["gear", "pair", "assembly"]
