"""How the parts of an assembly hold together: connectivity to ground, checked from the contacts.

The build verifies on the solids that every listed contact exists (faces within a micrometre)
and that no other pair shares volume (:func:`geargen.cad.assembly.pairwise_overlaps`). This
module reads those contacts as a graph and checks what they mean:

* every part reaches the ground (the structure fixed to the machine, or a part whose supports
  lie outside the model, such as a spindle) through contacts; a mesh holds nothing up;
* parts joined by plain contacts (pressed, clamped, bolted) form one rigid body; the joint
  elements (bearings, blade flexures, springs, motors: stator against rotor) let the parts on
  their two sides move, so they do not join bodies. A body that carries a gear rotates, and
  must not contain a stationary part (the ground, a carriage, a housing): rotating parts touch
  stationary ones only through joint elements;
* a joint element that touches a single body joins nothing: a bearing on its shaft with no
  seat supports nothing.

Pure graph code (no CAD kernel); :func:`geargen.pipeline.structure_check` feeds it the built
assembly's parts and verified contacts.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Iterable, Mapping

#: part kinds whose two sides may move against each other
JOINT_KINDS = ("bearing", "flexure", "spring", "motor")


@dataclass(frozen=True)
class StructureReport:
    """The findings of :func:`structure_check` (part names)."""

    bodies: tuple[tuple[str, ...], ...]  # rigid bodies, each sorted
    ungrounded: tuple[str, ...]  # parts that reach no ground through contacts
    rotating_on_stationary: tuple[tuple[str, str], ...]  # (rotating part, stationary part) in one body
    one_sided: tuple[tuple[str, tuple[str, ...]], ...]  # joint element, the parts (of one body) it touches

    @property
    def failures(self) -> list[str]:
        out = []
        if self.ungrounded:
            out.append("not connected to the ground through any contact: " + ", ".join(self.ungrounded))
        for rot, fixed in self.rotating_on_stationary:
            out.append(f"{rot} rotates, but a rigid contact joins it to the stationary {fixed} (no bearing between)")
        for joint, body in self.one_sided:
            out.append(f"{joint} touches only {', '.join(body)}: it joins nothing to anything (no seat on its other side)")
        return out

    def to_dict(self) -> dict:
        return {"bodies": [list(b) for b in self.bodies], "ungrounded": list(self.ungrounded),
                "rotating_on_stationary": [list(p) for p in self.rotating_on_stationary],
                "one_sided": [[j, list(b)] for j, b in self.one_sided], "failures": self.failures}


def structure_check(kinds: Mapping[str, str], contacts: Iterable[tuple[str, str]], ground: Iterable[str],
                    stationary: Iterable[str], rotating: Iterable[str]) -> StructureReport:
    """Check the assembly whose parts have ``kinds`` (name -> kind; :data:`JOINT_KINDS` are joint
    elements) and touch as ``contacts`` (pairs of names). ``ground``: parts held by the machine;
    ``stationary``: parts that must not turn (ground, carriages, housings); ``rotating``: parts
    that turn (the gears)."""
    names = sorted(kinds)
    known = set(names)
    pairs = [(a, b) for a, b in contacts if a in known and b in known and a != b]
    neighbours: dict[str, set[str]] = {n: set() for n in names}
    for a, b in pairs:
        neighbours[a].add(b)
        neighbours[b].add(a)

    # reach from the ground through any contact
    reached = set(g for g in ground if g in known)
    todo = list(reached)
    while todo:
        for m in neighbours[todo.pop()]:
            if m not in reached:
                reached.add(m)
                todo.append(m)
    ungrounded = tuple(n for n in names if n not in reached)

    # rigid bodies: union of plain contacts, joint elements each a body of their own
    parent = {n: n for n in names}

    def find(n):
        while parent[n] != n:
            parent[n] = parent[parent[n]]
            n = parent[n]
        return n

    for a, b in pairs:
        if kinds[a] not in JOINT_KINDS and kinds[b] not in JOINT_KINDS:
            parent[find(a)] = find(b)
    members: dict[str, list[str]] = {}
    for n in names:
        members.setdefault(find(n), []).append(n)
    bodies = tuple(sorted(tuple(sorted(m)) for m in members.values()))

    turning, still = set(rotating) & known, set(stationary) & known
    clashes = []
    for body in bodies:
        rot = [n for n in body if n in turning]
        fixed = [n for n in body if n in still]
        if rot and fixed:
            clashes.append((rot[0], fixed[0]))

    one_sided = []
    for n in names:
        if kinds[n] in JOINT_KINDS:
            if len({find(m) for m in neighbours[n]}) < 2:
                one_sided.append((n, tuple(sorted(neighbours[n]))))
    return StructureReport(bodies, ungrounded, tuple(clashes), tuple(one_sided))


def drive_structure(layout) -> StructureReport:
    """:func:`structure_check` of a resolved drive: its gears and hardware components, joined by
    the hardware's joints (meshes and rolling pairs hold nothing together); the gears turn, a
    planetary ring excepted (it is held)."""
    hardware = layout.hardware
    rolling = {frozenset(p) for p in hardware.rolling}
    contacts = [(a, b) for a, b, _ in hardware.contacts if frozenset((a, b)) not in rolling]
    rotating = [g.name for g in layout.gears if "planetary_ring" not in g.roles] + list(hardware.rotating)
    kinds = {g.name: "gear" for g in layout.gears} | {c.name: c.kind for c in hardware.components}
    return structure_check(kinds, contacts, hardware.ground, hardware.stationary, rotating)


__all__ = ["JOINT_KINDS", "StructureReport", "structure_check", "drive_structure"]
