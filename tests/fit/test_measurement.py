"""Reading NAME.csv + NAME.toml: validation errors name the column, line or key."""

from pathlib import Path

import numpy as np
import pytest

from geargen.fit.measurement import MeasurementError, PreloadModelSpec, read_measurement, write_measurement
from geargen.fit.simulate import PreloadTruth, TorqueTruth, simulate_preload_trace, simulate_torque_deflection

ROOT = Path(__file__).resolve().parents[2]

PRELOAD_TOML = """kind = "preload_trace"
description = "test"
[model]
drive = "type2"
teeth = [16, 48, 21, 112]
declared = ["eccentricity", "tooth_to_tooth"]
"""


def _write(tmp_path, csv_text, toml_text=PRELOAD_TOML, name="m"):
    (tmp_path / f"{name}.csv").write_text(csv_text)
    (tmp_path / f"{name}.toml").write_text(toml_text)
    return tmp_path / f"{name}.csv"


def _rows(n=60):
    t = np.arange(n) * 0.1
    return "\n".join(f"{a:.3f},{a * 60:.4f},{np.sin(a):.5f}" for a in t)


def test_round_trip_of_simulated_files(tmp_path):
    sim = simulate_preload_trace(PreloadTruth(), np.random.default_rng(1))
    csv = write_measurement(sim.measurement, tmp_path, "trace")
    m = read_measurement(csv)
    assert m.kind == "preload_trace" and m.samples == sim.measurement.samples
    assert np.allclose(m.angle_rad, sim.measurement.angle_rad, atol=1e-8)
    assert np.allclose(m.carriage_um, sim.measurement.carriage_um, atol=1e-5)
    assert m.model == sim.measurement.model
    sim = simulate_torque_deflection(TorqueTruth(), np.random.default_rng(1))
    m = read_measurement(write_measurement(sim.measurement, tmp_path, "torque"))
    assert m.kind == "torque_deflection" and np.allclose(m.rotation_rad, sim.measurement.rotation_rad, atol=1e-11)
    assert m.model.k3_Nm_per_rad == pytest.approx(sim.measurement.model.k3_Nm_per_rad)


def test_unknown_columns_ignored_with_a_note(tmp_path):
    csv = _write(tmp_path, "time_s,output_angle_deg,carriage_x_um,probe_volts\n" +
                 "\n".join(r + ",1.0" for r in _rows().splitlines()))
    m = read_measurement(csv)
    assert any("probe_volts" in n and "ignored" in n for n in m.notes)


def test_missing_column_is_named(tmp_path):
    csv = _write(tmp_path, "time_s,output_angle_deg,carriage_y_um\n" + _rows())
    with pytest.raises(MeasurementError, match="carriage_x_um"):
        read_measurement(csv)


def test_bad_value_names_line_and_column(tmp_path):
    rows = _rows().splitlines()
    rows[4] = "0.400,2.4,abc"
    csv = _write(tmp_path, "time_s,output_angle_deg,carriage_x_um\n" + "\n".join(rows))
    with pytest.raises(MeasurementError, match=r"line 6, column carriage_x_um.*'abc'"):
        read_measurement(csv)


def test_empty_cells_are_drop_outs(tmp_path):
    rows = _rows().splitlines()
    rows[10] = "1.000,60.0,"
    m = read_measurement(_write(tmp_path, "time_s,output_angle_deg,carriage_x_um\n" + "\n".join(rows)))
    assert m.samples == 59 and any("dropped" in n for n in m.notes)


def test_time_must_increase(tmp_path):
    rows = _rows().splitlines()
    rows[7], rows[8] = rows[8], rows[7]
    with pytest.raises(MeasurementError, match="time_s.*goes back in time at data row 9 \\(0.7 after 0.8\\)"):
        read_measurement(_write(tmp_path, "time_s,output_angle_deg,carriage_x_um\n" + "\n".join(rows)))


def test_equal_consecutive_times_are_the_loggers_resolution(tmp_path):
    """A logger stamping to 0.5 s with rows every 0.1 s: runs of five equal stamps, spread evenly
    to the next stamp (the last run over five median row spacings); a note says so."""
    rows = [r.split(",") for r in _rows().splitlines()]
    for r in rows:
        r[0] = f"{np.floor(float(r[0]) / 0.5 + 1e-9) * 0.5:.1f}"
    m = read_measurement(_write(tmp_path, "time_s,output_angle_deg,carriage_x_um\n" +
                                "\n".join(",".join(r) for r in rows)))
    assert m.time_s == pytest.approx(np.arange(60) * 0.1, abs=1e-12)
    assert any("48 rows share their time stamp" in n for n in m.notes)


