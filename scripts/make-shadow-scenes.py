#!/usr/bin/python3
"""Writes the shadow test scenes: a ground plane with two spheres, a box and a thin pole,
lit by one KHR_lights_punctual light (directional, point or spot) or by none (environment
only). Self-contained .gltf files (buffers as data URIs), deterministic, from Python's
standard library alone.

    scripts/make-shadow-scenes.py OUT_DIR

tests/data/shadows/ holds the committed output; tests/gpu/shadow_gpu_test.cpp and
`make fidelity-report` (bench/fidelity_report.py --shadows) render them.
"""
import base64
import json
import math
import os
import struct
import sys


def sphere(cx, cy, cz, radius, rings=24, segments=36):
    pos, nrm, idx = [], [], []
    for r in range(rings + 1):
        theta = math.pi * r / rings
        for s in range(segments + 1):
            phi = 2 * math.pi * s / segments
            n = (math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi))
            nrm.append(n)
            pos.append((cx + radius * n[0], cy + radius * n[1], cz + radius * n[2]))
    for r in range(rings):
        for s in range(segments):
            a = r * (segments + 1) + s
            b = a + segments + 1
            idx += [a, a + 1, b, b, a + 1, b + 1]
    return pos, nrm, idx


def box(lo, hi):
    pos, nrm, idx = [], [], []
    faces = [((1, 0, 0), 0, hi[0]), ((-1, 0, 0), 0, lo[0]), ((0, 1, 0), 1, hi[1]), ((0, -1, 0), 1, lo[1]),
             ((0, 0, 1), 2, hi[2]), ((0, 0, -1), 2, lo[2])]
    for n, axis, value in faces:
        u, v = [a for a in range(3) if a != axis]
        base = len(pos)
        quad = [(lo[u], lo[v]), (hi[u], lo[v]), (hi[u], hi[v]), (lo[u], hi[v])]
        for qu, qv in quad:
            p = [0.0, 0.0, 0.0]
            p[axis], p[u], p[v] = value, qu, qv
            pos.append(tuple(p))
            nrm.append(n)
        # Counter-clockwise seen from outside.
        a, b, c, d = base, base + 1, base + 2, base + 3
        cross = [0, 0, 0]
        eu, ev = [0, 0, 0], [0, 0, 0]
        eu[u], ev[v] = 1, 1
        cross = (eu[1] * ev[2] - eu[2] * ev[1], eu[2] * ev[0] - eu[0] * ev[2], eu[0] * ev[1] - eu[1] * ev[0])
        if sum(cross[i] * n[i] for i in range(3)) > 0:
            idx += [a, b, c, a, c, d]
        else:
            idx += [a, c, b, a, d, c]
    return pos, nrm, idx


def build(meshes, light):
    """meshes: [(name, (pos, nrm, idx), material index)]."""
    blob = bytearray()
    accessors, views, gl_meshes, nodes = [], [], [], []

    def add(data, fmt, count, kind, target, minmax=None):
        while len(blob) % 4:
            blob.append(0)
        offset = len(blob)
        blob.extend(data)
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(data), "target": target})
        acc = {"bufferView": len(views) - 1, "componentType": fmt, "count": count, "type": kind}
        if minmax:
            acc["min"], acc["max"] = minmax
        accessors.append(acc)
        return len(accessors) - 1

    for name, (pos, nrm, idx), material in meshes:
        lo = [min(p[i] for p in pos) for i in range(3)]
        hi = [max(p[i] for p in pos) for i in range(3)]
        p = add(b"".join(struct.pack("<3f", *v) for v in pos), 5126, len(pos), "VEC3", 34962, (lo, hi))
        n = add(b"".join(struct.pack("<3f", *v) for v in nrm), 5126, len(nrm), "VEC3", 34962)
        i = add(b"".join(struct.pack("<I", v) for v in idx), 5125, len(idx), "SCALAR", 34963)
        gl_meshes.append({"name": name, "primitives": [{"attributes": {"POSITION": p, "NORMAL": n}, "indices": i,
                                                         "material": material}]})
        nodes.append({"name": name, "mesh": len(gl_meshes) - 1})
    doc = {
        "asset": {"version": "2.0", "generator": "fresnel scripts/make-shadow-scenes.py"},
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "meshes": gl_meshes,
        "materials": [
            {"name": "ground", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1], "metallicFactor": 0,
                                                        "roughnessFactor": 0.9}},
            {"name": "red", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.15, 0.1, 1], "metallicFactor": 0,
                                                     "roughnessFactor": 0.5}},
            {"name": "metal", "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.9, 0.9, 1], "metallicFactor": 1,
                                                       "roughnessFactor": 0.35}},
            {"name": "blue", "pbrMetallicRoughness": {"baseColorFactor": [0.1, 0.25, 0.8, 1], "metallicFactor": 0,
                                                      "roughnessFactor": 0.7}},
        ],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()}],
    }
    if light:
        kind, node = light
        doc["extensionsUsed"] = ["KHR_lights_punctual"]
        doc["extensions"] = {"KHR_lights_punctual": {"lights": [kind]}}
        node["extensions"] = {"KHR_lights_punctual": {"light": 0}}
        doc["nodes"].append(node)
        doc["scenes"][0]["nodes"].append(len(doc["nodes"]) - 1)
    return doc


def look_rotation(direction):
    """The quaternion (x, y, z, w) turning -Z onto `direction` (a light's forward)."""
    d = [c / math.sqrt(sum(x * x for x in direction)) for c in direction]
    f = (0.0, 0.0, -1.0)
    axis = (f[1] * d[2] - f[2] * d[1], f[2] * d[0] - f[0] * d[2], f[0] * d[1] - f[1] * d[0])
    dot = sum(f[i] * d[i] for i in range(3))
    s = math.sqrt(sum(a * a for a in axis))
    if s < 1e-9:
        return [0, 0, 0, 1] if dot > 0 else [0, 1, 0, 0]
    angle = math.atan2(s, dot)
    k = math.sin(angle / 2) / s
    return [axis[0] * k, axis[1] * k, axis[2] * k, math.cos(angle / 2)]


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "."
    os.makedirs(out, exist_ok=True)
    meshes = [
        ("ground", box((-4, -0.05, -4), (4, 0, 4)), 0),
        ("sphere", sphere(-1.2, 0.7, 0.3, 0.7), 1),
        ("metal-sphere", sphere(1.3, 0.45, 1.0, 0.45), 2),
        ("box", box((0.4, 0, -1.6), (1.4, 1.0, -0.6)), 3),
        ("pole", box((-0.1, 0, -1.2), (0.0, 2.2, -1.1)), 1),
    ]
    scenes = {
        "shadow-directional": ({"type": "directional", "intensity": 3.0},
                               {"name": "sun", "rotation": look_rotation((0.45, -1.0, -0.35))}),
        "shadow-point": ({"type": "point", "intensity": 40.0},
                         {"name": "bulb", "translation": [0.6, 3.0, 1.2]}),
        "shadow-spot": ({"type": "spot", "intensity": 60.0, "spot": {"innerConeAngle": 0.35, "outerConeAngle": 0.6}},
                        {"name": "spot", "translation": [-1.5, 3.5, 2.5],
                         "rotation": look_rotation((1.2, -3.2, -2.6))}),
        "shadow-environment": (None, None),
    }
    for name, (kind, node) in scenes.items():
        doc = build(meshes, (kind, node) if kind else None)
        with open(os.path.join(out, name + ".gltf"), "w") as f:
            json.dump(doc, f, separators=(",", ":"))
            f.write("\n")


if __name__ == "__main__":
    main()
