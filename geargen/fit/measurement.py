"""A bench measurement: ``NAME.csv`` and its sidecar ``NAME.toml`` (contracts/measurements.md).

Reading validates everything and names the offending column, line or key. Channels come back
in the contract's units: carriage position in um, torque in Nm, angles in rad (the input and
output angle and rotation columns are converted from their suffix unit; ``_deg``/``_urad`` are
the contract spellings, other angle and length suffixes of :mod:`geargen.units` are accepted too).
Three kinds: ``preload_trace``, ``torque_deflection`` (which may hold several tests, numbered by
a ``test_nr`` column) and ``transmission_error``. The sidecar's optional ``[test]`` table says
how the datasheet figures are taken (:class:`DatasheetSettings`).

Rows with an empty or non-numeric-NaN value in a required column are dropped (a probe
drop-out) with a note; a missing temperature value is interpolated in time, with a note. Equal
consecutive times are a logger's finite time resolution: each run of equal stamps is spread
evenly to the next stamp (:func:`spread_equal_times`), with a note; a time that goes back is refused.
Unknown extra columns are ignored, with a note.

A record that cannot be fitted is refused with a :class:`MeasurementError` naming the file and
the column: no usable rows or too few, a column empty in every row, a record that spans no time,
a measured channel that is constant or reads one value in more than half of its rows at the
edge of its range or in all but a few (a stuck, saturated or disconnected probe; a torque held
at zero between load steps is a dwell, and is fitted), values beyond what double precision can square, a preload
trace whose output does not turn. The CSV is read in blocks straight into one float64 array per
used column, so reading a file costs about 8 bytes per used value, not the file's text.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from geargen.design.schema import load_toml
from geargen.errors import DesignError
from geargen.units import ANGLE_SUFFIXES, LENGTH_SUFFIXES

KINDS = ("preload_trace", "torque_deflection", "transmission_error")
DRIVE_TYPES = ("type1", "type2")
DECLARED_NAMES = ("eccentricity", "tooth_to_tooth")
UNITS = {"preload_trace": "um", "torque_deflection": "Nm", "transmission_error": "urad"}

#: channel -> (column stem, {suffix: factor to the channel's unit}); the first suffix is the contract's
_UM_PER = {u: f * 1000.0 for u, f in LENGTH_SUFFIXES.items()}
_URAD_ANGLES = {"urad": 1e-6, **{u: f for u, f in ANGLE_SUFFIXES.items() if u != "urad"}}
CHANNELS: dict[str, tuple[str, dict[str, float]]] = {
    "time": ("time", {"s": 1.0, "ms": 1e-3, "min": 60.0, "h": 3600.0}),
    "temperature": ("temperature", {"C": 1.0}),
    "angle": ("output_angle", {"deg": ANGLE_SUFFIXES["deg"], **{u: f for u, f in ANGLE_SUFFIXES.items() if u != "deg"}}),
    "input_angle": ("input_angle", {"deg": ANGLE_SUFFIXES["deg"], **{u: f for u, f in ANGLE_SUFFIXES.items() if u != "deg"}}),
    "carriage": ("carriage_x", {"um": 1.0, **{u: f for u, f in _UM_PER.items() if u != "um"}}),
    "torque": ("output_torque", {"Nm": 1.0, "Nmm": 1e-3, "kNm": 1e3}),
    "rotation": ("output_rotation", _URAD_ANGLES),
}
REQUIRED = {"preload_trace": ("time", "angle", "carriage"), "torque_deflection": ("time", "torque", "rotation"),
            "transmission_error": ("time", "input_angle", "angle")}
OPTIONAL = ("temperature",)
#: the column that numbers the tests of a torque_deflection record (a count: no unit suffix)
TEST_COLUMN = "test_nr"

MODEL_KEYS = {
    "preload_trace": ("drive", "teeth", "declared"),
    "torque_deflection": ("drive", "k1_Nm_per_rad", "k2_Nm_per_rad", "k3_Nm_per_rad", "preload_Nm"),
    "transmission_error": ("stages", "declared"),
}
TOP_KEYS = ("kind", "description", "model", "assembly", "test")
TEST_KEYS = ("rated_torque_Nm", "lost_motion_fraction", "stiffness_limits_Nm")
#: lost motion is measured at +-3 % of the rated torque unless the sidecar says otherwise (the
#: figure strain-wave and cycloid catalogues quote)
LOST_MOTION_FRACTION = 0.03
MIN_SAMPLES = 50
#: values (in the column's unit) beyond which squares and sums of squares leave double precision
MAX_MAGNITUDE = 1e100
MIN_SPAN = 1e-100


class MeasurementError(DesignError):
    """A measurement file or sidecar is missing, malformed or inconsistent.

    ``field`` names the file and the column, line or key (``run3.csv: column carriage_x_um``).
    """


# ----------------------------------------------------------------------------- model specs

@dataclass(frozen=True)
class PreloadModelSpec:
    """Declared model of a preload trace: teeth (input, cluster large, cluster small, output)
    and which error terms it declares."""

    teeth: tuple[int, int, int, int]
    declared: tuple[str, ...] = DECLARED_NAMES
    drive_type: str | None = None

    def __post_init__(self):
        if len(self.teeth) != 4 or not all(isinstance(z, int) and not isinstance(z, bool) and z >= 4 for z in self.teeth):
            raise MeasurementError("model.teeth", f"{list(self.teeth)!r} is not valid",
                                   "4 whole numbers >= 4: [input, cluster large, cluster small, output]")
        for d in self.declared:
            if d not in DECLARED_NAMES:
                raise MeasurementError("model.declared", f"{d!r} is not a declared-model term", ", ".join(map(repr, DECLARED_NAMES)))
        if self.drive_type is not None and self.drive_type not in DRIVE_TYPES:
            raise MeasurementError("model.drive", f"{self.drive_type!r} is not a valid choice", "'type1', 'type2'")


@dataclass(frozen=True)
class TorqueModelSpec:
    """Declared two-path law of a torque-deflection test, output-referred, in Nm/rad and Nm.
    Values may be None (no nominal values): the fit then starts from the data."""

    drive_type: str
    k1_Nm_per_rad: float | None = None
    k2_Nm_per_rad: float | None = None
    k3_Nm_per_rad: float | None = None
    preload_Nm: float | None = None

    def __post_init__(self):
        if self.drive_type not in DRIVE_TYPES:
            raise MeasurementError("model.drive", f"{self.drive_type!r} is not a valid choice", "'type1', 'type2'")
        for name in ("k1_Nm_per_rad", "k2_Nm_per_rad", "k3_Nm_per_rad"):
            v = getattr(self, name)
            if v is not None and not (math.isfinite(v) and v > 0):
                raise MeasurementError(f"model.{name}", f"{v!r} is out of range", "> 0 and finite")
        if self.preload_Nm is not None and not (math.isfinite(self.preload_Nm) and self.preload_Nm >= 0):
            raise MeasurementError("model.preload_Nm", f"{self.preload_Nm!r} is out of range", ">= 0 and finite")
        if self.drive_type == "type1" and self.k3_Nm_per_rad is not None:
            raise MeasurementError("model.k3_Nm_per_rad", "a type1 drive has no preload spring", "omit k3 for type1")

    @property
    def has_nominal(self) -> bool:
        """True when every value of the law is given."""
        need = ["k1_Nm_per_rad", "k2_Nm_per_rad", "preload_Nm"] + (["k3_Nm_per_rad"] if self.drive_type == "type2" else [])
        return all(getattr(self, n) is not None for n in need)


@dataclass(frozen=True)
class TransmissionModelSpec:
    """Declared model of a transmission-error record: the stages as (driver, driven) tooth counts,
    input to output, and which error terms it declares (contract: eccentricity of every shaft,
    each stage's tooth-mesh order and its second harmonic)."""

    stages: tuple[tuple[int, int], ...]
    declared: tuple[str, ...] = DECLARED_NAMES

    def __post_init__(self):
        ok = len(self.stages) >= 1 and all(
            isinstance(st, tuple) and len(st) == 2 and all(isinstance(z, int) and not isinstance(z, bool) and z >= 4
                                                          for z in st) for st in self.stages)
        if not ok:
            raise MeasurementError("model.stages", f"{[list(st) if isinstance(st, tuple) else st for st in self.stages]!r} "
                                   "is not valid", "a list of [driver, driven] tooth counts (whole numbers >= 4), "
                                   "input to output, e.g. [[16, 48], [21, 112]]")
        for d in self.declared:
            if d not in DECLARED_NAMES:
                raise MeasurementError("model.declared", f"{d!r} is not a declared-model term", ", ".join(map(repr, DECLARED_NAMES)))

    @property
    def ratio(self) -> float:
        """Input turns per output turn: the product of the stages' driven / driver teeth."""
        return float(np.prod([b / a for a, b in self.stages]))


@dataclass(frozen=True)
class DatasheetSettings:
    """How the datasheet figures of a torque_deflection record are taken (the sidecar's ``[test]``).

    ``rated_torque_Nm`` None: each test's largest |torque|; ``lost_motion_fraction``: lost motion
    is measured at +-this x the rated torque; ``stiffness_limits_Nm`` (T1, T2) None: the tool's
    choice (reported)."""

    rated_torque_Nm: float | None = None
    lost_motion_fraction: float = LOST_MOTION_FRACTION
    stiffness_limits_Nm: tuple[float, float] | None = None

    def __post_init__(self):
        if self.rated_torque_Nm is not None and not (math.isfinite(self.rated_torque_Nm) and self.rated_torque_Nm > 0):
            raise MeasurementError("test.rated_torque_Nm", f"{self.rated_torque_Nm!r} is out of range", "> 0 and finite")
        if not (math.isfinite(self.lost_motion_fraction) and 0 < self.lost_motion_fraction < 1):
            raise MeasurementError("test.lost_motion_fraction", f"{self.lost_motion_fraction!r} is out of range",
                                   "0 < fraction < 1 (of the rated torque)")
        lim = self.stiffness_limits_Nm
        if lim is not None and not (len(lim) == 2 and all(math.isfinite(v) for v in lim) and 0 < lim[0] < lim[1]):
            raise MeasurementError("test.stiffness_limits_Nm", f"{list(lim)!r} is not valid",
                                   "[T1, T2] with 0 < T1 < T2, in Nm")


# ----------------------------------------------------------------------------- measurement

SPECS = {"preload_trace": PreloadModelSpec, "torque_deflection": TorqueModelSpec,
         "transmission_error": TransmissionModelSpec}
ARRAYS = {"preload_trace": ("angle_rad", "carriage_um"), "torque_deflection": ("torque_Nm", "rotation_rad"),
          "transmission_error": ("input_angle_rad", "angle_rad")}
#: every per-sample array a Measurement may hold
ALL_ARRAYS = ("time_s", "angle_rad", "carriage_um", "torque_Nm", "rotation_rad", "input_angle_rad", "temperature_C",
              "test_nr")


@dataclass(frozen=True, eq=False)
class Measurement:
    """One validated measurement. Arrays are (n,) float in record (time) order.

    preload_trace: ``angle_rad`` (output angle), ``carriage_um``.
    torque_deflection: ``torque_Nm`` (output torque), ``rotation_rad`` (output rotation);
    ``test_nr`` (n,) the logger's test numbers, or None; ``test`` how the datasheet is taken.
    transmission_error: ``input_angle_rad`` and ``angle_rad`` (output angle); the transmission
    error itself is :attr:`te_urad`.
    ``temperature_C`` is None when the file has no temperature column. ``columns`` maps each
    channel (time, angle, input_angle, carriage, torque, rotation, temperature) to the CSV column
    it was read from; :meth:`column` falls back to the contract's spelling.
    """

    kind: str
    name: str
    time_s: np.ndarray
    model: PreloadModelSpec | TorqueModelSpec | TransmissionModelSpec
    angle_rad: np.ndarray | None = None
    carriage_um: np.ndarray | None = None
    torque_Nm: np.ndarray | None = None
    rotation_rad: np.ndarray | None = None
    temperature_C: np.ndarray | None = None
    description: str = ""
    notes: tuple[str, ...] = ()
    source: Path | None = None
    columns: dict = field(default_factory=dict)
    assembly: Path | None = None  # the design file the sidecar names (its error budget is compared)
    input_angle_rad: np.ndarray | None = None
    test_nr: np.ndarray | None = None
    test: DatasheetSettings = field(default_factory=DatasheetSettings)

    def __post_init__(self):
        if self.kind not in KINDS:
            raise MeasurementError("kind", f"{self.kind!r} is not a valid choice", ", ".join(map(repr, KINDS)))
        want = ARRAYS[self.kind]
        spec_type = SPECS[self.kind]
        if not isinstance(self.model, spec_type):
            raise MeasurementError("model", f"a {self.kind} needs a {spec_type.__name__}")
        n = np.asarray(self.time_s).size
        if n < MIN_SAMPLES:
            raise MeasurementError(f"{self.file}: samples", f"{n} samples are too few to fit", f">= {MIN_SAMPLES}")
        optional = tuple(name for name in ("temperature_C", "test_nr") if getattr(self, name) is not None)
        for name in ("time_s",) + want + optional:
            arr = getattr(self, name)
            if arr is None or np.asarray(arr).shape != (n,):
                raise MeasurementError(name, f"needs {n} values like time_s")
            if not np.all(np.isfinite(arr)):
                raise MeasurementError(name, "holds values that are not finite")
        if self.kind == "preload_trace" and np.ptp(self.angle_rad) < math.pi:
            raise MeasurementError(self.where("angle"), f"the output turns only {np.degrees(np.ptp(self.angle_rad)):.3g} deg",
                                   "a preload trace over one or more revolutions (at least half of one)")
        if self.kind == "transmission_error" and np.ptp(self.angle_rad) < math.pi:
            raise MeasurementError(self.where("angle"), f"the output turns only {np.degrees(np.ptp(self.angle_rad)):.3g} deg",
                                   "a transmission error record over one or more output revolutions (at least half of one)")
        if self.kind == "torque_deflection" and not np.ptp(self.torque_Nm) > 0:
            raise MeasurementError(self.where("torque"), "the torque never changes", "a torque cycled 0 -> +T -> -T -> 0")
        if self.kind == "torque_deflection" and not np.ptp(self.rotation_rad) > 0:
            raise MeasurementError(self.where("rotation"), "the rotation never changes", "a measured, varying rotation")
        step_ok = np.diff(self.time_s) > 0
        if not step_ok.all():
            i = int(np.flatnonzero(~step_ok)[0])
            raise MeasurementError(self.where("time"), f"not increasing at sample {i + 2} ({self.time_s[i + 1]} after {self.time_s[i]})",
                                   "rows in time order, strictly increasing time")

    def without(self, rows: np.ndarray, note: str) -> "Measurement":
        """This record with the samples where ``rows`` (bool, (n,)) is true left out, ``note`` added."""
        from dataclasses import replace
        keep = ~np.asarray(rows, dtype=bool)
        arrays = {name: (None if getattr(self, name) is None else np.asarray(getattr(self, name))[keep])
                  for name in ALL_ARRAYS}
        return replace(self, notes=self.notes + (note,), **arrays)

    @property
    def file(self) -> str:
        """The CSV's file name (``NAME.csv`` for a measurement made in memory)."""
        return self.source.name if self.source is not None else f"{self.name}.csv"

    def column(self, channel: str) -> str:
        """The CSV column a channel (time, angle, input_angle, carriage, torque, rotation,
        temperature) came from."""
        if channel in self.columns:
            return self.columns[channel]
        stem, suffixes = CHANNELS[channel]
        return f"{stem}_{next(iter(suffixes))}"

    def where(self, channel: str) -> str:
        """``FILE: column NAME`` of a channel, for error messages."""
        return f"{self.file}: column {self.column(channel)}"

    @property
    def samples(self) -> int:
        return int(np.asarray(self.time_s).size)

    @property
    def units(self) -> str:
        """Unit of the residual: um of carriage position, Nm of torque or urad of output angle."""
        return UNITS[self.kind]

    @property
    def te_urad(self) -> np.ndarray:
        """Transmission error, urad at the output: output angle - input angle / declared ratio
        (made once, then kept)."""
        cached = self.__dict__.get("_te_urad")
        if cached is None:
            cached = (self.angle_rad - self.input_angle_rad / self.model.ratio) * 1e6
            self.__dict__["_te_urad"] = cached
        return cached

    @property
    def signal(self) -> np.ndarray:
        """The measured quantity the residual is taken of (carriage um, torque Nm or TE urad)."""
        if self.kind == "preload_trace":
            return self.carriage_um
        return self.torque_Nm if self.kind == "torque_deflection" else self.te_urad


# ----------------------------------------------------------------------------- CSV

def _column_map(header: list[str], kind: str, where: str) -> tuple[dict[str, tuple[int, float, str]], list[str]]:
    """channel -> (column index, factor, column name); and the ignored columns."""
    wanted = REQUIRED[kind] + OPTIONAL
    found: dict[str, tuple[int, float, str]] = {}
    used = set()
    for ch in wanted:
        stem, suffixes = CHANNELS[ch]
        hits = [(i, suffixes[h[len(stem) + 1:]], h) for i, h in enumerate(header)
                if h.startswith(stem + "_") and h[len(stem) + 1:] in suffixes]
        if len(hits) > 1:
            raise MeasurementError(f"{where}: column {hits[1][2]}", f"given twice, also as {hits[0][2]}", "one column per quantity")
        if hits:
            found[ch] = hits[0]
            used.add(hits[0][0])
        elif ch in REQUIRED[kind]:
            allowed = ", ".join(f"{stem}_{u}" for u in suffixes)
            raise MeasurementError(f"{where}: column {stem}_{next(iter(suffixes))}",
                                   f"missing (a {kind} needs {', '.join(CHANNELS[c][0] + '_' + next(iter(CHANNELS[c][1])) for c in REQUIRED[kind])})",
                                   allowed)
    if kind == "torque_deflection" and TEST_COLUMN in header:
        index = header.index(TEST_COLUMN)
        found["test_nr"] = (index, 1.0, TEST_COLUMN)
        used.add(index)
    ignored = [h for i, h in enumerate(header) if i not in used]
    return found, ignored


def _parse_rows(lines: list[str], first_line: int, ncols: int, header: list[str], where: str) -> np.ndarray:
    """Slow, careful parse that names the line and column of a bad value; empty cells are NaN."""
    rows = []
    for lineno, line in enumerate(lines, start=first_line):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        cells = line.split(",")
        if len(cells) != ncols:
            raise MeasurementError(f"{where}: line {lineno}", f"has {len(cells)} values", f"{ncols}, one per header column")
        row = []
        for cell, name in zip(cells, header):
            cell = cell.strip()
            if cell == "":
                row.append(math.nan)
                continue
            try:
                row.append(float(cell))
            except ValueError:
                raise MeasurementError(f"{where}: line {lineno}, column {name}", f"{cell!r} is not a number") from None
        rows.append(row)
    return np.array(rows, dtype=float).reshape(-1, ncols)


#: bytes of CSV text parsed at a time: the file is never held whole, as text or as Python objects
CSV_BLOCK_BYTES = 1 << 24


def _decode(block: bytes, where: str, first_line: int) -> str:
    try:
        return block.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = first_line + block[:exc.start].count(b"\n")
        raise MeasurementError(f"{where}: line {line}", "is not UTF-8 text") from None


def _text_blocks(handle, first_line: int, where: str):
    """(line number of the block's first line, its lines) for blocks of whole lines of an open
    binary file, about :data:`CSV_BLOCK_BYTES` each."""
    carry = b""
    line = first_line
    while True:
        data = handle.read(CSV_BLOCK_BYTES)
        block = carry + data
        if not data:
            if block:
                lines = _decode(block, where, line).splitlines()
                yield line, lines
            return
        cut = block.rfind(b"\n")
        if cut < 0:
            cut = block.rfind(b"\r")
        if cut < 0:  # one very long line so far: read on
            carry = block
            continue
        carry = block[cut + 1:]
        lines = _decode(block[:cut + 1], where, line).splitlines()
        yield line, lines
        line += len(lines)


def _line_breaks(path: Path) -> int:
    """An upper bound on the lines of a file (its LF or, for old Mac files, CR count, plus one)."""
    lf = cr = 0
    with path.open("rb") as f:
        while data := f.read(CSV_BLOCK_BYTES):
            lf += data.count(b"\n")
            cr += data.count(b"\r")
    return max(lf, cr) + 1


def read_csv(path: Path, select=None) -> tuple[list[str], list[np.ndarray]]:
    """Header names and the float columns (NaN where a cell is empty) of a measurement CSV.

    ``select(header) -> column indices`` picks the columns to keep (default: all). The file is
    read in blocks of about :data:`CSV_BLOCK_BYTES`, each parsed by numpy (or, where numpy
    refuses it, by a careful parser that names the line and column of a bad value) straight
    into one preallocated float64 array per kept column, so reading costs 8 bytes per kept
    value plus one block, whatever the file's size.
    """
    where = path.name
    try:
        handle = path.open("rb")
    except FileNotFoundError:
        raise MeasurementError(str(path), "no such measurement file") from None
    header = None
    columns: list[np.ndarray] = []
    keep: list[int] = []
    rows = capacity = 0
    with handle:
        for first, lines in _text_blocks(handle, 1, where):
            if header is None:
                if first == 1 and lines:
                    lines[0] = lines[0].removeprefix("\ufeff")
                start = 0
                while start < len(lines) and (not lines[start].strip() or lines[start].lstrip().startswith("#")):
                    start += 1
                if start == len(lines):
                    continue
                header = _header(lines[start], first + start, where)
                keep = list(range(len(header))) if select is None else list(select(header))
                capacity = max(_line_breaks(path) - (first + start), 1)
                columns = [np.empty(capacity) for _ in keep]
                first, lines = first + start + 1, lines[start + 1:]
            if not any(line.strip() and not line.lstrip().startswith("#") for line in lines):
                continue
            try:
                table = np.loadtxt(lines, delimiter=",", ndmin=2, dtype=float, comments="#")
                if table.size == 0:
                    table = table.reshape(0, len(header))
                if table.shape[1] != len(header):
                    raise ValueError
            except ValueError:
                table = _parse_rows(lines, first, len(header), header, where)
            m = table.shape[0]
            if rows + m > capacity:  # line breaks the count did not see (unusual line ends)
                capacity = max(2 * capacity, rows + m)
                columns = [np.resize(c, capacity) for c in columns]
            for c, i in zip(columns, keep):
                c[rows:rows + m] = table[:, i]
            rows += m
    if header is None:
        raise MeasurementError(where, "is empty", "a header row of column names, then numbers")
    return header, [c[:rows] for c in columns]


def _header(line: str, lineno: int, where: str) -> list[str]:
    header = [h.strip().strip('"').strip("'").strip() for h in line.split(",")]
    if any(not h for h in header):
        raise MeasurementError(f"{where}: line {lineno}", "header has an empty column name")
    dup = [h for h in header if header.count(h) > 1]
    if dup:
        raise MeasurementError(f"{where}: column {dup[0]}", "appears twice in the header")
    return header


# ----------------------------------------------------------------------------- sidecar

def _number(table: dict, key: str, where: str) -> float | None:
    if key not in table:
        return None
    v = table[key]
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        raise MeasurementError(f"{where}.{key}", f"expected a number, got {v!r}")
    return float(v)


def _model_from_assembly(kind: str, design_path: Path, where: str, notes: list[str]):
    from geargen.design.assembly import load_design

    design = load_design(design_path)
    if kind in ("preload_trace", "transmission_error"):
        teeth = tuple(design.gear(g).teeth for g in ("input", "cluster_large", "cluster_small", "output"))
        if kind == "transmission_error":  # (input -> cluster large), (cluster small -> output)
            stages = [[teeth[0], teeth[1]], [teeth[2], teeth[3]]]
            notes.append(f"stages {stages} from the assembly {design_path.name}")
            return {"stages": stages}
        notes.append(f"teeth {list(teeth)} and drive {design.drive_type} from the assembly {design_path.name}")
        return {"teeth": list(teeth), "drive": design.drive_type}
    from geargen.drives.resolver import drive_from_design  # the drive as every command resolves it

    drive = drive_from_design(design)
    # TwoPathDrive in geargen's internal units: N*mm/rad and N*mm
    values = {"drive": drive.drive_type, "k1_Nm_per_rad": drive.k1 * 1e-3, "k2_Nm_per_rad": drive.k2 * 1e-3,
              "preload_Nm": drive.preload * 1e-3}
    if drive.drive_type == "type2":
        values["k3_Nm_per_rad"] = drive.k3 * 1e-3
    notes.append(f"drive law from the assembly {design_path.name}: " + ", ".join(f"{k} = {v:.6g}" if isinstance(v, float) else f"{k} = {v}" for k, v in values.items()))
    return values


def _load_sidecar(path: Path) -> dict:
    """The sidecar's TOML, read as a design file is (:func:`geargen.design.schema.load_toml`: a
    byte-order mark is taken; not UTF-8, nested too deep, too big or not TOML is a MeasurementError
    naming the file and why)."""
    try:
        return load_toml(path)
    except DesignError as exc:
        raise MeasurementError(path.name, exc.problem, exc.allowed) from None
    except OSError as exc:
        raise MeasurementError(str(path), f"cannot be read: {exc.strerror or exc}") from None


def _test_spec(data, where: str) -> DatasheetSettings:
    """The sidecar's optional ``[test]`` table (torque_deflection only)."""
    if not isinstance(data, dict):
        raise MeasurementError(f"{where}: test", "expected a table", ", ".join(TEST_KEYS))
    for key in data:
        if key not in TEST_KEYS:
            raise MeasurementError(f"{where}: test.{key}", "unknown key", ", ".join(TEST_KEYS))
    values = {k: _number(data, k, f"{where}: test") for k in ("rated_torque_Nm", "lost_motion_fraction")}
    limits = data.get("stiffness_limits_Nm")
    if limits is not None:
        if not (isinstance(limits, list) and len(limits) == 2
                and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in limits)):
            raise MeasurementError(f"{where}: test.stiffness_limits_Nm", f"expected two numbers, got {limits!r}",
                                   "[T1, T2] with 0 < T1 < T2, in Nm")
        limits = (float(limits[0]), float(limits[1]))
    try:
        return DatasheetSettings(rated_torque_Nm=values["rated_torque_Nm"],
                        lost_motion_fraction=(values["lost_motion_fraction"] if values["lost_motion_fraction"] is not None
                                              else LOST_MOTION_FRACTION),
                        stiffness_limits_Nm=limits)
    except MeasurementError as exc:
        raise MeasurementError(f"{where}: {exc.field}", exc.problem, exc.allowed) from None


