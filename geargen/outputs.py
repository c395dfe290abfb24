"""Where geargen writes, and how: outputs that never cost the user a file (standard library only).

The folder policy (``geargen build``, ``geargen gear``, ``geargen stiffness``). An output folder
is written only when it

- does not exist (it is created, and so are missing folders above it), or
- is an empty folder, or
- holds an earlier output of the same command for the same source: its ``manifest.json`` names
  the command (``"generator": "geargen build"``) and the source (the design file's absolute path;
  for a gear, the gear's name and where it came from), and the folder holds nothing the manifest
  does not list. Such an earlier output is replaced whole, by default: rebuilding a design into
  its own folder is the normal edit-and-build loop.

``--overwrite`` also replaces an earlier output of the same command for another source (another
design file with the same file name, an earlier gear of the same name from other options) and
an earlier output whose files were changed since geargen wrote them (sizes differ from the
manifest's). Nothing replaces a folder holding a file the manifest does not list, another
command's output, a plain file, the current folder or a mount point: geargen never deletes a
file it did not write. Every refusal is an :class:`~geargen.errors.OutputRefused` (exit status 3).

How a folder is written (:class:`OutputFolder`). Everything goes into a temporary folder beside
the target, ``.<target>.build.<pid>-<random>/``, whose first file is a marker
(``geargen-temporary.json``: process id, its start time, host); the output is built in its
``out/`` sub-folder, which replaces the target in one atomic exchange (Linux ``renameat2``
``RENAME_EXCHANGE``; elsewhere two renames, between which the target is briefly absent) once
every file is written. So the target is at every moment absent, the complete earlier output or
the complete new one. A process killed before it cleans up (``kill -9``, power loss) leaves its
temporary folder, marker and all; the next output into the same parent folder removes every such
folder whose process is gone (:func:`clean_stale_temporaries`) and reports any it cannot claim.

Files are written atomically (:func:`atomic_path`) and get the user's umask (0644 files and
0755 folders under the usual 022), never the 0600/0700 of :mod:`tempfile`.
"""

from __future__ import annotations

import ctypes
import errno
import json
import os
import re
import shutil
import socket
import sys
import tempfile
import time
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath

from geargen.errors import EnvironmentProblem, OutputRefused

MANIFEST = "manifest.json"
#: the date every exported file's header carries where its format asks for one (the STEP header's
#: time_stamp, ISO 8601; the DXF's creation and update dates): fixed, so that two builds of one
#: design give the same bytes and a shop's revision control sees no change where there is none;
#: the start of the Unix epoch, which no reader takes for a real date of writing
EXPORT_DATE = "1970-01-01T00:00:00"
MARKER = "geargen-temporary.json"
WORK = "out"
#: an empty temporary folder without a marker (a process killed between creating it and writing
#: the marker) is removed once its process is gone or it is this old (s)
EMPTY_GRACE_S = 60.0
_TEMPORARY = re.compile(r"^\..+\.build\.(?:(?P<pid>\d+)-)?[^/]+$")


# ---------------------------------------------------------------- modes


def current_umask() -> int:
    """The process's umask, read without changing it where the system tells it (Linux)."""
    try:
        with open("/proc/self/status") as fh:
            for line in fh:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError, IndexError):
        pass
    mask = os.umask(0o022)  # the only portable way to read it: set and restore at once
    os.umask(mask)
    return mask


def file_mode() -> int:
    """Mode of a new file under the user's umask (0644 under 022)."""
    return 0o666 & ~current_umask()


# ---------------------------------------------------------------- where a file may be written

#: the output folders being written now (between :meth:`OutputFolder.prepare` and its commit or
#: discard), resolved, each with the target it will become: while any is, :func:`atomic_path`
#: writes only inside one of them
_WRITING: dict[Path, Path] = {}

#: what a file system's refusal to write means, by errno, as messages say it
_WRITE_CAUSES = {errno.ENOSPC: "no space left on device", errno.EDQUOT: "disk quota exceeded",
                 errno.EROFS: "read-only file system", errno.EACCES: "permission denied",
                 errno.EPERM: "operation not permitted", errno.EFBIG: "file too large"}
