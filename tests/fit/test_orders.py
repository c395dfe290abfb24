"""Shaft and tooth-mesh orders of the paper's robot-joint train (16/48/21/112 teeth)."""

import pytest

from geargen.fit.orders import attribute_order, declared_orders, train_orders

TEETH = (16, 48, 21, 112)


def test_orders_per_output_revolution():
    o = {t.name: t.order for t in train_orders(TEETH)}
    assert o["output"] == 1.0
    assert o["cluster"] == pytest.approx(112 / 21)            # 5.333: the cluster turns z_out/z_cs
    assert o["input"] == pytest.approx(112 / 21 * 48 / 16)    # 16: ratio of the whole train
    assert o["mesh2"] == 112                                   # every output tooth passes mesh 2 once
    assert o["mesh1"] == pytest.approx(112 / 21 * 48)         # 256 = input order x z_in


def test_declared_orders():
    names = [t.name for t in declared_orders(TEETH, ("eccentricity",))]
    assert names == ["output", "cluster", "input"]
    assert len(declared_orders(TEETH, ("eccentricity", "tooth_to_tooth"))) == 5


@pytest.mark.parametrize("order,name,multiple", [
    (2.0, "output", 2), (2 * 112 / 21, "cluster", 2), (16.0, "input", 1), (224.0, "mesh2", 2),
    (256.004, "mesh1", 1), (48.0, "input", 3),
])
def test_attribution_prefers_the_smallest_multiple(order, name, multiple):
    t, m = attribute_order(order, train_orders(TEETH))
    assert (t.name, m) == (name, multiple)


def test_no_attribution_off_the_train():
    assert attribute_order(7.3, train_orders(TEETH)) is None
    assert attribute_order(2.05, train_orders(TEETH)) is None