def read_sidecar(path: Path, notes: list[str], test_out: list | None = None
                 ) -> tuple[str, str, PreloadModelSpec | TorqueModelSpec | TransmissionModelSpec, Path | None]:
    """(kind, description, model spec, assembly path) from a sidecar TOML; errors name the key.
    ``test_out``, when given, receives the ``[test]`` table's :class:`DatasheetSettings`."""
    where = path.name
    if not path.exists():
        raise MeasurementError(str(path), "missing: every NAME.csv needs its sidecar NAME.toml beside it")
    data = _load_sidecar(path)
    unknown = [k for k in data if k not in TOP_KEYS]
    if unknown:
        raise MeasurementError(f"{where}: {unknown[0]}", "unknown key", ", ".join(TOP_KEYS))
    kind = data.get("kind")
    if kind is None:
        raise MeasurementError(f"{where}: kind", "missing", ", ".join(map(repr, KINDS)))
    if kind not in KINDS:
        raise MeasurementError(f"{where}: kind", f"{kind!r} is not a valid choice", ", ".join(map(repr, KINDS)))
    description = data.get("description", "")
    if not isinstance(description, str):
        raise MeasurementError(f"{where}: description", "expected a string")
    if "test" in data:
        if kind != "torque_deflection":
            raise MeasurementError(f"{where}: test", f"a {kind} has no datasheet settings",
                                   "a [test] table in a torque_deflection sidecar only")
        spec = _test_spec(data["test"], where)
        if test_out is not None:
            test_out.append(spec)
    model = data.get("model")
    assembly = data.get("assembly")
    if model is None and assembly is None:
        if kind == "torque_deflection":
            # a specimen nobody declared (a bought servo, a printed actuator): the two-path law of
            # a type 1 drive with no nominal values is then the declared model, fitted from the data
            notes.append("no [model] in the sidecar: the declared model is a type1 two-path law with no nominal "
                         "values, fitted from the data")
            return kind, description, TorqueModelSpec("type1"), None
        raise MeasurementError(f"{where}: model", "missing", "a [model] table, or assembly = \"design.toml\"")
    table: dict[str, Any] = {}
    design_path = None
    if assembly is not None:
        if not isinstance(assembly, str) or not assembly:
            raise MeasurementError(f"{where}: assembly", f"expected a path, got {assembly!r}")
        design_path = (path.parent / assembly).resolve()
        try:
            table.update(_model_from_assembly(kind, design_path, f"{where}: ", notes))
        except MeasurementError:
            raise
        except DesignError as exc:
            raise MeasurementError(f"{where}: assembly ({assembly}): {exc.field}", exc.problem, exc.allowed) from None
    if model is not None:
        if not isinstance(model, dict):
            raise MeasurementError(f"{where}: model", "expected a table")
        mw = f"{where}: model"
        other = {k for kk, keys in MODEL_KEYS.items() if kk != kind for k in keys} - set(MODEL_KEYS[kind])
        for key in model:
            if key in MODEL_KEYS[kind]:
                continue
            if key in other:
                notes.append(f"sidecar key model.{key} ignored: it belongs to another measurement kind")
                continue
            raise MeasurementError(f"{mw}.{key}", "unknown key", ", ".join(MODEL_KEYS[kind]))
        overridden = [k for k in model if k in table and k in MODEL_KEYS[kind]]
        if overridden:
            notes.append("sidecar [model] overrides the assembly for " + ", ".join(overridden))
        table.update({k: v for k, v in model.items() if k in MODEL_KEYS[kind]})
    mw = f"{where}: model"
    if kind in ("preload_trace", "transmission_error"):
        declared = _declared(table, mw, notes)
    if kind == "transmission_error":
        stages = table.get("stages")
        if stages is None:
            raise MeasurementError(f"{mw}.stages", "missing", "a list of [driver, driven] tooth counts, input to output")
        if not (isinstance(stages, list) and stages and all(isinstance(st, list) for st in stages)):
            raise MeasurementError(f"{mw}.stages", f"{stages!r} is not valid",
                                   "a list of [driver, driven] tooth counts (whole numbers >= 4), input to output")
        try:
            spec = TransmissionModelSpec(stages=tuple(tuple(st) for st in stages), declared=declared)
        except MeasurementError as exc:
            raise MeasurementError(f"{where}: {exc.field}", exc.problem, exc.allowed) from None
        return kind, description, spec, design_path
    drive = table.get("drive")
    if drive is not None and drive not in DRIVE_TYPES:
        raise MeasurementError(f"{mw}.drive", f"{drive!r} is not a valid choice", "'type1', 'type2'")
    if kind == "preload_trace":
        teeth = table.get("teeth")
        if teeth is None:
            raise MeasurementError(f"{mw}.teeth", "missing", "[input, cluster large, cluster small, output] tooth counts")
        if not isinstance(teeth, list) or len(teeth) != 4 or not all(isinstance(z, int) and not isinstance(z, bool) and z >= 4 for z in teeth):
            raise MeasurementError(f"{mw}.teeth", f"{teeth!r} is not valid", "4 whole numbers >= 4: [input, cluster large, cluster small, output]")
        return (kind, description, PreloadModelSpec(teeth=tuple(teeth), declared=declared, drive_type=drive), design_path)
    if drive is None:
        raise MeasurementError(f"{mw}.drive", "missing", "'type1', 'type2'")
    values = {k: _number(table, k, mw) for k in MODEL_KEYS[kind][1:]}
    if drive == "type1" and values["k3_Nm_per_rad"] is not None:
        raise MeasurementError(f"{mw}.k3_Nm_per_rad", "a type1 drive has no preload spring", "omit k3_Nm_per_rad for type1")
    try:
        spec = TorqueModelSpec(drive_type=drive, **values)
    except MeasurementError as exc:
        raise MeasurementError(f"{where}: {exc.field}", exc.problem, exc.allowed) from None
    missing = [k for k in ("k1_Nm_per_rad", "k2_Nm_per_rad", "preload_Nm") + (("k3_Nm_per_rad",) if drive == "type2" else ())
               if values[k] is None]
    if missing:
        notes.append("no nominal values for " + ", ".join(missing) + ": the nominal stage is null and the fit starts from the data")
    return kind, description, spec, design_path


