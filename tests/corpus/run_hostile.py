#!/usr/bin/env python3
"""Hostile-input checks through the CLI: URI policy, truncated GLB files, a PNG that
claims to be 100000x100000. Generates every file itself (no shared assets needed).

usage: run_hostile.py FRESNEL_BINARY
"""
import base64, json, os, struct, subprocess, sys, tempfile, time, zlib

import sanitizer_report

failures = []


def fresnel(binary, *args, timeout=20):
    rc, err, secs, notes = sanitizer_report.run_step([binary, *args], timeout)
    for note in notes:
        print(f"note: {note}")
    if sanitizer_report.finding(err):
        expect(f"no sanitizer report from fresnel {' '.join(args)}", False, err[-1500:])
    return rc, err, (timeout if rc == "timeout" else secs)


def expect(name, cond, detail=""):
    print(("ok   " if cond else "FAIL ") + name + ("" if cond else f": {detail}"))
    if not cond:
        failures.append(name)


def png_bytes(width, height, with_data=True):
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    ihdr = struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)
    out = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr)
    if with_data:
        raw = b"".join(b"\x00" + b"\x80\x80\x80\xff" * width for _ in range(height))
        out += chunk(b"IDAT", zlib.compress(raw))
    else:
        out += chunk(b"IDAT", zlib.compress(b"\x00" * 64))  # far too little data for the claimed size
    return out + chunk(b"IEND", b"")


def triangle_gltf(image_uri=None, embed_buffer=True):
    pos = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    uv = struct.pack("<6f", 0, 0, 1, 0, 0, 1)
    buf = pos + uv
    doc = {
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 0}]}],
        "materials": [{"pbrMetallicRoughness": {}}],
        "buffers": [{"byteLength": len(buf)}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 24}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]},
                      {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"}],
    }
    if embed_buffer:
        doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(buf).decode()
    if image_uri is not None:
        doc["images"] = [{"uri": image_uri}]
        doc["textures"] = [{"source": 0}]
        doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 0}
    return doc, buf


def glb(doc, bin_data):
    js = json.dumps(doc).encode()
    js += b" " * (-len(js) % 4)
    bin_data += b"\x00" * (-len(bin_data) % 4)
    body = struct.pack("<II", len(js), 0x4E4F534A) + js + struct.pack("<II", len(bin_data), 0x004E4942) + bin_data
    return struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body


