#!/usr/bin/env python3
"""How `fresnel render` scales (printed figures, not a timed test): cost against instances,
triangles, draws, lights and texture bytes, each with its slope, on scenes generated here
(glTF files written by this script), next to the same run's peer where one exists.

1. Instances: N placements of one model (DamagedHelmet when ../shared has it, else a generated
   textured sphere) as a scene file naming the model N times, against the peer: the same
   placements as N nodes of one glTF sharing one mesh (and as EXT_mesh_gpu_instancing).
2. Triangles: one sphere of T triangles.
3. Draws: N spheres, each its own mesh and material (no instancing possible).
4. Lights: L point lights (KHR_lights_punctual) over one sphere, shadows on and off.
5. Texture bytes: one quad with a base colour texture of S x S texels.
6. A big scene: ~1,000 nodes and ~2M triangles (40 distinct meshes, textures), its load, frame
   and resident memory against the sum of its decoded data (vertices, indices, texels).

Each row: wall time of the process, the JSON line's load/upload/frame ms, draw calls, peak RSS.
Slopes are least-squares fits of the total wall time (and peak memory) against the size.

usage: scaling_bench.py FRESNEL_EXE SHARED_DIR [--quick] [--json]
"""
import json
import math
import shutil
import os
import struct
import subprocess
import sys
import tempfile
import time

SIZE = "512x512"


def sphere(segments, rings, scale=1.0):
    """A UV sphere: positions, normals, uvs (flat float lists) and uint32 indices."""
    pos, nrm, uv, idx = [], [], [], []
    for r in range(rings + 1):
        v = r / rings
        th = v * math.pi
        for s in range(segments + 1):
            u = s / segments
            ph = u * 2 * math.pi
            x, y, z = math.sin(th) * math.cos(ph), math.cos(th), math.sin(th) * math.sin(ph)
            pos += [x * scale, y * scale, z * scale]
            nrm += [x, y, z]
            uv += [u, v]
    w = segments + 1
    for r in range(rings):
        for s in range(segments):
            a, b = r * w + s, r * w + s + 1
            c, d = a + w, b + w
            idx += [a, c, b, b, c, d]
    return pos, nrm, uv, idx


class Gltf:
    """A glTF 2.0 file built in memory: one buffer (.bin beside it)."""

    def __init__(self):
        self.doc = {"asset": {"version": "2.0", "generator": "fresnel scaling_bench"}, "buffers": [], "bufferViews": [],
                    "accessors": [], "meshes": [], "materials": [], "nodes": [], "scenes": [{"nodes": []}], "scene": 0}
        self.bin = bytearray()

    def _view(self, data, target=None):
        while len(self.bin) % 4:
            self.bin.append(0)
        view = {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)}
        if target:
            view["target"] = target
        self.bin += data
        self.doc["bufferViews"].append(view)
        return len(self.doc["bufferViews"]) - 1

    def accessor(self, values, kind, comps, ints=False, target=34962):
        fmt = ("<%dI" if ints else "<%df") % len(values)
        view = self._view(struct.pack(fmt, *values), target)
        acc = {"bufferView": view, "componentType": 5125 if ints else 5126, "count": len(values) // comps, "type": kind}
        if not ints and kind == "VEC3":
            acc["min"] = [min(values[i::3]) for i in range(3)]
            acc["max"] = [max(values[i::3]) for i in range(3)]
        self.doc["accessors"].append(acc)
        return len(self.doc["accessors"]) - 1

    def mesh(self, geometry, material):
        pos, nrm, uv, idx = geometry
        attrs = {"POSITION": self.accessor(pos, "VEC3", 3), "NORMAL": self.accessor(nrm, "VEC3", 3),
                 "TEXCOORD_0": self.accessor(uv, "VEC2", 2)}
        prim = {"attributes": attrs, "indices": self.accessor(idx, "SCALAR", 1, True, 34963), "material": material}
        self.doc["meshes"].append({"primitives": [prim]})
        return len(self.doc["meshes"]) - 1

    def material(self, color, texture=None):
        m = {"pbrMetallicRoughness": {"baseColorFactor": color + [1.0], "metallicFactor": 0.2, "roughnessFactor": 0.5}}
        if texture is not None:
            m["pbrMetallicRoughness"]["baseColorTexture"] = {"index": texture}
        self.doc["materials"].append(m)
        return len(self.doc["materials"]) - 1

    def texture_png(self, size, seed):
        """A size x size RGB PNG of noise (barely compressible, so its decode costs what its texels do)."""
        import numpy as np
        import zlib
        rng = np.random.default_rng(seed)
        rgb = rng.integers(0, 256, size=(size, size, 3), dtype=np.uint8)
        raw = np.concatenate([np.zeros((size, 1), np.uint8), rgb.reshape(size, size * 3)], axis=1).tobytes()

        def chunk(tag, data):
            return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data) & 0xffffffff)
        png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", size, size, 8, 2, 0, 0, 0))
        png += chunk(b"IDAT", zlib.compress(raw, 1)) + chunk(b"IEND", b"")
        view = self._view(png)
        self.doc.setdefault("images", []).append({"bufferView": view, "mimeType": "image/png"})
        self.doc.setdefault("textures", []).append({"source": len(self.doc["images"]) - 1})
        return len(self.doc["textures"]) - 1

    def node(self, mesh=None, translation=None, scale=None, extensions=None):
        n = {}
        if mesh is not None:
            n["mesh"] = mesh
        if translation:
            n["translation"] = translation
        if scale:
            n["scale"] = scale
        if extensions:
            n["extensions"] = extensions
        self.doc["nodes"].append(n)
        self.doc["scenes"][0]["nodes"].append(len(self.doc["nodes"]) - 1)
        return len(self.doc["nodes"]) - 1

    def write(self, path):
        self.doc["buffers"] = [{"byteLength": len(self.bin), "uri": os.path.basename(path)[:-5] + ".bin"}]
        with open(path[:-5] + ".bin", "wb") as f:
            f.write(self.bin)
        with open(path, "w") as f:
            json.dump(self.doc, f)
        return path


