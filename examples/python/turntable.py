#!/usr/bin/env python3
"""A turntable: N frames around a model, written as numbered PNG files.

    PYTHONPATH=build/python python3 examples/python/turntable.py model.glb frames/ --frames 36

One scene, loaded once; one renderer, the model uploaded once and the environment baked once: each
frame is a draw and a read-back (compare `fresnel render --turntable 36`, which does the same).
"""
import argparse
import pathlib

import fresnel


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("model", nargs="?", help="glTF, OBJ or scene file (default: the built-in demo)")
    p.add_argument("output", type=pathlib.Path, help="folder for frame-000.png ...")
    p.add_argument("--frames", type=int, default=36)
    p.add_argument("--size", default="512x512", help="WxH (the render.size setting)")
    p.add_argument("--pitch", type=float, default=15.0)
    p.add_argument("--env", default="automatic", help="an .hdr/.exr, studio, ... (the environment setting)")
    a = p.parse_args()

    scene = fresnel.load(a.model)
    job = fresnel.Job(size=a.size, pitch=a.pitch, env=a.env)
    a.output.mkdir(parents=True, exist_ok=True)
    for i in range(a.frames):
        image = fresnel.render(scene, job, yaw=360.0 * i / a.frames)
        fresnel.save(a.output / f"frame-{i:03d}.png", image)
    print(f"wrote {a.frames} frames to {a.output}/")


if __name__ == "__main__":
    main()
