#!/usr/bin/env python3
"""Synthetic training data: random views of a model, each an image with its exact depth, normals,
material ids and mask.

    PYTHONPATH=build/python python3 examples/python/synthetic_data.py model.glb data/ --samples 100

Per sample: a random orbit camera (yaw, pitch, distance), environment rotation and intensity, and
material variant (KHR_materials_variants, when the model has some), rendered on the GPU; the depth,
normal, material-id and mask arrays come from fresnel.surfaces (one ray per pixel centre: exact,
float32, no blending at edges). Written as data/sample-00000.npz (image uint8 (H, W, 3), depth
float32 (H, W) with inf where nothing, normal float32 (H, W, 3) in world space, material int32
(H, W), mask bool (H, W), and the camera's view and projection matrices) plus a PNG of the image.
"""
import argparse
import pathlib

import numpy as np

import fresnel


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("model", nargs="?", help="glTF, OBJ or scene file (default: the built-in demo)")
    p.add_argument("output", type=pathlib.Path)
    p.add_argument("--samples", type=int, default=20)
    p.add_argument("--size", default="256x256")
    p.add_argument("--env", default="studio", help="the environment (an .hdr/.exr gives real light to rotate)")
    p.add_argument("--seed", type=int, default=0)
    a = p.parse_args()

    rng = np.random.default_rng(a.seed)
    base = fresnel.load(a.model)
    # One loaded scene per variant (a variant is applied when the file is loaded).
    scenes = [base] + [fresnel.load(a.model, variant=v) for v in base.variants]
    a.output.mkdir(parents=True, exist_ok=True)
    for i in range(a.samples):
        scene = scenes[rng.integers(len(scenes))]
        job = fresnel.Job(size=a.size, env=a.env,
                          yaw=rng.uniform(0, 360), pitch=rng.uniform(-20, 60), distance=rng.uniform(1.0, 2.0),
                          env_rotation=rng.uniform(0, 360), env_intensity=rng.uniform(0.6, 1.4))
        image = fresnel.render(scene, job)
        g = fresnel.surfaces(scene, job)
        camera = scene.camera(job)
        np.savez_compressed(a.output / f"sample-{i:05d}.npz", image=image, depth=g["depth"], normal=g["normal"],
                            material=g["material"], mask=g["mask"], view=camera["view"],
                            projection=camera["projection"])
        fresnel.save(a.output / f"sample-{i:05d}.png", image)
    print(f"wrote {a.samples} samples to {a.output}/ ({len(scenes)} material variant(s))")


if __name__ == "__main__":
    main()
