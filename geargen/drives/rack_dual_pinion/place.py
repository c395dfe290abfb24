"""The Type 2 dual-pinion rack drive placed: ``[layout] kind = "rack_dual_pinion"``.

A machine slide's rack drive as Hale & Slocum say Fig. 4's should have been: two path shafts
``pinion_spacing`` apart above a straight rack, each carrying a rack pinion (gear table
``pinion``) and above it a path gear (``path_gear``); the motor's input gear (``input``) on the
symmetry line meshes both path gears and rides on a preload carriage that slides along the
symmetry line, its spring pushing the input toward the shafts (radial-motion preload, Fig. 9).
The motor is at the common input, so the carriage spring is in neither path: Type 2.

Placement (the maths in :mod:`geargen.core.rack_drive`; frame: the rack's pitch line on the x
axis, teeth up, gear axes +z, the symmetry line x = 0):

* the rack (a :class:`geargen.families.rack.spec.RackSpec` made from the pinion's tooth system, spur,
  generating tip rounding, unthinned) is ``slide_travel`` + the pinions' span long, a whole even
  number of pitches, centred on x = 0 with a tooth space there (its phase);
* each pinion's centre height gives the rack mesh its backlash (the point of the ``rack_backlash``
  range that ``model_tooth_thickness`` names: the middle, the least or the most) by the centre offset
  (:func:`geargen.families.rack.geometry.centre_offset_for_backlash`), and each pinion is turned against the rack
  on its working flank, the loaded flank gap short;
* the input and path gears' teeth are made within their allowances for the ``path_backlash`` range
  at the design centre distance; the path gear is keyed to its pinion at the timing that closes the loop with
  the carriage at its nominal height (the assembler's mark, reported); the input stands
  symmetric, and the carriage height where the loop closes is solved (root find) and placed.

Everything downstream reads this one :class:`RackDrivePlacement` (``Layout.placement``): the
solids, the checks (:mod:`geargen.drives.rack_dual_pinion.verdict`), the stiffness and preload report.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from geargen.families.rack.geometry import centre_offset_for_backlash, rack_pinion_geometry
from geargen.core.rack_drive import (RackDriveFrame, carriage_k3, keying_for_closure, path_stiffness_at_rack,
                                     pinion_rotation_on_rack, preload_forces, solve_carriage)
from geargen.design.assembly import Design
from geargen.design.gear import GearSpec
from geargen.families.rack.spec import RackSpec
from geargen.errors import DesignError, GeometryError
from geargen.model.allowance import MeshRange, model_gears, model_source
from geargen.model.layout import GearPlacement, Layout, MeshPlacement, modelled_backlash, ratio_check, running_backlash
from geargen.units import LENGTH_SUFFIXES

#: the gear tables the drive reads
ROLES = ("pinion", "path_gear", "input")


@dataclass(frozen=True)
class RackDrivePlacement:
    """The placed rack drive (mm, rad, N): the one home of its numbers.

    ``rack_offset``: the pinions' centre offset from the rack's nominal mesh (+ away);
    ``rack_backlash``: circumferential backlash of each rack mesh there (closed form);
    ``keying``: path gear a's rotation minus pinion a's (b is the mirror image, ``-keying``);
    ``carriage_y``/``carriage_y_nominal``: the input's centre height where the loop closes and the
    design's; ``lever``: rack travel per carriage travel (each path, mm/mm);
    ``loop_error_travel``: the carriage travel that absorbs ``[layout] rack_loop_error``.
    """

    rack: RackSpec
    pinion: GearSpec
    path_gear: GearSpec
    input: GearSpec
    frame: RackDriveFrame
    rack_offset: float
    rack_backlash: float
    rack_backlash_range: tuple[float, float]
    path_backlash_range: tuple[float, float]
    modelled_path_backlash: float
    loaded_flank_gap: float
    keying: float
    input_rotation: float
    carriage_y: float
    carriage_y_nominal: float
    carriage_travel: float
    cos_gamma: float
    lever: float
    loop_error: float
    spring_force: float
    spring_rate: float
    max_rack_force: float | None
    elastic_modulus: float
    shear_modulus: float
    shaft_twist_length: float  # path shaft between the pinion's and the path gear's mid-faces

    @property
    def carriage_deviation(self) -> float:
        return self.carriage_y - self.carriage_y_nominal

    @property
    def loop_error_travel(self) -> float:
        """Carriage travel (mm, total) that a rack loop error ``e`` needs: ``e / (2 lambda)`` (each
        path takes half of it)."""
        return self.loop_error / (2 * self.lever)

    def backlash_travel(self, path_backlash: float, rack_backlash: float) -> float:
        """Carriage travel toward the shafts (mm) when the teeth are made to other backlashes than
        modelled (circumferential, mm): the input meshes' working gaps open by half the extra
        path backlash, ``cos(alpha_t)`` of it along the lines of action, which the carriage closes
        at ``cos(gamma)``; each pinion turns on by half the extra rack backlash, which the carriage
        takes up at the lever ``lambda``."""
        modelled = self.modelled_path_backlash
        along = (path_backlash - modelled) * math.cos(self.input.transverse_pressure_angle) / 2
        return along / self.cos_gamma + (rack_backlash - self.rack_backlash) / (2 * self.lever)

    @property
    def tolerance_travel(self) -> float:
        """The largest carriage travel (mm, either way) over the design's backlash ranges: teeth at
        the ranges' smallest or largest backlash, both meshes alike."""
        return max(abs(self.backlash_travel(self.path_backlash_range[i], self.rack_backlash_range[i])) for i in (0, 1))

    @property
    def sensitivity(self) -> float:
        """Carriage travel per unit of loop error at the rack (mm/mm): ``1 / (2 lambda)``."""
        return 1.0 / (2 * self.lever)

    def forces(self, drive_torque: float = 0.0):
        return preload_forces(self.spring_force, self.cos_gamma, self.input.base_radius, self.path_gear.base_radius,
                              self.pinion.reference_radius, drive_torque)

    def stiffness(self) -> dict[str, float]:
        """Paths, carriage spring and Eqs. 5-6 at the rack (N/mm along x): Eq. 1 meshes
        (``E w / 11`` on the narrower face) and the path shaft's torsion between the placed gears'
        mid-faces (the pinion's bore as its diameter), the input held."""
        from geargen.core.drive import TwoPathDrive
        from geargen.core.stiffness import mesh_stiffness, shaft_torsional_stiffness
        e = self.elastic_modulus
        k_in = float(mesh_stiffness(e, min(self.input.face_width, self.path_gear.face_width)))
        k_rack = float(mesh_stiffness(e, min(self.rack.face_width, self.pinion.face_width)))
        k_shaft = shaft_torsional_stiffness(self.shear_modulus, self.pinion.hub.bore_diameter, self.shaft_twist_length)
        k_path = path_stiffness_at_rack(k_in, k_rack, self.path_gear.base_radius, self.pinion.reference_radius,
                                        self.rack.transverse_pressure_angle, k_shaft)
        k3 = carriage_k3(self.spring_rate, self.lever)
        preload = self.forces().mesh_force_at_rest * self.path_gear.base_radius / self.pinion.reference_radius
        drive = TwoPathDrive("type2", k_path, k_path, preload, k3)
        return {"input_mesh": k_in, "rack_mesh": k_rack, "path_shaft_torsion": k_shaft, "k1": k_path, "k2": k_path, "k3": k3,
                "drive": drive.drive_stiffness, "loop": drive.loop_stiffness,
                "drive_type1": 2 * k_path, "loop_preload": preload}


