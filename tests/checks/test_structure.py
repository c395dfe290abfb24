"""The structure check (geargen.checks.structure) on small hand-made assemblies: each finding
appears exactly when the contacts say so, and joint elements do not weld bodies together."""

from geargen.checks.structure import structure_check

# a shaft on two bearings in a housing, a gear on the shaft
KINDS = {"housing": "housing", "shaft": "shaft", "gear": "gear", "b1": "bearing", "b2": "bearing"}
CONTACTS = [("gear", "shaft"), ("b1", "shaft"), ("b2", "shaft"), ("b1", "housing"), ("b2", "housing")]


def _check(kinds=KINDS, contacts=CONTACTS):
    return structure_check(kinds, contacts, ground=["housing"], stationary=["housing"], rotating=["gear"])


def test_a_shaft_on_two_seated_bearings_is_sound():
    r = _check()
    assert r.failures == []
    # bearings are bodies of their own; the gear and its shaft one body; the housing another
    assert ("gear", "shaft") in r.bodies and ("housing",) in r.bodies and ("b1",) in r.bodies


def test_a_bearing_without_a_seat_joins_nothing():
    r = _check(contacts=[c for c in CONTACTS if c != ("b2", "housing")])
    assert r.one_sided == (("b2", ("shaft",)),)
    assert r.ungrounded == () and r.rotating_on_stationary == ()
    assert len(r.failures) == 1 and "b2 touches only shaft" in r.failures[0]


def test_a_shaft_rubbing_on_the_housing_is_found():
    r = _check(contacts=CONTACTS + [("shaft", "housing")])
    assert r.rotating_on_stationary == (("gear", "housing"),)
    # the bearings now touch one body on both sides: they carry nothing either
    assert {j for j, _ in r.one_sided} == {"b1", "b2"}


def test_parts_held_by_nothing_are_ungrounded():
    kinds = dict(KINDS, motor="motor", coupling="shaft")
    r = _check(kinds, CONTACTS + [("coupling", "motor")])
    assert r.ungrounded == ("coupling", "motor")
    assert ("motor", ("coupling",)) in r.one_sided  # a motor is stator against rotor: it needs both sides


def test_a_flexure_carries_a_stationary_carriage():
    kinds = dict(KINDS, carriage="carriage", blade="flexure")
    contacts = [("blade", "housing"), ("blade", "carriage"), ("b1", "carriage"), ("b2", "carriage"),
                ("gear", "shaft"), ("b1", "shaft"), ("b2", "shaft")]
    r = structure_check(kinds, contacts, ground=["housing"], stationary=["housing", "carriage"], rotating=["gear"])
    assert r.failures == []
    # without the blade the carriage and everything on it float
    r = structure_check(kinds, contacts[1:], ground=["housing"], stationary=["housing", "carriage"], rotating=["gear"])
    assert set(r.ungrounded) == {"blade", "b1", "b2", "carriage", "gear", "shaft"}