def _declared(table: dict, mw: str, notes: list[str]) -> tuple[str, ...]:
    """The model's ``declared`` list (preload_trace, transmission_error); both terms when not given."""
    declared = table.get("declared")
    if declared is None:
        declared = list(DECLARED_NAMES)
        notes.append("model.declared not given: the declared model holds eccentricity and tooth_to_tooth")
    if not isinstance(declared, list) or not all(isinstance(d, str) for d in declared):
        raise MeasurementError(f"{mw}.declared", f"expected a list of names, got {declared!r}", ", ".join(map(repr, DECLARED_NAMES)))
    for d in declared:
        if d not in DECLARED_NAMES:
            raise MeasurementError(f"{mw}.declared", f"{d!r} is not a declared-model term", ", ".join(map(repr, DECLARED_NAMES)))
    return tuple(dict.fromkeys(declared))


# ----------------------------------------------------------------------------- reading

def _repeated_value(v: np.ndarray) -> tuple[float, int] | None:
    """(value, rows) when one value fills more than half of v, else None. Such a value is the
    median, so one partial sort finds it whatever the length."""
    if v.size == 0:
        return None
    med = float(np.median(v))
    count = int(np.count_nonzero(v == med))
    return (med, count) if 2 * count > v.size else None


def _check_channels(kind: str, data: dict[str, np.ndarray], cols: dict, where: str, notes: list[str]) -> None:
    """Degenerate channels of a usable record, each named by its column.

    The measured channels (carriage, torque, rotation) are noise-estimated from runs of four
    consecutive readings (:mod:`geargen.fit.noise`, a median): a channel that reads one value in
    more than half of its rows makes that median a flat run. Such a probe is stuck, saturated at
    its range limit, or disconnected when the value is the smallest or largest it reads, or when
    fewer than :data:`MIN_SAMPLES` rows read anything else; a value inside the range with enough
    rows elsewhere is a load held there (a torque test that dwells at zero between load steps),
    noted and fitted.
    """
    def column(ch):
        return f"{where}: column {cols[ch][2]}"

    def as_read(ch, value):  # the value in the column's own unit
        return f"{value / cols[ch][1]:.6g}"

    for ch, v in data.items():  # (temperature and test numbers may still hold gaps)
        finite = v if ch not in ("temperature", "test_nr") else v[np.isfinite(v)]
        if finite.size == 0:
            continue
        scale = abs(cols[ch][1])
        biggest, span = float(np.max(np.abs(finite))), float(np.ptp(finite))
        if biggest > MAX_MAGNITUDE * scale:
            raise MeasurementError(column(ch), f"holds a value of magnitude {biggest / scale:.3g}",
                                   f"|value| <= {MAX_MAGNITUDE:.0e}: squares of residuals must stay finite in double precision")
        if 0 < span < MIN_SPAN * scale:
            raise MeasurementError(column(ch), f"varies by only {span / scale:.3g} over the record",
                                   f"a variation > {MIN_SPAN:.0e}: squares of the noise level must stay above zero "
                                   "in double precision")
    t = data["time"]
    if np.ptp(t) == 0:
        raise MeasurementError(column("time"), f"every usable row has the same time {as_read('time', t[0])}: "
                               "the record spans no time", "rows in time order, strictly increasing time")
    if kind in ("preload_trace", "transmission_error"):
        turn = float(np.ptp(data["angle"]))
        if turn < math.pi:
            raise MeasurementError(column("angle"), f"the output turns only {np.degrees(turn):.3g} deg",
                                   f"a {kind.replace('_', ' ')} over one or more output revolutions (at least half of one)")
    if kind == "transmission_error":
        if np.ptp(data["input_angle"]) == 0:
            raise MeasurementError(column("input_angle"), f"is constant: every usable row reads "
                                   f"{as_read('input_angle', data['input_angle'][0])}", "the input turning with the output")
        return
    measured = ("carriage",) if kind == "preload_trace" else ("torque", "rotation")
    for ch in measured:
        v = data[ch]
        if np.ptp(v) == 0:
            what = "the torque never changes" if ch == "torque" else "is constant"
            raise MeasurementError(column(ch), f"{what}: every usable row reads {as_read(ch, v[0])}",
                                   "a torque cycled 0 -> +T -> -T -> 0" if ch == "torque" else
                                   "a measured, varying signal")
        stuck = _repeated_value(v)
        if not stuck:
            continue
        value, count = stuck
        elsewhere = v.size - count
        if value in (float(v.min()), float(v.max())) or elsewhere < MIN_SAMPLES:
            raise MeasurementError(column(ch), f"reads {as_read(ch, value)} in {count} of {v.size} usable rows: "
                                   "the probe is stuck, saturated at its range limit or disconnected, and the "
                                   "noise level cannot be estimated from its readings",
                                   f"one value in at most half of the rows, or a value inside the range held "
                                   f"(a dwell) with at least {MIN_SAMPLES} rows reading other values")
        notes.append(f"column {cols[ch][2]} reads {as_read(ch, value)} in {count} of {v.size} rows, inside its range: "
                     "taken as a level held (a dwell), not a stuck probe")