def rack_drive(layout: Layout) -> RackDrivePlacement | None:
    """The layout's rack drive placement (None for another kind of drive)."""
    return layout.placement if isinstance(layout.placement, RackDrivePlacement) else None


def _gear(design: Design, role: str) -> GearSpec:
    if role not in design.gears:
        raise DesignError(f"gears.{role}", "missing: a rack dual-pinion drive needs gear tables "
                          + ", ".join(f"[gears.{r}]" for r in ROLES), f"a [gears.{role}] table")
    g = design.gears[role]
    if not isinstance(g, GearSpec) or g.kind != "external":
        raise DesignError(f"gears.{role}.kind", f"{getattr(g, 'kind', type(g).__name__)!r}: the rack drive's "
                          f"{role} is an external spur gear", "'external'")
    if g.helix_angle != 0:
        # the closure and the placement hold in one transverse plane; helical paths are not placed here
        raise DesignError(f"gears.{role}.helix_angle_deg", "the rack drive is placed with spur gears", "0")
    return g


def _rack(design: Design, s: dict, pinion: GearSpec) -> RackSpec:
    """The rack: the pinion's tooth system, ``slide_travel`` + the pinions' span (centre to centre
    plus a tip diameter) long, rounded up to a whole even number of pitches (a space at x = 0)."""
    pitch = math.pi * pinion.module
    length = s["slide_travel"] + s["pinion_spacing"] + 2 * pinion.tip_radius
    teeth = math.ceil(length / pitch - 1e-9)
    teeth += teeth % 2
    back = s["rack_back_height"] if s["rack_back_height"] is not None else 2 * pinion.module
    try:
        return RackSpec(teeth=teeth, module=pinion.module, pressure_angle=pinion.pressure_angle,
                        face_width=s["rack_face_width"] or pinion.face_width,
                        pitch_line_height=back + 1.25 * pinion.module, tip_rounding="generating",
                        name="rack", length_unit=design.length_unit if design.length_unit in ("mm", "in") else "mm")
    except DesignError as exc:
        raise DesignError(f"layout (the rack: {exc.field})", exc.problem, exc.allowed) from None


