#!/usr/bin/env python3
"""Shadows against path-traced truth (issue 31): the shadow scenes of tests/data/shadows (a ground
plane with two spheres, a box and a pole under one directional, point or spot light of
KHR_lights_punctual, and under the studio environment alone), 2 cameras each, rendered by
`fresnel render` with `--shadows off --ao off`, `--shadows soft` and soft with `--ao ssao`,
`--ao baked` or baked with `--env-light dominant` (the environment's key light drawn as a
shadowed directional light), and by `fresnel trace` (every bounce, and direct light only), each
compared with Blender Cycles (../shared/tools/cycles-ref --punctual, which gives glTF's lights zero
size; 256 spp, 16 bounces, black world for the lit scenes) by ../shared/tools/fidelity/compare.py
(PSNR and model-viewer's RMS score in dB over the non-black pixels). Blender turns glTF's spot cone
into its own blend (a wider, different falloff), so the spot scene is judged against `fresnel
trace` instead; every scene is also compared with `fresnel trace --max-bounces 1`, the light
transport the rasteriser computes (no light bounced off the ground). Cycles' images are made once
into --refs (about 25 s each on 2 cores) and reused. Standard library only; exits 0 with a note
when ../shared or blender is absent.
  usage: bench/shadow_fidelity.py FRESNEL_BINARY [--refs DIR] [--samples N] [--spp N] [--rays N] [--quick]
"""
import argparse
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cycles_refs import cycles_image, locations, metrics  # noqa: E402

SCENES = ["directional", "point", "spot", "environment"]
ENV_FILE = "studio_small_03_1k.hdr"  # occlusion_fidelity.py's "studio"
VIEWS = [(20, 30), (-35, 20)]
# key, --shadows, --ao, --env-light
VARIANTS = [("off", "off", "off", "off"), ("soft", "soft", "off", "off"), ("ssao", "soft", "ssao", "off"),
            ("baked", "soft", "baked", "off"), ("light", "soft", "baked", "dominant")]
NAMES = {"trace": "`fresnel trace`", "direct": "trace, direct light", "off": "shadows off, ao off",
         "soft": "`--shadows soft`", "ssao": "soft + `--ao ssao`", "baked": "soft + `--ao baked`",
         "light": "soft + baked + `--env-light dominant`"}