def spread_equal_times(t: np.ndarray) -> tuple[np.ndarray, int]:
    """Times of a logger that stamps with a finite resolution: non-decreasing ``t`` with runs of
    equal stamps. Each run of k rows at one stamp is spread evenly from that stamp towards the
    next (row i of the run at ``i / k`` of the way), the last run over k median row spacings.
    Returns (strictly increasing times, rows that shared a stamp with the row before); ``t``
    itself when no stamp repeats."""
    t = np.asarray(t, dtype=float)
    new_run = np.empty(t.size, dtype=bool)
    new_run[0] = True
    np.greater(t[1:], t[:-1], out=new_run[1:])
    shared = int(t.size - np.count_nonzero(new_run))
    if shared == 0:
        return t, 0
    starts = np.flatnonzero(new_run)
    lengths = np.diff(np.append(starts, t.size))
    stamps = t[starts]
    if starts.size > 1:
        row_spacing = float(np.median(np.diff(stamps) / lengths[:-1]))
        ends = np.append(stamps[1:], stamps[-1] + lengths[-1] * row_spacing)
    else:
        ends = stamps + 1.0  # one stamp: the record spans no time (refused by the checks)
    run = np.cumsum(new_run) - 1
    within = np.arange(t.size) - starts[run]
    out = stamps[run] + within / lengths[run] * (ends - stamps)[run]
    return out, shared