#: free space (bytes) below which a write that failed without saying why (the CAD kernel's) is
#: taken to have failed for want of space: less than any file geargen writes needs
FULL_DISK_BYTES = 64 * 1024


def os_cause(exc: OSError) -> str:
    """The cause of an OSError as a message says it: ``"no space left on device"``, ..."""
    return _WRITE_CAUSES.get(exc.errno) or (exc.strerror or str(exc)).lower()


def writing_into(folder: Path, target: Path) -> None:
    """Declare ``folder`` an output folder being written, to become ``target`` (see :func:`confined`)."""
    _WRITING[Path(os.path.realpath(folder))] = Path(target)


def done_writing(folder: Path) -> None:
    _WRITING.pop(Path(os.path.realpath(folder)), None)


def shown_path(path) -> Path:
    """Where ``path`` (inside an output folder being written) will be once the folder is in place:
    what a message names, rather than the temporary folder."""
    real = Path(os.path.realpath(path))
    for folder, target in _WRITING.items():
        if real.is_relative_to(folder):
            return target / real.relative_to(folder)
    return Path(path)


def confined(path) -> Path:
    """``path``, when it may be written: while output folders are being written, only a path that
    resolves (symbolic links and ``..`` followed) inside one of them; an :class:`OutputRefused`
    otherwise, before anything is written. The one check between every file geargen writes and a
    name that would lead it out of its folder."""
    path = Path(path)
    if not _WRITING:
        return path
    real = Path(os.path.realpath(path))
    if not any(real.is_relative_to(folder) for folder in _WRITING):
        raise OutputRefused(str(path), f"resolves to {real}, outside the output folder being written "
                            f"({', '.join(map(str, _WRITING.values()))})", "geargen writes only inside its output folder")
    return path


def _full_disk(folder: Path) -> bool:
    try:
        st = os.statvfs(folder)
    except (OSError, AttributeError):
        return False
    return st.f_bavail * st.f_frsize < FULL_DISK_BYTES


@contextmanager
def atomic_path(path, user_file: bool = False):
    """Yield a temporary path next to ``path`` (same suffix); on success move it onto ``path``
    with the user's umask mode (``tempfile`` makes 0600 files). A failure or an interruption
    removes the temporary file and leaves any old ``path`` untouched.

    Every file geargen writes goes through here: ``path`` must be :func:`confined` to the output
    folder being written, unless ``user_file`` (a file the user named, ``--json FILE``). The file
    system's refusal (a full disk, a quota, a read-only file system) is an OSError naming ``path``
    (an environment problem, exit status 3); so is a write that failed without saying why (the CAD
    kernel's) on a file system with no space left."""
    path = Path(path) if user_file else confined(path)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=f".{path.stem}.", suffix=f".tmp{path.suffix}", dir=path.parent)
        os.close(fd)
    except OSError as exc:
        raise OSError(exc.errno, os_cause(exc), str(shown_path(path))) from None
    try:
        yield Path(tmp)
        os.chmod(tmp, file_mode())
        os.replace(tmp, path)
    except OSError as exc:
        _remove(tmp)
        raise OSError(exc.errno, os_cause(exc), str(shown_path(path))) from None
    except Exception:
        full = _full_disk(path.parent)  # before the partial file is removed: it may hold the last space
        _remove(tmp)
        if full:
            raise OSError(errno.ENOSPC, _WRITE_CAUSES[errno.ENOSPC], str(shown_path(path))) from None
        raise
    except BaseException:
        _remove(tmp)
        raise


def write_file(path, content: str | bytes) -> Path:
    """Write ``content`` (text as UTF-8, or bytes) to ``path`` through :func:`atomic_path`."""
    path = Path(path)
    with atomic_path(path) as tmp:
        tmp.write_bytes(content.encode("utf-8") if isinstance(content, str) else content)
    return path


def _remove(path) -> None:
    try:
        os.unlink(path)
    except FileNotFoundError:
        pass