def replicate(model, places, out):
    """`model` (.glb or .gltf with its files beside it) as one glTF whose scene holds each root's
    subtree once per place (wrapped in a node at that translation): N nodes sharing the meshes."""
    folder = os.path.dirname(os.path.abspath(model))
    if model.lower().endswith(".glb"):
        data = open(model, "rb").read()
        length = struct.unpack_from("<I", data, 12)[0]
        doc = json.loads(data[20:20 + length])
        rest = 20 + length
        bin_length = struct.unpack_from("<I", data, rest)[0]
        bin_path = out[:-5] + ".bin"
        with open(bin_path, "wb") as f:
            f.write(data[rest + 8:rest + 8 + bin_length])
        doc["buffers"][0]["uri"] = os.path.basename(bin_path)
    else:
        doc = json.load(open(model))
    for entry in doc.get("buffers", []) + doc.get("images", []):
        uri = entry.get("uri")
        if uri and not uri.startswith("data:") and not os.path.exists(os.path.join(os.path.dirname(out), uri)):
            entry["uri"] = os.path.join(folder, uri)
    nodes = doc.get("nodes", [])
    roots = doc["scenes"][doc.get("scene", 0)]["nodes"]

    def copy(index):
        n = dict(nodes[index])
        if "children" in n:
            n["children"] = [copy(c) for c in n["children"]]
        nodes.append(n)
        return len(nodes) - 1
    scene_nodes = []
    for t in places:
        children = [copy(r) for r in roots]
        nodes.append({"translation": t, "children": children})
        scene_nodes.append(len(nodes) - 1)
    doc["scenes"] = [{"nodes": scene_nodes}]
    doc["scene"] = 0
    with open(out, "w") as f:
        json.dump(doc, f)
    return out


def run(exe, model, extra=()):
    """`fresnel render --json` twice (the first warms the driver's shader cache and the page
    cache): the faster run's JSON line, wall seconds and peak resident MiB."""
    a, b = run_once(exe, model, extra), run_once(exe, model, extra)
    return a if a["wall_s"] < b["wall_s"] else b


def run_once(exe, model, extra=()):
    cmd = [exe, "render", model, "-o", os.path.join(tempfile.gettempdir(), "fresnel-scaling.png"), "--size", SIZE,
           "--json"] + list(extra)
    t0 = time.perf_counter()
    p = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if p.returncode != 0:
        raise SystemExit("failed: %s\n%s" % (" ".join(cmd), p.stderr))
    j = json.loads(p.stdout.strip().splitlines()[-1])
    j["wall_s"] = wall
    # The process's own peak (VmHWM): ru_maxrss would keep this script's size from before the exec.
    j["rss_mib"] = j["peak_rss_mib"]
    return j


def slope(xs, ys):
    n = len(xs)
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx if sxx else 0.0


