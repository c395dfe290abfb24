"""What a gear family provides (:class:`GearFamily`): the interface every layer calls, so that
none of them asks which family a gear is.

A family lives in ``geargen/families/<kind>/``, one file per layer role:

- ``spec.py`` (design): its spec and its ``[gear]`` table's keys;
- ``geometry.py`` (core): its closed-form geometry;
- ``solid.py`` (cad): its solid, the only file that imports the kernel;
- ``pair.py`` (checks): its pair check;
- ``data.py`` (model): its gear data (the JSON a ``geargen gear`` run writes);
- ``options.py`` (commands): its own ``geargen gear --kind <kind>`` options;
- ``drawing.py`` (report): its drawing sheets;
- ``family.py``: the module that is its :class:`GearFamily`, listed in :mod:`geargen.families.registry`.

``family.py`` imports its spec at its top and every other role inside the function that needs
it, so that reading a design table never loads the kernel or the drawing code. A family may reuse
another's files (the worm wheel reads the worm set's spec, data, options and drawing).
"""

from __future__ import annotations

from dataclasses import dataclass
from types import ModuleType
from typing import Any, Mapping, Protocol, Sequence


@dataclass(frozen=True)
class ToothForm:
    """What the cylindrical-gear layers (the ISO 6336 rating :mod:`geargen.core.load_capacity`, the
    mass, the mesh loads, the hardware clearance) see of a family's teeth, as data, so that they
    read it instead of asking the kind:

    - ``curvature``: the sign of the family's flank curvature as the mate of an external pinion:
      +1 convex (an external gear: 1/rho_red = 1/rho_1 + 1/rho_2, u = z_2/z_1), -1 concave (a ring:
      1/rho_red = 1/rho_1 - 1/rho_2, u = -z_2/z_1, its loaded flank faces the pinion's way), 0
      straight (a rack: rho_2 and u infinite). A gear that is not convex is rated at its root as a
      rack (z -> infinity, ISO 6336-3), has Z_D = 1 (ISO 6336-2), no finite mass in K_v and cannot
      be the pinion;
    - ``helices``: helices across the face (2: a double-helical gear, each half carrying b/2);
    - ``rim_outside_root``: its body is a rim outside its teeth (a ring: its section is the rim disc
      less the teeth's outline; ISO 6336-3's internal rim factor Y_B = 1.15 ln(8.324 m_n/s_R)); else
      its body is inside the root circle (Y_B = 1.6 ln(2.242 h_t/s_R));
    - ``root_note``: the sentence the rating adds when the family is gear 2 (None: none).
    """

    curvature: int
    helices: int = 1
    rim_outside_root: bool = False
    root_note: str | None = None


class GearFamily(Protocol):
    """A gear family (a ``family.py`` module satisfies it):

    - ``KIND``: the ``kind`` a ``[gear]`` table names it by (and its specs' ``kind``);
    - ``FIELDS``: the :class:`geargen.design.schema.Field` list of its table (validation, reference);
    - ``RATING_SCOPE``: None when ISO 6336 rates the family's load capacity, else the sentence naming
      the standard that would (:func:`geargen.core.load_capacity.rating_scope`);
    - ``TOOTH_FORM``: its :class:`ToothForm` (None: not a cylindrical involute form, bevel and worm);
    - ``read_table(data, where, name, length_unit)``: its spec from a design table, keys named
      ``where.KEY`` in errors (:func:`geargen.design.gear.gear_from_table`'s signature);
    - ``build(spec, check, tolerance)``: its solid (``shape``, ``name``, ``spec``, ``length_unit``);
      ``tolerance`` (mm) is the spline fit tolerance of a family fitted to a sampled tooth profile
      (None: its default), which a family with a fixed fit (rack, bevel, worm) does not take;
    - ``gear_data(spec)``: its gear data (a dict in its length unit, gear-data contract), or None when
      they come from the cylindrical gear's tooth profile (:func:`geargen.model.gear_data.gear_data`);
    - ``drawings(data, spec, folder, name, source, design_file)``: its sheets written,
      ``{"svg"|"pdf": path}``, or None when the cylindrical gear drawing
      (:func:`geargen.report.drawing.gear_drawings`) draws it;
    - ``toothed_mass(spec, back)``: (volume mm^3, axial moment mm^5, unit density) of the family's
      solid with ``back`` when a drive holds it as a toothed hardware part
      (:class:`geargen.model.components.Toothed`, :func:`geargen.model.mass.component_mass`), from
      its closed forms; None for a family no drive holds so;
    - ``options()``: the module of its own ``geargen gear`` options (``add_arguments(group)``,
      ``OPTIONS`` {dest: (flag, key stem, is a length)}, ``COMMON``: the common options it reads;
      ``with_allowance(spec, (upper_um, lower_um))`` when its spec carries the allowance
      ``--thickness-allowance`` enters, the rack's), or None when it takes the common options only.
    """

    KIND: str
    FIELDS: Sequence[Any]
    RATING_SCOPE: str | None
    TOOTH_FORM: ToothForm | None

    def read_table(self, data: Mapping[str, Any], where: str = "gear", name: str | None = None,
                   length_unit: str | None = None) -> Any: ...

    def build(self, spec: Any, check: bool = False, tolerance: float | None = None) -> Any: ...

    def gear_data(self, spec: Any) -> dict | None: ...

    def drawings(self, data: dict, spec: Any, folder: Any, name: str, source: str,
                 design_file: str) -> dict | None: ...

    def toothed_mass(self, spec: Any, back: str) -> tuple[float, float] | None: ...

    def options(self) -> ModuleType | None: ...


__all__ = ["GearFamily", "ToothForm"]
