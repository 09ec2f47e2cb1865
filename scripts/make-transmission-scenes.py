#!/usr/bin/python3
"""Writes the test scenes of KHR_materials_transmission, _volume and _dispersion.

Each scene: two spheres in front of a textured, opaque backdrop (a colourful checker on a
quad), so refraction, its roughness blur, the volume's attenuation and dispersion all show.
Self-contained .gltf files (buffers and images as data URIs), written by this script alone
(Python's standard library: the PNGs are encoded here too), deterministic.

    scripts/make-transmission-scenes.py OUT_DIR

tests/data/transmission/ holds the committed output; the Khronos Sample Renderer's images of
them are under tests/data/transmission/refs/ (see README.md there).
"""
import base64
import json
import math
import os
import struct
import sys
import zlib


def png(width, height, rgba_rows):
    """An 8-bit RGBA PNG from rows of bytes."""
    raw = b"".join(b"\x00" + bytes(row) for row in rgba_rows)

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def checker_png(n=64, cells=8):
    rows = []
    for y in range(n):
        row = []
        for x in range(n):
            cx, cy = x * cells // n, y * cells // n
            if (cx + cy) % 2 == 0:
                row += [235, 235, 235, 255]
            else:  # a hue per cell, so displacement by refraction is visible
                h = ((cx * 3 + cy * 5) % 8) / 8.0
                r = int(255 * (0.5 + 0.5 * math.cos(2 * math.pi * h)))
                g = int(255 * (0.5 + 0.5 * math.cos(2 * math.pi * (h - 1 / 3))))
                b = int(255 * (0.5 + 0.5 * math.cos(2 * math.pi * (h - 2 / 3))))
                row += [r, g, b, 255]
        rows.append(row)
    return png(n, n, rows)


