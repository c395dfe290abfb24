"""The output-folder policy and the safe writing of :mod:`geargen.outputs` (no CAD kernel: fast).

Earlier outputs are made here as geargen writes them (a manifest listing files with their sizes),
so each rule of the policy is checked on its own: what is written, replaced, refused, and that a
refused folder keeps every file.
"""

import errno
import json
import os
import socket
import subprocess
import sys
from pathlib import Path

import pytest

from geargen import outputs
from geargen.errors import EnvironmentProblem, OutputRefused
from geargen.outputs import OutputFolder, check_output_folder, clean_stale_temporaries

BUILD = "geargen build"


def _earlier_output(folder: Path, source: str, generator: str = BUILD, files=None) -> Path:
    """A folder as an earlier geargen output leaves it: files plus a manifest listing them."""
    folder.mkdir(parents=True, exist_ok=True)
    files = files or {"assembly.step": b"ISO-10303-21;\n", "report.md": b"# report\n"}
    for name, data in files.items():
        (folder / name).parent.mkdir(exist_ok=True)
        (folder / name).write_bytes(data)
    manifest = {"generator": generator, "source": source,
                "files": {n: {"bytes": len(d)} for n, d in files.items()}}
    (folder / "manifest.json").write_text(json.dumps(manifest))
    return folder


def _tree(folder: Path) -> dict[str, bytes]:
    return {p.name: p.read_bytes() for p in sorted(folder.iterdir())}


# ---------------------------------------------------------------- the policy


def test_new_and_empty_folders_are_written(tmp_path):
    assert check_output_folder(tmp_path / "new", BUILD, "/d/x.toml", "x") == "new"
    (tmp_path / "empty").mkdir()
    assert check_output_folder(tmp_path / "empty", BUILD, "/d/x.toml", "x") == "empty"


def test_a_folder_with_files_geargen_did_not_write_is_refused_even_with_overwrite(tmp_path):
    folder = tmp_path / "here"
    folder.mkdir()
    (folder / "X.toml").write_text('name = "x"\n')
    (folder / "notes.txt").write_text("mine")
    for overwrite in (False, True):
        with pytest.raises(OutputRefused, match=r"did not write \(X.toml, notes.txt\)"):
            check_output_folder(folder, BUILD, "/d/X.toml", "X", overwrite=overwrite)
    assert _tree(folder) == {"X.toml": b'name = "x"\n', "notes.txt": b"mine"}


def test_an_earlier_build_of_the_same_design_is_replaced(tmp_path):
    folder = _earlier_output(tmp_path / "out", "/d/X.toml")
    assert check_output_folder(folder, BUILD, "/d/X.toml", "X") == "replace"


def test_an_earlier_build_with_a_user_file_is_refused_even_with_overwrite(tmp_path):
    folder = _earlier_output(tmp_path / "out", "/d/X.toml")
    (folder / "my_notes.txt").write_text("measured on the bench")
    for overwrite in (False, True):
        with pytest.raises(OutputRefused, match="manifest does not list \\(my_notes.txt\\)"):
            check_output_folder(folder, BUILD, "/d/X.toml", "X", overwrite=overwrite)


def test_a_sub_folder_the_manifest_lists_is_looked_into(tmp_path):
    """The build's review/ page: listed files in a sub-folder are the build's; a user's file or
    folder in it, an unlisted folder, a link, or a changed file there are treated as at the top."""
    page = {"review/index.html": b"<html>", "review/data.js": b"window.X = 1;"}
    folder = _earlier_output(tmp_path / "out", "/d/X.toml", files={"report.md": b"# report\n", **page})
    assert check_output_folder(folder, BUILD, "/d/X.toml", "X") == "replace"
    (folder / "review" / "data.js").write_text("window.X = 2; // mine")
    with pytest.raises(OutputRefused, match=r"changed since geargen wrote them \(review/data.js\)"):
        check_output_folder(folder, BUILD, "/d/X.toml", "X")
    assert check_output_folder(folder, BUILD, "/d/X.toml", "X", overwrite=True) == "replace"
    for extra in ("review/notes.txt", "review/mine/a.txt", "other/a.txt"):
        (folder / extra).parent.mkdir(parents=True, exist_ok=True)
        (folder / extra).write_text("mine")
        shown = extra if extra.startswith("review/n") else extra.rsplit("/", 1)[0]
        for overwrite in (False, True):
            with pytest.raises(OutputRefused, match=f"manifest does not list \\({shown}\\)"):
                check_output_folder(folder, BUILD, "/d/X.toml", "X", overwrite=overwrite)
        (folder / extra).unlink()
        if extra != "review/notes.txt":
            (folder / extra).parent.rmdir()
    (folder / "review" / "link.js").symlink_to(folder / "report.md")
    with pytest.raises(OutputRefused, match=r"manifest does not list \(review/link.js\)"):
        check_output_folder(folder, BUILD, "/d/X.toml", "X", overwrite=True)


