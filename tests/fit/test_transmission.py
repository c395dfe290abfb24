"""Transmission-error records (contracts/measurements.md, ``transmission_error``): orders of a
train of stages, the file round trip through ``geargen fit``, and the undeclared effects' parameters
against what the record shows directly. (Each undeclared effect found with its parameters: the
``te/`` cases of fit_cases.py, run by test_selection.py.)"""

import json

import numpy as np
import pytest

from geargen.cli import main
from geargen.fit.datasheet import datasheet
from geargen.fit.measurement import read_measurement, write_measurement
from geargen.fit.orders import transmission_declared_orders, transmission_orders
from geargen.fit.selection import diagnose
from geargen.fit.simulate import TransmissionSettings, TransmissionTruth, simulate_transmission_error


def test_orders_of_the_papers_train_as_two_stages():
    """Input 16 -> 48 (cluster), 21 -> 112 (output): per output turn the cluster turns 112/21, the
    input 16/3 x 3 = 16 times; 16 x 16 = 48 x 16/3 = 256 teeth pass mesh 1, 112 mesh 2."""
    orders = {t.name: t.order for t in transmission_orders(((16, 48), (21, 112)))}
    assert orders == pytest.approx({"input": 16.0, "shaft1": 112 / 21, "output": 1.0, "mesh1": 256.0, "mesh2": 112.0})
    declared = [t.order for t in transmission_declared_orders(((16, 48), (21, 112)), ("eccentricity", "tooth_to_tooth"))]
    assert sorted(declared) == pytest.approx(sorted([16.0, 112 / 21, 1.0, 256.0, 512.0, 112.0, 224.0]))
    assert [t.order for t in transmission_declared_orders(((16, 48), (21, 112)), ("eccentricity",))] == \
        pytest.approx([16.0, 112 / 21, 1.0])


def test_through_the_files(tmp_path, capsys):
    sim = simulate_transmission_error(TransmissionTruth(backlash_half_width_urad=12.0), np.random.default_rng(41))
    csv = write_measurement(sim.measurement, tmp_path, "te")
    back = read_measurement(csv)
    # the written angles carry 1e-10 deg (1.7e-6 urad): the error survives the text
    assert np.max(np.abs(back.te_urad - sim.measurement.te_urad)) < 1e-4
    assert main(["fit", str(csv), "--no-plots"]) == 0
    j = json.loads((tmp_path / "te.fit.json").read_text())
    assert j["kind"] == "transmission_error" and j["units"] == "urad"
    assert set(j["noise_channels"]) == {"input_angle_urad", "output_angle_urad"}
    assert [e["effect"] for e in j["effects_added"]] == ["hysteresis"]
    (e,) = j["effects_added"]
    assert e["half_width"] == pytest.approx(12.0, rel=0.05) and e["backlash_urad"] == pytest.approx(2 * e["half_width"])
    assert j["datasheet"]["transmission_accuracy_urad"] == pytest.approx(datasheet(back)["transmission_accuracy_urad"],
                                                                         rel=1e-5)  # (6 digits in the JSON)
    out = capsys.readouterr().out
    assert "transmission accuracy" in out and "+ hysteresis" in out
    md = (tmp_path / "te_fit" / "report.md").read_text()
    assert "Transmission accuracy" in md and "transmission error at the output" in md


def test_ratio_error_is_the_ratio_the_encoders_read():
    """An encoder count mismatch of +2e-5 on gears without periodic errors: the measured ratio, the
    slope of the input angle on the output angle by least squares over the record (a direct
    reading, no model), is what the effect reports; the error grows by 2e-5 x 2.4 pi rad = 151 urad
    over the 1.2 turns."""
    sim = simulate_transmission_error(TransmissionTruth(ratio_relative=2e-5, eccentricity_urad=(0.0, 0.0, 0.0),
                                                        mesh_urad=((0.0, 0.0), (0.0, 0.0))), np.random.default_rng(42))
    m = sim.measurement
    report = diagnose(m).to_json()
    (e,) = report["effects_added"]
    slope = np.polyfit(m.angle_rad, m.input_angle_rad, 1)[0]
    # 1 urad of encoder noise over 7.5 rad of output and 12,000 samples moves the slope by 1e-9; the
    # JSON's 6 digits of 9.00018 are 6e-7 of it
    assert e["measured_ratio"] == pytest.approx(slope, rel=1e-6)
    assert e["relative"] == pytest.approx(slope / m.model.ratio - 1.0, rel=1e-3)


def test_a_pulse_wider_than_a_turn_or_a_backlash_wider_than_the_record_is_absurd():
    """The plausibility rule for transmission records, on the fits themselves."""
    from geargen.fit.model import ModelFit, Term
    from geargen.fit.noise import noise_of_transmission
    from geargen.fit.transmission import TransmissionModel
    sim = simulate_transmission_error(TransmissionTruth(), np.random.default_rng(43),
                                      TransmissionSettings(revolutions=1.1))
    m = sim.measurement
    model = TransmissionModel(m, noise_of_transmission(m.time_s, m.input_angle_rad * 1e6, m.angle_rad * 1e6, m.te_urad))
    span = float(np.ptp(m.te_urad))
    fit = ModelFit(terms=(Term("hysteresis", params=(1.0,)), Term("tooth_pulse", "output", 1.0, (10.0, 400.0))),
                   rss=1.0, n_fitted=m.samples, n_params=3, values=({"half_width": 0.6 * span},
                                                                    {"width_deg": 400.0}), declared_values={})
    assert "wider than the whole range" in model.implausible(fit, 0)
    assert "no pulse within one turn" in model.implausible(fit, 1)
    ok = ModelFit(terms=fit.terms, rss=1.0, n_fitted=m.samples, n_params=3,
                  values=({"half_width": 0.3 * span}, {"width_deg": 30.0}), declared_values={})
    assert model.implausible(ok, 0) is None and model.implausible(ok, 1) is None