# ---------------------------------------------------------------- single files


def check_file_target(target, flag: str) -> None:
    """Refuse, before any work, a file output (``--json FILE``) that cannot be written: a folder
    given as the file, or a place where no file can be created. ``-`` (standard output) passes."""
    if target is None or str(target) == "-":
        return
    path = Path(target).expanduser()
    if path.is_dir():
        raise EnvironmentProblem(flag, f"{target} is a folder, not a file", "give a file name, or - for standard output")
    _check_can_create(path.parent, flag)


def write_text(target, text: str, flag: str) -> Path | None:
    """Write ``text`` to the file ``target`` the user named with ``flag`` (``--json FILE``)
    atomically, or to standard output when it is ``-``. Returns the path written (None for
    standard output)."""
    if str(target) == "-":
        sys.stdout.write(text)
        sys.stdout.flush()
        return None
    check_file_target(target, flag)
    path = Path(target).expanduser()
    try:
        with atomic_path(path, user_file=True) as tmp:
            tmp.write_text(text)
    except OSError as exc:
        raise EnvironmentProblem(flag, f"cannot write {target}: {os_cause(exc)}") from None
    return path


def json_default(value):
    """``json.dumps``' ``default`` for numpy scalars (what the commands' JSON may hold)."""
    if hasattr(value, "item"):
        return value.item()
    raise TypeError(f"not JSON serialisable: {type(value).__name__}")


def add_plot_arguments(p, suffix: str) -> None:
    """``--out``, ``--overwrite`` and ``--no-plots`` of a command whose plots go to
    ``exports/<design file name>-<suffix>`` (:func:`plot_folder`)."""
    p.add_argument("--out", metavar="DIR", default=None,
                   help=f"folder for the PNG plots (default: exports/<design file name>-{suffix}); must not exist, "
                        f"be empty, or hold an earlier {suffix} output of the same design file, which is replaced")
    p.add_argument("--overwrite", action="store_true",
                   help=f"also replace an earlier {suffix} output of another design file (never a folder holding "
                        "files geargen did not write)")
    p.add_argument("--no-plots", action="store_true", help="skip the plots (and the output folder)")


def plot_folder(args, design, suffix: str, generator: str, source: str | None = None, source_text: str | None = None):
    """The :class:`OutputFolder` of a command's plots: ``--out`` or ``exports/<design file name>-<suffix>``
    (beside the build's folder, never in it), owned by ``generator`` for the design file (or for
    ``source``, said as ``source_text``, where the output is of more than the design file)."""
    if source is None:
        source = str(Path(design.path or args.design).resolve())
        source_text = f"the design file {source}"
    target = Path(args.out) if args.out else Path("exports") / f"{Path(args.design).stem}-{suffix}"
    return OutputFolder(target, generator, source, source_text,
                        overwrite=args.overwrite, flag="--out" if args.out else "output folder")


def _nearest_existing(path: Path) -> Path:
    path = Path(os.path.abspath(path))
    while not path.exists() and path != path.parent:
        path = path.parent
    return path


def _check_can_create(folder: Path, flag: str) -> None:
    """Refuse when nothing can be created in ``folder`` (or the nearest folder above it that exists)."""
    anc = _nearest_existing(folder)
    if not anc.is_dir():
        raise EnvironmentProblem(flag, f"{anc} is a file, not a folder")
    if not os.access(anc, os.W_OK | os.X_OK):
        reason = "read-only file system" if _read_only(anc) else "permission denied"
        raise EnvironmentProblem(flag, f"cannot write in {anc}: {reason}", "choose a writable output folder")


def _read_only(path: Path) -> bool:
    try:
        return bool(os.statvfs(path).f_flag & os.ST_RDONLY)
    except (OSError, AttributeError):
        return False


# ---------------------------------------------------------------- the folder policy


