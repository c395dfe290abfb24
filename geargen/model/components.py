"""The parts of a resolved drive and the joints between them, as data.

A :class:`Component` is one part: its body (:class:`geargen.model.bodies.Body`, or a toothed
part's spec), where it stands (a 4x4 placement, mm, into the drive's frame), the sub-assembly it
belongs to and how it moves. A :class:`Joint` says how two parts meet: ``fixed`` (pressed,
clamped, bolted, seated: one rigid body), ``bearing`` (a bearing ring on its shaft or in its
seat), ``sliding`` (a fit that slides), ``flexure`` (a blade clamped at its ends), ``spring``
(a spring on its seat), ``motor`` (a motor's stator and rotor), ``rolling`` (two parts that roll
on each other) and ``mesh`` (two toothed parts in mesh: checked by the mesh checkers, not as a
contact). Every joint but a mesh is a contact the solids must show.

The drive kinds lay their hardware out into a :class:`ComponentSet` (:mod:`geargen.drives`); the
CAD layer builds each component's body (:mod:`geargen.cad.components`), the hardware check reads
the same bodies analytically (:mod:`geargen.checks.hardware`), the structure check reads the
joints, and the train reads the bodies' mass properties. Pure data: no kernel.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from geargen.families.bevel.geometry import flat_back_envelope
from geargen.model.bodies import Body, describe, fuse, revolve, world_box

#: the joint kinds (see the module docstring)
JOINT_KINDS = ("fixed", "bearing", "sliding", "flexure", "spring", "motor", "rolling", "mesh")

#: colours (r, g, b, alpha) by component kind, for the STEP, the render and the review page
COLOURS: dict[str, tuple[float, float, float, float]] = {
    "gear": (0.72, 0.74, 0.78, 1.0),
    "gear_output": (0.55, 0.60, 0.70, 1.0),
    "gear_input": (0.85, 0.65, 0.30, 1.0),
    "gear_cluster": (0.45, 0.62, 0.80, 1.0),
    "bevel": (0.80, 0.55, 0.25, 1.0),
    "shaft": (0.35, 0.35, 0.38, 1.0),
    "bearing": (0.20, 0.45, 0.30, 1.0),
    "motor": (0.12, 0.12, 0.14, 1.0),
    "carriage": (0.78, 0.80, 0.84, 1.0),
    "flexure": (0.25, 0.35, 0.75, 1.0),
    "spring": (0.90, 0.78, 0.15, 1.0),
    "reference": (0.70, 0.70, 0.72, 0.25),
    "stop": (0.80, 0.20, 0.20, 1.0),
    "friction": (0.85, 0.35, 0.10, 1.0),
    "housing": (0.62, 0.64, 0.60, 0.35),
    "quill": (0.50, 0.54, 0.60, 1.0),
}


def transform(translate=(0.0, 0.0, 0.0), axis=(0.0, 0.0, 1.0), angle: float = 0.0) -> np.ndarray:
    """4x4 placement: a rotation by ``angle`` (rad) about ``axis`` through the origin, then a translation."""
    a = np.asarray(axis, dtype=float)
    a = a / np.linalg.norm(a)
    c, s = math.cos(angle), math.sin(angle)
    k = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    r = np.eye(3) * c + s * k + (1 - c) * np.outer(a, a)
    m = np.eye(4)
    m[:3, :3] = r
    m[:3, 3] = translate
    return m


def at(x=0.0, y=0.0, z=0.0) -> np.ndarray:
    """The placement of a part translated to (x, y, z)."""
    return transform((x, y, z))


def along_x(x, y, z, towards_minus: bool = False) -> np.ndarray:
    """Local +z along world +x (or -x), local origin at (x, y, z)."""
    return transform((x, y, z), (0, 1, 0), -math.pi / 2 if towards_minus else math.pi / 2)


@dataclass(frozen=True)
class Toothed:
    """A toothed part of a drive's hardware, made by its family: ``spec`` (a bevel gear of the motor
    drive), and its ``back``: "flat" for a bevel gear cut flat through its heel root circle
    (:func:`geargen.families.bevel.geometry.bevel_core`), "spherical" for the heel sphere."""

    spec: Any
    back: str = "spherical"


@dataclass(frozen=True, eq=False)
class Component:
    """One part of the drive (mm): ``body`` in its own frame (a :class:`Body`, or for a toothed
    part its spec: :attr:`toothed`), ``placement`` (4, 4) into the drive's frame.

    ``group`` is the sub-assembly (the STEP tree), ``kind`` a colour key of :data:`COLOURS`,
    ``role`` what it is for the report ("gear", "reference", ...). ``shared``: parts with equal
    bodies that are the same article (two bearings alike) share one solid, which the assembly
    STEP writes as one product. ``envelope``: a simple body holding the part (a spring's tube),
    the overlap checks' first test. ``toothed``: a gear made by its family (a bevel gear of the
    motor drive: its spec and the back it is cut with)."""

    name: str
    body: Body | None
    placement: np.ndarray
    group: str
    kind: str
    role: str = "part"
    description: str = ""
    shared: bool = False
    envelope: Body | None = None
    toothed: Any = None

    @property
    def colour(self) -> tuple[float, float, float, float]:
        return COLOURS.get(self.kind, COLOURS["gear"])

    def to_dict(self, scale: float = 1.0) -> dict[str, Any]:
        """The component for ``resolved.json`` (lengths divided by ``scale``: the design's unit)."""
        m = np.array(self.placement, dtype=float).copy()
        m[:3, 3] /= scale
        return {"name": self.name, "group": self.group, "kind": self.kind, "role": self.role,
                "description": self.description,
                "body (mm)": describe(self.body) if self.body is not None else None,
                "toothed": None if self.toothed is None else getattr(self.toothed, "name", str(self.toothed)),
                "placement": m.round(12).tolist()}


@dataclass(frozen=True)
class Joint:
    """How two parts meet (:data:`JOINT_KINDS`), and why."""

    a: str
    b: str
    kind: str
    why: str


@dataclass
class ComponentSet:
    """Collects a drive's non-gear parts and joints while its hardware lays them out; also how
    they hold together: held by the machine (``ground``; or supported outside the model),
    never turning (``stationary``), turning besides the gears (``rotating``)."""

    components: list[Component] = field(default_factory=list)
    joints: list[Joint] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    dimensions: dict[str, Any] = field(default_factory=dict)
    ground: list[str] = field(default_factory=list)
    stationary: list[str] = field(default_factory=list)
    rotating: list[str] = field(default_factory=list)
    # hardware keys the file left out whose default the layout sized from the placed drive:
    # (design key, value in mm, why)
    defaults: list[tuple[str, float, str]] = field(default_factory=list)
    # part -> (design key, value in mm, what it does): a value of the designer's that the layout
    # found moves the part clear of what it would run into (offered with an overlap)
    fixes: dict[str, tuple[str, float, str]] = field(default_factory=dict)

    def add(self, name: str, body: Body | None, placement: np.ndarray, group: str, kind: str, role: str = "part",
            description: str = "", shared: bool = False, envelope: Body | None = None, toothed=None) -> str:
        if any(c.name == name for c in self.components):
            raise ValueError(f"two parts named {name!r}")
        self.components.append(Component(name, body, np.asarray(placement, dtype=float), group, kind, role,
                                         description, shared, envelope, toothed))
        return name

    def join(self, a: str, b: str, why: str, kind: str = "fixed") -> None:
        if kind not in JOINT_KINDS:
            raise ValueError(f"joint kind {kind!r}")
        self.joints.append(Joint(a, b, kind, why))

    def component(self, name: str) -> Component:
        for c in self.components:
            if c.name == name:
                return c
        raise KeyError(name)

    def world_box(self, name: str) -> tuple[np.ndarray, np.ndarray]:
        """The axis-aligned box (world, mm) holding component ``name`` (its body's box, placed)."""
        c = self.component(name)
        return placed_box(c.body, c.placement)

    def freeze(self) -> "Hardware":
        fixed = [g for g in self.ground if g not in self.rotating] + self.stationary  # a spindle turns
        return Hardware(tuple(self.components), tuple(self.joints), tuple(self.notes), dict(self.dimensions),
                        tuple(dict.fromkeys(self.ground)), tuple(dict.fromkeys(fixed)),
                        tuple(dict.fromkeys(self.rotating)), tuple(self.defaults), dict(self.fixes))


def analytic_body(component: Component) -> Body:
    """The body the analytic readers use for ``component``: its own, or for a toothed part its
    family's envelope (a flat-backed bevel gear: :func:`geargen.families.bevel.geometry.flat_back_envelope`)."""
    if component.body is not None:
        return component.body
    return toothed_envelope(component.toothed)


def toothed_envelope(toothed: Toothed) -> Body:
    """The revolved envelope of a toothed hardware part (see :func:`analytic_body`)."""
    if toothed.back != "flat":
        raise ValueError(f"no envelope of a {toothed.back!r}-backed toothed part")
    return fuse([revolve(p) for p in flat_back_envelope(toothed.spec)], toothed.spec.name)


def placed_box(body: Body, placement: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The world axis-aligned box of ``body`` placed by ``placement`` (:func:`geargen.model.bodies.world_box`)."""
    return world_box(body, placement)


@dataclass(frozen=True)
class Hardware:
    """The non-gear parts of a resolved drive and the joints among all its parts (gears included),
    frozen (:meth:`ComponentSet.freeze`)."""

    components: tuple[Component, ...] = ()
    joints: tuple[Joint, ...] = ()
    notes: tuple[str, ...] = ()
    dimensions: dict[str, Any] = field(default_factory=dict)
    ground: tuple[str, ...] = ()
    stationary: tuple[str, ...] = ()
    rotating: tuple[str, ...] = ()
    defaults: tuple[tuple[str, float, str], ...] = ()
    fixes: dict[str, tuple[str, float, str]] = field(default_factory=dict)

    def component(self, name: str) -> Component:
        for c in self.components:
            if c.name == name:
                return c
        raise KeyError(name)

    @property
    def contacts(self) -> list[tuple[str, str, str]]:
        """Every joint the solids must show as a contact (all but meshes): (part, part, why)."""
        return [(j.a, j.b, j.why) for j in self.joints if j.kind != "mesh"]

    @property
    def rolling(self) -> tuple[tuple[str, str], ...]:
        """Pairs that roll on each other (meshes among them): they hold nothing together."""
        return tuple((j.a, j.b) for j in self.joints if j.kind in ("rolling", "mesh"))

    @property
    def meshing(self) -> tuple[tuple[str, str, str], ...]:
        return tuple((j.a, j.b, j.why) for j in self.joints if j.kind == "mesh")

    def to_dict(self, scale: float = 1.0) -> dict[str, Any]:
        return {"components": [c.to_dict(scale) for c in self.components],
                "joints": [{"a": j.a, "b": j.b, "kind": j.kind, "why": j.why} for j in self.joints],
                "ground": list(self.ground), "stationary": list(self.stationary), "rotating": list(self.rotating),
                "defaults": [{"key": k, "value": v / scale, "why": why} for k, v, why in self.defaults],
                "fixes": {part: {"key": k, "value": v / scale, "why": why} for part, (k, v, why) in self.fixes.items()}}


__all__ = ["Toothed", "JOINT_KINDS", "COLOURS", "transform", "at", "along_x", "Component", "Joint", "ComponentSet",
           "Hardware", "placed_box", "analytic_body", "toothed_envelope"]
