#!/usr/bin/python3
"""docs/images/match.png: what `fresnel convert --match` gives, beside obj2gltf, under the one
OpenGL 1 light (peer-report.sh's protocol) and under the studio environment (peer_report_ibl.py's).

Columns: the OpenGL 1 original (under the environment: its intent, peer_report_ibl.py),
`--match opengl1`, `--match albedo` (the default), obj2gltf 3.2.0. Rows: one light, the studio
environment. The scene: make-scenes' spheres (rows red, black, blue, white; Ns rising to the right).

usage: /usr/bin/python3 bench/match_picture.py [--build build] [--out docs/images/match.png]
Needs what peer_report_ibl.py needs, and Pillow.
"""
import argparse
import os
import subprocess
import sys

import numpy as np
from PIL import Image, ImageDraw

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from peer_report_ibl import environment_lights, opengl1_intent, white_peak  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--out", default=os.path.join(ROOT, "docs", "images", "match.png"))
    parser.add_argument("--size", type=int, default=300)
    args = parser.parse_args()
    build = os.path.abspath(args.build)
    sys.path.insert(0, os.path.join(build, "python"))
    import fresnel  # noqa: E402

    shared = os.environ.get("FRESNEL_SHARED_DIR", os.path.join(ROOT, "..", "shared"))
    ref_tool = os.path.join(shared, "tools", "ogl1-ref")
    env_path = os.path.join(shared, "assets", "env", "studio_small_03_1k.hdr")
    obj2gltf = os.path.join(build, "node-tools", "node_modules", ".bin", "obj2gltf")
    exe = os.path.join(build, "bin", "fresnel")
    work = os.path.join(build, "match-picture")
    os.makedirs(work, exist_ok=True)
    subprocess.run(["/usr/bin/python3", os.path.join(ref_tool, "make-scenes"), os.path.join(work, "scenes")], check=True,
                   stdout=subprocess.DEVNULL)
    obj = os.path.join(work, "scenes", "spheres.obj")
    files = {}
    for match in ("opengl1", "albedo"):
        files[match] = os.path.join(work, f"spheres.{match}.glb")
        subprocess.run([exe, "convert", obj, files[match], "--quiet", "--match", match], check=True, stderr=subprocess.DEVNULL)
    files["obj2gltf"] = os.path.join(work, "spheres.obj2gltf.glb")
    subprocess.run([obj2gltf, "-i", obj, "-o", files["obj2gltf"]], check=True, cwd=os.path.dirname(obj), stdout=subprocess.DEVNULL)

    size = (args.size, args.size)
    yaw, pitch = 0, 0
    renderer = fresnel.Renderer()
    lights = environment_lights(fresnel.read(env_path), 4096)
    intensity = 1.0 / white_peak(lights)
    lights = [(az, el, tuple(c * intensity for c in colour)) for az, el, colour in lights]
    original = fresnel.load(obj)

    rows = []
    # One light: OpenGL 1 (fresnel's ogl1-pixel, which ogl1_ref_test holds to Mesa), then the glTF files.
    one = fresnel.Job(size=size, yaw=yaw, pitch=pitch, shading="ogl1-pixel", env="none", background="0,0,0")
    one.add_light("dir:30,45,1")
    row = [renderer.render(original, one)[..., :3]]
    for who in ("opengl1", "albedo", "obj2gltf"):
        j = fresnel.Job(size=size, yaw=yaw, pitch=pitch, env="none", background="0,0,0", tonemap="none", encoding="srgb",
                        ao="off", shadows="off", scene_lights=False)
        j.add_light("dir:30,45,3.14159265")
        row.append(renderer.render(fresnel.load(files[who]), j)[..., :3])
    rows.append(row)
    intent = opengl1_intent(fresnel, renderer, original, lights, size, yaw, pitch)
    row = [np.round(intent * 255.0).astype(np.uint8)]
    for who in ("opengl1", "albedo", "obj2gltf"):
        j = fresnel.Job(size=size, yaw=yaw, pitch=pitch, env=env_path, env_intensity=intensity, background="0,0,0",
                        tonemap="none", encoding="srgb", ao="off", shadows="off")
        row.append(renderer.render(fresnel.load(files[who]), j)[..., :3])
    rows.append(row)

    # Crop every tile to the union of what any of them covers, with a margin.
    covered = np.zeros(rows[0][0].shape[:2], bool)
    for images in rows:
        for image in images:
            covered |= image.max(axis=2) > 8
    ys, xs = np.nonzero(covered)
    margin = 6
    y0, y1 = max(0, ys.min() - margin), min(covered.shape[0], ys.max() + margin + 1)
    x0, x1 = max(0, xs.min() - margin), min(covered.shape[1], xs.max() + margin + 1)
    rows = [[image[y0:y1, x0:x1] for image in images] for images in rows]
    label_h = 22
    h, w = rows[0][0].shape[:2]
    sheet = Image.new("RGB", (4 * w, 2 * (h + label_h)), (255, 255, 255))
    draw = ImageDraw.Draw(sheet)
    titles = [["OpenGL 1, one light", "--match opengl1", "--match albedo", "obj2gltf"],
              ["OpenGL 1 intent, studio", "--match opengl1", "--match albedo", "obj2gltf"]]
    for r, images in enumerate(rows):
        for c, image in enumerate(images):
            x, y = c * w, r * (h + label_h)
            draw.text((x + 6, y + 5), titles[r][c], fill=(0, 0, 0))
            sheet.paste(Image.fromarray(np.ascontiguousarray(image)), (x, y + label_h))
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    # A dithered 256-colour palette keeps the committed picture small for what it shows.
    sheet.quantize(colors=256, method=Image.Quantize.MEDIANCUT, dither=Image.Dither.FLOYDSTEINBERG).save(args.out + ".tmp.png", optimize=True)
    os.replace(args.out + ".tmp.png", args.out)
    print(args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