@dataclass
class FolderState:
    """What an existing output folder holds, seen by the policy.

    ``kind``: ``"absent"``, ``"empty"``, ``"output"`` (a folder with a geargen manifest) or
    ``"foreign"`` (no readable manifest). ``unknown``: entries the manifest does not list;
    ``changed``: listed files whose size is not the manifest's.
    """

    kind: str
    generator: str | None = None
    source: str | None = None
    unknown: list[str] = field(default_factory=list)
    changed: list[str] = field(default_factory=list)


def _legacy_source(generator: str, data: dict) -> str | None:
    """The source of a manifest written before manifests said it (builds only: the design file)."""
    design = data.get("design")
    if generator == "geargen build" and isinstance(design, dict) and design.get("file"):
        return str(Path(design["file"]).resolve())
    return None


def _unlisted(target: Path, listed: set[str]) -> list[str]:
    """The entries of ``target`` that ``listed`` (file paths relative to it, ``/``-separated) does
    not account for: a file not listed, a symbolic link, a folder holding no listed file (not
    looked into). A folder holding listed files (the build's ``review/``) is looked into."""
    folders = {parent.as_posix() for name in listed for parent in PurePosixPath(name).parents} - {"."}
    unknown = []
    for root, dirs, names in os.walk(target):
        here = Path(root).relative_to(target)
        kept = []
        for name in sorted(dirs + names):
            rel = (here / name).as_posix()
            path = target / rel
            if path.is_symlink() or (path.is_dir() and rel not in folders) or (path.is_file() and rel not in listed) \
                    or not (path.is_dir() or path.is_file()):
                unknown.append(rel)
            elif path.is_dir():
                kept.append(name)
        dirs[:] = [d for d in dirs if d in kept]
    return unknown


def inspect_folder(target: Path) -> FolderState:
    """The state of ``target`` (which must not be a plain file)."""
    if not os.path.lexists(target):
        return FolderState("absent")
    entries = sorted(os.listdir(target))
    if not entries:
        return FolderState("empty")
    try:
        data = json.loads((target / MANIFEST).read_text())
    except (OSError, ValueError):
        data = None
    if not isinstance(data, dict) or not isinstance(data.get("files"), dict):
        return FolderState("foreign", unknown=entries)
    files = data["files"]
    unknown = _unlisted(target, set(files) | {MANIFEST})
    changed = []
    for name, info in files.items():
        size = info.get("bytes") if isinstance(info, dict) else None
        p = target / name
        if isinstance(size, int) and p.is_file() and p.stat().st_size != size:
            changed.append(name)
    generator = data.get("generator") if isinstance(data.get("generator"), str) else None
    if generator and re.fullmatch(r"geargen \d[\w.+-]*", generator) and "design" not in data:
        generator = "geargen gear"  # gear folders written before manifests named the command (source unknown)
    source = data.get("source") if isinstance(data.get("source"), str) else None
    if source is None and generator is not None:
        source = _legacy_source(generator, data)
    return FolderState("output", generator, source, unknown, changed)


def _listing(names: list[str], most: int = 4) -> str:
    shown = ", ".join(names[:most])
    return shown + (f" and {len(names) - most} more" if len(names) > most else "")


def _cwd() -> Path | None:
    try:
        return Path.cwd().resolve()
    except OSError:  # the current folder was deleted
        return None


