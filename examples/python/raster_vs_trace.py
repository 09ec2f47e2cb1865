#!/usr/bin/env python3
"""The rasteriser against the path tracer on one job: both images, their difference, the metrics.

    PYTHONPATH=build/python python3 examples/python/raster_vs_trace.py model.glb out/ --spp 128

The tracer is the ground truth for the rasteriser (docs/trace.md); --max-bounces 1 gives it the
rasteriser's light transport (direct light only), the default all of it.
"""
import argparse
import pathlib

import numpy as np

import fresnel


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("model", nargs="?")
    p.add_argument("output", type=pathlib.Path)
    p.add_argument("--size", default="384x384")
    p.add_argument("--spp", type=int, default=64)
    p.add_argument("--max-bounces", type=int, default=16)
    p.add_argument("--env", default="automatic")
    a = p.parse_args()

    scene = fresnel.load(a.model)
    # A colour background: the tracer shows the environment sharp, the rasteriser blurred by default.
    job = fresnel.Job(size=a.size, env=a.env, background=(0, 0, 0))
    raster = fresnel.render(scene, job)
    traced = fresnel.trace(scene, job, spp=a.spp, max_bounces=a.max_bounces, dtype="uint8",
                           progress=lambda f: print(f"\rtracing {f:4.0%}", end="", flush=True))
    print()
    difference = np.abs(raster.astype(np.int16) - traced.astype(np.int16)).max(axis=2)
    heat = np.clip(difference * 8, 0, 255).astype(np.uint8)
    a.output.mkdir(parents=True, exist_ok=True)
    fresnel.save(a.output / "raster.png", raster)
    fresnel.save(a.output / "trace.png", traced)
    fresnel.save(a.output / "difference.png", np.stack([heat] * 3, axis=2))
    m = fresnel.compare(raster, traced, mask="auto")
    print(f"raster vs trace over the model: PSNR {m['psnr_db']:.2f} dB, SSIM {m['ssim']:.4f}, FLIP {m['flip']:.4f}")


if __name__ == "__main__":
    main()
