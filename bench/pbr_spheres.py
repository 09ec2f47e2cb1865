#!/usr/bin/env python3
"""Writes glTF test scenes of PBR spheres for bench/peer-report-reverse.sh (glTF -> OBJ/MTL):

    bench/pbr_spheres.py OUT_DIR

  dielectrics.gltf  4 dielectric spheres, roughness 0.2 / 0.4 / 0.6 / 0.9, four colours
  metals.gltf       4 metal spheres (gold, copper, silver, iron), roughness 0.25 .. 0.8
  mixed.gltf        half-metallic and glossy-dark cases
Each sphere is a UV sphere (32 x 16) with normals, in a row along +X, one material each.
"""
import base64
import json
import math
import struct
import sys
from pathlib import Path


def sphere(rings=16, segments=32):
    pos, nrm, idx = [], [], []
    for r in range(rings + 1):
        theta = math.pi * r / rings
        for s in range(segments + 1):
            phi = 2 * math.pi * s / segments
            n = (math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi))
            pos += n
            nrm += n
    for r in range(rings):
        for s in range(segments):
            a = r * (segments + 1) + s
            b = a + segments + 1
            idx += [a, a + 1, b, a + 1, b + 1, b]
    return pos, nrm, idx


def scene(materials):
    pos, nrm, idx = sphere()
    data = struct.pack(f"<{len(pos)}f", *pos) + struct.pack(f"<{len(nrm)}f", *nrm) + struct.pack(f"<{len(idx)}I", *idx)
    n = len(pos) // 3
    doc = {
        "asset": {"version": "2.0", "generator": "fresnel bench/pbr_spheres.py"},
        "buffers": [{"byteLength": len(data), "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 12 * n, "target": 34962},
            {"buffer": 0, "byteOffset": 12 * n, "byteLength": 12 * n, "target": 34962},
            {"buffer": 0, "byteOffset": 24 * n, "byteLength": 4 * len(idx), "target": 34963},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": n, "type": "VEC3", "min": [-1, -1, -1], "max": [1, 1, 1]},
            {"bufferView": 1, "componentType": 5126, "count": n, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5125, "count": len(idx), "type": "SCALAR"},
        ],
        "materials": [],
        "meshes": [],
        "nodes": [],
        "scenes": [{"nodes": []}],
        "scene": 0,
    }
    for i, (name, color, metallic, roughness) in enumerate(materials):
        doc["materials"].append({"name": name, "pbrMetallicRoughness": {
            "baseColorFactor": list(color) + [1.0], "metallicFactor": metallic, "roughnessFactor": roughness}})
        doc["meshes"].append({"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": i}]})
        doc["nodes"].append({"mesh": i, "translation": [2.3 * (i - (len(materials) - 1) / 2), 0, 0]})
        doc["scenes"][0]["nodes"].append(i)
    return doc


SCENES = {
    "dielectrics": [("red", (0.8, 0.1, 0.1), 0.0, 0.2), ("green", (0.2, 0.7, 0.2), 0.0, 0.4),
                    ("blue", (0.15, 0.25, 0.8), 0.0, 0.6), ("grey", (0.5, 0.5, 0.5), 0.0, 0.9)],
    "metals": [("gold", (1.0, 0.766, 0.336), 1.0, 0.25), ("copper", (0.955, 0.638, 0.538), 1.0, 0.4),
               ("silver", (0.972, 0.96, 0.915), 1.0, 0.6), ("iron", (0.56, 0.57, 0.58), 1.0, 0.8)],
    "mixed": [("half-metal", (0.7, 0.5, 0.3), 0.5, 0.5), ("glossy-black", (0.02, 0.02, 0.02), 0.0, 0.15),
              ("white-rough", (0.9, 0.9, 0.9), 0.0, 1.0), ("dark-metal", (0.3, 0.3, 0.35), 1.0, 0.3)],
}


def main():
    if len(sys.argv) != 2:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    out = Path(sys.argv[1])
    out.mkdir(parents=True, exist_ok=True)
    for name, mats in SCENES.items():
        (out / f"{name}.gltf").write_text(json.dumps(scene(mats)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
