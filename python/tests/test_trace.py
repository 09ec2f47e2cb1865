"""The path tracer and the surface images from Python."""
import threading

import numpy as np
import pytest

import fresnel
from conftest import psnr, run_cli


def test_trace_equals_the_cli(exe, demo, tmp_path):
    out = tmp_path / "t.png"
    run_cli(exe, "trace", "-o", str(out), "--size", "64x48", "--spp", "4", "--seed", "7", "--yaw", "20")
    image = fresnel.trace(demo, size=(64, 48), spp=4, seed=7, yaw=20, dtype="uint8")
    assert image.shape == (48, 64, 3) and image.dtype == np.uint8
    assert psnr(image, fresnel.read(out)[:, :, :3]) >= 60.0
    exr = tmp_path / "t.exr"
    run_cli(exe, "trace", "-o", str(exr), "--size", "64x48", "--spp", "4", "--seed", "7", "--max-bounces", "2")
    linear = fresnel.trace(demo, size=(64, 48), spp=4, seed=7, max_bounces=2)
    assert linear.dtype == np.float32 and linear.shape == (48, 64, 4)
    assert np.allclose(linear, fresnel.read(exr), rtol=2e-3, atol=2e-3)


def test_raw_radiance_and_seeds(demo):
    a = fresnel.trace(demo, size=(32, 24), spp=2, radiance=True, background=(0, 0, 0))
    b = fresnel.trace(demo, size=(32, 24), spp=2, radiance=True, background=(0, 0, 0), threads=1)
    assert np.array_equal(a, b)  # the same seed on any number of threads
    c = fresnel.trace(demo, size=(32, 24), spp=2, seed=1, radiance=True, background=(0, 0, 0))
    assert not np.array_equal(a, c)
    assert a[:, :, 3].max() == 1.0 and a[0, 0, 3] == 0.0  # coverage


def test_rasteriser_and_tracer_agree_on_the_demo(demo):
    # Direct light, the environment unshadowed: the rasteriser's light transport (24.0 dB measured
    # at this size, where each sphere is a few pixels wide and edges dominate).
    job = fresnel.Job(size=(96, 72), background=(0, 0, 0))
    raster = fresnel.render(demo, job)
    traced = fresnel.trace(demo, job, spp=64, max_bounces=1, env_visibility=False, dtype="uint8")
    assert fresnel.compare(raster, traced)["psnr_db"] > 21.0


def test_progress_and_stopping(demo):
    seen = []
    fresnel.trace(demo, size=(64, 64), spp=2, progress=seen.append)
    assert seen and seen[-1] == pytest.approx(1.0) and all(0 <= f <= 1 for f in seen)

    def stop(fraction):
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        fresnel.trace(demo, size=(64, 64), spp=64, progress=stop)


def test_the_gil_is_released_while_tracing(demo):
    ticks = []
    done = threading.Event()

    def count():
        while not done.is_set():
            ticks.append(1)
            done.wait(0.005)

    t = threading.Thread(target=count)
    t.start()
    fresnel.trace(demo, size=(96, 96), spp=8)
    done.set()
    t.join()
    assert len(ticks) > 5


def test_surfaces(demo):
    job = fresnel.Job(size=(80, 60), pitch=10)
    g = fresnel.surfaces(demo, job)
    assert g["depth"].shape == (60, 80) and g["position"].shape == (60, 80, 3) and g["uv"].shape == (60, 80, 2)
    mask = g["mask"]
    assert mask.dtype == bool and 0 < mask.sum() < mask.size
    assert np.isinf(g["depth"][~mask]).all() and (g["material"][~mask] == -1).all()
    assert set(np.unique(g["material"][mask])) <= set(range(49))
    assert len(np.unique(g["node"][mask])) > 20  # many spheres, each its own node
    n = g["normal"][mask]
    assert np.allclose(np.linalg.norm(n, axis=1), 1.0, atol=1e-4)
    # The positions project back to their pixels through the job's camera, at their depth.
    cam = demo.camera(job)
    ys, xs = np.nonzero(mask)
    p = np.c_[g["position"][ys, xs], np.ones(len(xs))]
    view = p @ cam["view"].T
    assert np.allclose(-view[:, 2], g["depth"][ys, xs], rtol=1e-4, atol=1e-4)
    clip = view @ cam["projection"].T
    ndc = clip[:, :2] / clip[:, 3:4]
    px = (ndc[:, 0] + 1) / 2 * 80 - 0.5
    py = (1 - ndc[:, 1]) / 2 * 60 - 0.5
    assert np.abs(px - xs).max() < 1e-2 and np.abs(py - ys).max() < 1e-2
    # The rasteriser covers the same pixels.
    alpha = fresnel.channel(demo, "normal", job, background="transparent")[:, :, 3] > 0.5
    assert (alpha == mask).mean() > 0.99


def test_trace_errors(demo, tmp_path):
    with pytest.raises(ValueError, match="spp"):
        fresnel.trace(demo, size=(8, 8), spp=0)
    with pytest.raises(fresnel.Error) as e:
        fresnel.trace(demo, size=(8, 8), env=str(tmp_path / "nope.hdr"))
    assert "nope.hdr" in str(e.value)