def test_an_earlier_build_of_another_design_file_needs_overwrite(tmp_path):
    folder = _earlier_output(tmp_path / "out", "/a/X.toml")
    with pytest.raises(OutputRefused, match="for /a/X.toml, not for the other file.*--overwrite"):
        check_output_folder(folder, BUILD, "/b/X.toml", "the other file")
    assert check_output_folder(folder, BUILD, "/b/X.toml", "b", overwrite=True) == "replace"


def test_files_changed_since_geargen_wrote_them_need_overwrite(tmp_path):
    folder = _earlier_output(tmp_path / "out", "/d/X.toml")
    (folder / "report.md").write_text("# report\nmy own remarks\n")
    with pytest.raises(OutputRefused, match=r"changed since geargen wrote them \(report.md\)"):
        check_output_folder(folder, BUILD, "/d/X.toml", "X")
    assert check_output_folder(folder, BUILD, "/d/X.toml", "X", overwrite=True) == "replace"


def test_another_commands_output_is_never_replaced(tmp_path):
    folder = _earlier_output(tmp_path / "out", "/d/X.toml")
    for overwrite in (False, True):
        with pytest.raises(OutputRefused, match="output of geargen build, not of geargen gear"):
            check_output_folder(folder, "geargen gear", "gear g from options", "g", overwrite=overwrite)


def test_a_build_manifest_without_source_is_recognised_by_its_design_file(tmp_path):
    """Builds written before manifests carried "source" name their design file in design.file."""
    folder = _earlier_output(tmp_path / "out", "unused")
    m = json.loads((folder / "manifest.json").read_text())
    del m["source"]
    m["design"] = {"name": "x", "file": str(tmp_path / "X.toml")}
    (folder / "manifest.json").write_text(json.dumps(m))
    assert check_output_folder(folder, BUILD, str(tmp_path / "X.toml"), "X") == "replace"
    with pytest.raises(OutputRefused, match="--overwrite"):
        check_output_folder(folder, BUILD, str(tmp_path / "Y.toml"), "Y")


def test_a_file_the_current_folder_and_a_mount_point_are_refused(tmp_path, monkeypatch):
    (tmp_path / "some_file").write_text("data")
    with pytest.raises(OutputRefused, match="--out .*some_file: is a file, not a folder"):
        check_output_folder(tmp_path / "some_file", BUILD, "/d/X.toml", "X")
    (tmp_path / "cwd").mkdir()
    monkeypatch.chdir(tmp_path / "cwd")
    with pytest.raises(OutputRefused, match="is the current folder"):
        check_output_folder((tmp_path / "cwd").resolve(), BUILD, "/d/X.toml", "X")
    mnt = tmp_path / "mnt"
    mnt.mkdir()
    monkeypatch.setattr(outputs.os.path, "ismount", lambda p: Path(p) == mnt)
    with pytest.raises(OutputRefused, match="is a mount point"):
        check_output_folder(mnt, BUILD, "/d/X.toml", "X")


# ---------------------------------------------------------------- writing a folder


def _write_some(folder: Path) -> None:
    (folder / "a.txt").write_text("new a")
    with outputs.atomic_path(folder / "b.step") as tmp:
        tmp.write_text("new b")
    (folder / "manifest.json").write_text(json.dumps(
        {"generator": BUILD, "source": "/d/X.toml",
         "files": {"a.txt": {"bytes": 5}, "b.step": {"bytes": 5}}}))


def test_output_folder_writes_replaces_and_leaves_no_temporary(tmp_path):
    target = tmp_path / "exports" / "X"
    out = OutputFolder(target, BUILD, "/d/X.toml")
    _write_some(out.prepare())
    assert not target.exists()  # nothing at the target before the commit
    assert out.commit() == target
    assert sorted(p.name for p in target.iterdir()) == ["a.txt", "b.step", "manifest.json"]
    # again: the earlier build of the same design is replaced whole
    earlier = target.stat().st_ino
    again = OutputFolder(target, BUILD, "/d/X.toml")
    work = again.prepare()
    (work / "a.txt").write_text("second")
    (work / "manifest.json").write_text(json.dumps({"generator": BUILD, "source": "/d/X.toml",
                                                    "files": {"a.txt": {"bytes": 6}}}))
    again.commit()
    assert sorted(p.name for p in target.iterdir()) == ["a.txt", "manifest.json"]
    assert (target / "a.txt").read_text() == "second"
    assert target.stat().st_ino != earlier
    assert sorted(p.name for p in (tmp_path / "exports").iterdir()) == ["X"]  # no temporary folders