def place_rack_drive(design: Design, s: dict) -> Layout:
    """The resolved rack drive (see the module docstring)."""
    pinion, path, inp = (_gear(design, r) for r in ROLES)
    if not pinion.hub.bore_diameter > 0:
        raise DesignError("gears.pinion.bore_diameter_mm", "missing: the path shaft (the pinion's bore) carries the "
                          "path's torque between its gears", "a bore diameter > 0")
    if path.module != inp.module or path.pressure_angle != inp.pressure_angle:
        raise DesignError("gears.input.module_mm", "the input meshes the path gears: same module and pressure angle",
                          f"{path.module:.6g} mm, {math.degrees(path.pressure_angle):.6g} deg")
    rule = s["model_tooth_thickness"]
    gap = s["loaded_flank_gap"]
    h = s["pinion_spacing"] / 2
    a_nom = s["input_centre_distance"]
    if a_nom <= h:
        raise DesignError("layout.input_centre_distance", f"{a_nom:.6g} mm cannot reach path shafts {h:.6g} mm "
                          "either side of the symmetry line", f"> {h:.6g} mm (half the pinion spacing)")
    path_range = (s["path_backlash_min"], s["path_backlash_max"])
    rack_range = (s["rack_backlash_min"], s["rack_backlash_max"])
    keys = ("layout.path_backlash_min", "layout.path_backlash_max")
    made = model_gears(design, rule, [MeshRange(inp, path, *path_range, a_nom, keys)])
    inp, path = made[inp.name], made[path.name]
    rack = _rack(design, s, pinion)
    # the rack meshes' backlash comes from the pinions' centre height (the rack's backlash from
    # centre offset): the model's point taken on the rack range (most material, least backlash)
    rack_target = modelled_backlash(*rack_range, rule)
    offset = centre_offset_for_backlash(rack, pinion, rack_target)
    geom = rack_pinion_geometry(rack, pinion, offset)
    unit = design.length_unit
    k = 1.0 / LENGTH_SUFFIXES[unit]
    # each loop stands a loaded flank gap short of its working flanks: the backlash must leave it
    for key, backlash in (("rack_backlash_max" if rule == "min_material" else "rack_backlash_min",
                           geom.backlash_circumferential),
                          ("path_backlash_max" if rule == "min_material" else "path_backlash_min",
                           running_backlash(inp, path, a_nom))):
        if backlash <= 2 * gap:
            raise DesignError(f"layout.{key}_{s['_units'].get(key, unit)}", f"the modelled backlash "
                              f"{backlash * k:.4g} {unit} leaves no room for the loaded flank gap "
                              f"({gap * k:.4g} {unit}) on the working flank without closing the other",
                              f"a range whose modelled backlash exceeds {2 * gap * k:.4g} {unit}")
    shaft_y = geom.centre_height
    frame = RackDriveFrame(h, shaft_y, inp.teeth, path.teeth, path.reference_radius, path.base_radius,
                           inp.base_radius, pinion.reference_radius)
    y_nom = shaft_y + math.sqrt(a_nom ** 2 - h ** 2)

    def backlash_of(c: float) -> float:  # the input mesh's circumferential backlash at centre distance c
        return running_backlash(inp, path, c)

    # pinion a pushes the rack toward +x (counter-clockwise), pinion b is its mirror image
    rot_pinion_a = pinion_rotation_on_rack(h, pinion.reference_radius, 0.0, geom.backlash_circumferential, gap, +1)
    rot_input = -math.pi / 2  # a tooth on the symmetry line toward the shafts: the input stands symmetric
    keying = keying_for_closure(frame, rot_pinion_a, rot_input, backlash_of, gap, y_nom) % (2 * math.pi)
    try:
        y_c = solve_carriage(frame, rot_pinion_a + keying, rot_input, backlash_of, gap, y_nom,
                             search=0.5 * math.pi * inp.module)
    except GeometryError as exc:
        raise DesignError("layout.input_centre_distance", str(exc), "a centre distance the input and path gears "
                          "mesh at") from None
    # heights: the rack from z = 0, each pinion centred on it, the path gear above the pinion, the
    # input centred on the path gear
    z_rack = 0.0
    z_pinion = z_rack + (rack.face_width - pinion.face_width) / 2
    z_path = z_pinion + pinion.face_width + s["path_gear_axial_gap"]
    z_input = z_path + (path.face_width - inp.face_width) / 2
    cos_g = frame.cos_gamma(y_c)
    placement = RackDrivePlacement(
        rack=rack, pinion=pinion, path_gear=path, input=inp, frame=frame, rack_offset=offset,
        rack_backlash=geom.backlash_circumferential, rack_backlash_range=rack_range, path_backlash_range=path_range,
        modelled_path_backlash=running_backlash(inp, path, float(frame.centre_distance(y_c))),
        loaded_flank_gap=gap, keying=keying, input_rotation=rot_input, carriage_y=y_c, carriage_y_nominal=y_nom,
        carriage_travel=s["carriage_travel"], cos_gamma=cos_g, lever=frame.lever(y_c),
        loop_error=s["rack_loop_error"], spring_force=s["carriage_preload_force_N"],
        spring_rate=s["carriage_spring_rate_N_per_mm"], max_rack_force=s["max_rack_force_N"],
        elastic_modulus=s["gear_elastic_modulus_GPa"] * 1e3, shear_modulus=s["shaft_shear_modulus_GPa"] * 1e3,
        shaft_twist_length=(z_path + path.face_width / 2) - (z_pinion + pinion.face_width / 2))
    n_half = rack.teeth // 2
    gears = [
        GearPlacement("rack", rack, (-n_half * rack.transverse_pitch, -rack.pitch_line_height), z_rack, 0.0,
                      "rack", ("rack",)),
        GearPlacement("pinion_a", pinion, (h, shaft_y), z_pinion, rot_pinion_a, "path_a", ("pinion",)),
        GearPlacement("path_gear_a", path, (h, shaft_y), z_path, rot_pinion_a + keying, "path_a", ("path_gear",)),
        GearPlacement("pinion_b", pinion, (-h, shaft_y), z_pinion, math.pi - rot_pinion_a, "path_b", ("pinion",)),
        GearPlacement("path_gear_b", path, (-h, shaft_y), z_path, math.pi - rot_pinion_a - keying, "path_b",
                      ("path_gear",)),
        GearPlacement("input", inp, (0.0, y_c), z_input, rot_input, "input", ("input",)),
    ]
    plane = z_input + inp.face_width / 2
    c = float(frame.centre_distance(y_c))
    meshes = (
        MeshPlacement("mesh_input_a", "input", inp, "path_gear_a", path, plane, *path_range,
                      running_backlash(inp, path, c), True, "input cw", c, keys),
        MeshPlacement("mesh_input_b", "input", inp, "path_gear_b", path, plane, *path_range,
                      running_backlash(inp, path, c), True, "input ccw", c, keys),
    )
    notes = [f"rack drive: carriage (input centre) at y = {y_c * k:.6g} {unit} above the rack's pitch line, "
             f"{(y_c - y_nom) * k:+.3g} {unit} from nominal; the loop closes there (both pinions tight on the rack)",
             f"rack drive: path gear keyed {math.degrees(keying):.6g} deg from its pinion on shaft a "
             f"({-math.degrees(keying):.6g} deg on shaft b)",
             f"rack drive: rack {rack.teeth} teeth ({rack.length * k:.6g} {unit}), pinion centres "
             f"{offset * k:+.4g} {unit} from the nominal rack mesh (backlash {geom.backlash_circumferential * k:.4g} "
             f"{unit})"]
    source = model_source(rule)
    thinning = {g.name: {"source": source if g.name.startswith(("input", "path_gear")) else "design"} for g in gears}
    return Layout(design=design, kind="rack_dual_pinion", gears=tuple(gears), meshes=meshes, settings=s,
                  ratio=ratio_check(design, s, Fraction(path.teeth, inp.teeth), "motor to path shafts"),
                  notes=tuple(notes), placement=placement, carriage_travel=s["carriage_travel"], thinning=thinning)


