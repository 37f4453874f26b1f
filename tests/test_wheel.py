"""What `pip install .` puts into site-packages: one `arbor` namespace (arbor.engine, arbor.game, arbor.assets),
nothing called engine, game or benchmarks that could clash with another package, and a working `arbor` command
run from another folder (so the data is found inside the installed package, not beside a checkout)."""

from __future__ import annotations

import os
import subprocess
import sys
import sysconfig
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
# what a fresh venv made with --without-pip holds before anything is installed into it
VENV_OWN = {"_distutils_hack", "distutils-precedence.pth", "__pycache__"}


@pytest.fixture(scope="module")
def installed(tmp_path_factory) -> Path:
    """A fresh venv with Arbor's wheel installed (its dependencies come from this test's environment)."""
    work = tmp_path_factory.mktemp("wheel")
    run = dict(check=True, capture_output=True, text=True, timeout=300)
    try:
        subprocess.run([sys.executable, "-m", "pip", "wheel", "-q", "--no-deps", "-w", str(work), str(ROOT)], **run)
    except subprocess.CalledProcessError as exc:
        pytest.fail(f"the wheel does not build: {exc.stderr[-2000:]}")
    wheel = next(work.glob("arbor_trees-*.whl"))  # the distribution arbor-trees (README: why)
    venv = work / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(venv)], **run)
    python = venv / "bin" / "python"
    subprocess.run([sys.executable, "-m", "pip", "--python", str(python), "install", "-q", "--no-deps", "--no-index",
                    str(wheel)], **run)
    return venv


def _site_packages(venv: Path) -> Path:
    return next((venv / "lib").glob("python3.*/site-packages"))


def test_site_packages_holds_arbor_and_nothing_else_of_ours(installed):
    names = {p.name for p in _site_packages(installed).iterdir()} - VENV_OWN
    dist_info = {n for n in names if n.endswith(".dist-info")}
    assert names - dist_info == {"arbor"}
    assert [n.split("-")[0] for n in dist_info] == ["arbor_trees"]
    arbor = _site_packages(installed) / "arbor"
    assert {p.name for p in arbor.iterdir()} >= {"engine", "game", "assets"}
    assert (arbor / "assets" / "lsystems" / "game_tree.lsys").is_file()
    assert not (arbor / "benchmarks").exists() and not (arbor / "tests").exists()


def test_installed_arbor_renders_from_another_folder(installed, tmp_path):
    # The installed copy imports its dependencies from this environment; a path line in a .pth file adds the
    # folder without running the .pth files in it, so the checkout's editable install stays out of sight.
    (_site_packages(installed) / "_deps.pth").write_text(sysconfig.get_paths()["purelib"] + "\n")
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH",)}
    env["NUMBA_DISABLE_JIT"] = "1"  # the kernels as plain Python: a small tree, and no 20 s compile
    out = tmp_path / "tree.png"
    source = _site_packages(installed) / "arbor" / "assets" / "lsystems" / "abop_2_8_tree.lsys"
    proc = subprocess.run([str(installed / "bin" / "arbor"), "render", str(source), "--steps", "4", "--size",
                           "160x120", "--out", str(out)], cwd=tmp_path, env=env, capture_output=True, text=True,
                          timeout=300)
    assert proc.returncode == 0, proc.stderr[-2000:]
    probe = subprocess.run([str(installed / "bin" / "python"), "-c",
                            "import arbor.engine, arbor.game; print(arbor.engine.__file__)"],
                           cwd=tmp_path, env=env, capture_output=True, text=True, timeout=60)
    assert str(_site_packages(installed)) in probe.stdout, probe.stdout + probe.stderr
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and out.stat().st_size > 1000
