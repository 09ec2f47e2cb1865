#!/usr/bin/env python3
"""A material sweep: one material's roughness x metallic as a grid of renders, labelled.

    PYTHONPATH=build/python python3 examples/python/material_sweep.py model.glb sweep.png --steps 5

Each cell is the model with the material's roughnessFactor and metallicFactor set through the
material property registry (Scene.with_material: the names and checks of scene files' overrides).
With matplotlib installed the grid is drawn with axes; otherwise it is assembled with NumPy.
"""
import argparse

import numpy as np

import fresnel


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("model", nargs="?", help="glTF or OBJ (default: the built-in demo, whose spheres each have a material)")
    p.add_argument("output", help="the grid image (.png)")
    p.add_argument("--material", default=None, help="name or index (default: every material)")
    p.add_argument("--steps", type=int, default=5)
    p.add_argument("--cell", type=int, default=160, help="cell size in pixels")
    a = p.parse_args()

    scene = fresnel.load(a.model)
    material = int(a.material) if a.material and a.material.isdigit() else a.material
    values = np.linspace(0.0, 1.0, a.steps)
    rows = []
    for metallic in values[::-1]:
        row = []
        for roughness in values:
            cell = scene.with_material(material, roughnessFactor=float(roughness), metallicFactor=float(metallic))
            row.append(fresnel.render(cell, size=(a.cell, a.cell), pitch=10))
        rows.append(np.concatenate(row, axis=1))
    grid = np.concatenate(rows, axis=0)
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(8, 8))
        ax.imshow(grid, extent=(-0.5 / (a.steps - 1), 1 + 0.5 / (a.steps - 1)) * 2)
        ax.set_xlabel("roughnessFactor")
        ax.set_ylabel("metallicFactor")
        fig.savefig(a.output, dpi=100, bbox_inches="tight")
    except ImportError:
        fresnel.save(a.output, grid)
    print(f"wrote {a.output}: roughness 0..1 left to right, metallic 0..1 bottom to top")


if __name__ == "__main__":
    main()