@pytest.mark.parametrize("umask", [0o022, 0o027])
def test_files_and_folders_get_the_users_umask(tmp_path, umask):
    """tempfile makes 0600 files and 0700 folders; the exports are the user's ordinary files."""
    old = os.umask(umask)
    try:
        target = tmp_path / "X"
        out = OutputFolder(target, BUILD, "/d/X.toml")
        _write_some(out.prepare())
        out.commit()
    finally:
        os.umask(old)
    assert (target.stat().st_mode & 0o777) == 0o777 & ~umask
    for name in ("a.txt", "b.step", "manifest.json"):  # b.step went through tempfile.mkstemp
        assert ((target / name).stat().st_mode & 0o777) == 0o666 & ~umask, name


def test_discard_removes_the_temporary_and_the_folders_prepare_made(tmp_path):
    target = tmp_path / "a" / "b" / "X"
    out = OutputFolder(target, BUILD, "/d/X.toml")
    _write_some(out.prepare())
    out.discard()
    assert list(tmp_path.iterdir()) == []


def test_a_file_put_into_the_target_during_the_build_stops_the_commit(tmp_path):
    target = tmp_path / "X"
    target.mkdir()
    out = OutputFolder(target, BUILD, "/d/X.toml")
    _write_some(out.prepare())
    (target / "dropped_meanwhile.txt").write_text("mine")
    with pytest.raises(OutputRefused, match="dropped_meanwhile.txt"):
        out.commit()
    out.discard()
    assert _tree(target) == {"dropped_meanwhile.txt": b"mine"}
    assert sorted(p.name for p in tmp_path.iterdir()) == ["X"]


def test_an_unwritable_parent_is_an_environment_problem_before_any_work(tmp_path, monkeypatch):
    monkeypatch.setattr(outputs.os, "access", lambda path, mode: False)
    with pytest.raises(EnvironmentProblem, match="cannot write in"):
        OutputFolder(tmp_path / "X", BUILD, "/d/X.toml", flag="--out").prepare()
    assert list(tmp_path.iterdir()) == []


def test_exchange_swaps_two_folders_in_one_step(tmp_path):
    a, b = tmp_path / "a", tmp_path / "b"
    a.mkdir()
    b.mkdir()
    (a / "in_a").write_text("a")
    (b / "in_b").write_text("b")
    if not outputs.exchange(a, b):
        pytest.skip("no atomic exchange on this system or file system (two renames are used)")
    assert [p.name for p in a.iterdir()] == ["in_b"] and [p.name for p in b.iterdir()] == ["in_a"]


# ---------------------------------------------------------------- stale temporary folders


def _dead_pid() -> int:
    p = subprocess.Popen([sys.executable, "-c", "pass"])
    p.wait()
    return p.pid


def _temporary(parent: Path, name: str, marker: dict | None, content: bool = True) -> Path:
    folder = parent / name
    (folder / "out").mkdir(parents=True)
    if content:
        (folder / "out" / "assembly.step").write_bytes(b"x" * 1000)
    if marker is not None:
        (folder / outputs.MARKER).write_text(json.dumps(marker))
    return folder


def test_stale_temporaries_of_dead_processes_are_removed_live_ones_kept(tmp_path):
    dead = _dead_pid()
    me = outputs._marker()
    stale = _temporary(tmp_path, f".X.build.{dead}-abc", outputs._marker(dead) | {"pid": dead})
    live = _temporary(tmp_path, f".X.build.{os.getpid()}-def", me)
    reused = _temporary(tmp_path, ".Y.build.1-ghi", me | {"process_start_ticks": (me["process_start_ticks"] or 0) + 1})
    elsewhere = _temporary(tmp_path, ".Z.build.1-jkl", me | {"host": socket.gethostname() + "-other"})
    unmarked = _temporary(tmp_path, ".W.build.oldstyle", None)
    empty = tmp_path / f".V.build.{dead}-mno"
    empty.mkdir()
    user = tmp_path / ".my.build.notes"  # the pattern, but a file: never touched
    user.write_text("mine")
    done = clean_stale_temporaries(tmp_path)
    removed = {stale, empty} | ({reused} if me["process_start_ticks"] is not None else set())
    assert set(done.removed) == removed
    assert {p for p, _ in done.left} == {elsewhere, unmarked}
    assert live.exists() and user.read_text() == "mine"
    for p in removed:
        assert not p.exists()