REFS = {"Cycles": "Cycles", "trace": "fresnel trace", "direct": "trace --max-bounces 1"}
SIZE = "512x512"
DISPLAY = ["--tonemap", "neutral", "--encoding", "gamma2.2", "--background", "0,0,0"]
SHADOW_TARGET, TRACE_TARGET = 8.0, 6.0


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("fresnel")
    ap.add_argument("--refs", default=None, help="folder of Cycles' images (default: BUILD/cycles-refs beside the binary)")
    ap.add_argument("--samples", type=int, default=256, help="Cycles' samples per pixel")
    ap.add_argument("--spp", type=int, default=256, help="fresnel trace's samples per pixel")
    ap.add_argument("--rays", type=int, default=128, help="--ao-rays")
    ap.add_argument("--quick", action="store_true", help="one view of each scene")
    a = ap.parse_args()
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    shared, cycles, compare, refs = locations(__file__, a.fresnel, a.refs)
    env_path = os.path.join(shared, "assets/env", ENV_FILE)
    if not os.path.exists(compare):
        print("shadow_fidelity: ../shared (tools) is absent; nothing to compare")
        return 0
    fresnel = os.path.abspath(a.fresnel)
    os.makedirs(refs, exist_ok=True)

    def two_metrics(test, ref):
        j = metrics(compare, test, ref)
        return float(j["psnr_db"]), float(j["mv_rms_db"])

    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for scene in SCENES:
            path = os.path.join(root, "tests/data/shadows", f"shadow-{scene}.gltf")
            lit = scene != "environment"
            if not os.path.exists(path) or (not lit and not os.path.exists(env_path)):
                continue
            for yaw, pitch in VIEWS[:1] if a.quick else VIEWS:
                name = f"shadow-{scene}_yaw{yaw}_pitch{pitch}"
                view = ["--size", SIZE, "--yaw", str(yaw), "--pitch", str(pitch)]
                truth = os.path.join(refs, f"{name}_{a.samples}spp.png")
                # The lit scenes under a black world (their light alone), the environment scene
                # under the studio; the film is transparent either way (black background).
                light = ["--punctual", "--env-color", "0,0,0"] if lit else ["--env", env_path]
                if not cycles_image(cycles, truth, ["--model", path, *view, *light, "--samples", str(a.samples),
                                                    "--bounces", "16"], f"{name} ({a.samples} spp)"):
                    continue
                fenv = ["--env", "none"] if lit else ["--env", env_path, "--no-scene-lights"]
                images = {}
                for key, bounces in (("trace", "16"), ("direct", "1")):
                    images[key] = os.path.join(tmp, f"{name}_{key}.png")
                    subprocess.run([fresnel, "trace", path, "-o", images[key], *view, *DISPLAY, *fenv, "--spp", str(a.spp),
                                    "--max-bounces", bounces], capture_output=True, text=True, check=True)
                for key, shadows, ao, light in VARIANTS:
                    images[key] = os.path.join(tmp, f"{name}_{key}.png")
                    subprocess.run([fresnel, "render", path, "-o", images[key], *view, *DISPLAY, *fenv, "--shadows", shadows,
                                    "--ao", ao, "--ao-rays", str(a.rays), "--env-light", light],
                                   capture_output=True, text=True, check=True)
                keys = [k for k, _, _, _ in VARIANTS]
                # Against Cycles; the spot light also against fresnel trace (Blender's cone differs);
                # every scene against fresnel trace's direct light (the rasteriser's light transport).
                row = {"view": f"shadow-{scene} {yaw}/{pitch}", "scene": scene,
                       "Cycles": {k: two_metrics(images[k], truth) for k in ["trace", "direct"] + keys}}
                if scene == "spot":
                    row["trace"] = {k: two_metrics(images[k], images["trace"]) for k in ["direct"] + keys}
                row["direct"] = {k: two_metrics(images[k], images["direct"]) for k in keys}
                rows.append(row)
                for ref in REFS:
                    if ref in row:
                        print(f"{row['view']:28s} vs {REFS[ref]:27s} " + "  ".join(
                            f"{k} {m[0]:6.2f}/{m[1]:6.2f}" for k, m in row[ref].items()), flush=True)
    if not rows:
        print("shadow_fidelity: no view had its scene and Cycles' image")
        return 0
    keys = [k for k, _, _, _ in VARIANTS]
    cols = ["trace", "direct"] + keys
    cell = lambda m: f"{m[0]:.2f} / {m[1]:.2f}" if m else "-"
    print()
    print("PSNR / model-viewer RMS score, dB (higher PSNR, lower model-viewer score: closer)")
    print()
    print("| view | reference | " + " | ".join(NAMES[k] for k in cols) + " |")
    print("|---" * (len(cols) + 2) + "|")
    for r in rows:
        for ref in REFS:
            if ref in r:
                print(f"| {r['view']} | {REFS[ref]} | " + " | ".join(cell(r[ref].get(k)) for k in cols) + " |")
    # The measure: each view against Cycles, except the spot light's, against fresnel trace.
    judged = lambda r, k: r["trace"][k] if r["scene"] == "spot" else r["Cycles"][k]
    groups = [(label, rs) for label, rs in (("lit", [r for r in rows if r["scene"] != "environment"]),
                                            ("environment", [r for r in rows if r["scene"] == "environment"])) if rs]
    mean = lambda rs, f: sum(f(r) for r in rs) / len(rs)
    for label, rs in groups:
        for ref, name in ((None, "Cycles; spot: fresnel trace" if label == "lit" else "Cycles"), ("direct", REFS["direct"])):
            f = (lambda k: lambda r: judged(r, k)) if ref is None else (lambda k: lambda r: r["direct"][k])
            print(f"| mean of {len(rs)} {label} | {name} | " + " | ".join(
                "-" if ref is not None and k in ("trace", "direct") or ref is None and label == "lit" and k == "trace"
                else f"{mean(rs, lambda r: f(k)(r)[0]):.2f} / {mean(rs, lambda r: f(k)(r)[1]):.2f}" for k in cols) + " |")
    print()
    cyc = [r for r in rows if r["scene"] != "spot"]  # views whose trace is itself judged against Cycles
    for key in keys[1:]:
        parts = []
        for label, rs in groups:
            gain = mean(rs, lambda r: judged(r, key)[0] - judged(r, "off")[0])
            least = min(judged(r, key)[0] - judged(r, "off")[0] for r in rs)
            target = f"; target >= +{SHADOW_TARGET:.0f} dB: {'met' if gain >= SHADOW_TARGET else 'not met'}" if label == "lit" else ""
            parts.append(f"{gain:+.2f} dB on {len(rs)} {label} view{'s' if len(rs) > 1 else ''} (least {least:+.2f}{target})")
        line = f"{NAMES[key]}: closer to Cycles (spot: to trace) than shadows off by " + ", ".join(parts)
        if cyc:
            dist = mean(cyc, lambda r: r["Cycles"]["trace"][0] - r["Cycles"][key][0])
            worst = max(r["Cycles"]["trace"][0] - r["Cycles"][key][0] for r in cyc)
            line += (f"; {dist:.2f} dB below fresnel trace against Cycles on {len(cyc)} views (worst {worst:.2f};"
                     f" target <= {TRACE_TARGET:.0f} dB: {'met' if dist <= TRACE_TARGET else 'not met'})")
        line += "; against trace's direct light " + ", ".join(
            f"{mean(rs, lambda r: r['direct'][key][0]):.2f} dB ({mean(rs, lambda r: r['direct'][key][0] - r['direct']['off'][0]):+.2f})"
            f" on {label}" for label, rs in groups)
        print(line)
    return 0


if __name__ == "__main__":
    sys.exit(main())
