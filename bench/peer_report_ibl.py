#!/usr/bin/python3
"""Issue 34, item 5: OBJ -> glTF conversion against obj2gltf under image-based light.

bench/peer-report.sh compares the two conversions under the one light OpenGL 1 was fitted to. A
converted model is mostly seen in glTF viewers under an environment, so this protocol lights the same
scenes (../shared/tools/ogl1-ref/make-scenes) with the studio environment
(../shared/assets/env/studio_small_03_1k.hdr) and asks which glTF looks more like what the MTL meant.

What the MTL means under an environment (the "OpenGL 1 intent"). OpenGL 1 cannot draw an environment,
but its lighting is a sum over lights and has no shadows, so the environment is taken as the limit of
many directional lights: the sphere is cut into N equal-area cells (bands of equal height x equal
azimuth steps), each cell becomes one OpenGL 1 directional light from its radiance-weighted mean
direction whose colour is the cell's radiance integrated over its solid angle / pi (an OpenGL light of
colour 1 is the pi lux directional light of issue 10's protocol, as in peer-report.sh). Energy is kept
exactly; what a cell blurs is the light within ~3 degrees (N = 4096), finer than the sharpest
highlight OpenGL 1 allows (shininess <= 128). The sum is drawn by `--shading ogl1-pixel` (fresnel's
OpenGL 1 per fragment, which ogl1_ref_test holds to Mesa's fixed-function pipeline), 16 lights a pass,
in float, and clamped once at the end, as OpenGL 1 clamps its colour; the emission and ambient base is
counted once. Written raw (OpenGL 1 does not encode), as ogl1-ref writes its PNGs.

Scenes: make-scenes' and three of ../shared/assets/obj (spider, regr01, cube_usemtl) where present.
The two glTF files (`fresnel convert --match opengl1`, obj2gltf 3.2.0 with its defaults) are drawn by
`fresnel render` as a glTF viewer shows them: the environment's image-based light alone, tone mapping
none, sRGB encoding, black background, occlusion and shadows off. PSNR over the object's pixels
(mask auto), per scene and view.

usage: /usr/bin/python3 bench/peer_report_ibl.py [--build build] [--out DIR] [--cells 4096] [--quick]
Needs build/python (the fresnel module), ../shared/tools/ogl1-ref and obj2gltf under
BUILD/node-tools (cd BUILD/node-tools && npm install obj2gltf@3.2.0); Debian's python3 with NumPy.
"""
import argparse
import datetime
import math
import os
import subprocess
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def environment_lights(env, cells):
    """The environment (H, W, >=3 float, equirectangular as fresnel samples it) as `cells` directional
    lights: a list of (azimuth, elevation, (r, g, b)) in --light's convention (arriving from), each
    colour the cell's integral of radiance over solid angle / pi."""
    h, w = env.shape[:2]
    bands = int(round(math.sqrt(cells)))
    columns = cells // bands
    # Pixel centres: u across, v down; direction as fresnel's equirect_to_direction.
    u = (np.arange(w) + 0.5) / w
    v = (np.arange(h) + 0.5) / h
    phi = (u - 0.5) * 2.0 * math.pi
    theta = v * math.pi
    st, ct = np.sin(theta)[:, None], np.cos(theta)[:, None]
    d = np.stack([-st * np.sin(phi)[None, :], np.broadcast_to(ct, (h, w)), st * np.cos(phi)[None, :]], axis=-1)
    d_omega = (math.pi / h) * (2.0 * math.pi / w) * np.broadcast_to(st, (h, w))
    radiance = env[..., :3].astype(np.float64)
    # Equal-area cells: `bands` equal steps of height (y = cos theta), `columns` equal steps of azimuth.
    band = np.minimum(((1.0 - d[..., 1]) * 0.5 * bands).astype(int), bands - 1)
    column = np.minimum((u * columns).astype(int), columns - 1)[None, :]
    cell = (band * columns + column).ravel()
    energy = (radiance * d_omega[..., None]).reshape(-1, 3)
    weight = energy.sum(axis=1)
    colour = np.zeros((bands * columns, 3))
    for c in range(3):
        colour[:, c] = np.bincount(cell, energy[:, c], bands * columns)
    mean = np.zeros((bands * columns, 3))
    centre = np.zeros((bands * columns, 3))
    flat = d.reshape(-1, 3)
    area = d_omega.ravel()
    for c in range(3):
        mean[:, c] = np.bincount(cell, flat[:, c] * weight, bands * columns)
        centre[:, c] = np.bincount(cell, flat[:, c] * area, bands * columns)
    lights = []
    for i in range(bands * columns):
        direction = mean[i] if weight_sum(mean[i]) > 0 else centre[i]
        n = np.linalg.norm(direction)
        if n == 0 or colour[i].max() <= 0:
            continue
        x, y, z = direction / n
        azimuth = math.degrees(math.atan2(x, z))
        elevation = math.degrees(math.asin(max(-1.0, min(1.0, y))))
        lights.append((azimuth, elevation, tuple(colour[i] / math.pi)))
    return lights