def report(placement: RackDrivePlacement) -> dict[str, Any]:
    """The drive's report values (mm, N, N/mm): carriage, lever, forces of Fig. 9, Eqs. 5-6."""
    f0 = placement.forces()
    out = {"carriage_y": placement.carriage_y, "carriage_y_nominal": placement.carriage_y_nominal,
           "carriage_deviation": placement.carriage_deviation, "carriage_travel": placement.carriage_travel,
           "lever": placement.lever, "sensitivity": placement.sensitivity, "cos_gamma": placement.cos_gamma,
           "loop_error_travel": placement.loop_error_travel, "tolerance_travel": placement.tolerance_travel,
           "keying_rad": placement.keying,
           "rack_offset": placement.rack_offset, "rack_backlash": placement.rack_backlash,
           "spring_force": placement.spring_force, "mesh_force_at_rest": f0.mesh_force_at_rest,
           "unloading_rack_force": f0.unloading_rack_force, "stiffness": placement.stiffness()}
    if placement.max_rack_force is not None:
        torque = placement.max_rack_force * placement.pinion.reference_radius / placement.path_gear.base_radius \
            * placement.input.base_radius
        f = placement.forces(torque)
        out.update(max_rack_force=placement.max_rack_force, mesh_force_1=f.mesh_force_1, mesh_force_2=f.mesh_force_2)
    return out


__all__ = ["ROLES", "RackDrivePlacement", "rack_drive", "place_rack_drive", "report"]
