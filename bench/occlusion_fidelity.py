#!/usr/bin/env python3
"""Occlusion against path-traced truth (issue 31): image-based light of 16 views (4 shared models x
2 environments x 2 cameras) rendered by `fresnel render` with `--ao off`, `--ao baked`, `--ao ssao`,
`--env-light dominant` (the environment's dominant light drawn as a shadowed directional light) and
both, and by
the Khronos glTF Sample Renderer (../shared/refs/khronos), each compared with Blender Cycles
(../shared/tools/cycles-ref, 256 spp, 16 bounces) by ../shared/tools/fidelity/compare.py (PSNR over
the model's pixels). Cycles' images are made once into --refs (about 25 s each on 2 cores) and
reused. Standard library only; exits 0 with a note when ../shared is absent.
  usage: bench/occlusion_fidelity.py FRESNEL_BINARY [--refs DIR] [--samples N] [--rays N] [--quick]
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cycles_refs import cycles_image, locations, metrics  # noqa: E402

MODELS = ["DamagedHelmet", "Suzanne", "2CylinderEngine", "Duck"]
ENVS = {"studio": "studio_small_03_1k.hdr", "potsdamer": "potsdamer_platz_1k.hdr"}
VIEWS = {"front": (0, 0), "q": (45, 20)}
VARIANTS = [("off", "off", "off"), ("baked", "baked", "off"), ("ssao", "ssao", "off"), ("light", "off", "dominant"),
            ("both", "baked", "dominant"), ("ssao+light", "ssao", "dominant")]
NAMES = {"off": "fresnel, defaults", "baked": "`--ao baked`", "ssao": "`--ao ssao`", "light": "`--env-light dominant`",
         "both": "baked + dominant", "ssao+light": "ssao + dominant"}


def model_file(shared, name):
    folder = os.path.join(shared, "assets/models", name)
    for ext in (".glb", ".gltf"):
        if os.path.exists(os.path.join(folder, name + ext)):
            return os.path.join(folder, name + ext)
    return None


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("fresnel")
    ap.add_argument("--refs", default=None, help="folder of Cycles' images (default: BUILD/cycles-refs beside the binary)")
    ap.add_argument("--samples", type=int, default=256)
    ap.add_argument("--rays", type=int, default=128, help="--ao-rays")
    ap.add_argument("--quick", action="store_true", help="the front views of the studio only")
    a = ap.parse_args()
    shared, cycles, compare, refs = locations(__file__, a.fresnel, a.refs)
    if not (os.path.exists(compare) and os.path.isdir(os.path.join(shared, "refs/khronos"))):
        print("occlusion_fidelity: ../shared (tools, refs) is absent; nothing to compare")
        return 0
    fresnel = os.path.abspath(a.fresnel)
    os.makedirs(refs, exist_ok=True)

    def psnr(test, ref):
        return float(metrics(compare, test, ref)["psnr_db"])

    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for env, env_file in ENVS.items():
            for model in MODELS:
                for view, (yaw, pitch) in VIEWS.items():
                    if a.quick and (env != "studio" or view != "front"):
                        continue
                    path = model_file(shared, model)
                    khronos = os.path.join(shared, "refs/khronos", env, f"{model}_{view}.png")
                    env_path = os.path.join(shared, "assets/env", env_file)
                    if not (path and os.path.exists(khronos) and os.path.exists(env_path)):
                        continue
                    truth = os.path.join(refs, f"{model}_{env}_{view}_{a.samples}spp.png")
                    if not cycles_image(cycles, truth, ["--model", path, "--env", env_path, "--size", "512x512", "--yaw",
                                                        str(yaw), "--pitch", str(pitch), "--samples", str(a.samples)],
                                        f"{model} {env} {view} ({a.samples} spp)"):
                        continue
                    row = {"view": f"{model} {env} {view}", "khronos": psnr(khronos, truth)}
                    for key, ao, light in VARIANTS:
                        out = os.path.join(tmp, f"{model}_{env}_{view}_{key}.png")
                        j = json.loads(subprocess.run(
                            [fresnel, "render", path, "-o", out, "--size", "512x512", "--yaw", str(yaw), "--pitch", str(pitch),
                             "--tonemap", "neutral", "--encoding", "gamma2.2", "--background", "0,0,0", "--env", env_path,
                             "--no-scene-lights", "--ao", ao, "--ao-rays", str(a.rays), "--env-light", light, "--json"],
                            capture_output=True, text=True, check=True).stdout)
                        row[key] = psnr(out, truth)
                        if key == "baked":
                            row["ao_ms"] = j.get("ao_ms", 0.0)
                            row["vertices"] = j.get("ao_vertices", 0)
                    rows.append(row)
                    print(f"{row['view']:34s} Khronos {row['khronos']:6.2f} dB  " +
                          "  ".join(f"{k} {row[k]:6.2f}" for k, _, _ in VARIANTS) +
                          f" dB  (bake {row['ao_ms']:.0f} ms, {row['vertices']} vertices)", flush=True)
    if not rows:
        print("occlusion_fidelity: no view had its model, environment and references")
        return 0
    n = len(rows)
    mean = lambda k: sum(r[k] for r in rows) / n
    keys = [k for k, _, _ in VARIANTS]
    print()
    print("| view | Khronos renderer | " + " | ".join(NAMES[k] for k in keys) + " |")
    print("|---" * (len(keys) + 2) + "|")
    for r in rows:
        print(f"| {r['view']} | {r['khronos']:.2f} dB | " + " | ".join(f"{r[k]:.2f} dB" for k in keys) + " |")
    print(f"| mean of {n} | {mean('khronos'):.2f} dB | " + " | ".join(f"{mean(k):.2f} dB" for k in keys) + " |")
    print()
    for key in keys[1:]:
        better = sum(1 for r in rows if r[key] > r["khronos"])
        print(f"{NAMES[key]}: closer to Cycles than the Khronos renderer on {better} of {n} views, by "
              f"{mean(key) - mean('khronos'):+.2f} dB on average (target: every view, >= +3 dB)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
