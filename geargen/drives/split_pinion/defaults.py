"""The split pinion's default hardware: its [parts] sized from the pinions, the output and what the file gives.

Every [parts] key of a split pinion may be left out, or the whole table; each is sized by the
rule below from the gears' bores and faces and from the [parts] values the file does give.
Lengths are rounded up to 0.5 mm (1/32 in); an inch design takes the inch values in brackets and
inch bearings.

- `bearing_clearance`: 0.5 mm (0.02 in) between a bearing and a gear face;
- `hollow_shaft_outer_diameter`: the stiff pinion's bore (the hollow shaft fills it);
  `output_shaft_diameter`: the output's bore;
- `bearing_outer_diameter`, `bearing_width` (the pair on the hollow shaft),
  `compliant_bearing_*` (over the compliant pinion) and `output_bearing_*`: the ISO 15 series 19
  bearing (inch: ABMA R series) whose bore is the shaft's; a bore that is no standard one needs
  its bearing given (the refusal names the key and the standard bores);
- `bearing_spacing`: three times the stiff pinion's overhang beyond the upper bearing of the pair
  (half a bearing, a clearance and half the pinion's face): a base three times the overhang;
- `hollow_shaft_length`: the inner shaft twists over ten of its diameters (the compliant pinion's
  bore) from the collar to the compliant pinion, the loop's soft spring; at least through the
  stiff pinion, the bearing pair and a clearance below it;
- `collar_outer_diameter`: 1.75 hollow-shaft diameters; `collar_width`: 1.5 inner-shaft
  diameters (the clamp's grip); `collar_slot`: 1.5 mm (1/16 in), a saw cut;
- `housing_margin`: 5 mm (0.2 in) of plate around the outermost bearing seats.
"""

from __future__ import annotations

from typing import Any, Mapping

from geargen.design.catalogue import Readers, completing, put_bearing

#: the bearing series of every shaft: thin section, the pinions close to the output
SERIES = "19"
#: the inner shaft's twisting length over its diameter: the loop's soft spring
TWIST_DIAMETERS = 10.0


def complete(data: Mapping[str, Any], readers: Readers, fields: list) -> tuple[dict[str, Any], tuple]:
    """The module's rules on ``data`` (``fields``: the kind's [parts] fields): the file completed,
    and what was added (nothing where :func:`geargen.design.catalogue.completing` says so)."""
    start = completing(data, readers, fields, roles=("pinion_stiff", "pinion_compliant", "output"))
    if start is None:
        return dict(data), ()
    design, s, (stiff, compliant, output), c = start
    gap = c.stated("bearing_clearance", 0.5, 0.02, "0.5 mm (0.02 in) between a bearing and a gear face")
    d_hollow = c.length("hollow_shaft_outer_diameter", stiff.hub.bore_diameter,
                        f"the bore of gears.{stiff.name}, which the hollow shaft fills", exact=True)
    d_inner = compliant.hub.bore_diameter
    d_output = c.length("output_shaft_diameter", output.hub.bore_diameter, f"the bore of gears.{output.name}",
                        exact=True)
    _, width = put_bearing(c, c.unit, "bearing", d_hollow, SERIES, stiff.name, "the preloaded pair on the hollow shaft")
    put_bearing(c, c.unit, "compliant_bearing", d_inner, SERIES, compliant.name, "the inner shaft's outboard bearing")
    put_bearing(c, c.unit, "output_bearing", d_output, SERIES, output.name, "the output shaft's pair")
    overhang = width / 2 + gap + stiff.face_width / 2
    spacing = c.length("bearing_spacing", max(3 * overhang, width + gap), f"three times the stiff pinion's "
                       f"overhang of {c.shown(overhang)} beyond the upper bearing")
    through = stiff.face_width + gap + spacing + width + gap
    twist = TWIST_DIAMETERS * d_inner - s["pinion_axial_gap"]
    c.length("hollow_shaft_length", max(twist, through), f"the inner shaft twisting over {TWIST_DIAMETERS:g} of its "
             f"diameters (the loop's soft spring), at least through the stiff pinion and its bearing pair "
             f"({c.shown(through)})")
    c.length("collar_outer_diameter", 1.75 * d_hollow, "1.75 hollow-shaft diameters")
    c.length("collar_width", 1.5 * d_inner, "1.5 inner-shaft diameters: the clamp's grip")
    c.stated("collar_slot", 1.5, 0.0625, "1.5 mm (1/16 in): a saw cut")
    c.stated("housing_margin", 5.0, 0.2, "5 mm (0.2 in) of plate around the outermost bearing seats")
    return c.result()


__all__ = ["complete", "SERIES", "TWIST_DIAMETERS"]