def weight_sum(vector):
    return float(np.abs(vector).sum())


def white_peak(lights, normals=2000):
    """The brightest a white Lambertian surface (OpenGL 1's Kd 1) gets under `lights`: the largest
    luminance of sum(colour max(n.l, 0)) over a Fibonacci set of normals."""
    i = np.arange(normals) + 0.5
    y = 1.0 - 2.0 * i / normals
    r = np.sqrt(1.0 - y * y)
    a = math.pi * (3.0 - math.sqrt(5.0)) * i
    n = np.stack([r * np.cos(a), y, r * np.sin(a)], axis=1)
    l = np.array([[math.cos(math.radians(e)) * math.sin(math.radians(az)), math.sin(math.radians(e)),
                   math.cos(math.radians(e)) * math.cos(math.radians(az))] for az, e, _ in lights])
    colour = np.array([c for _, _, c in lights]) @ np.array([0.2126, 0.7152, 0.0722])
    return float((np.maximum(n @ l.T, 0.0) @ colour).max())


def opengl1_intent(fresnel, renderer, scene, lights, size, yaw, pitch, clamp=True):
    """OpenGL 1's lighting of `scene` summed over `lights`, clamped once: float (H, W, 3), raw."""
    def job():
        return fresnel.Job(size=size, yaw=yaw, pitch=pitch, shading="ogl1-pixel", env="none", background="0,0,0")

    # One light of colour 0: the emission and ambient every pass also carries, counted once.
    base_job = job()
    base_job.add_light("dir:0,90,0")
    base = renderer.render(scene, base_job, dtype="float32")[..., :3].astype(np.float64)
    total = base.copy()
    for start in range(0, len(lights), 16):
        j = job()
        for azimuth, elevation, (r, g, b) in lights[start:start + 16]:
            j.add_light(f"dir:{azimuth:.6f},{elevation:.6f},1,{r:.9g},{g:.9g},{b:.9g}")
        total += renderer.render(scene, j, dtype="float32")[..., :3] - base
    return np.clip(total, 0.0, 1.0) if clamp else total


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--out", default=None, help="work folder (default BUILD/peer-report-ibl)")
    parser.add_argument("--env", default=None, help="environment (default ../shared/assets/env/studio_small_03_1k.hdr)")
    parser.add_argument("--cells", type=int, default=4096, help="directional lights standing for the environment")
    parser.add_argument("--size", type=int, default=256)
    parser.add_argument("--quick", action="store_true", help="four scenes, one view")
    parser.add_argument("--scenes", default=None, help="only these scenes (comma-separated names)")
    parser.add_argument("--report", default=None, help="also write the Markdown table here")
    parser.add_argument("--match", default="opengl1", choices=["opengl1", "albedo"], help="convert's --match (default opengl1)")
    args = parser.parse_args()

    build = os.path.abspath(args.build)
    sys.path.insert(0, os.path.join(build, "python"))
    import fresnel  # noqa: E402 (from the build folder)

    shared = os.environ.get("FRESNEL_SHARED_DIR", os.path.join(ROOT, "..", "shared"))
    ref_tool = os.path.join(shared, "tools", "ogl1-ref")
    env_path = args.env or os.path.join(shared, "assets", "env", "studio_small_03_1k.hdr")
    obj2gltf = os.path.join(build, "node-tools", "node_modules", ".bin", "obj2gltf")
    exe = os.path.join(build, "bin", "fresnel")
    for need in (exe, os.path.join(ref_tool, "make-scenes"), env_path, obj2gltf):
        if not os.path.exists(need):
            print(f"peer_report_ibl: missing {need}", file=sys.stderr)
            return 2
    out = os.path.abspath(args.out or os.path.join(build, "peer-report-ibl"))
    scenes_dir = os.path.join(out, "scenes")
    os.makedirs(out, exist_ok=True)
    subprocess.run(["/usr/bin/python3", os.path.join(ref_tool, "make-scenes"), scenes_dir], check=True, stdout=subprocess.DEVNULL)

    env = fresnel.read(env_path)
    lights = environment_lights(env, args.cells)
    # Exposure as issue 10's one light: a white Lambertian surface at its brightest shows 1.0.
    intensity = 1.0 / white_peak(lights)
    lights = [(az, el, tuple(c * intensity for c in colour)) for az, el, colour in lights]
    size = (args.size, args.size)
    views = [(0, 0)] if args.quick else [(0, 0), (45, 20)]
    objs = [os.path.join(scenes_dir, f) for f in sorted(os.listdir(scenes_dir)) if f.endswith(".obj")]
    # Real models beside the generated scenes: ../shared's OBJ cases with materials and maps.
    objs += [p for p in (os.path.join(shared, "assets", "obj", f + ".obj") for f in ("spider", "regr01", "cube_usemtl"))
             if os.path.exists(p)]
    only = args.scenes.split(",") if args.scenes else ["spheres", "sanity-spec32", "textured", "spider"] if args.quick else None
    if only:
        objs = [p for p in objs if os.path.basename(p)[:-4] in only]

    rows = []
    renderer = fresnel.Renderer()
    for obj in objs:
        name = os.path.basename(obj)[:-4]
        ours = os.path.join(out, name + ".ours.glb")
        peer = os.path.join(out, name + ".peer.glb")
        subprocess.run([exe, "convert", obj, ours, "--quiet", "--match", args.match], check=True)
        subprocess.run([obj2gltf, "-i", obj, "-o", peer], check=True, cwd=os.path.dirname(obj), stdout=subprocess.DEVNULL)
        original = fresnel.load(obj)
        converted = {who: fresnel.load(path) for who, path in (("ours", ours), ("peer", peer))}
        for yaw, pitch in views:
            tag = f"{name}.y{yaw}.p{pitch}"
            intent = opengl1_intent(fresnel, renderer, original, lights, size, yaw, pitch)
            intent8 = np.round(intent * 255.0).astype(np.uint8)
            fresnel.save(os.path.join(out, tag + ".intent.png"), intent8)
            row = [name, f"{yaw}, {pitch}"]
            pixels = None
            for who in ("ours", "peer"):
                job = fresnel.Job(size=size, yaw=yaw, pitch=pitch, env=env_path, env_intensity=intensity, background="0,0,0", tonemap="none",
                                  encoding="srgb", ao="off", shadows="off")
                image = renderer.render(converted[who], job)
                fresnel.save(os.path.join(out, f"{tag}.{who}.png"), image)
                m = fresnel.compare(image[..., :3], intent8, mask="auto")
                row.append(m["psnr_db"])
                pixels = m["pixels"] if pixels is None else max(pixels, m["pixels"])
            if pixels == 0:  # seen edge on (sanity-plane from the front): nothing to compare
                print(f"{name:16s} {yaw:3d},{pitch:3d}  no object pixels", flush=True)
                continue
            rows.append(row)
            print(f"{name:16s} {yaw:3d},{pitch:3d}  ours {row[2]:6.2f} dB  obj2gltf {row[3]:6.2f} dB", flush=True)

    table = [
        "# OBJ -> glTF under image-based light: fresnel convert against obj2gltf 3.2.0",
        "",
        f"Generated by `bench/peer_report_ibl.py` on {datetime.date.today().isoformat()}. The OpenGL 1 intent: the MTL "
        f"lit by {os.path.basename(env_path)} (intensity {intensity:.3f}: a white Lambertian surface at its brightest shows 1.0) as {len(lights)} OpenGL 1 directional lights (equal-area cells, energy kept), "
        f"`--shading ogl1-pixel`, summed in float and clamped once. Both glTF files (`fresnel convert --match {args.match}`, "
        "obj2gltf defaults) rendered by `fresnel render --env ENV --env-intensity I --background 0,0,0 --tonemap none --encoding srgb "
        f"--ao off --shadows off`, {args.size}x{args.size}. PSNR (dB) over the object's pixels against the intent.",
        "",
        "| scene | view (yaw, pitch) | fresnel convert | obj2gltf |",
        "|---|---|---|---|",
    ]
    table += [f"| {r[0]} | {r[1]} | {r[2]:.1f} | {r[3]:.1f} |" for r in rows]
    wins = sum(1 for r in rows if r[2] > r[3])
    table += ["", f"Views with no object pixels (a plane seen edge on) are left out. fresnel closer on {wins} of {len(rows)}; mean {np.mean([r[2] for r in rows]):.1f} dB against "
              f"{np.mean([r[3] for r in rows]):.1f} dB."]
    text = "\n".join(table) + "\n"
    with open(os.path.join(out, "peer-report-ibl.md"), "w") as f:
        f.write(text)
    if args.report:
        with open(args.report, "w") as f:
            f.write(text)
    print(text)
    return 0 if wins == len(rows) else 1


if __name__ == "__main__":
    sys.exit(main())
