"""The command line: exit statuses, messages without tracebacks, and outputs that never cost the
user a file (issue 10). Each reviewer's reproduction has its test here; the policy itself is
tested piece by piece in tests/test_outputs.py.

Exit statuses: 0 ok, 1 a check failed, 2 bad input, 3 environment or interrupted, 4 a bug.
Most refusals happen before anything is built, so most tests here are fast; those that build
an assembly or kill builds are marked slow.
"""

import json
import os
import random
import shutil
import signal
import subprocess
import sys
import textwrap
import threading
import time
from pathlib import Path

import pytest

from geargen import __version__
from geargen import pipeline as pl
from geargen.cli import main

ROOT = Path(__file__).resolve().parents[1]
SPLIT = ROOT / "assemblies" / "split_pinion.toml"  # the fastest assembly to build (~5 s)
ROBOT = ROOT / "assemblies" / "robot_joint.toml"
GEAR_TOML = '[gear]\nteeth = 20\nmodule_mm = 1.0\npressure_angle_deg = 20\nface_width_mm = 5\n'


def _env() -> dict:
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT)] + [p for p in [env.get("PYTHONPATH")] if p])
    env.pop("GEARGEN_DEBUG", None)
    return env


def _cli(*args) -> list[str]:
    return [sys.executable, "-m", "geargen.cli", *map(str, args)]


def _tree(folder: Path) -> dict[str, bytes]:
    return {p.name: p.read_bytes() for p in sorted(folder.iterdir())}


def _fake_build(folder: Path, design: Path) -> Path:
    """A folder as an earlier ``geargen build`` of ``design`` leaves it (manifest lists the files)."""
    folder.mkdir(parents=True)
    (folder / "assembly.step").write_bytes(b"ISO-10303-21;\n")
    manifest = {"generator": "geargen build", "source": str(design.resolve()),
                "design": {"name": "split_pinion", "file": str(design.resolve())},
                "files": {"assembly.step": {"format": "step", "bytes": 14}}}
    (folder / "manifest.json").write_text(json.dumps(manifest))
    return folder


def _temporaries(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.glob(".*.build.*"))


def _live_in_group(pgid: int) -> list[int]:
    """Processes (not zombies) of process group ``pgid`` (Linux /proc)."""
    found = []
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            text = stat.read_text()
        except OSError:
            continue
        rest = text[text.rindex(")") + 2:].split()
        if int(rest[2]) == pgid and rest[0] not in ("Z", "X"):
            found.append(int(stat.parent.name))
    return found


def _wait_group_gone(pgid: int, timeout: float = 10.0) -> list[int]:
    deadline = time.monotonic() + timeout
    while (left := _live_in_group(pgid)) and time.monotonic() < deadline:
        time.sleep(0.05)
    return left


linux_only = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="uses /proc and fork")


# ---------------------------------------------------------------- version, help, exit statuses


def test_version_prints_the_package_version(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["--version"])
    assert exc.value.code == 0
    assert capsys.readouterr().out.strip() == f"geargen {__version__}"


def test_help_lists_the_exit_statuses(capsys):
    for argv in (["--help"], ["build", "--help"]):
        with pytest.raises(SystemExit):
            main(argv)
        out = capsys.readouterr().out
        assert "exit status:" in out
        for code in ("0  ok", "1  a check failed", "2  bad input", "3  environment", "4  internal error"):
            assert code in out, (argv, code)


def test_missing_design_file_and_a_folder_as_design_file_are_environment_problems(tmp_path, capsys):
    """Reproduction: a folder given as the design file raised IsADirectoryError (traceback, exit 1)."""
    assert main(["build", str(tmp_path / "nope.toml")]) == 3
    assert "nope.toml: no such design file" in capsys.readouterr().err
    for command in ("build", "synth", "stiffness", "check", "gear"):
        assert main([command, str(tmp_path)]) == 3, command
        err = capsys.readouterr().err
        assert "is a folder, not a design file" in err and "Traceback" not in err, command
    assert list(tmp_path.iterdir()) == []