def check_output_folder(target: Path, generator: str, source: str, source_text: str, overwrite: bool = False,
                        flag: str = "--out") -> str:
    """Apply the folder policy to ``target`` (absolute); returns ``"new"``, ``"empty"`` or
    ``"replace"``, or raises :class:`OutputRefused` saying why and what would work."""
    shown = f"{flag} {target}"
    if os.path.lexists(target) and not target.is_dir():
        raise OutputRefused(shown, "is a file, not a folder", "give a folder that does not exist yet")
    if target.is_dir() and os.path.ismount(target):
        raise OutputRefused(shown, "is a mount point: geargen replaces its output folder whole, which a mount "
                            "point cannot be", "give a new folder inside it")
    state = inspect_folder(target)
    if state.kind == "absent":
        return "new"
    if target == _cwd() and state.kind != "foreign":
        raise OutputRefused(shown, "is the current folder: geargen replaces its output folder whole",
                            "give a new folder, e.g. a sub-folder of this one")
    if state.kind == "empty":
        return "empty"
    if state.kind == "foreign":
        raise OutputRefused(shown, f"holds files geargen did not write ({_listing(state.unknown)})",
                            f"{generator} writes only into a new or empty folder, or over its own earlier "
                            "output; geargen never deletes a file it did not write")
    if state.unknown:
        raise OutputRefused(shown, f"holds files its manifest does not list ({_listing(state.unknown)})",
                            "geargen never deletes a file it did not write: move them, or choose another folder")
    if state.generator != generator:
        raise OutputRefused(shown, f"holds the output of {state.generator or 'another program'}, not of {generator}",
                            "choose another folder")
    if state.source != source and not overwrite:
        raise OutputRefused(shown, f"holds an earlier output of {generator} for "
                            f"{state.source or 'an unrecorded source'}, not for {source_text}",
                            "--overwrite replaces it")
    if state.changed and not overwrite:
        raise OutputRefused(shown, f"holds files changed since geargen wrote them ({_listing(state.changed)})",
                            "--overwrite replaces them")
    return "replace"


# ---------------------------------------------------------------- temporary folders


def _process_start(pid: int) -> tuple[str, int] | None:
    """(state, start time in clock ticks since boot) of process ``pid`` from /proc, or None."""
    try:
        with open(f"/proc/{pid}/stat") as fh:
            text = fh.read()
        rest = text[text.rindex(")") + 2:].split()
        return rest[0], int(rest[19])
    except (OSError, ValueError, IndexError):
        return None


def _marker(pid: int | None = None) -> dict:
    pid = os.getpid() if pid is None else pid
    start = _process_start(pid)
    return {"generator": "geargen", "kind": "temporary output folder",
            "note": "an unfinished geargen output; removed by the next geargen output here once this process is gone",
            "pid": pid, "process_start_ticks": start[1] if start else None, "host": socket.gethostname(),
            "created": time.time()}


def process_alive(pid: int, start_ticks: int | None = None) -> bool:
    """Whether process ``pid`` runs (a zombie does not), and is the one that started at
    ``start_ticks`` when given (a reused pid is not)."""
    if not isinstance(pid, int) or pid <= 0:
        return False
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        pass  # another user's process: it exists
    seen = _process_start(pid)
    if seen is None:
        return True  # no /proc: trust kill(0)
    state, start = seen
    if state in ("Z", "X"):
        return False
    return start_ticks is None or start == start_ticks


def _read_marker(folder: Path) -> dict | None:
    try:
        data = json.loads((folder / MARKER).read_text())
    except (OSError, ValueError):
        return None
    return data if isinstance(data, dict) and data.get("generator") == "geargen" else None


def _remove_temporary(folder: Path) -> bool:
    """Remove a temporary folder, its marker last (so an interrupted removal stays claimable)."""
    try:
        for entry in os.scandir(folder):
            if entry.name == MARKER:
                continue
            if entry.is_dir(follow_symlinks=False):
                shutil.rmtree(entry.path)
            else:
                os.unlink(entry.path)
        if (folder / MARKER).exists():
            os.unlink(folder / MARKER)
        os.rmdir(folder)
        return True
    except OSError:
        return False


@dataclass
class Cleanup:
    """What :func:`clean_stale_temporaries` did: folders removed, folders left (with the reason)."""

    removed: list[Path] = field(default_factory=list)
    left: list[tuple[Path, str]] = field(default_factory=list)


