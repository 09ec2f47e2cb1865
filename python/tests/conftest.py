"""Fixtures of the Python module's tests (run by `make test` as ctest's python_test, or by hand:
PYTHONPATH=build/python FRESNEL_EXE=build/bin/fresnel python3 -m pytest python/tests)."""
import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

import fresnel


@pytest.fixture(scope="session")
def exe():
    path = os.environ.get("FRESNEL_EXE")
    if not path or not pathlib.Path(path).exists():
        pytest.skip("FRESNEL_EXE (the fresnel program) is not set")
    return path


@pytest.fixture(scope="session")
def shared():
    """../shared (the assets): tests that use it skip without it."""
    path = pathlib.Path(os.environ.get("FRESNEL_SHARED_DIR", pathlib.Path(__file__).parents[2] / ".." / "shared"))
    if not (path / "assets" / "models").is_dir():
        pytest.skip("the shared assets are absent")
    return path


@pytest.fixture(scope="session")
def helmet(shared):
    return shared / "assets" / "models" / "DamagedHelmet" / "DamagedHelmet.glb"


@pytest.fixture(scope="session")
def demo():
    return fresnel.load()


def run_cli(exe, *args):
    """Runs `fresnel ARGS --json` and returns its JSON line."""
    out = subprocess.run([exe, *args, "--json"], check=True, capture_output=True, text=True).stdout
    return json.loads(out.strip().splitlines()[-1])


def psnr(a, b):
    a = np.asarray(a, dtype=np.float64)
    b = np.asarray(b, dtype=np.float64)
    peak = 255.0 if np.asarray(a).dtype != np.float64 or a.max() > 1.5 else 1.0
    mse = np.mean((a - b) ** 2)
    return 99.0 if mse == 0 else 10 * np.log10(peak * peak / mse)