def test_bad_design_content_and_bad_flags_are_bad_input(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    bad.write_text("name = \n")
    assert main(["build", str(bad), "--out", str(tmp_path / "out")]) == 2
    assert "not valid TOML" in capsys.readouterr().err
    with pytest.raises(SystemExit) as exc:
        main(["build", str(SPLIT), "--no-such-flag"])
    assert exc.value.code == 2
    assert not (tmp_path / "out").exists()


def test_an_internal_error_is_status_4_with_a_short_message(monkeypatch, capsys):
    import geargen.commands.synth as synth

    def broken(args):
        raise ZeroDivisionError("division by zero")

    monkeypatch.setattr(synth, "run", broken)
    monkeypatch.delenv("GEARGEN_DEBUG", raising=False)
    assert main(["synth", str(ROBOT)]) == 4
    err = capsys.readouterr().err
    assert "internal error: ZeroDivisionError" in err and "this is a bug" in err and "Traceback" not in err
    monkeypatch.setenv("GEARGEN_DEBUG", "1")
    assert main(["synth", str(ROBOT)]) == 4
    assert "Traceback" in capsys.readouterr().err


# ---------------------------------------------------------------- reproduction 1: --out . deleted everything


def test_build_out_dot_beside_the_design_file_deletes_nothing(tmp_path, monkeypatch, capsys):
    """Reproduction: ``geargen build X.toml --out .`` deleted the current folder, design file included."""
    (tmp_path / "X.toml").write_text(SPLIT.read_text())
    (tmp_path / "notes.txt").write_text("mine")
    monkeypatch.chdir(tmp_path)
    before = _tree(tmp_path)
    t0 = time.perf_counter()
    assert main(["build", "X.toml", "--out", ".", "--quiet"]) == 3
    err = capsys.readouterr().err
    assert "--out" in err and "did not write (X.toml, notes.txt)" in err
    assert _tree(tmp_path) == before
    assert time.perf_counter() - t0 < 5  # refused before any solid was built


def test_an_earlier_build_holding_a_user_file_is_never_replaced(tmp_path, monkeypatch, capsys):
    design = tmp_path / "X.toml"
    design.write_text(SPLIT.read_text())
    monkeypatch.chdir(tmp_path)
    folder = _fake_build(tmp_path / "exports" / "X", design)
    (folder / "bench_notes.txt").write_text("mine")
    before = _tree(folder)
    for extra in ([], ["--overwrite"]):
        assert main(["build", "X.toml", "--quiet", *extra]) == 3
        assert "bench_notes.txt" in capsys.readouterr().err
    assert _tree(folder) == before


# ---------------------------------------------------------------- reproduction 4: two files, one name


def test_default_output_folder_follows_the_design_file_name(tmp_path):
    """Reproduction: two design files with the same ``name =`` wrote the same exports/<name>/."""
    one, two = tmp_path / "one.toml", tmp_path / "two.toml"
    one.write_text(SPLIT.read_text())
    two.write_text(SPLIT.read_text())
    a, b = pl.load(one), pl.load(two)
    assert a.name == b.name == "split_pinion"
    assert pl.default_out_dir(a) == Path("exports/one") and pl.default_out_dir(b) == Path("exports/two")


def test_another_design_file_of_the_same_file_name_needs_overwrite(tmp_path, monkeypatch, capsys):
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    for d in ("a", "b"):
        (tmp_path / d / "X.toml").write_text(SPLIT.read_text())
    monkeypatch.chdir(tmp_path)
    folder = _fake_build(tmp_path / "exports" / "X", tmp_path / "a" / "X.toml")
    before = _tree(folder)
    assert main(["build", "b/X.toml", "--quiet"]) == 3
    err = capsys.readouterr().err
    assert "a/X.toml" in err and "--overwrite replaces it" in err
    assert _tree(folder) == before


# ---------------------------------------------------------------- reproduction 3: --out a file


@pytest.mark.parametrize("argv", [["build", SPLIT], ["gear", "--teeth", "20", "--module", "1", "--face-width", "5"],
                                  ["stiffness", ROBOT]], ids=["build", "gear", "stiffness"])
def test_out_naming_a_file_is_refused(tmp_path, capsys, argv):
    """Reproduction: ``--out some_file`` silently turned the file into a folder."""
    f = tmp_path / "some_file"
    f.write_text("data")
    assert main([*map(str, argv), "--out", str(f)]) == 3
    err = capsys.readouterr().err
    assert "--out" in err and "is a file, not a folder" in err
    assert f.read_text() == "data" and sorted(p.name for p in tmp_path.iterdir()) == ["some_file"]


def test_json_naming_a_folder_is_refused(tmp_path, capsys):
    assert main(["stiffness", str(ROBOT), "--json", str(tmp_path), "--no-plots"]) == 3
    assert "--json" in capsys.readouterr().err


# ---------------------------------------------------------------- reproduction 8: gear options and folders


def test_gear_design_file_with_a_gear_option_is_refused_naming_it(tmp_path, capsys):
    """Reproduction: ``geargen gear FILE --teeth 30`` ignored --teeth."""
    (tmp_path / "g.toml").write_text(GEAR_TOML)
    assert main(["gear", str(tmp_path / "g.toml"), "--teeth", "30", "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert "--teeth" in err and "conflicts with the design file" in err
    assert not (tmp_path / "o").exists()


def test_gear_option_errors_name_the_flag(tmp_path, capsys):
    assert main(["gear", "--teeth", "0", "--module", "1", "--face-width", "5", "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert "--teeth: 0 is out of range" in err and "options." not in err
    assert main(["gear", "--teeth", "20", "--module", "1", "--face-width-mm", "-5", "--out", str(tmp_path / "o")]) == 2
    assert "--face-width-mm: -5 is out of range" in capsys.readouterr().err


def test_gear_into_a_build_folder_is_refused(tmp_path, capsys):
    """Reproduction: ``gear --out <a build dir>`` merged itself into the assembly's manifest."""
    folder = _fake_build(tmp_path / "build", SPLIT)
    before = _tree(folder)
    (tmp_path / "g.toml").write_text(GEAR_TOML)
    for extra in ([], ["--overwrite"]):
        assert main(["gear", str(tmp_path / "g.toml"), "--out", str(folder), "--no-stl", *extra]) == 3
        assert "holds the output of geargen build, not of geargen gear" in capsys.readouterr().err
    assert _tree(folder) == before


# ---------------------------------------------------------------- reproduction 2: stiffness inside the build


def test_stiffness_writes_beside_the_build_folder_not_inside(tmp_path, monkeypatch):
    """Reproduction: stiffness wrote exports/<name>/stiffness, which the next build deleted."""
    design = tmp_path / "X.toml"
    design.write_text(ROBOT.read_text())
    monkeypatch.chdir(tmp_path)
    assert main(["stiffness", "X.toml"]) == 0
    plots = tmp_path / "exports" / "X-stiffness"
    manifest = json.loads((plots / "manifest.json").read_text())
    assert manifest["generator"] == "geargen stiffness" and manifest["source"] == str(design.resolve())
    assert sorted(manifest["files"]) == sorted(p.name for p in plots.glob("*.png")) and len(manifest["files"]) == 3
    build_folder = tmp_path / pl.default_out_dir(pl.load(design))
    assert build_folder not in plots.parents and plots != build_folder
    # the same design again replaces its own plots; a user's file there stops it
    assert main(["stiffness", "X.toml"]) == 0
    (plots / "mine.txt").write_text("mine")
    assert main(["stiffness", "X.toml"]) == 3
    assert (plots / "mine.txt").read_text() == "mine"


# ---------------------------------------------------------------- reproduction 7: read-only, mount point


def _private_mount(tmp_path: Path, options: str) -> tuple[list[str], Path]:
    """A command prefix that runs the rest in a private mount namespace with a tmpfs mounted
    (``options``) at a fresh folder; skips where the system does not allow it."""
    mnt = tmp_path / "mnt"
    mnt.mkdir()
    if shutil.which("unshare") is None:
        pytest.skip("no unshare")
    prefix = ["unshare", "-m", "sh", "-c", 'mount -t tmpfs -o "$1" none "$2" && shift 2 && exec "$@"', "sh",
              options, str(mnt)]
    probe = subprocess.run(prefix + ["true"], capture_output=True)
    if probe.returncode != 0:
        pytest.skip(f"cannot mount in a private namespace here: {probe.stderr.decode().strip()}")
    return prefix, mnt


def test_read_only_output_is_refused_before_any_work(tmp_path):
    if os.geteuid() == 0:
        prefix, ro = _private_mount(tmp_path, "ro")
    else:
        prefix, ro = [], tmp_path / "ro"
        ro.mkdir()
        ro.chmod(0o555)
    t0 = time.perf_counter()
    done = subprocess.run(prefix + _cli("build", SPLIT, "--out", ro / "out"), capture_output=True, text=True,
                          env=_env(), timeout=120)
    assert done.returncode == 3, done.stderr
    assert "--out" in done.stderr and "cannot write in" in done.stderr and "Traceback" not in done.stderr
    assert "gear solids" not in done.stderr  # checked before any solid was built
    assert time.perf_counter() - t0 < 30


def test_a_mount_point_as_out_is_refused(tmp_path):
    prefix, mnt = _private_mount(tmp_path, "rw")
    done = subprocess.run(prefix + _cli("build", SPLIT, "--out", mnt), capture_output=True, text=True,
                          env=_env(), timeout=120)
    assert done.returncode == 3, done.stderr
    assert "is a mount point" in done.stderr and "Traceback" not in done.stderr


# ---------------------------------------------------------------- reproduction 5: the child dies with its parent


@linux_only
def test_the_mesh_check_child_dies_with_its_parent_even_on_sigkill():
    """Reproduction: the forked mesh-check process outlived a killed build."""
    code = ("import time\nfrom geargen.pipeline import Alongside\n"
            "a = Alongside.start(time.sleep, 120)\nprint(a._process.pid, flush=True)\ntime.sleep(120)\n")
    p = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True, env=_env(),
                         start_new_session=True)
    try:
        child = int(p.stdout.readline())
        assert child in _live_in_group(p.pid)
        os.kill(p.pid, signal.SIGKILL)
        p.wait(timeout=10)
        assert _wait_group_gone(p.pid, timeout=5) == []
    finally:
        for pid in _live_in_group(p.pid):
            os.kill(pid, signal.SIGKILL)
        p.stdout.close()


@linux_only
def test_the_next_output_removes_temporaries_of_killed_runs_and_reports_unknown_ones(tmp_path, capsys):
    """Reproduction: an interrupted build left its hidden ``.NAME.build.*`` folder forever."""
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    stale = tmp_path / f".g.build.{dead.pid}-killed"
    (stale / "out").mkdir(parents=True)
    (stale / "out" / "assembly.step").write_bytes(b"x" * 100_000)
    (stale / "geargen-temporary.json").write_text(json.dumps({"generator": "geargen", "pid": dead.pid}))
    unknown = tmp_path / ".g.build.someone_elses"
    unknown.mkdir()
    (unknown / "data").write_text("mine")
    assert main(["gear", "--teeth", "12", "--module", "1", "--face-width", "2", "--no-stl",
                 "--out", str(tmp_path / "g")]) == 0
    assert not stale.exists() and (unknown / "data").read_text() == "mine"
    assert f"left {unknown}" in capsys.readouterr().err
    assert _temporaries(tmp_path) == [unknown.name]


# ---------------------------------------------------------------- builds (slow)


def _sigint_as_at_a_terminal() -> None:
    """In the child before exec: Ctrl-C's default action. A runner that starts the tests as a
    background job has SIGINT ignored, the build would inherit that and rightly keep ignoring it."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def _start_build(design: Path, out: Path, quiet: bool = True, cwd: Path | None = None):
    return subprocess.Popen(_cli("build", design, "--out", out, *(["--quiet"] if quiet else [])),
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL if quiet else subprocess.PIPE,
                            text=True, env=_env(), cwd=cwd, start_new_session=True,
                            preexec_fn=_sigint_as_at_a_terminal)


def _snapshot(folder: Path):
    """None if absent; else (manifest text, {file: size}), asserting the build is complete: the
    folder holds exactly the manifest's files, each of its recorded size."""
    if not folder.exists():
        return None
    text = (folder / "manifest.json").read_text()
    files = {p.relative_to(folder).as_posix(): p.stat().st_size for p in folder.rglob("*") if p.is_file()}
    listed = json.loads(text)["files"]
    assert set(files) == set(listed) | {"manifest.json"}
    assert all(files[n] == e["bytes"] for n, e in listed.items())
    return text, files


@pytest.mark.slow
@linux_only
@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM], ids=["ctrl-c", "sigterm"])
def test_an_interrupted_build_cleans_up_and_exits_3(tmp_path, sig):
    """Reproduction: Ctrl-C gave a traceback and exit 1; SIGTERM left the temporary folder and
    an orphaned mesh-check process."""
    out = tmp_path / "out"
    p = _start_build(SPLIT, out, quiet=False)
    err: list[str] = []
    reader = threading.Thread(target=lambda: err.extend(iter(p.stderr.readline, "")), daemon=True)
    reader.start()
    deadline = time.monotonic() + 120
    while not any("mesh checks: started" in line for line in err) and p.poll() is None \
            and time.monotonic() < deadline:
        time.sleep(0.02)
    assert p.poll() is None, "".join(err)
    time.sleep(0.5)  # into the next steps, with the second process running
    os.kill(p.pid, sig)
    p.wait(timeout=60)
    reader.join(timeout=10)
    text = "".join(err)
    assert p.returncode == 3, text
    how = "Ctrl-C" if sig == signal.SIGINT else "SIGTERM"
    assert f"interrupted ({how})" in text and "Traceback" not in text
    assert not out.exists() and _temporaries(tmp_path) == []
    assert _wait_group_gone(p.pid) == []


def test_a_signal_while_forking_interrupts_the_build():
    """A SIGTERM that arrived while the build forked one of its processes (the drawings', the
    figures', the mesh checks') was raised inside the fork's at-fork hooks, where Python ignores
    exceptions: the build went on and exited 0 (seen once in CI-like runs). The hook here sends
    the signal at exactly that moment."""
    code = textwrap.dedent("""
        import os, signal
        from geargen.cli import _sigterm_as_interrupt
        from geargen.errors import Interrupted
        from geargen.pipeline import Alongside
        os.register_at_fork(after_in_parent=lambda: os.kill(os.getpid(), signal.SIGTERM))
        import multiprocessing, time
        with _sigterm_as_interrupt():
            mark = Alongside.started()
            try:
                job = Alongside.start(time.sleep, 30)
            except Interrupted:
                # the child made before the signal was raised: nobody holds it, the build's cleanup ends it
                Alongside.end_started_since(mark)
                print("interrupted", [p.is_alive() for p in multiprocessing.active_children()])
            else:
                print("went on", job.result(30))
    """)
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert done.stdout.strip() == "interrupted []", done.stdout + done.stderr


@pytest.mark.slow
def test_the_build_reports_each_step_on_a_line_of_its_own_in_order(tmp_path, capsys):
    """The progress a user reads: "[k/N] step ... t s" once per step, k = 1..N in order, no line holding
    two steps (a step done inside another's, the checks collected while the STEP files are written,
    prints after it, not into its line)."""
    assert main(["build", str(SPLIT), "--out", str(tmp_path / "out")]) == 0
    lines = capsys.readouterr().err.splitlines()  # progress on stderr, the folder on stdout
    steps = [line for line in lines if line.startswith("[")]
    assert all(line.count("/") >= 1 and line.count("[") == 1 and " ... " in line and " s" in line for line in steps)
    numbers = [line[1:line.index("]")].split("/") for line in steps]
    total = int(numbers[0][1])
    assert [int(k) for k, _ in numbers] == list(range(1, total + 1)) and {int(n) for _, n in numbers} == {total}
    assert [line.split("] ")[1].split(" ...")[0] for line in steps if "mesh checks" in line] == ["mesh checks"]


def test_rebuild_replaces_its_own_build_and_keeps_the_stiffness_plots(tmp_path, monkeypatch, capsys):
    """Reproductions 1, 2, 6 on real builds: the same design rebuilds into its folder; the
    stiffness plots beside it survive; exports have the user's umask; a user's file stops it."""
    (tmp_path / "X.toml").write_text(SPLIT.read_text())
    monkeypatch.chdir(tmp_path)
    assert main(["stiffness", "X.toml"]) == 0
    plots = _tree(tmp_path / "exports" / "X-stiffness")
    assert main(["build", "X.toml", "--quiet"]) == 0
    first = _snapshot(tmp_path / "exports" / "X")
    assert main(["build", "X.toml", "--quiet"]) == 0
    second = _snapshot(tmp_path / "exports" / "X")
    assert second[0] != first[0] and set(second[1]) == set(first[1])  # replaced whole (new timings)
    assert _tree(tmp_path / "exports" / "X-stiffness") == plots
    mask = os.umask(0)
    os.umask(mask)
    folder = tmp_path / "exports" / "X"
    assert folder.stat().st_mode & 0o777 == 0o777 & ~mask
    assert {p.stat().st_mode & 0o777 for p in folder.rglob("*") if p.is_file()} == {0o666 & ~mask}
    assert (folder / "review").stat().st_mode & 0o777 == 0o777 & ~mask
    # the review page's sub-folder is covered by the policy like the rest: a changed file there
    # needs --overwrite, a user's file there stops even --overwrite
    (folder / "review" / "data.js").write_text("changed")
    assert main(["build", "X.toml", "--quiet"]) == 3
    assert "review/data.js" in capsys.readouterr().err
    (folder / "review" / "notes.txt").write_text("mine")
    assert main(["build", "X.toml", "--quiet", "--overwrite"]) == 3
    assert "review/notes.txt" in capsys.readouterr().err
    (folder / "review" / "notes.txt").unlink()
    assert main(["build", "X.toml", "--quiet", "--overwrite"]) == 0
    (folder / "mine.txt").write_text("mine")
    assert main(["build", "X.toml", "--quiet", "--overwrite"]) == 3
    assert "mine.txt" in capsys.readouterr().err and (folder / "mine.txt").read_text() == "mine"
    assert _temporaries(tmp_path / "exports") == []


@pytest.mark.slow
@linux_only
def test_sigkill_at_random_moments_leaves_the_target_absent_or_complete(tmp_path):
    """Killing a build with SIGKILL at 10 random moments leaves the target either absent or the
    complete earlier build (or, killed after the swap, the complete new one), no orphaned
    process, and the next build cleans up after it."""
    out = tmp_path / "out"
    t0 = time.monotonic()
    first = _start_build(SPLIT, out)
    assert first.wait(timeout=300) == 0
    duration = time.monotonic() - t0
    earlier = _snapshot(out)
    assert earlier is not None
    rng = random.Random(10)
    outcomes = []
    for moment in [rng.uniform(0.05, 1.0) * duration for _ in range(10)]:
        p = _start_build(SPLIT, out)
        time.sleep(moment)
        killed = p.poll() is None
        if killed:
            os.kill(p.pid, signal.SIGKILL)
        p.wait(timeout=300)
        assert _wait_group_gone(p.pid, timeout=3) == [], f"orphaned process after a kill at {moment:.2f} s"
        now = _snapshot(out)  # asserts completeness when present
        if now is None:
            outcomes.append("absent")
        elif now == earlier:
            outcomes.append("earlier")
        else:  # a complete new build: the kill came after the swap, or the build had ended
            outcomes.append("new" if killed else "finished")
            earlier = now
    print("after each kill, the target was:", outcomes)
    assert outcomes.count("finished") < 5, outcomes  # most moments really killed a build
    last = _start_build(SPLIT, out)
    assert last.wait(timeout=300) == 0
    assert _snapshot(out) is not None
    assert _temporaries(tmp_path) == [], outcomes


# ---------------------------------------------------------------- a full disk (issue 31)

GEAR_OPTIONS = ["--teeth", "21", "--module", "1", "--face-width", "5", "--no-stl", "--no-drawing"]


@pytest.mark.parametrize("code, cause", [(28, "no space left on device"), (122, "disk quota exceeded"),
                                         (30, "read-only file system"), (13, "permission denied")])
def test_a_file_system_refusing_the_step_file_is_exit_3_saying_why(code, cause, tmp_path, monkeypatch, capsys):
    # errno 28 ENOSPC, 122 EDQUOT, 30 EROFS, 13 EACCES (Linux); the STEP file is written by Python from the
    # kernel's bytes, so the refusal is the OSError it is. Before: exit 2 "STEP write failed", no cause.
    import errno as errno_module
    assert (errno_module.ENOSPC, errno_module.EDQUOT, errno_module.EROFS, errno_module.EACCES) == (28, 122, 30, 13)
    write_bytes = Path.write_bytes

    def refusing(self, data):
        if self.suffix == ".step":
            raise OSError(code, os.strerror(code), str(self))
        return write_bytes(self, data)

    monkeypatch.setattr(Path, "write_bytes", refusing)
    out = tmp_path / "g"
    assert main(["gear", *GEAR_OPTIONS, "--out", str(out)]) == 3
    err = capsys.readouterr().err
    assert f"geargen gear: error: {cause}: {out / 'gear_21.step'}" in err
    assert list(tmp_path.iterdir()) == []  # no output, no temporary folder


def test_a_really_full_disk_is_exit_3_no_space_left(tmp_path):
    """A 200 kB tmpfs in a private mount namespace (root in a container: ``unshare -m``); a gear's
    STEP file is 1 MB. Skipped where no such file system can be mounted."""
    disk = tmp_path / "disk"
    disk.mkdir()
    script = f"mount -t tmpfs -o size=200k tmpfs {disk} || exit 99; cd {disk} && " \
             f"{' '.join(_cli('gear', *GEAR_OPTIONS, '--out', 'g'))}; echo rc=$?; ls -A"
    try:
        done = subprocess.run(["unshare", "-m", "sh", "-c", script], capture_output=True, text=True, env=_env(),
                              timeout=300)
    except FileNotFoundError:
        pytest.skip("no unshare")
    if done.returncode == 99 or "rc=" not in done.stdout:
        pytest.skip(f"cannot mount a tmpfs here: {done.stderr.strip()[:200]}")
    assert "rc=3" in done.stdout and done.stdout.strip().endswith("rc=3")  # and nothing left on the disk
    assert f"geargen gear: error: no space left on device: {disk / 'g' / 'gear_21.step'}" in done.stderr
