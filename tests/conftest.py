"""Session fixtures shared by the test folders: the shipped assemblies, each built once per session."""

import contextlib
import fcntl
import io
import os
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
ASSEMBLY_DESIGNS = {"robot_joint": ROOT / "assemblies/robot_joint.toml", "c_axis": ROOT / "assemblies/c_axis.toml",
                    "split_pinion": ROOT / "assemblies/split_pinion.toml",
                    "axial_preload": ROOT / "assemblies/axial_preload.toml",
                    "split_pinion_inch": ROOT / "assemblies/split_pinion_inch.toml",
                    "metric_dual_pinion": ROOT / "assemblies/metric_dual_pinion.toml",
                    "planetary_dual_pinion": ROOT / "assemblies/planetary_dual_pinion.toml",
                    "rack_drive": ROOT / "assemblies/rack_drive.toml",
                    # gears and a synthesis only: built with the default hardware
                    "gears_only": ROOT / "tests/data/metric_dual_pinion.toml"}


class BuiltAssemblies:
    """Each assembly of :data:`ASSEMBLY_DESIGNS` built once per session, when a test first asks
    for it, with ``geargen build DESIGN --out DIR --quiet`` through :func:`geargen.cli.main` (the
    README's command for the robot joint, the documented one for the others).

    ``built[name]`` is the export folder (a test fails with the command's message if the build
    did; the build is not repeated for the next test). :meth:`step` re-reads a part's STEP file
    once per session (reading the large gears takes ~1 s each).
    """

    def __init__(self, root: Path):
        self.root = root
        self._built: dict[str, tuple[Path, str | None]] = {}
        self._steps: dict[tuple[str, str], object] = {}

    def __getitem__(self, name: str) -> Path:
        if name not in self._built:
            self._built[name] = self._build_once(name)
        folder, problem = self._built[name]
        if problem is not None:
            pytest.fail(f"geargen build {name} failed: {problem}", pytrace=False)
        return folder

    def _build_once(self, name: str) -> tuple[Path, str | None]:
        """Build ``name`` unless another test process (pytest-xdist worker) of this session already
        did: the first to take the lock builds, the others wait and read its folder or its failure."""
        from geargen.cli import main
        folder = self.root / name / name
        problem_file = self.root / f"{name}.problem"
        self.root.mkdir(parents=True, exist_ok=True)
        with open(self.root / f"{name}.lock", "w") as lock:
            fcntl.flock(lock, fcntl.LOCK_EX)
            if problem_file.exists():
                return folder, problem_file.read_text()
            if (folder / "manifest.json").exists():
                return folder, None
            err = io.StringIO()
            try:
                with contextlib.redirect_stderr(err):
                    code = main(["build", str(ASSEMBLY_DESIGNS[name]), "--out", str(folder), "--quiet"])
                problem = None if code == 0 else f"exit status {code}: {err.getvalue()}"
            except BaseException as exc:  # noqa: BLE001 - reported to every test that needs this build
                problem = f"{type(exc).__name__}: {exc}\n{err.getvalue()}"
            if problem is not None:
                problem_file.write_text(problem)
            return folder, problem

    def step(self, name: str, part: str):
        """The re-imported STEP file of ``part`` (:class:`geargen.cad.export.StepContents`)."""
        key = (name, part)
        if key not in self._steps:
            from geargen.cad.export import read_step
            self._steps[key] = read_step(self[name] / f"{part}.step")
        return self._steps[key]


@pytest.fixture(scope="session")
def built_assemblies(tmp_path_factory) -> BuiltAssemblies:
    """The shipped assemblies built once per session (:class:`BuiltAssemblies`)."""
    base = tmp_path_factory.getbasetemp()
    # pytest-xdist workers each get <session>/popen-gwN: share the session's folder between them
    shared = base.parent if os.environ.get("PYTEST_XDIST_WORKER") else base
    return BuiltAssemblies(shared / "shared-assemblies")


def debian_tool(executable: str, package: str) -> str:
    """The path of ``executable``; when missing and running as root with apt-get, the Debian
    ``package`` is installed first. Else the test is skipped, except in CI (``CI`` set), where it fails."""
    found = next((p for p in (f"/usr/bin/{executable}", shutil.which(executable)) if p and os.access(p, os.X_OK)), None)
    if found:
        return found
    if os.geteuid() == 0 and shutil.which("apt-get"):
        env = dict(os.environ, DEBIAN_FRONTEND="noninteractive")
        for cmd in (["apt-get", "update"], ["apt-get", "install", "-y", "--no-install-recommends", package]):
            done = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=900)
            if done.returncode != 0:
                pytest.fail(f"{' '.join(cmd)} failed:\n{done.stderr[-2000:]}")
        if os.access(f"/usr/bin/{executable}", os.X_OK):
            return f"/usr/bin/{executable}"
        pytest.fail(f"apt-get installed {package} but /usr/bin/{executable} is missing")
    if os.environ.get("CI"):
        pytest.fail(f"no {executable}, and it cannot be installed here (not root or no apt-get); CI must have it")
    pytest.skip(f"no {executable} (install the {package} package, or run as root to have it installed)")


@pytest.fixture(scope="session")
def chromium() -> str:
    """The Chromium executable (installed from the Debian packages when running as root)."""
    for name in ("chromium", "chromium-browser"):
        path = shutil.which(name)
        if path and os.access(path, os.X_OK):
            return path
    return debian_tool("chromium", "chromium")


@pytest.fixture(scope="session")
def poppler() -> dict[str, str]:
    """``pdftoppm`` and ``pdftotext`` (poppler-utils, installed when running as root)."""
    return {tool: debian_tool(tool, "poppler-utils") for tool in ("pdftoppm", "pdftotext")}