def main():
    binary = sys.argv[1]
    with tempfile.TemporaryDirectory() as tmp:
        model_dir = os.path.join(tmp, "model")
        os.makedirs(model_dir)
        outside = os.path.join(tmp, "outside.png")
        with open(outside, "wb") as f:
            f.write(png_bytes(4, 4))
        out_png = os.path.join(tmp, "out.png")

        def write_model(name, doc):
            path = os.path.join(model_dir, name)
            with open(path, "w") as f:
                json.dump(doc, f)
            return path

        # URI policy.
        for label, uri in (("dot-dot", "../../../../etc/passwd"), ("absolute", outside),
                           ("http", "http://example.com/texture.png")):
            path = write_model(label + ".gltf", triangle_gltf(uri)[0])
            for cmd in (["info", path], ["render", path, "-o", out_png, "--size", "32x32", "--no-ibl"]):
                rc, err, _ = fresnel(binary, *cmd)
                expect(f"{label} URI refused by {cmd[0]}", rc == 1 and uri in err and "fresnel: error:" in err,
                       f"exit {rc}, stderr {err[-300:]!r}")
        path = os.path.join(model_dir, "absolute.gltf")
        rc, err, _ = fresnel(binary, "render", path, "-o", out_png, "--size", "32x32", "--allow-external-files", "--no-ibl")
        expect("absolute URI loads with --allow-external-files", rc == 0, f"exit {rc}: {err[-300:]!r}")
        path = os.path.join(model_dir, "http.gltf")
        rc, err, _ = fresnel(binary, "info", path, "--allow-external-files")
        expect("http URI refused even with --allow-external-files", rc == 1 and "http://" in err, f"exit {rc}")

        # A PNG claiming 100000 x 100000 pixels: refused quickly, naming the limit, no 40 GB allocation.
        with open(os.path.join(model_dir, "huge.png"), "wb") as f:
            f.write(png_bytes(100000, 100000, with_data=False))
        path = write_model("huge.gltf", triangle_gltf("huge.png")[0])
        rc, err, secs = fresnel(binary, "render", path, "-o", out_png, "--size", "32x32", "--no-ibl")
        expect("100000x100000 PNG: clear message naming the limit, within seconds",
               rc in (0, 1) and "limit" in err and "100000" in err and secs < 10,
               f"exit {rc} in {secs:.1f} s: {err[-300:]!r}")

        # Truncated GLB at every length: exit 1 with a clear message, quickly.
        doc, buf = triangle_gltf(embed_buffer=False)
        data = glb(doc, buf)
        bad, slow = [], 0.0
        for n in range(0, len(data)):
            p = os.path.join(tmp, "cut.glb")
            with open(p, "wb") as f:
                f.write(data[:n])
            rc, err, secs = fresnel(binary, "info", p)
            slow = max(slow, secs)
            if rc != 1 or "fresnel: error:" not in err:
                bad.append((n, rc, err[-200:]))
        expect(f"GLB truncated at each of {len(data)} lengths -> exit 1 with message", not bad, str(bad[:3]))
        expect("truncated GLB handled quickly", slow < 5, f"slowest {slow:.1f} s")
        full = os.path.join(tmp, "full.glb")
        with open(full, "wb") as f:
            f.write(data)
        rc, err, _ = fresnel(binary, "info", full)
        expect("the untruncated GLB loads", rc == 0, err[-300:])

        # OBJ/MTL: the same path policy for mtllib and texture maps, errors naming FILE: line N.
        def write_text(name, text):
            path = os.path.join(model_dir, name)
            with open(path, "w") as f:
                f.write(text)
            return path
        tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl m\nf 1/1 2/2 3/3\n"
        with open(os.path.join(tmp, "outside.mtl"), "w") as f:
            f.write("newmtl m\nKd 1 0 0\n")
        for label, ref in (("dot-dot", "../outside.mtl"), ("absolute", os.path.join(tmp, "outside.mtl")),
                           ("http", "http://example.com/x.mtl")):
            path = write_text(f"mtllib-{label}.obj", f"mtllib {ref}\n" + tri)
            for cmd in (["info", path], ["render", path, "-o", out_png, "--size", "32x32", "--no-ibl"]):
                rc, err, _ = fresnel(binary, *cmd)
                expect(f"OBJ mtllib {label} refused by {cmd[0]}",
                       rc == 1 and ref in err and "line 1:" in err and "fresnel: error:" in err,
                       f"exit {rc}, stderr {err[-300:]!r}")
        for label, ref in (("dot-dot", "../outside.png"), ("absolute", outside)):
            write_text(f"map-{label}.mtl", f"newmtl m\nmap_Kd {ref}\n")
            path = write_text(f"map-{label}.obj", f"mtllib map-{label}.mtl\n" + tri)
            rc, err, _ = fresnel(binary, "render", path, "-o", out_png, "--size", "32x32", "--no-ibl")
            expect(f"OBJ map_Kd {label} refused", rc == 1 and f"map-{label}.mtl: line 2:" in err, f"exit {rc}: {err[-300:]!r}")
        rc, err, _ = fresnel(binary, "render", os.path.join(model_dir, "map-absolute.obj"), "-o", out_png,
                             "--size", "32x32", "--no-ibl", "--allow-external-files")
        expect("OBJ absolute map_Kd loads with --allow-external-files", rc == 0, f"exit {rc}: {err[-300:]!r}")
        write_text("huge.mtl", "newmtl m\nmap_Kd huge.png\n")
        path = write_text("huge.obj", "mtllib huge.mtl\n" + tri)
        rc, err, secs = fresnel(binary, "render", path, "-o", out_png, "--size", "32x32", "--no-ibl")
        expect("OBJ with a 100000x100000 PNG map: message naming the limit, within seconds",
               rc in (0, 1) and "limit" in err and secs < 10, f"exit {rc} in {secs:.1f} s: {err[-300:]!r}")
        # A 100000-sided star (concave at every other vertex): triangulated within seconds.
        import math
        n = 100000
        star = "".join(f"v {(1 if i % 2 else 0.3) * math.cos(2 * math.pi * i / n):.7f} "
                       f"{(1 if i % 2 else 0.3) * math.sin(2 * math.pi * i / n):.7f} 0\n" for i in range(n))
        path = write_text("star.obj", star + "f " + " ".join(str(i + 1) for i in range(n)) + "\n")
        rc, err, secs = fresnel(binary, "info", path, "--json")
        expect("100000-sided concave polygon: loads within 20 s", rc == 0 and secs < 20, f"exit {rc} in {secs:.1f} s")
        # Truncated OBJ at every length: loads (exit 0) or a clear error (exit 1), never a crash.
        data = ("mtllib m.mtl\no a\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\ns 1\n"
                "usemtl m\nf 1/1/1 2/1/1 3/1/1 4/1/1\nf -4 -3 -2\nl 1 2\n")
        write_text("m.mtl", "newmtl m\nKd 0.5 0.5 0.5\nNs 20\n")
        bad = []
        for k in range(len(data)):
            path = write_text("cut.obj", data[:k])
            rc, err, _ = fresnel(binary, "info", path)
            if rc not in (0, 1) or (rc == 1 and "fresnel: error:" not in err):
                bad.append((k, rc, err[-200:]))
        expect(f"OBJ truncated at each of {len(data)} lengths -> exit 0 or 1 with message", not bad, str(bad[:3]))
    print(f"{len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
