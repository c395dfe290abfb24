"""The resolved drive: one place where every gear's final teeth, centre, height and phase are decided.

Every command starts here (``geargen synth``, ``check``, ``stiffness``, ``build`` and ``fit``
with ``assembly =``): :func:`resolve` turns a loaded design into a :class:`Layout` - each
gear's tooth thickness as modelled (the thinning the design states, or made at the point of its
tooth-thickness allowance ``[layout] model_tooth_thickness`` asks for, said so in ``notes``), every
centre, height and rotation, each mesh's operating centre distance and backlash - and nothing
downstream re-derives a placement. :meth:`Layout.to_dict` is what is written beside every export.

Frame: the output gear's centre is the origin, +x the symmetry line towards the input, +z the
gear axes (as :mod:`geargen.core.synthesis`). A gear is placed by ``centre`` (x, y), ``z``
(height of its local z = 0 face) and ``rotation`` (about its own axis; its tooth 0 is on local
+x at local z = 0). For helical gears the synthesis' rotations hold in one transverse plane per
mesh (the cluster's own gear faces); the mate's rotation is carried to its own z = 0 face
through the helix (``section_rotation``).

Tooth thickness (:mod:`geargen.model.allowance`). ``model_tooth_thickness`` = "as_designed" keeps
the gear tables' thinning; "mid_tolerance", "max_material" or "min_material" make each gear at that
point of its allowance, the allowance taken from its mesh's backlash range *where the mesh runs*:
the preload carriage settles where the loop closes, so mesh 1's centre distance is not quite the
design's, and the modelled teeth are iterated with it to the fixed point. Without a
``[layout] model_tooth_thickness`` the gear tables decide: "as_designed" when any gear of the
train states its thinning, else "mid_tolerance".
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction
from functools import cached_property
from typing import Any

from geargen.core.involute import reference_tooth_thickness
from geargen.core.stiffness import drive_train, stiffness_inputs
from geargen.design.assembly import Design
from geargen.design.cluster import ClusterSpec
from geargen.design.gear import GearSpec
from geargen.design.layout import MODEL_POINTS, MODEL_TOOTH_THICKNESS, POSITIONS
from geargen.families.registry import tooth_form
from geargen.core.accuracy import gear_errors
from geargen.design.checks import checks_settings
from geargen.design.duty import duty_settings, gear_materials
from geargen.design.export import export_settings
from geargen.design.parts import parts_settings
from geargen.design.resolved import DesignIdentity, identity_of
from geargen.design.stages import stages
from geargen.design.stiffness import stiffness_design
from geargen.design.train import train_settings
from geargen.profile.tooth import section_rotation
from geargen.units import LENGTH_SUFFIXES

class ResolvedSettings:
    """The design's sections as the drive's downstream modules read them (issue 26), internal
    units: each section a downstream module needs, read by the module that owns it (``[checks]``
    by :func:`geargen.design.checks.checks_settings`, ...) the first time it is asked for and
    kept. A section the drive never needs is never read (a design built without validation, e.g.
    while its defaults are sized, is placed without the sections it lacks being refused), and one
    it needs is read once per resolved drive."""

    def __init__(self, design) -> None:
        self._design = design
        self._errors: dict[str, Any] = {}
        self._rated: dict[str, Any] = {}

    @property
    def gears(self) -> dict[str, Any]:
        """The design's gears as read (table name -> spec; the modelled teeth are the Layout's)."""
        return self._design.gears

    def has(self, section: str) -> bool:
        """Whether the file gives (or the default hardware fills in) ``[section]``."""
        return bool(self._design.section(section))

    @cached_property
    def checks(self):
        """``[checks]`` (:class:`geargen.design.checks.ChecksSettings`; absent: every default)."""
        return checks_settings(self._design)

    @cached_property
    def export(self) -> dict[str, Any]:
        """``[export]`` (:func:`geargen.design.export.export_settings`)."""
        return export_settings(self._design)

    @cached_property
    def parts(self) -> dict[str, Any]:
        """``[parts]`` for the drive's hardware (:func:`geargen.design.parts.parts_settings`); refused
        when the design has none (ask :meth:`has` first)."""
        return parts_settings(self._design)

    @cached_property
    def train(self):
        """``[train]`` (:class:`geargen.design.train.TrainSettings`; absent: every default)."""
        return train_settings(self._design)

    @cached_property
    def stiffness(self):
        """The stiffness-step sections (:class:`geargen.design.stiffness.StiffnessDesign`)."""
        return stiffness_design(self._design)

    @cached_property
    def drive_train(self):
        """The train ``[stiffness] train`` names (:func:`geargen.core.stiffness.drive_train`; None
        for a custom train)."""
        return drive_train(self._design, self.stiffness.stiffness)

    @cached_property
    def stiffness_inputs(self):
        """What the stiffness summary reads (:class:`geargen.core.stiffness.StiffnessInputs`); refused
        without ``[preload]`` or a drive type (ask :meth:`has` first)."""
        return stiffness_inputs(self._design, self.stiffness)

    @cached_property
    def stages(self) -> tuple:
        """The upstream stages of ``[stages]`` (:func:`geargen.design.stages.stages`)."""
        return stages(self._design)

    @cached_property
    def duty(self):
        """``[duty]`` (:class:`geargen.design.duty.DutySpec`; absent: every default)."""
        return duty_settings(self._design)

    @cached_property
    def materials(self) -> dict[str, Any]:
        """Gear name -> its ISO 6336-5 material (:func:`geargen.design.duty.gear_materials`)."""
        return gear_materials(self._design, self.duty)

    def rated_material(self, gear: str):
        """The ISO 6336-5 material the design's rating names for ``gear`` (its [materials.GEAR] table
        or a [duty] material key), or None where the design names none (geargen's default is not a
        designer's choice to put on a drawing)."""
        if gear not in self._rated:
            named = gear in self._design.section("materials") or "material" not in self.duty.defaulted
            self._rated[gear] = self.materials.get(gear) if named else None
        return self._rated[gear]

    def gives_errors(self, gear: str) -> bool:
        """Whether ``[errors]`` gives a budget of its own for ``gear``."""
        return bool(self._design.section("errors").get(gear))

    def gear_errors(self, gear: str):
        """One gear's error budget (:func:`geargen.core.accuracy.gear_errors`; None: none given)."""
        if gear not in self._errors:
            self._errors[gear] = gear_errors(self._design, gear)
        return self._errors[gear]



@dataclass(frozen=True)
class GearPlacement:
    """One toothed part of the assembly (a gear, or a one-piece cluster), placed (mm, rad)."""

    name: str
    spec: GearSpec | ClusterSpec
    centre: tuple[float, float]
    z: float
    rotation: float
    group: str = "gears"
    roles: tuple[str, ...] = ()

    @property
    def gears(self) -> tuple[GearSpec, ...]:
        """The toothed bodies of the part: one gear, or a cluster's large and small gear."""
        if isinstance(self.spec, ClusterSpec):
            return (self.spec.large, self.spec.small)
        return (self.spec,)

    def face_z(self, gear: GearSpec) -> tuple[float, float]:
        """World z range of the toothed face of ``gear`` (one of :attr:`gears`)."""
        if isinstance(self.spec, ClusterSpec) and gear is self.spec.small:
            z0 = self.z + self.spec.small_gear_z
            return z0, z0 + gear.face_width
        return self.z, self.z + gear.face_width

    def rotation_at(self, gear: GearSpec, z: float) -> float:
        """Rotation of ``gear``'s transverse section at world height ``z`` (tooth 0 centreline)."""
        z0 = self.face_z(gear)[0]
        form = tooth_form(gear)
        if form is not None and form.curvature == 0:  # straight flanks: a rack's section slides
            if gear.is_helical:  # a helical rack's section slides along it: no rotation to give
                raise ValueError(f"{self.name}: a helical rack's section is not a rotation")
            return self.rotation
        return self.rotation + section_rotation(gear, z - z0)

    @property
    def height(self) -> tuple[float, float]:
        lo = min(self.face_z(g)[0] for g in self.gears)
        hi = max(self.face_z(g)[1] for g in self.gears)
        return lo, hi


@dataclass(frozen=True)
class MeshPlacement:
    """One mesh to check: gear 1 (turned by the checker) and gear 2 (held), their placements.

    ``plane`` is the world height of the checked transverse section (the middle of the faces'
    overlap); ``backlash_min``/``backlash_max`` the design range of the circumferential backlash
    (mm, transverse, at the reference pitch circles, positive clearance); ``modelled_backlash``
    what the modelled teeth give where the mesh runs (at ``centre_distance``, the distance of
    the placed centres), in the same kind. ``engaged`` False: the pinions are slid out of this
    mesh (disengaged position), only their axial clearance is checked.
    """

    name: str
    part1: str
    gear1: GearSpec
    part2: str
    gear2: GearSpec
    plane: float
    backlash_min: float
    backlash_max: float
    modelled_backlash: float
    engaged: bool = True
    working_flank: str = ""
    centre_distance: float = math.nan
    # the design-file keys of the backlash range, without their unit suffix (min, max), and the centre
    # distance its gears' tooth-thickness allowances are taken at: where the mesh runs with its gears
    # made at the middle of their allowances (NaN: where it is placed; a dual pinion's carriage mesh
    # placed with other teeth runs elsewhere: geargen.model.allowance)
    range_keys: tuple[str, str] = ("", "")
    allowance_centre_distance: float = math.nan


@dataclass(frozen=True)
class Layout:
    """The resolved drive: where every gear is, its teeth as modelled, and what each mesh must
    satisfy (mm, rad). Immutable: every command reads the same one (see the module docstring).

    ``thinning``: per gear part name, the circumferential tooth thinning at the reference circle
    the solids are built with (mm) and where it comes from (``"design"``, or the point of its
    allowance: :func:`geargen.model.allowance.model_source`). ``placement``: the synthesis' placement of the modelled gears
    (:class:`geargen.core.synthesis.Placement`) for a dual-pinion drive.
    """

    design: Design
    kind: str
    gears: tuple[GearPlacement, ...]
    meshes: tuple[MeshPlacement, ...]
    position: str = "engaged"
    synthesis: Any = None  # geargen.model.synthesis.SynthesisRun for a dual-pinion drive
    carriage_x: float | None = None
    carriage_travel: float | None = None
    engagement: Any = None  # geargen.core.flexures.HelicalEngagement when the pinions slide
    axial_shift: dict[str, float] = field(default_factory=dict)  # part -> slide along +z (disengaged)
    ratio: dict[str, Any] = field(default_factory=dict)
    notes: tuple[str, ...] = ()
    settings: dict[str, Any] = field(default_factory=dict)
    placement: Any = None
    thinning: dict[str, dict[str, Any]] = field(default_factory=dict)
    # what a drive kind placed by its own module reports about itself (mm, rad, N; e.g. the axial
    # preload's slide, spring force and stiffnesses): written beside every export, in internal units
    drive_report: dict[str, Any] = field(default_factory=dict)
    # the non-gear parts and every joint (geargen.model.components.Hardware), laid out by the
    # drive kind's hardware when the drive is resolved (geargen.drives.resolver); None: no hardware
    hardware: Any = None
    # the drive kind (geargen.drives.kind.DriveKind): what the verdict and the reports ask of it
    drive: Any = field(default=None, compare=False, repr=False)
    # the design's name, path and units (geargen.design.resolved), and its settings read once: what
    # every module downstream of the resolution reads instead of the design; made from ``design``
    # when the Layout is made (a replace() carries them)
    identity: DesignIdentity = field(default=None, compare=False, repr=False)
    resolved: ResolvedSettings = field(default=None, compare=False, repr=False)

    def __post_init__(self) -> None:
        if self.identity is None:
            object.__setattr__(self, "identity", identity_of(self.design))
        if self.resolved is None:
            object.__setattr__(self, "resolved", ResolvedSettings(self.design))

    def gear(self, name: str) -> GearPlacement:
        for g in self.gears:
            if g.name == name:
                return g
        raise KeyError(name)

    def mesh(self, name: str) -> MeshPlacement:
        for m in self.meshes:
            if m.name == name:
                return m
        raise KeyError(name)

    def to_dict(self) -> dict[str, Any]:
        """The resolved values in the design's length unit (angles in rad and deg): what is
        written beside every export and what every command reports."""
        unit = self.identity.length_unit
        k = 1.0 / LENGTH_SUFFIXES[unit]
        gears = []
        for g in self.gears:
            gears.append({"name": g.name, "centre": [g.centre[0] * k, g.centre[1] * k], "z": g.z * k,
                          "rotation_rad": g.rotation, "rotation_deg": math.degrees(g.rotation),
                          "teeth": [b.teeth for b in g.gears],
                          "thinning_circumferential": [b.thinning * k for b in g.gears],
                          "thinning_source": self.thinning.get(g.name, {}).get("source", "design")})
        meshes = []
        for m in self.meshes:
            meshes.append({"name": m.name, "gear1": m.part1, "gear2": m.part2, "engaged": m.engaged,
                           "centre_distance": m.centre_distance * k,
                           "backlash": m.modelled_backlash * k,
                           "backlash_design_min": m.backlash_min * k, "backlash_design_max": m.backlash_max * k,
                           "working_flank": m.working_flank, "plane_z": m.plane * k})
        return {"length_unit": unit, "kind": self.kind, "position": self.position,
                "backlash_kind": BACKLASH_KIND,
                "rotation_convention": "tooth 0 centreline of the gear's section at its own z = 0 face, "
                                       "CCW from +x about the gear's centre",
                "loaded_flank_gap": (self.settings.get("loaded_flank_gap") or 0.0) * k,
                "carriage_x": None if self.carriage_x is None else self.carriage_x * k,
                "gears": gears, "meshes": meshes, "notes": list(self.notes),
                "defaulted": {d.key: d.value for d in self.identity.defaulted},
                **({"drive_report (mm, rad, N, N mm)": self.drive_report} if self.drive_report else {}),
                **({"hardware": self.hardware.to_dict(1.0 / k)} if self.hardware is not None else {})}


#: the one kind of backlash the resolved model, the checks' design range and the reports share
BACKLASH_KIND = "circumferential, transverse, at the reference pitch circle of gear 1 (j_bt / cos alpha_t)"


def layout_settings(design: Design) -> dict[str, Any]:
    """``[layout]`` validated (:func:`geargen.design.layout.layout_settings`; internal units)."""
    from geargen.design.layout import layout_settings as read
    return read(design)


def modelled_backlash(lo: float, hi: float, point: str) -> float:
    """The backlash of the range [``lo``, ``hi``] that a mesh's ``model_tooth_thickness`` point
    gives where no tooth thickness sets it (a rack mesh's, set by the pinion's height): the most
    material the least backlash; "as_designed" takes the middle."""
    w = MODEL_POINTS.get(point, MODEL_POINTS["mid_tolerance"])[0]
    return w * lo + (1 - w) * hi


def ratio_check(design: Design, settings: dict, train_ratio: Fraction, what: str) -> dict[str, Any]:
    """The exact ratio from encoder to output: the upstream stages (the gears of ``[stages]``, or
    ``[layout] upstream_stages`` as driver and driven teeth) times the train."""
    total = Fraction(train_ratio)
    described = []
    from geargen.design.stages import stages
    stage_list = stages(design)
    for st in stage_list:
        total *= st.ratio(design.gears)
        if st.kind == "planetary":  # ring fixed, sun in, carrier out
            described.append(f"(1 + {design.gear(st.ring).teeth}/{design.gear(st.sun).teeth})")
        else:
            described.append(f"{design.gear(st.driven).teeth}/{design.gear(st.driver).teeth}")
    for driver, driven in () if stage_list else settings["upstream_stages"]:
        total *= Fraction(driven, driver)
        described.append(f"{driven}/{driver}")
    required = settings["required_ratios"]
    ok = (not required) or any(total == Fraction(r) for r in required)
    text = " x ".join(described + [f"{train_ratio}"]) + f" = {total}"
    return {"train": train_ratio, "total": total, "required": list(required), "ok": ok,
            "text": text, "what": what}


def is_drive(design: Design) -> bool:
    """Whether the design describes a drive to resolve (a [layout] or a [synthesis]); a design
    without either only declares gear pairs to check ([checks] meshes) or a gear."""
    return bool(design.section("layout") or design.section("synthesis"))


def running_backlash(a: GearSpec, b: GearSpec, centre_distance: float) -> float:
    """Backlash of the modelled gears ``a`` (gear 1) and ``b`` at ``centre_distance`` (mm), in
    the kind of :data:`BACKLASH_KIND`: from their tooth-thickness deficit at the reference circle
    and the change of the working pressure angle with the centre distance."""
    from geargen.core.synthesis import backlash_from_thickness_deficit
    deficit = a.transverse_pitch - reference_tooth_thickness(a) - reference_tooth_thickness(b)
    standard = (a.teeth + b.teeth) * a.transverse_module / 2
    return float(backlash_from_thickness_deficit(deficit, centre_distance, standard, a.transverse_pressure_angle))


__all__ = ["ResolvedSettings", "MODEL_TOOTH_THICKNESS", "POSITIONS", "BACKLASH_KIND", "GearPlacement", "MeshPlacement", "Layout",
           "layout_settings", "is_drive", "running_backlash", "modelled_backlash", "ratio_check"]