def test_outputs_module_does_not_load_the_cad_kernel():
    code = ("import sys, geargen.outputs; "
            "print(','.join(m for m in sys.modules if m.split('.')[0] in ('cadquery', 'OCP', 'numpy')))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.strip()
    assert out == ""


# ---------------------------------------------------------------- single files


def test_write_text_dash_is_standard_output_and_a_folder_is_refused(tmp_path, capsys):
    assert outputs.write_text("-", '{"a": 1}\n', "--json") is None
    assert capsys.readouterr().out == '{"a": 1}\n'
    with pytest.raises(EnvironmentProblem, match="--json: .* is a folder, not a file"):
        outputs.write_text(tmp_path, "x", "--json")
    path = outputs.write_text(tmp_path / "sub" / "r.json", "x\n", "--json")
    assert path.read_text() == "x\n" and (path.stat().st_mode & 0o777) == 0o666 & ~outputs.current_umask()


def test_atomic_path_leaves_nothing_on_failure(tmp_path):
    target = tmp_path / "r.json"
    target.write_text("old")
    with pytest.raises(RuntimeError):
        with outputs.atomic_path(target) as tmp:
            tmp.write_text("half")
            raise RuntimeError("disk full")
    assert [p.name for p in tmp_path.iterdir()] == ["r.json"] and target.read_text() == "old"


def test_a_gear_folder_from_before_manifests_named_the_command_needs_overwrite(tmp_path):
    folder = _earlier_output(tmp_path / "g", "unused", generator="geargen 0.1.0", files={"g.step": b"step"})
    m = json.loads((folder / "manifest.json").read_text())
    del m["source"]
    (folder / "manifest.json").write_text(json.dumps(m))
    with pytest.raises(OutputRefused, match="unrecorded source.*--overwrite"):
        check_output_folder(folder, "geargen gear", "gear g from options", "g")
    assert check_output_folder(folder, "geargen gear", "gear g from options", "g", overwrite=True) == "replace"
    with pytest.raises(OutputRefused, match="output of geargen gear, not of geargen build"):
        check_output_folder(folder, BUILD, "/d/g.toml", "g", overwrite=True)


# ---------------------------------------------------------------- the file system says no


@pytest.mark.parametrize("code, cause", [(errno.ENOSPC, "no space left on device"), (errno.EDQUOT, "disk quota exceeded"),
                                         (errno.EROFS, "read-only file system"), (errno.EACCES, "permission denied")])
def test_a_refused_write_names_the_cause_and_the_final_file(code, cause, tmp_path):
    folder = OutputFolder(tmp_path / "out", "geargen test", "source")
    work = folder.prepare()
    try:
        with pytest.raises(OSError) as info:
            with outputs.atomic_path(work / "part.step") as tmp:
                tmp.write_text("half")
                raise OSError(code, os.strerror(code))
    finally:
        folder.discard()
    # the errno kept (the command line's exit 3), the cause as a message says it, the file named where
    # it will be once the folder is in place (not the temporary folder)
    assert (info.value.errno, info.value.strerror, info.value.filename) == (code, cause, str(tmp_path / "out" / "part.step"))
    assert list(tmp_path.iterdir()) == []


def test_a_write_that_failed_without_a_cause_on_a_full_disk_is_a_full_disk(tmp_path, monkeypatch):
    # the CAD kernel's writer says only "failed"; on a file system with no space left that is the cause
    class Full:
        f_bavail, f_frsize = 0, 4096

    def failing_write(target):
        with outputs.atomic_path(target) as tmp:
            tmp.write_text("half")
            raise RuntimeError("the kernel's write failed")

    with pytest.raises(RuntimeError):  # space left: the failure is not the disk's
        failing_write(tmp_path / "a.step")
    monkeypatch.setattr(outputs.os, "statvfs", lambda path: Full())
    with pytest.raises(OSError) as info:
        failing_write(tmp_path / "a.step")
    assert (info.value.errno, str(info.value)) == (errno.ENOSPC, f"[Errno 28] no space left on device: '{tmp_path / 'a.step'}'")
    assert list(tmp_path.iterdir()) == []