def stripes_png(n=16):
    """R: vertical stripes 1 / 0.25 (a transmission texture), G: a ramp (a thickness texture)."""
    rows = []
    for y in range(n):
        row = []
        for x in range(n):
            r = 255 if (x * 4 // n) % 2 == 0 else 64
            g = int(255 * (0.25 + 0.75 * y / (n - 1)))
            row += [r, g, 0, 255]
        rows.append(row)
    return png(n, n, rows)


class Builder:
    def __init__(self):
        self.bin = bytearray()
        self.g = {"asset": {"version": "2.0", "generator": "fresnel scripts/make-transmission-scenes.py"},
                  "scene": 0, "scenes": [{"nodes": []}], "nodes": [], "meshes": [], "materials": [],
                  "accessors": [], "bufferViews": [], "buffers": [], "images": [], "textures": [],
                  "samplers": [{"magFilter": 9729, "minFilter": 9987}], "extensionsUsed": []}

    def view(self, data, target):
        while len(self.bin) % 4:
            self.bin.append(0)
        self.g["bufferViews"].append({"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data), "target": target})
        self.bin += data
        return len(self.g["bufferViews"]) - 1

    def accessor(self, values, kind, comps):
        if kind == "index":
            data = struct.pack("<%dI" % len(values), *values)
            v = self.view(data, 34963)
            self.g["accessors"].append({"bufferView": v, "componentType": 5125, "count": len(values), "type": "SCALAR"})
        else:
            flat = [c for p in values for c in p]
            data = struct.pack("<%df" % len(flat), *flat)
            v = self.view(data, 34962)
            a = {"bufferView": v, "componentType": 5126, "count": len(values), "type": {2: "VEC2", 3: "VEC3"}[comps]}
            if kind == "position":
                a["min"] = [min(p[i] for p in values) for i in range(3)]
                a["max"] = [max(p[i] for p in values) for i in range(3)]
            self.g["accessors"].append(a)
        return len(self.g["accessors"]) - 1

    def mesh(self, positions, normals, uvs, indices, material):
        prim = {"attributes": {"POSITION": self.accessor(positions, "position", 3),
                               "NORMAL": self.accessor(normals, "normal", 3),
                               "TEXCOORD_0": self.accessor(uvs, "uv", 2)},
                "indices": self.accessor(indices, "index", 1), "material": material}
        self.g["meshes"].append({"primitives": [prim]})
        return len(self.g["meshes"]) - 1

    def node(self, mesh, translation):
        self.g["nodes"].append({"mesh": mesh, "translation": translation})
        self.g["scenes"][0]["nodes"].append(len(self.g["nodes"]) - 1)

    def texture(self, png_bytes):
        self.g["images"].append({"uri": "data:image/png;base64," + base64.b64encode(png_bytes).decode()})
        self.g["textures"].append({"source": len(self.g["images"]) - 1, "sampler": 0})
        return len(self.g["textures"]) - 1

    def material(self, m):
        self.g["materials"].append(m)
        for e in m.get("extensions", {}):
            if e not in self.g["extensionsUsed"]:
                self.g["extensionsUsed"].append(e)
        return len(self.g["materials"]) - 1

    def write(self, path):
        self.g["buffers"] = [{"byteLength": len(self.bin),
                              "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(self.bin)).decode()}]
        for k in ["images", "textures", "extensionsUsed"]:
            if not self.g[k]:
                del self.g[k]
        with open(path, "w") as f:
            json.dump(self.g, f, indent=1)
            f.write("\n")


def sphere(radius, rings=24, segments=36):
    pos, nrm, uv, idx = [], [], [], []
    for r in range(rings + 1):
        th = math.pi * r / rings
        for s in range(segments + 1):
            ph = 2 * math.pi * s / segments
            n = (math.sin(th) * math.sin(ph), math.cos(th), math.sin(th) * math.cos(ph))
            pos.append(tuple(radius * c for c in n))
            nrm.append(n)
            uv.append((s / segments, r / rings))
    for r in range(rings):
        for s in range(segments):
            a = r * (segments + 1) + s
            b = a + segments + 1
            idx += [a, b, a + 1, a + 1, b, b + 1]
    return pos, nrm, uv, idx


def quad(half, z):
    pos = [(-half, -half, z), (half, -half, z), (half, half, z), (-half, half, z)]
    return pos, [(0, 0, 1)] * 4, [(0, 1), (1, 1), (1, 0), (0, 0)], [0, 1, 2, 0, 2, 3]


def scene(spheres):
    """spheres: two material dicts (left, right) for spheres of radius 0.55 at x = -/+0.62."""
    b = Builder()
    checker = b.texture(checker_png())
    backdrop = b.material({"name": "backdrop", "pbrMetallicRoughness": {
        "baseColorTexture": {"index": checker}, "metallicFactor": 0.0, "roughnessFactor": 0.7}, "doubleSided": True})
    b.node(b.mesh(*quad(1.4, -0.9), backdrop), [0, 0, 0])
    ball = sphere(0.55)
    for m, x in zip(spheres, (-0.62, 0.62)):
        if callable(m):
            m = m(b)
        b.node(b.mesh(*ball, b.material(m)), [x, 0, 0])
    return b


def glass(name, roughness, base=(1, 1, 1, 1), ext=None):
    m = {"name": name, "pbrMetallicRoughness": {"baseColorFactor": list(base), "metallicFactor": 0.0,
                                               "roughnessFactor": roughness}, "extensions": ext or {}}
    return m


SCENES = {
    # Thin-walled transmission (no volume): the backdrop seen straight through, blurred by roughness;
    # the right sphere's transmission from a texture (R stripes), tinted.
    "transmission": [
        glass("clear", 0.0, ext={"KHR_materials_transmission": {"transmissionFactor": 1.0}}),
        lambda b: glass("frosted", 0.35, base=(0.8, 0.9, 1.0, 1.0), ext={"KHR_materials_transmission": {
            "transmissionFactor": 1.0, "transmissionTexture": {"index": b.texture(stripes_png())}}}),
    ],
    # Refraction through a volume (thickness = the sphere's diameter) with Beer-Lambert
    # attenuation; the right one rougher, at ior 1.3, its thickness from a texture (G ramp).
    "volume": [
        glass("amber", 0.0, ext={"KHR_materials_transmission": {"transmissionFactor": 1.0},
                                 "KHR_materials_volume": {"thicknessFactor": 1.1, "attenuationDistance": 0.8,
                                                          "attenuationColor": [1.0, 0.55, 0.2]}}),
        lambda b: glass("teal", 0.25, ext={"KHR_materials_transmission": {"transmissionFactor": 1.0},
                                           "KHR_materials_ior": {"ior": 1.3},
                                           "KHR_materials_volume": {"thicknessFactor": 1.1,
                                                                    "thicknessTexture": {"index": b.texture(stripes_png())},
                                                                    "attenuationDistance": 0.5,
                                                                    "attenuationColor": [0.3, 0.75, 0.9]}}),
    ],
    # Dispersion: the same volume without attenuation, dispersion 3 and 10.
    "dispersion": [
        glass("prism3", 0.0, ext={"KHR_materials_transmission": {"transmissionFactor": 1.0},
                                  "KHR_materials_volume": {"thicknessFactor": 1.1},
                                  "KHR_materials_dispersion": {"dispersion": 3.0}}),
        glass("prism10", 0.1, ext={"KHR_materials_transmission": {"transmissionFactor": 1.0},
                                   "KHR_materials_ior": {"ior": 1.7},
                                   "KHR_materials_volume": {"thicknessFactor": 1.1},
                                   "KHR_materials_dispersion": {"dispersion": 10.0}}),
    ],
}


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: make-transmission-scenes.py OUT_DIR")
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    for name, spheres in SCENES.items():
        scene(spheres).write(os.path.join(out, name + ".gltf"))
        print(os.path.join(out, name + ".gltf"))


if __name__ == "__main__":
    main()