def test_other_units_are_converted(tmp_path):
    m = read_measurement(_write(tmp_path, "time_s,output_angle_rad,carriage_x_mm\n" + _rows()))
    assert m.carriage_um[1] == pytest.approx(1000 * np.sin(0.1), rel=1e-4)
    assert any("converted" in n for n in m.notes)


@pytest.mark.parametrize("toml_text,match", [
    ('kind = "preload"\n[model]\nteeth = [16, 48, 21, 112]\n', "kind.*not a valid choice"),
    ('kind = "preload_trace"\n[model]\nteeth = [16, 48, 21]\n', "model.teeth"),
    ('kind = "preload_trace"\n[model]\nteeth = [16, 48, 21, 112]\ndeclared = ["runout"]\n', "model.declared"),
    ('kind = "preload_trace"\n[model]\nteeth = [16, 48, 21, 112]\ngear_ratio = 3\n', "model.gear_ratio: unknown key"),
    ('kind = "preload_trace"\ncolour = "red"\n[model]\nteeth = [16, 48, 21, 112]\n', "colour: unknown key"),
    ('kind = "preload_trace"\n', "model: missing"),
    ('kind = "torque_deflection"\n[model]\ndrive = "type1"\nk1_Nm_per_rad = 1e5\nk2_Nm_per_rad = 1e5\n'
     'k3_Nm_per_rad = 1e4\npreload_Nm = 5\n', "k3_Nm_per_rad: a type1 drive has no preload spring"),
    ('kind = "torque_deflection"\n[model]\ndrive = "type2"\nk1_Nm_per_rad = -4\n', "k1_Nm_per_rad.*out of range"),
    ('kind = "torque_deflection"\n[model]\nk1_Nm_per_rad = 4e5\n', "model.drive: missing"),
])
def test_sidecar_errors_name_the_key(tmp_path, toml_text, match):
    header = "time_s,output_torque_Nm,output_rotation_urad\n" if "torque" in toml_text else \
        "time_s,output_angle_deg,carriage_x_um\n"
    with pytest.raises(MeasurementError, match=match):
        read_measurement(_write(tmp_path, header + _rows(), toml_text))


def test_missing_sidecar(tmp_path):
    (tmp_path / "lonely.csv").write_text("time_s,output_angle_deg,carriage_x_um\n" + _rows())
    with pytest.raises(MeasurementError, match="lonely.toml.*sidecar"):
        read_measurement(tmp_path / "lonely.csv")


def test_keys_of_the_other_kind_are_noted_not_fatal(tmp_path):
    m = read_measurement(_write(tmp_path, "time_s,output_angle_deg,carriage_x_um\n" + _rows(),
                                PRELOAD_TOML + "k1_Nm_per_rad = 4e5\n"))
    assert any("k1_Nm_per_rad ignored" in n for n in m.notes)


def test_teeth_from_an_assembly(tmp_path):
    design = ROOT / "assemblies" / "robot_joint.toml"
    toml_text = f'kind = "preload_trace"\nassembly = "{design.as_posix()}"\n'
    m = read_measurement(_write(tmp_path, "time_s,output_angle_deg,carriage_x_um\n" + _rows(), toml_text))
    assert m.model == PreloadModelSpec(teeth=(16, 48, 21, 112), declared=("eccentricity", "tooth_to_tooth"),
                                       drive_type="type2")


def test_torque_law_from_an_assembly(tmp_path):
    from geargen.design.assembly import load_design
    from geargen.drives.resolver import drive_from_design
    design = ROOT / "assemblies" / "robot_joint.toml"
    drive = drive_from_design(load_design(design))  # the drive as stiffness and build report it
    toml_text = f'kind = "torque_deflection"\nassembly = "{design.as_posix()}"\n'
    m = read_measurement(_write(tmp_path, "time_s,output_torque_Nm,output_rotation_urad\n" + _rows(), toml_text))
    # the law's N*mm/rad and N*mm become the contract's Nm/rad and Nm
    assert m.model.k1_Nm_per_rad == pytest.approx(drive.k1 / 1e3)
    assert m.model.k3_Nm_per_rad == pytest.approx(drive.k3 / 1e3)
    assert m.model.preload_Nm == pytest.approx(drive.preload / 1e3)
    assert any("from the assembly" in n for n in m.notes)


def test_a_preload_trace_must_turn(tmp_path):
    rows = "\n".join(f"{i * 0.1:.3f},{i * 0.5:.4f},{np.sin(i):.5f}" for i in range(60))
    with pytest.raises(MeasurementError, match="output_angle_deg: the output turns only 29.5 deg"):
        read_measurement(_write(tmp_path, "time_s,output_angle_deg,carriage_x_um\n" + rows))