def clean_stale_temporaries(parent: Path) -> Cleanup:
    """Remove the temporary folders in ``parent`` left by geargen processes that are gone.

    A folder is claimed when its name has the pattern ``.<name>.build.<...>`` and it holds
    geargen's marker whose process (pid, start time, host) no longer runs; an empty one when the
    process named in its name is gone or it is older than :data:`EMPTY_GRACE_S`. Folders of the
    pattern without a marker (earlier geargen versions, or someone else's) are left and reported.
    """
    out = Cleanup()
    try:
        entries = list(os.scandir(parent))
    except OSError:
        return out
    host = socket.gethostname()
    for entry in entries:
        m = _TEMPORARY.match(entry.name)
        if m is None or not entry.is_dir(follow_symlinks=False):
            continue
        folder = Path(entry.path)
        marker = _read_marker(folder)
        if marker is not None:
            if marker.get("host") not in (None, host):
                out.left.append((folder, f"made on host {marker.get('host')}: cannot tell whether that build runs"))
                continue
            if process_alive(marker.get("pid"), marker.get("process_start_ticks")):
                continue  # a build running now
            if _remove_temporary(folder):
                out.removed.append(folder)
            else:
                out.left.append((folder, "could not be removed"))
            continue
        try:
            empty = not os.listdir(folder)
            age = time.time() - folder.stat().st_mtime
        except OSError:
            continue
        if empty:
            pid = int(m.group("pid")) if m.group("pid") else None
            if (pid is not None and not process_alive(pid)) or age > EMPTY_GRACE_S:
                try:
                    os.rmdir(folder)
                    out.removed.append(folder)
                except OSError:
                    pass
            continue
        out.left.append((folder, "no geargen marker (an earlier geargen version's, or not geargen's): "
                                 "remove it by hand if it is an interrupted build"))
    return out


# ---------------------------------------------------------------- swapping into place

_AT_FDCWD = -100
_RENAME_EXCHANGE = 2


def exchange(a: Path, b: Path) -> bool:
    """Swap the paths ``a`` and ``b`` in one atomic step (Linux ``renameat2``); False where the
    system or the file system cannot, so the caller falls back to two renames."""
    if not sys.platform.startswith("linux"):
        return False
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        fn = libc.renameat2
    except (OSError, AttributeError):
        return False
    fn.argtypes = [ctypes.c_int, ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p, ctypes.c_uint]
    fn.restype = ctypes.c_int
    if fn(_AT_FDCWD, os.fsencode(a), _AT_FDCWD, os.fsencode(b), _RENAME_EXCHANGE) == 0:
        return True
    err = ctypes.get_errno()
    if err in (errno.EINVAL, errno.ENOSYS, errno.EOPNOTSUPP):
        return False
    raise OSError(err, os.strerror(err), str(b))


def swap_into_place(work: Path, target: Path, temporary: Path) -> None:
    """Put the finished folder ``work`` (inside ``temporary``) at ``target``; an earlier
    ``target`` ends inside ``temporary`` (whose marker still claims it) for removal."""
    if target.is_dir() and not target.is_symlink():
        if exchange(work, target):
            return
        previous = temporary / "previous"
        os.rename(target, previous)
        try:
            os.rename(work, target)
        except BaseException:
            os.rename(previous, target)
            raise
        return
    os.rename(work, target)


