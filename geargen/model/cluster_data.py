"""A cluster gear's data (``drawings/NAME.json`` of the build): the two gears of one cluster as the
part is made, their shared bore, axial layout, and the angular relation between their teeth with
its tolerance. Lengths in the design's length unit, angles in degrees.

A cluster is found in the resolved drive by its placements' roles: a one-piece cluster is one
placement holding both gears (:class:`geargen.design.cluster.ClusterSpec`, roles ``cluster_large``
and ``cluster_small``); a cluster made of two parts (the large gear pressed and bonded on the small
gear's shaft) is two placements of one ``group`` with those roles. Identical clusters (both paths'
clusters) are one article, one data set.

The tooth phase is read from the placed model, never recomputed: the rotation of the small gear's
tooth 0 at its lowest face (its placement's :meth:`~geargen.model.layout.GearPlacement.rotation_at`,
plus a one-piece cluster's ``relative_phase``, by which its solid turns the small gear) less the large
gear's tooth 0 at its lowest face, reduced to the nearest small-gear tooth: (-p/2, p/2] with p the
small gear's angular pitch, counter-clockwise about the axis seen from the small gear's end.

Tolerance of the phase: a phase error delta of one cluster changes its path's lost motion by delta
(at the cluster), as a backlash change of delta r at either of the cluster's meshes (r the gear's
reference radius there); each path's backlash may lie anywhere in its mesh's design range
[j_min, j_max], so the two paths may differ by j_max - j_min. Two clusters each within +/- T differ
by up to 2 T: T = min over the cluster's meshes of (j_max - j_min) / (2 r).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from geargen.design.cluster import ClusterSpec
from geargen.units import from_mm

LARGE, SMALL = "cluster_large", "cluster_small"


@dataclass(frozen=True)
class PlacedCluster:
    """One cluster of the drive: its name (the article's), the placements of its large and small gear
    (the same placement for a one-piece cluster) and the two gears' specs."""

    name: str
    large_placement: object
    small_placement: object
    large: object
    small: object

    @property
    def one_piece(self) -> bool:
        return self.large_placement is self.small_placement


def _article_name(large_name: str, small_name: str) -> str:
    common = ""
    for a, b in zip(large_name, small_name):
        if a != b:
            break
        common += a
    return common.rstrip("_-.") or f"{large_name}_{small_name}"


def drive_clusters(layout) -> list[PlacedCluster]:
    """Every distinct cluster article of the resolved drive (the first of identical ones)."""
    out, seen = [], set()
    groups: dict[str, dict[str, object]] = {}
    for placed in layout.gears:
        if isinstance(placed.spec, ClusterSpec):
            key = (placed.spec.large.name, placed.spec.small.name)
            if key not in seen:
                seen.add(key)
                out.append(PlacedCluster(placed.spec.name, placed, placed, placed.spec.large, placed.spec.small))
            continue
        for role in placed.roles:
            if role in (LARGE, SMALL):
                groups.setdefault(placed.group, {})[role] = placed
    for members in groups.values():
        if LARGE in members and SMALL in members:
            large, small = members[LARGE].spec, members[SMALL].spec
            if (large.name, small.name) not in seen:
                seen.add((large.name, small.name))
                out.append(PlacedCluster(_article_name(large.name, small.name), members[LARGE], members[SMALL],
                                         large, small))
    return out


def tooth_phase(cluster: PlacedCluster) -> tuple[float, float]:
    """(phase as placed, phase reduced to the nearest small-gear tooth) in rad (module docstring)."""
    large_at = cluster.large_placement.rotation_at(cluster.large, cluster.large_placement.face_z(cluster.large)[0])
    small_at = cluster.small_placement.rotation_at(cluster.small, cluster.small_placement.face_z(cluster.small)[0])
    if cluster.one_piece:
        small_at += cluster.large_placement.spec.relative_phase
    raw = small_at - large_at
    pitch = 2 * math.pi / cluster.small.teeth
    reduced = raw - pitch * math.floor(raw / pitch + 0.5)
    return raw, reduced


def phase_tolerance(layout, cluster: PlacedCluster) -> tuple[float, str]:
    """+/- T (rad) and the mesh it comes from (module docstring); (nan, "") without an engaged mesh."""
    best, where = math.inf, ""
    for m in layout.meshes:
        if not m.engaged:
            continue
        for gear, other in ((m.gear1, m.gear2), (m.gear2, m.gear1)):
            if gear.name in (cluster.large.name, cluster.small.name) and other.name not in (cluster.large.name,
                                                                                            cluster.small.name):
                t = (m.backlash_max - m.backlash_min) / (2 * gear.reference_radius)
                if t < best:
                    best, where = t, f"{m.name} ({gear.name} with {other.name})"
    return (best, where) if math.isfinite(best) else (math.nan, "")


def _gear_block(spec, unit: str) -> dict:
    def L(v):
        return float(from_mm(v, unit))
    return {"name": spec.name, "teeth": spec.teeth, "normal_module_mm": spec.module,
            "normal_pressure_angle_deg": math.degrees(spec.pressure_angle),
            "helix_angle_deg": math.degrees(spec.helix_angle), "hand": spec.hand if spec.is_helical else None,
            "profile_shift_normal": spec.profile_shift, "reference_diameter": L(2 * spec.reference_radius),
            "tip_diameter": L(2 * spec.tip_radius), "face_width": L(spec.face_width),
            "tooth_data_drawing": f"{spec.name}-drawing.svg"}


def cluster_data(layout, cluster: PlacedCluster) -> dict:
    """The cluster's data dict (module docstring)."""
    unit = layout.identity.length_unit
    large, small = cluster.large, cluster.small

    def L(v):
        return float(from_mm(v, unit))

    z_large = cluster.large_placement.face_z(large)
    z_small = cluster.small_placement.face_z(small)
    raw, reduced = tooth_phase(cluster)
    tol, where = phase_tolerance(layout, cluster)
    hub = large.hub
    return {
        "name": cluster.name, "kind": "cluster", "length_unit": unit,
        "construction": "one piece" if cluster.one_piece else "two parts, bonded",
        "construction_note": None if cluster.one_piece else "the large gear pressed and bonded on the small gear's "
                                                            "shaft, its teeth phased to the small gear's as stated",
        "large": _gear_block(large, unit), "small": _gear_block(small, unit),
        # axial layout from the large gear's lower face (the part's datum face)
        "large_face": [0.0, L(z_large[1] - z_large[0])],
        "small_face": [L(z_small[0] - z_large[0]), L(z_small[1] - z_large[0])],
        "axial_gap": L(z_small[0] - z_large[1]),
        "overall_length": L(max(z_large[1], z_small[1]) - min(z_large[0], z_small[0])),
        "spacer_diameter": (L(cluster.large_placement.spec.spacer_diameter_resolved)
                            if cluster.one_piece and cluster.large_placement.spec.axial_gap > 0 else None),
        "bore_diameter": L(hub.bore_diameter) if hub.bore_diameter > 0 else None,
        "keyway": {"width": L(hub.keyway_width), "depth": L(hub.keyway_depth)} if hub.keyway_width > 0 else None,
        "tooth_phase_deg": math.degrees(reduced),
        "tooth_phase_as_placed_deg": math.degrees(raw),
        "tooth_phase_definition": "angle from the centre of a large-gear tooth (tooth 0, at the large gear's lower "
                                  "face) to the nearest small-gear tooth centre (at the small gear's lower face), "
                                  "counter-clockwise seen from the small gear's end",
        "tooth_phase_tolerance_deg": None if math.isnan(tol) else math.degrees(tol),
        "tooth_phase_tolerance_arc_small": None if math.isnan(tol) else L(tol * small.reference_radius),
        "tooth_phase_tolerance_source": (f"+/- (j_max - j_min) / (2 r) of {where}: two clusters within it differ by "
                                         "at most the mesh's design backlash range" if where else "no engaged mesh"),
    }


__all__ = ["PlacedCluster", "drive_clusters", "tooth_phase", "phase_tolerance", "cluster_data"]
