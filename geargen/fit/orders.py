"""Shaft and tooth-mesh orders of a dual-pinion train, counted per output revolution.

Train (Hale & Slocum, Fig. 10): input pinion z_in meshes with the large gear z_cl of each
cluster (mesh 1); the small gear z_cs of each cluster meshes with the output z_out (mesh 2).
One output revolution turns

- the output once                                   -> order 1
- each cluster z_out / z_cs times                   -> order z_out/z_cs
- the input (z_out / z_cs) * (z_cl / z_in) times    -> order z_out/z_cs * z_cl/z_in

and passes z_out teeth through mesh 2 and (z_out / z_cs) * z_cl teeth through mesh 1: those
are the tooth-mesh orders.
"""

from __future__ import annotations

from dataclasses import dataclass

#: what each declared-model name puts in the model
DECLARED_TERMS = {
    "eccentricity": ("output", "cluster", "input"),
    "tooth_to_tooth": ("mesh1", "mesh2"),
}


@dataclass(frozen=True)
class TrainOrder:
    """One shaft or tooth-mesh order: ``name`` (output, cluster, input, mesh1, mesh2),
    ``kind`` ("shaft" or "mesh"), ``order`` per output revolution, ``description``."""

    name: str
    kind: str
    order: float
    description: str


def train_orders(teeth: tuple[int, int, int, int]) -> tuple[TrainOrder, ...]:
    """The five orders of the train from teeth (input, cluster large, cluster small, output)."""
    z_in, z_cl, z_cs, z_out = (int(z) for z in teeth)
    cluster = z_out / z_cs
    return (
        TrainOrder("output", "shaft", 1.0, "output shaft, once per revolution"),
        TrainOrder("cluster", "shaft", cluster, f"cluster shafts, {z_out}/{z_cs} per output revolution"),
        TrainOrder("input", "shaft", cluster * z_cl / z_in,
                   f"input shaft, {z_out}/{z_cs} x {z_cl}/{z_in} per output revolution"),
        TrainOrder("mesh1", "mesh", cluster * z_cl, f"mesh 1 (input {z_in} / cluster large {z_cl}) tooth passing"),
        TrainOrder("mesh2", "mesh", float(z_out), f"mesh 2 (cluster small {z_cs} / output {z_out}) tooth passing"),
    )


def declared_orders(teeth: tuple[int, int, int, int], declared: tuple[str, ...],
                    tolerance: float = 1e-9) -> tuple[TrainOrder, ...]:
    """The orders a declared model holds (each distinct order once)."""
    wanted = {name for term in declared for name in DECLARED_TERMS[term]}
    out: list[TrainOrder] = []
    for t in train_orders(teeth):
        if t.name in wanted and all(abs(t.order - o.order) > tolerance for o in out):
            out.append(t)
    return tuple(out)


def attribute_order(order: float, train: tuple[TrainOrder, ...], tolerance: float = 0.02,
                    max_multiple: int = 64) -> tuple[TrainOrder, int] | None:
    """The shaft or mesh whose whole multiple ``order`` is, within ``tolerance`` orders.

    When several fit (order 16 is 16 x output and 1 x input) the smallest multiple wins: the
    physically simplest source. Returns (TrainOrder, multiple) or None.
    """
    best = None
    for t in train:
        m = round(order / t.order)
        if 1 <= m <= max_multiple and abs(order - m * t.order) <= tolerance:
            if best is None or m < best[1]:
                best = (t, m)
    return best


# ----------------------------------------------------------------------- transmission error

def transmission_orders(stages: tuple[tuple[int, int], ...]) -> tuple[TrainOrder, ...]:
    """Shaft and tooth-mesh orders of a train of stages (driver, driven), input to output, per
    output revolution: ``input``, ``shaft1`` ... (the shafts between the stages), ``output``; and
    ``mesh1`` ... (the driver's teeth passing per output revolution)."""
    stages = tuple((int(a), int(b)) for a, b in stages)
    count = len(stages)
    # the shaft before stage j turns prod_{i >= j} driven_i / driver_i times per output turn
    turns = [1.0] * (count + 1)
    for j in range(count - 1, -1, -1):
        turns[j] = turns[j + 1] * stages[j][1] / stages[j][0]
    shafts = []
    for j, order in enumerate(turns):
        if j == 0:
            name, text = "input", "input shaft"
        elif j == count:
            name, text = "output", "output shaft"
        else:
            name, text = f"shaft{j}", f"shaft between stage {j} and {j + 1}"
        shafts.append(TrainOrder(name, "shaft", order, f"{text}, {order:.6g} per output revolution"))
    meshes = [TrainOrder(f"mesh{j + 1}", "mesh", turns[j] * a, f"stage {j + 1} ({a} driving {b}) tooth passing")
              for j, (a, b) in enumerate(stages)]
    return tuple(shafts + meshes)


def transmission_declared_orders(stages: tuple[tuple[int, int], ...], declared: tuple[str, ...],
                                 tolerance: float = 1e-9) -> tuple[TrainOrder, ...]:
    """The orders the declared model of a transmission-error record holds (contract): once per turn
    of every shaft (``eccentricity``), each stage's tooth-mesh order and its second harmonic
    (``tooth_to_tooth``); each distinct order once."""
    out: list[TrainOrder] = []
    for t in transmission_orders(stages):
        wanted = ("eccentricity" in declared and t.kind == "shaft") or ("tooth_to_tooth" in declared and t.kind == "mesh")
        if not wanted:
            continue
        terms = [t] if t.kind == "shaft" else [t, TrainOrder(f"{t.name} x2", "mesh", 2.0 * t.order,
                                                             f"second harmonic of {t.description}")]
        for term in terms:
            if all(abs(term.order - o.order) > tolerance for o in out):
                out.append(term)
    return tuple(out)
