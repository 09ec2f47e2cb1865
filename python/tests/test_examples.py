"""The examples of examples/python run (small sizes) and write what they say."""
import os
import pathlib
import subprocess
import sys

import numpy as np

import fresnel

EXAMPLES = pathlib.Path(__file__).parents[2] / "examples" / "python"


def run(name, *args):
    env = dict(os.environ, PYTHONPATH=str(pathlib.Path(fresnel.__file__).parents[1]))
    return subprocess.run([sys.executable, str(EXAMPLES / name), *map(str, args)], check=True, capture_output=True,
                          text=True, env=env).stdout


def test_turntable(tmp_path):
    run("turntable.py", tmp_path, "--frames", 3, "--size", "48x32")
    frames = sorted(tmp_path.glob("frame-*.png"))
    assert len(frames) == 3 and fresnel.read(frames[0]).shape == (32, 48, 4)


def test_synthetic_data(tmp_path):
    run("synthetic_data.py", tmp_path, "--samples", 2, "--size", "40x30")
    d = np.load(tmp_path / "sample-00001.npz")
    assert d["image"].shape == (30, 40, 3) and d["depth"].shape == (30, 40) and d["normal"].shape == (30, 40, 3)
    assert d["mask"].any() and np.isfinite(d["depth"][d["mask"]]).all() and d["view"].shape == (4, 4)


def test_material_sweep(tmp_path):
    out = run("material_sweep.py", tmp_path / "sweep.png", "--steps", 2, "--cell", 24, "--material", 0)
    assert (tmp_path / "sweep.png").exists() and "roughness" in out


def test_raster_vs_trace(tmp_path):
    out = run("raster_vs_trace.py", tmp_path, "--size", "48x36", "--spp", 4)
    assert "PSNR" in out and (tmp_path / "difference.png").exists()


def test_every_example_has_help():
    for script in EXAMPLES.glob("*.py"):
        assert "usage" in run(script.name, "--help")