def table(title, unit, rows, per, per_name):
    """rows: (size, label, json)."""
    print("\n%s" % title)
    print("  %-26s %9s %9s %9s %9s %7s %9s %9s" % (unit, "wall s", "load ms", "upload", "frame ms", "draws", "instanced", "RSS MiB"))
    for size, label, j in rows:
        print("  %-26s %9.3f %9.1f %9.1f %9.1f %7d %9d %9.0f" % (label, j["wall_s"], j["load_ms"], j["upload_ms"],
                                                                  j["frame_ms"], j["draw_calls"], j.get("instanced_draws", 0),
                                                                  j["rss_mib"]))
    xs = [r[0] / per for r in rows]
    print("  slope: %.4g s and %.4g MiB per %s (wall, peak RSS); frame %.4g ms per %s" % (
        slope(xs, [r[2]["wall_s"] for r in rows]), slope(xs, [r[2]["rss_mib"] for r in rows]), per_name,
        slope(xs, [r[2]["frame_ms"] for r in rows]), per_name))


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    quick = "--quick" in sys.argv
    as_json = "--json" in sys.argv
    if len(args) < 2:
        print(__doc__)
        return 2
    exe, shared = os.path.abspath(args[0]), os.path.abspath(args[1])
    work = tempfile.mkdtemp(prefix="fresnel-scaling-")
    results = {}

    # 1. Instances.
    helmet = os.path.join(shared, "assets", "models", "DamagedHelmet", "DamagedHelmet.glb")
    if not os.path.exists(helmet):
        g = Gltf()
        g.node(g.mesh(sphere(64, 32), g.material([0.8, 0.6, 0.4], g.texture_png(1024, 1))))
        helmet = g.write(os.path.join(work, "model.gltf"))
    counts = [1, 4, 16] if quick else [1, 4, 16, 64]
    rows_file, rows_nodes, rows_flat = [], [], []
    for n in counts:
        side = math.ceil(math.sqrt(n))
        places = [[2.2 * (k % side), 0, 2.2 * (k // side)] for k in range(n)]
        scene = {"fresnel": 1, "models": [{"path": helmet, "translation": t} for t in places]}
        path = os.path.join(work, "copies%d.fresnel.json" % n)
        with open(path, "w") as f:
            json.dump(scene, f)
        rows_file.append((n, "%d copies (scene file)" % n, run(exe, path, ["--allow-external-files"])))
        rows_flat.append((n, "%d copies, --no-instancing" % n, run(exe, path, ["--allow-external-files", "--no-instancing"])))
        # The peer: the same placements as N nodes of one glTF sharing the model's meshes.
        peer = replicate(helmet, places, os.path.join(work, "nodes%d.gltf" % n))
        rows_nodes.append((n, "%d nodes (one glTF)" % n, run(exe, peer, ["--allow-external-files"])))
    table("Instances: one model placed N times by a scene file (%s)" % os.path.basename(helmet), "placements",
          rows_file, 1, "placement")
    table("  the same without instanced draws (--no-instancing: a draw per placement)", "placements", rows_flat, 1,
          "placement")
    table("  peer: the same placements as N nodes of one glTF sharing its meshes", "placements", rows_nodes, 1, "placement")
    last, peer_last = rows_file[-1][2], rows_nodes[-1][2]
    print("  %d placements: the scene file takes %.2fx the wall time and %.2fx the memory of the one-glTF case"
          " (target: within 1.5x)" % (counts[-1], last["wall_s"] / peer_last["wall_s"], last["rss_mib"] / peer_last["rss_mib"]))
    results["instances"] = [(r[0], r[2]) for r in rows_file]

    # 2. Triangles.
    rows = []
    for seg in ([64, 256, 512] if quick else [64, 256, 512, 1024]):
        g = Gltf()
        g.node(g.mesh(sphere(seg, seg // 2), g.material([0.7, 0.7, 0.7])))
        tris = seg * (seg // 2) * 2
        rows.append((tris, "%d triangles" % tris, run(exe, g.write(os.path.join(work, "tris%d.gltf" % seg)))))
    table("Triangles: one sphere", "triangles", rows, 1e6, "million triangles")
    results["triangles"] = [(r[0], r[2]) for r in rows]

    # 3. Draws.
    rows = []
    for n in ([10, 100, 400] if quick else [10, 100, 400, 1000]):
        g = Gltf()
        side = math.ceil(math.sqrt(n))
        for k in range(n):
            m = g.mesh(sphere(16, 8), g.material([0.3 + 0.6 * (k % 7) / 7, 0.5, 0.4]))
            g.node(m, translation=[2.2 * (k % side), 0, 2.2 * (k // side)])
        rows.append((n, "%d distinct meshes" % n, run(exe, g.write(os.path.join(work, "draws%d.gltf" % n)))))
    table("Draws: N spheres, each its own mesh and material", "draws", rows, 1, "draw")
    results["draws"] = [(r[0], r[2]) for r in rows]

    # 4. Lights.
    for shadows in ("soft", "off"):
        rows = []
        for n in [1, 4, 8, 16]:
            g = Gltf()
            g.node(g.mesh(sphere(64, 32), g.material([0.7, 0.7, 0.7])))
            g.node(g.mesh(sphere(16, 8), g.material([0.5, 0.5, 0.5])), translation=[0, -3, 0], scale=[6, 0.1, 6])
            lights = []
            for k in range(n):
                a = 2 * math.pi * k / n
                lights.append({"type": "point", "intensity": 20.0 / n, "color": [1, 1, 1]})
                g.node(translation=[3 * math.cos(a), 3, 3 * math.sin(a)],
                       extensions={"KHR_lights_punctual": {"light": k}})
            g.doc["extensions"] = {"KHR_lights_punctual": {"lights": lights}}
            g.doc["extensionsUsed"] = ["KHR_lights_punctual"]
            path = g.write(os.path.join(work, "lights%d.gltf" % n))
            rows.append((n, "%d point lights" % n, run(exe, path, ["--no-ibl", "--shadows", shadows])))
        table("Lights: point lights (KHR_lights_punctual), shadows %s" % shadows, "lights", rows, 1, "light")
        results["lights_" + shadows] = [(r[0], r[2]) for r in rows]

    # 5. Texture bytes.
    rows = []
    for size in ([256, 1024, 2048] if quick else [256, 1024, 2048, 4096]):
        g = Gltf()
        g.node(g.mesh(sphere(32, 16), g.material([1, 1, 1], g.texture_png(size, 2))))
        mb = size * size * 4 / 2**20
        rows.append((mb, "%d^2 texels (%.0f MiB RGBA)" % (size, mb), run(exe, g.write(os.path.join(work, "tex%d.gltf" % size)))))
    table("Texture bytes: one base colour texture", "texture", rows, 1, "MiB of RGBA texels")
    results["texture_mib"] = [(r[0], r[2]) for r in rows]

    # 6. A big scene.
    g = Gltf()
    meshes = []
    textures = [g.texture_png(512, k) for k in range(8)]
    vertex_bytes = 0
    for k in range(40):
        seg = 40 + 4 * (k % 5)
        geo = sphere(seg, seg // 2, 0.5 + 0.02 * k)
        vertex_bytes += len(geo[0]) * 4 * 8 // 3 + len(geo[3]) * 4
        meshes.append((g.mesh(geo, g.material([0.2 + 0.02 * k, 0.5, 0.6], textures[k % 8])), len(geo[3]) // 3))
    tris = 0
    nodes = 1000
    for k in range(nodes):
        m, t = meshes[(k * 7) % len(meshes)]
        tris += t
        g.node(m, translation=[1.5 * (k % 32), 0.3 * (k % 3), 1.5 * (k // 32)])
    path = g.write(os.path.join(work, "big.gltf"))
    texel_bytes = 8 * 512 * 512 * 4 * 4 // 3
    big = run(exe, path)
    flat = run(exe, path, ["--no-instancing"])
    decoded = (vertex_bytes + texel_bytes) / 2**20
    print("\nA big scene: %d nodes, %.2fM triangles drawn, 40 meshes, 8 textures of 512^2" % (nodes, tris / 1e6))
    print("  wall %.2f s, load %.0f ms, upload %.0f ms, frame %.0f ms, %d draws (%d instanced, %d culled)" % (
        big["wall_s"], big["load_ms"], big["upload_ms"], big["frame_ms"], big["draw_calls"], big.get("instanced_draws", 0),
        big.get("culled_draws", 0)))
    # The process without a scene: the GL context (llvmpipe's own memory), the environment, the program.
    g = Gltf()
    g.node(g.mesh(sphere(4, 2), g.material([0.5, 0.5, 0.5])))
    empty = run(exe, g.write(os.path.join(work, "empty.gltf")))
    print("  --no-instancing: wall %.2f s, frame %.0f ms, %d draws, peak RSS %.0f MiB" % (
        flat["wall_s"], flat["frame_ms"], flat["draw_calls"], flat["rss_mib"]))
    grown = big["rss_loaded_mib"] - empty["rss_loaded_mib"]
    print("  resident once loaded and uploaded: %.0f MiB, %.0f MiB over a one-sphere render's %.0f MiB, against %.1f MiB"
          " of decoded data (vertices, indices, texels with mips): %.2fx (llvmpipe keeps its copy of the uploads in"
          " the same memory)" % (big["rss_loaded_mib"], grown, empty["rss_loaded_mib"], decoded, grown / decoded))
    print("  peak RSS %.0f MiB (the frame: llvmpipe bins every triangle it draws; %.0f MiB over the one-sphere"
          " render's peak)" % (big["rss_mib"], big["rss_mib"] - empty["rss_mib"]))
    results["big"] = {"nodes": nodes, "triangles": tris, "decoded_mib": decoded, "run": big, "empty_rss_mib": empty["rss_mib"]}
    if as_json:
        print(json.dumps(results))
    shutil.rmtree(work, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