def read_measurement(csv_path: str | Path) -> Measurement:
    """Read and validate ``NAME.csv`` and its sidecar ``NAME.toml``.

    Degenerate records (no usable rows, too few, a channel that is empty, constant or stuck on
    one value, a record that spans no time or a preload trace whose output does not turn) are
    refused with a :class:`MeasurementError` that names the file and the column.
    """
    csv_path = Path(csv_path)
    if csv_path.suffix.lower() == ".toml":
        csv_path = csv_path.with_suffix(".csv")
    where = csv_path.name
    notes: list[str] = []
    tests: list[DatasheetSettings] = []
    kind, description, model, assembly = read_sidecar(csv_path.with_suffix(".toml"), notes, tests)
    found: dict = {}

    def select(header):
        cols, ignored = _column_map(header, kind, where)
        found.update(cols=cols, ignored=ignored)
        return [i for i, _, _ in cols.values()]

    _, arrays = read_csv(csv_path, select)
    cols, ignored = found["cols"], found["ignored"]
    if ignored:
        notes.append("unknown columns ignored: " + ", ".join(ignored))
    for ch, (_, _, name) in cols.items():
        if ch not in CHANNELS:  # (the test number is a count)
            continue
        stem, suffixes = CHANNELS[ch]
        if name != f"{stem}_{next(iter(suffixes))}":
            notes.append(f"column {name} converted from its unit")
    data = dict(zip(cols, arrays))
    for ch, (_, factor, _) in cols.items():
        if factor != 1.0:
            data[ch] *= factor  # in place: the column arrays belong to this reader
    required = REQUIRED[kind]
    names = ", ".join(cols[ch][2] for ch in required)
    rows = data["time"].size
    if rows == 0:
        raise MeasurementError(f"{where}: columns {names}", "no data rows under the header",
                               f">= {MIN_SAMPLES} rows of numbers")
    bad_rows = np.zeros(rows, bool)
    for ch in required:
        v = data[ch]
        if np.any(np.isinf(v)):
            row = int(np.flatnonzero(np.isinf(v))[0])
            raise MeasurementError(f"{where}: column {cols[ch][2]}", f"value {v[row]} in data row {row + 1} is not finite")
        missing = np.isnan(v)
        if missing.all():
            raise MeasurementError(f"{where}: column {cols[ch][2]}",
                                   f"is empty in every one of its {rows} rows (all probe drop-outs)", "measured values")
        bad_rows |= missing
        del missing
    dropped = int(bad_rows.sum())
    if dropped:
        notes.append(f"{dropped} rows with a missing value in a required column dropped (probe drop-outs)")
        keep = ~bad_rows
        data = {ch: v[keep] for ch, v in data.items()}
        del keep
    t = data["time"]
    if t.size < MIN_SAMPLES:
        raise MeasurementError(f"{where}: columns {names}",
                               f"only {t.size} rows hold all of them ({rows} rows read, {dropped} with a drop-out): "
                               "too few to fit", f">= {MIN_SAMPLES} rows")
    _check_channels(kind, data, cols, where, notes)
    step_ok = np.diff(t) >= 0
    if not step_ok.all():
        i = int(np.flatnonzero(~step_ok)[0])
        row = int(np.flatnonzero(~bad_rows)[i + 1]) + 1 if dropped else i + 2
        raise MeasurementError(f"{where}: column {cols['time'][2]}",
                               f"goes back in time at data row {row} ({t[i + 1]} after {t[i]})",
                               "rows in time order (equal consecutive times are taken as the logger's resolution)")
    del step_ok, bad_rows
    t, shared = spread_equal_times(t)
    if shared:
        data["time"] = t
        notes.append(f"{shared} rows share their time stamp with the row before (the logger's time resolution): "
                     "each run of equal stamps is spread evenly up to the next stamp")
    temperature = data.get("temperature")
    if temperature is not None:
        good = np.isfinite(temperature)
        if not good.any():
            notes.append("temperature column is empty: ignored")
            temperature = None
        elif not good.all():
            notes.append(f"{int((~good).sum())} missing temperature values interpolated in time")
            temperature = np.interp(t, t[good], temperature[good])
    test_nr = _test_numbers(data.get("test_nr"), where, notes)
    common = dict(kind=kind, name=csv_path.stem, time_s=t, model=model, temperature_C=temperature,
                  description=description, notes=tuple(notes), source=csv_path.resolve(),
                  columns={ch: name for ch, (_, _, name) in cols.items()}, assembly=assembly,
                  test=tests[0] if tests else DatasheetSettings())
    if kind == "preload_trace":
        return Measurement(angle_rad=data["angle"], carriage_um=data["carriage"], **common)
    if kind == "transmission_error":
        return Measurement(input_angle_rad=data["input_angle"], angle_rad=data["angle"], **common)
    return Measurement(torque_Nm=data["torque"], rotation_rad=data["rotation"], test_nr=test_nr, **common)