class OutputFolder:
    """One output folder written by the policy above: :meth:`prepare` (before any work: refuses
    what the policy refuses, proves the folder can be written, cleans stale temporaries, warns
    on standard error about those it cannot claim) gives the folder to write into; :meth:`commit` moves it into place; :meth:`discard` drops it.

    ``generator`` is the command (``"geargen build"``); ``source`` what the output is of, as
    recorded in the manifest's ``"source"``; ``source_text`` says it in messages; ``flag`` names
    the option the target came from (``--out``), or says it is the default folder.
    """

    def __init__(self, target, generator: str, source: str, source_text: str | None = None, overwrite: bool = False,
                 flag: str = "--out"):
        self.target = Path(os.path.abspath(Path(target).expanduser()))
        if self.target.is_dir():
            self.target = self.target.resolve()
        self.generator = generator
        self.source = source
        self.source_text = source_text or source
        self.overwrite = overwrite
        self.flag = flag
        self.temporary: Path | None = None
        self.cleanup = Cleanup()
        self.verdict: str | None = None
        self._made: list[Path] = []

    @property
    def work(self) -> Path:
        if self.temporary is None:
            raise RuntimeError("OutputFolder.prepare() first")
        return self.temporary / WORK

    def check(self) -> str:
        self.verdict = check_output_folder(self.target, self.generator, self.source, self.source_text,
                                           self.overwrite, self.flag)
        return self.verdict

    def prepare(self) -> Path:
        self.check()
        parent = self.target.parent
        shown = f"{self.flag} {self.target}"
        _check_can_create(parent, shown)
        if self.verdict == "replace" and not os.access(self.target, os.W_OK | os.X_OK):
            raise EnvironmentProblem(shown, "the earlier output cannot be replaced: permission denied")
        try:
            self._made = _make_folders(parent)
            self.cleanup = clean_stale_temporaries(parent)
            self.temporary = Path(tempfile.mkdtemp(prefix=f".{self.target.name}.build.{os.getpid()}-", dir=parent))
            (self.temporary / MARKER).write_text(json.dumps(_marker(), indent=2) + "\n")
            os.mkdir(self.temporary / WORK, 0o777)  # the umask applies: 0755 under 022
            writing_into(self.temporary / WORK, self.target)
        except OSError as exc:
            self.discard()
            raise EnvironmentProblem(shown, f"cannot write in {parent}: {exc.strerror or exc}",
                                     "choose a writable output folder") from None
        except BaseException:  # Ctrl-C, SIGTERM
            self.discard()
            raise
        for folder, why in self.cleanup.left:  # the user has to decide about these
            print(f"{self.generator}: warning: left {folder}: {why}", file=sys.stderr)
        return self.work

    def commit(self) -> Path:
        """Move the written folder onto the target (checked again: it may have changed meanwhile)."""
        self.check()
        work = self.work
        try:
            swap_into_place(work, self.target, self.temporary)
        except OSError as exc:
            raise EnvironmentProblem(f"{self.flag} {self.target}", f"cannot move the output into place: "
                                     f"{os_cause(exc)}") from None
        done_writing(work)
        _remove_temporary(self.temporary)
        self.temporary = None
        self._made = []
        return self.target

    def commit_with_manifest(self, design, design_file: str, extra: dict | None = None) -> Path:
        """Write the folder's manifest.json (the generator, the source it is recognised by, the
        version, the design, ``extra``, every file written) and :meth:`commit`; the target."""
        from geargen import __version__
        manifest = {"generator": self.generator, "source": self.source, "version": __version__,
                    "design": {"name": design.name, "file": design_file, "sha256": design.sha256},
                    **(extra or {}), "files": manifest_files(self.work)}
        with atomic_path(self.work / MANIFEST) as tmp:
            tmp.write_text(json.dumps(manifest, indent=2) + "\n")
        return self.commit()

    def discard(self) -> None:
        """Remove the temporary folder and any folder :meth:`prepare` created above the target."""
        if self.temporary is not None:
            done_writing(self.temporary / WORK)
            _remove_temporary(self.temporary)
            self.temporary = None
        for folder in reversed(self._made):
            try:
                os.rmdir(folder)
            except OSError:
                break
        self._made = []


def _make_folders(folder: Path) -> list[Path]:
    """Create ``folder`` and missing folders above it (umask modes); returns those created, top first."""
    missing = []
    p = folder
    while not os.path.lexists(p) and p != p.parent:
        missing.append(p)
        p = p.parent
    for p in reversed(missing):
        os.mkdir(p, 0o777)
    return list(reversed(missing))


def manifest_files(folder: Path, skip: tuple[str, ...] = (MANIFEST,)) -> dict[str, dict]:
    """``{name: {"bytes": size}}`` of the files in ``folder`` (for manifests that list plain files)."""
    return {p.name: {"bytes": p.stat().st_size} for p in sorted(Path(folder).iterdir())
            if p.is_file() and p.name not in skip}


__all__ = ["MANIFEST", "EXPORT_DATE", "OutputFolder", "FolderState", "Cleanup", "atomic_path", "confined", "os_cause", "check_file_target",
           "check_output_folder", "clean_stale_temporaries", "current_umask", "exchange", "file_mode", "write_file",
           "inspect_folder", "manifest_files", "process_alive", "swap_into_place", "write_text"]