def _test_numbers(values: np.ndarray | None, where: str, notes: list[str]) -> np.ndarray | None:
    """The ``test_nr`` column: whole numbers; a missing cell continues the test of the row before."""
    if values is None:
        return None
    good = np.isfinite(values)
    if not good.any():
        notes.append(f"column {TEST_COLUMN} is empty: ignored")
        return None
    bad = good & (values != np.round(values))
    if bad.any():
        row = int(np.flatnonzero(bad)[0])
        raise MeasurementError(f"{where}: column {TEST_COLUMN}", f"value {values[row]:g} in data row {row + 1} is not a "
                               "whole number", "test numbers: whole numbers, one per test")
    if not good.all():
        notes.append(f"{int((~good).sum())} empty {TEST_COLUMN} cells continue the test of the row before")
        index = np.where(good, np.arange(values.size), -1)
        np.maximum.accumulate(index, out=index)
        first = int(np.flatnonzero(good)[0])
        index[:first] = first
        values = values[index]
    return values


# ----------------------------------------------------------------------------- writing

def write_measurement(meas: Measurement, directory: str | Path, name: str | None = None,
                      extra_columns: dict[str, np.ndarray] | None = None) -> Path:
    """Write ``NAME.csv`` and ``NAME.toml`` in the contract's spellings; returns the CSV path.

    ``extra_columns`` adds columns the reader must ignore (to exercise that path).
    """
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    name = name or meas.name
    if meas.kind == "preload_trace":
        cols = {"time_s": meas.time_s, "output_angle_deg": np.degrees(meas.angle_rad), "carriage_x_um": meas.carriage_um}
        fmt = ["%.6f", "%.7f", "%.5f"]
    elif meas.kind == "transmission_error":
        # 1e-10 deg is 1.7e-6 urad: the transmission error survives the text to far below any encoder
        cols = {"time_s": meas.time_s, "input_angle_deg": np.degrees(meas.input_angle_rad),
                "output_angle_deg": np.degrees(meas.angle_rad)}
        fmt = ["%.6f", "%.10f", "%.10f"]
    else:
        cols = {"time_s": meas.time_s, "output_torque_Nm": meas.torque_Nm, "output_rotation_urad": meas.rotation_rad * 1e6}
        fmt = ["%.6f", "%.6f", "%.5f"]
        if meas.test_nr is not None:
            cols[TEST_COLUMN] = meas.test_nr
            fmt.append("%d")
    if meas.temperature_C is not None:
        cols["temperature_C"] = meas.temperature_C
        fmt.append("%.5f")
    for k, v in (extra_columns or {}).items():
        cols[k] = v
        fmt.append("%.6g")
    csv_path = directory / f"{name}.csv"
    np.savetxt(csv_path, np.column_stack(list(cols.values())), delimiter=",", fmt=fmt,
               header=",".join(cols), comments="")
    m = meas.model
    lines = [f'kind = "{meas.kind}"', f"description = {_toml_string(meas.description)}", "", "[model]"]
    if isinstance(m, TransmissionModelSpec):
        lines.append("stages = [" + ", ".join(f"[{a}, {b}]" for a, b in m.stages) + "]")
        lines.append("declared = [" + ", ".join(f'"{d}"' for d in m.declared) + "]")
    elif isinstance(m, PreloadModelSpec):
        if m.drive_type:
            lines.append(f'drive = "{m.drive_type}"')
        lines.append(f"teeth = [{', '.join(str(z) for z in m.teeth)}]")
        lines.append("declared = [" + ", ".join(f'"{d}"' for d in m.declared) + "]")
    else:
        lines.append(f'drive = "{m.drive_type}"')
        for key in MODEL_KEYS["torque_deflection"][1:]:
            v = getattr(m, key)
            if v is not None:
                lines.append(f"{key} = {v!r}")
    if meas.kind == "torque_deflection" and meas.test != DatasheetSettings():
        t = meas.test
        lines += ["", "[test]", f"lost_motion_fraction = {t.lost_motion_fraction!r}"]
        if t.rated_torque_Nm is not None:
            lines.append(f"rated_torque_Nm = {t.rated_torque_Nm!r}")
        if t.stiffness_limits_Nm is not None:
            lines.append(f"stiffness_limits_Nm = [{t.stiffness_limits_Nm[0]!r}, {t.stiffness_limits_Nm[1]!r}]")
    (directory / f"{name}.toml").write_text("\n".join(lines) + "\n")
    return csv_path


def _toml_string(s: str) -> str:
    return '"' + s.replace("\\", "\\\\").replace('"', '\\"').replace("\n", " ") + '"'
