#!/usr/bin/env python3
"""What each real-time approximation costs: the fidelity report (issue 11, item 5).

For every case (shared model x environment) it renders, with one camera, size and tone mapping:
  raster  `fresnel render`                                  (split sum, prefiltered lobes, no shadows)
  1b      `fresnel trace --bounces 1 --no-env-visibility`  (the rasteriser's light transport, integrated exactly)
  full    `fresnel trace`                                   (ground truth: 16 bounces, shadowed environment)
  full'   `fresnel trace` with another seed                (the trace's own noise floor)
and measures with `fresnel compare --mask auto --json` (PSNR and mean FLIP over the model's pixels):
  raster vs full   what the real-time path costs in all
  raster vs 1b     the split sum and prefiltering alone
  1b vs full       visibility and multiple bounces
  full' vs full    noise
Where ../shared/tools/cycles-ref/examples exists it also compares `fresnel render` and `fresnel trace`
with Blender Cycles' images (same views as bench/trace_agreement.sh).

Writes docs/fidelity/report.md, one thumbnail per case (raster | trace | FLIP of raster vs trace,
128 px each) and, with --readme, the summary between the fidelity-report markers of README.md.
Standard library only.
  usage: bench/fidelity_report.py FRESNEL_BINARY [--size N] [--spp N] [--cycles-spp N] [--threads N]
                                  [--out DIR] [--readme docs/fidelity.md] [--quick]
"""
import argparse
import shutil
import datetime
import json
import os
import struct
import subprocess
import sys
import tempfile
import time
import zlib

MODELS = [  # (name, file under assets/models, what it exercises)
    ("DamagedHelmet", "DamagedHelmet/DamagedHelmet.glb", "all core PBR textures"),
    ("NormalTangentTest", "NormalTangentTest/NormalTangentTest.glb", "normal maps, glossy metal bowls"),
    ("Suzanne", "Suzanne/Suzanne.gltf", "textured metallic-roughness, concave"),
    ("ClearCoatTest", "ClearCoatTest/ClearCoatTest.gltf", "KHR_materials_clearcoat"),
]
ENVS = [  # (short name, file under assets/env)
    ("studio", "studio_small_03_1k.hdr"),
    ("potsdamer", "potsdamer_platz_1k.hdr"),
]
THUMB = 128


# ---- PNG (8-bit, non-interlaced: what fresnel writes) -------------------------------------------
def read_png(path):
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError(f"{path}: not a PNG")
    pos, idat, w = 8, [], 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        pos += 12 + n
        if kind == b"IHDR":
            w, h, depth, ctype, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if depth != 8 or interlace or ctype not in (0, 2, 4, 6):
                raise ValueError(f"{path}: only 8-bit non-interlaced grey/RGB(A) PNGs are read")
            ch = {0: 1, 2: 3, 4: 2, 6: 4}[ctype]
        elif kind == b"IDAT":
            idat.append(body)
        elif kind == b"IEND":
            break
    raw, stride = zlib.decompress(b"".join(idat)), w * ch
    rows, prev = [], bytearray(stride)
    for y in range(h):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - ch] if i >= ch else 0
            b, c = prev[i], prev[i - ch] if i >= ch else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    # to RGB rows
    rgb = []
    for line in rows:
        out = bytearray(w * 3)
        for x in range(w):
            px = line[x * ch:(x + 1) * ch]
            out[x * 3:x * 3 + 3] = bytes((px[0],) * 3) if ch <= 2 else px[:3]
        rgb.append(out)
    return w, h, rgb


def write_png(path, w, h, rows):
    raw = b"".join(b"\x00" + bytes(r) for r in rows)
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def downscale(img, cw, ch, size):
    """Box-filter the top-left cw x ch of img to size x size (cw, ch multiples of size)."""
    _, _, rows = img
    fx, fy = cw // size, ch // size
    out = []
    for y in range(size):
        line = bytearray(size * 3)
        for x in range(size):
            for c in range(3):
                s = 0
                for yy in range(y * fy, (y + 1) * fy):
                    r = rows[yy]
                    for xx in range(x * fx, (x + 1) * fx):
                        s += r[xx * 3 + c]
                line[x * 3 + c] = (s + fx * fy // 2) // (fx * fy)
        out.append(line)
    return out


def thumbnail(path, size, images):
    """images: [(png path, crop width, crop height)] side by side, 2 px dark gap."""
    parts = [downscale(read_png(p), cw, ch, THUMB) for p, cw, ch in images]
    gap = 2
    w = THUMB * len(parts) + gap * (len(parts) - 1)
    rows = []
    for y in range(THUMB):
        line = bytearray()
        for i, p in enumerate(parts):
            if i:
                line += bytes((40, 40, 40) * gap)
            line += p[y]
        rows.append(line)
    write_png(path, w, THUMB, rows)


# ---- fresnel -------------------------------------------------------------------------------------
def run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)}\n{r.stdout}{r.stderr}")
    return r.stdout


def compare(fresnel, a, b, heatmap=None):
    cmd = [fresnel, "compare", a, b, "--mask", "auto", "--json"] + (["--heatmap", heatmap] if heatmap else [])
    j = json.loads(run(cmd))
    return j["psnr_db"], j["flip"]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("fresnel")
    ap.add_argument("--size", type=int, default=256)
    ap.add_argument("--spp", type=int, default=128)
    ap.add_argument("--cycles-spp", type=int, default=128, help="trace samples for the vs-Cycles views (512^2); 0 skips them")
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--out", default=None, help="report folder (default: docs/fidelity)")
    ap.add_argument("--readme", default=None, help="README.md whose fidelity-report section to update")
    ap.add_argument("--quick", action="store_true", help="one model, one environment, 16 spp (a smoke test)")
    a = ap.parse_args()
    if a.size % THUMB:
        sys.exit(f"fidelity_report: --size must be a multiple of {THUMB}")
    fresnel = os.path.realpath(a.fresnel)
    root = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))
    shared = os.environ.get("FRESNEL_SHARED_DIR", os.path.join(root, "..", "shared"))
    out = a.out or os.path.join(root, "docs", "fidelity")
    models, envs, spp = (MODELS[:1], ENVS[:1], 16) if a.quick else (MODELS, ENVS, a.spp)
    if not os.path.isdir(os.path.join(shared, "assets")):
        print(f"fidelity_report: {shared}/assets is absent; nothing to report")
        return 0
    os.makedirs(out, exist_ok=True)
    t_start = time.time()
    tmp = tempfile.mkdtemp(prefix="fidelity-")
    size = f"{a.size}x{a.size}"
    cases = []
    for mname, mfile, what in models:
        model = os.path.join(shared, "assets", "models", mfile)
        for ename, efile in envs:
            env = os.path.join(shared, "assets", "env", efile)
            if not (os.path.exists(model) and os.path.exists(env)):
                print(f"skip {mname} x {ename}: asset absent")
                continue
            name = f"{mname}_{ename}"
            common = [model, "--size", size, "--yaw", "30", "--pitch", "15", "--env", env, "--background", "0,0,0",
                      "--tonemap", "neutral", "--no-scene-lights"]
            p = {k: os.path.join(tmp, f"{name}_{k}.png") for k in ("raster", "b1", "full", "full2", "heat")}
            t0 = time.time()
            run([fresnel, "render", *common, "-o", p["raster"]])
            t_raster = time.time() - t0
            trace = [fresnel, "trace", *common, "--spp", str(spp), "--threads", str(a.threads), "--json"]
            t_b1 = json.loads(run(trace + ["-o", p["b1"], "--bounces", "1", "--no-env-visibility"]))["trace_ms"] / 1000
            t_full = json.loads(run(trace + ["-o", p["full"]]))["trace_ms"] / 1000
            run(trace + ["-o", p["full2"], "--seed", "7"])
            c = {
                "raster_full": compare(fresnel, p["raster"], p["full"], p["heat"]),
                "raster_b1": compare(fresnel, p["raster"], p["b1"]),
                "b1_full": compare(fresnel, p["b1"], p["full"]),
                "noise": compare(fresnel, p["full2"], p["full"]),
            }
            thumb = f"{name}.png"
            thumbnail(os.path.join(out, thumb), THUMB, [(p["raster"], a.size, a.size), (p["full"], a.size, a.size),
                                                         (p["heat"], a.size, a.size)])
            cases.append(dict(model=mname, env=ename, envfile=efile, what=what, thumb=thumb, t_raster=t_raster,
                              t_b1=t_b1, t_full=t_full, **c))
            print(f"{name:32s} raster-full {c['raster_full'][0]:6.2f} dB {c['raster_full'][1]:.3f}  raster-1b "
                  f"{c['raster_b1'][0]:6.2f} dB {c['raster_b1'][1]:.3f}  1b-full {c['b1_full'][0]:6.2f} dB "
                  f"{c['b1_full'][1]:.3f}  noise {c['noise'][0]:6.2f} dB {c['noise'][1]:.3f}  "
                  f"(trace {t_full:.1f} s)", flush=True)

    shadows = shadow_cases(fresnel, root, shared, tmp, a, spp)

    cycles = []
    examples = os.path.join(shared, "tools", "cycles-ref", "examples")
    jsonl = os.path.join(examples, "results.jsonl")
    if a.cycles_spp > 0 and not a.quick and os.path.exists(jsonl):
        for line in open(jsonl):
            r = json.loads(line)
            model = os.path.join(shared, "assets/models", r["model"].rsplit(".", 1)[0], r["model"])
            env = os.path.join(shared, "assets/env", r["env"])
            ref = os.path.join(examples, r["out"])
            if not (os.path.exists(model) and os.path.exists(env) and os.path.exists(ref)) \
                    or r.get("punctual") or r.get("background") != "black":
                continue
            cam = r["camera"]  # cycles-ref's --env-rotation 90 is fresnel's 0
            common = [model, "--size", f"{r['width']}x{r['height']}", "--yaw", str(cam["yaw_deg"]),
                      "--pitch", str(cam["pitch_deg"]), "--fov", str(cam["yfov_deg"]), "--env", env,
                      "--env-rotation", str(r["env_rotation_deg"] - 90.0), "--env-intensity", str(r["ibl_intensity"]),
                      "--background", "0,0,0", "--tonemap", r["tonemap"], "--encoding", "gamma2.2", "--no-scene-lights"]
            t_out, r_out = os.path.join(tmp, "cy_trace_" + r["out"]), os.path.join(tmp, "cy_render_" + r["out"])
            run([fresnel, "trace", *common, "-o", t_out, "--spp", str(a.cycles_spp), "--max-bounces",
                 str(r["bounces"] + 1), "--threads", str(a.threads)])
            run([fresnel, "render", *common, "-o", r_out])
            row = dict(view=f"{r['model'].rsplit('.', 1)[0]}, yaw {cam['yaw_deg']:g} / pitch {cam['pitch_deg']:g}",
                       env=r["env"], samples=r["samples"], bounces=r["bounces"], size=f"{r['width']}²",
                       render=compare(fresnel, r_out, ref), trace=compare(fresnel, t_out, ref))
            cycles.append(row)
            print(f"vs Cycles {row['view']:40s} render {row['render'][0]:6.2f} dB {row['render'][1]:.3f}  "
                  f"trace {row['trace'][0]:6.2f} dB {row['trace'][1]:.3f}", flush=True)

    elapsed = time.time() - t_start
    with open(os.path.join(out, "results.json"), "w") as f:
        json.dump(dict(size=a.size, spp=spp, cycles_spp=a.cycles_spp, minutes=round(elapsed / 60, 2),
                       cases=cases, cycles=cycles, shadows=shadows), f, indent=1)
    write_report(out, cases, cycles, a, spp, elapsed, shadows)
    if a.readme:
        update_readme(a.readme, cases, spp, a.size, out)
    for f in os.listdir(tmp):
        os.remove(os.path.join(tmp, f))
    os.rmdir(tmp)
    print(f"wrote {os.path.join(out, 'report.md')} in {elapsed / 60:.1f} min")
    return 0


def pf(v):
    return f"{v[0]:.2f} dB / {v[1]:.3f}"


def mean(cases, key, i):
    return sum(c[key][i] for c in cases) / len(cases)


SHADOW_SCENES = ("directional", "point", "spot")


def shadow_cases(fresnel, root, shared, tmp, a, spp):
    """The shadow scenes (tests/data/shadows, scripts/make-shadow-scenes.py): `fresnel render` with
    --shadows off and soft against `fresnel trace` (all bounces: the truth) and `trace --max-bounces 1`
    (direct light: what the rasteriser computes for punctual lights), and against Blender Cycles
    (../shared/tools/cycles-ref --punctual) where `blender` is installed (spot lights: Blender's cone
    blend differs from glTF's, so judge them against the tracer)."""
    scenes = os.path.join(root, "tests", "data", "shadows")
    cycles_ref = os.path.join(shared, "tools", "cycles-ref", "render")
    have_cycles = shutil.which("blender") is not None and os.path.exists(cycles_ref) and not a.quick
    rows = []
    for light in SHADOW_SCENES[:1] if a.quick else SHADOW_SCENES:
        scene = os.path.join(scenes, f"shadow-{light}.gltf")
        common = [scene, "--size", f"{a.size}x{a.size}", "--yaw", "20", "--pitch", "30", "--env", "none",
                  "--background", "0,0,0", "--tonemap", "neutral"]
        p = {k: os.path.join(tmp, f"shadow_{light}_{k}.png") for k in ("off", "soft", "b1", "full", "cycles")}
        run([fresnel, "render", *common, "--shadows", "off", "-o", p["off"]])
        t0 = time.time()
        run([fresnel, "render", *common, "-o", p["soft"]])
        t_soft = time.time() - t0
        trace = [fresnel, "trace", *common, "--spp", str(spp), "--threads", str(a.threads)]
        run(trace + ["-o", p["b1"], "--max-bounces", "1"])
        run(trace + ["-o", p["full"]])
        row = dict(light=light, t_render=t_soft,
                   off_full=compare(fresnel, p["off"], p["full"]), soft_full=compare(fresnel, p["soft"], p["full"]),
                   off_b1=compare(fresnel, p["off"], p["b1"]), soft_b1=compare(fresnel, p["soft"], p["b1"]))
        if have_cycles:
            try:
                run([cycles_ref, "--model", scene, "--out", p["cycles"], "--punctual", "--env-color", "0,0,0", "--size",
                     f"{a.size}x{a.size}", "--yaw", "20", "--pitch", "30", "--samples", str(spp)])
                row.update(off_cycles=compare(fresnel, p["off"], p["cycles"]),
                           soft_cycles=compare(fresnel, p["soft"], p["cycles"]),
                           trace_cycles=compare(fresnel, p["full"], p["cycles"]))
            except RuntimeError as e:
                print(f"cycles-ref failed on {scene}: {e}", flush=True)
        rows.append(row)
        print(f"shadows {light:12s} off-trace {row['off_full'][0]:6.2f} dB  soft-trace {row['soft_full'][0]:6.2f} dB  "
              f"off-direct {row['off_b1'][0]:6.2f} dB  soft-direct {row['soft_b1'][0]:6.2f} dB", flush=True)
    return rows


def write_report(out, cases, cycles, a, spp, elapsed, shadows=()):
    today = datetime.date.today().isoformat()
    L = ["# Fidelity report: what each real-time approximation costs", "",
         f"Generated by `bench/fidelity_report.py` (`make fidelity-report`) on {today} in {elapsed / 60:.1f} min "
         "on a shared 2-core machine. Do not edit by hand.", "",
         f"Every case is rendered at {a.size}x{a.size}, yaw 30 / pitch 15 (the README's camera convention), "
         "image-based light only (`--no-scene-lights`), black background, neutral tone mapping, sRGB, three ways:", "",
         "- **raster**: `fresnel render` (split-sum specular, prefiltered radiance and a 16² irradiance cube, "
         "the occlusion texture, no environment shadows, one bounce);",
         f"- **1-bounce**: `fresnel trace --bounces 1 --no-env-visibility`, {spp} spp: the rasteriser's light "
         "transport (direct environment light, never shadowed) integrated exactly;",
         f"- **trace**: `fresnel trace`, {spp} spp, up to 16 bounces with the environment shadowed: the ground truth.", "",
         "Metrics: `fresnel compare --mask auto` (over the pixels where either image shows the model): PSNR in dB "
         "(higher is closer) / mean LDR-FLIP (0 = identical, lower is closer).", "",
         "- **raster vs trace**: everything the real-time path costs;",
         "- **raster vs 1-bounce**: the split sum, prefiltering and the irradiance cube (same transport), plus the "
         "occlusion texture, which the rasteriser multiplies in and the tracer ignores (DamagedHelmet and "
         "NormalTangentTest have one; Suzanne and ClearCoatTest do not);",
         "- **1-bounce vs trace**: what environment visibility (shadows, occlusion) and multiple bounces add;",
         f"- **noise floor**: `fresnel trace` with seed 7 vs seed 0 at {spp} spp. No comparison with a traced image "
         "can read much above this PSNR (or below this FLIP); figures near it are limited by the trace's noise, "
         "not by the approximation.", "",
         "| model | environment | raster vs trace | raster vs 1-bounce | 1-bounce vs trace | noise floor | trace time |",
         "|---|---|---|---|---|---|---|"]
    for c in cases:
        L.append(f"| {c['model']} | {c['env']} | {pf(c['raster_full'])} | {pf(c['raster_b1'])} | {pf(c['b1_full'])} "
                 f"| {pf(c['noise'])} | {c['t_full']:.1f} s |")
    if cases:
        L.append(f"| **mean** | | {mean(cases, 'raster_full', 0):.2f} dB / {mean(cases, 'raster_full', 1):.3f} "
                 f"| {mean(cases, 'raster_b1', 0):.2f} dB / {mean(cases, 'raster_b1', 1):.3f} "
                 f"| {mean(cases, 'b1_full', 0):.2f} dB / {mean(cases, 'b1_full', 1):.3f} "
                 f"| {mean(cases, 'noise', 0):.2f} dB / {mean(cases, 'noise', 1):.3f} | |")
    L += ["", "Environments: " + ", ".join(f"{e} = `{f}`" for e, f in ENVS) + " (`../shared/assets/env`). Models: "
          + "; ".join(f"{m} ({w})" for m, _, w in MODELS) + ".", ""]
    if cycles:
        L += ["## vs Blender Cycles", "",
              f"The views of `../shared/tools/cycles-ref/examples` (Cycles 3.4, {cycles[0]['samples']} spp, "
              f"{cycles[0]['bounces']} bounces, {cycles[0]['size']}, their camera and environment settings, as "
              f"`bench/trace_agreement.sh`); `fresnel trace` at {a.cycles_spp} spp. PSNR / mean FLIP against Cycles:", "",
              "| view | environment | `fresnel render` vs Cycles | `fresnel trace` vs Cycles |", "|---|---|---|---|"]
        for r in cycles:
            L.append(f"| {r['view']} | `{r['env']}` | {pf(r['render'])} | {pf(r['trace'])} |")
        L.append(f"| **mean** | | {mean(cycles, 'render', 0):.2f} dB / {mean(cycles, 'render', 1):.3f} "
                 f"| {mean(cycles, 'trace', 0):.2f} dB / {mean(cycles, 'trace', 1):.3f} |")
        L += ["", "Cycles shades the glTF importer's Principled BSDF, fresnel the glTF BRDF; both traces carry noise.", ""]
    if shadows:
        with_cycles = any("soft_cycles" in r for r in shadows)
        L += ["## Shadows of punctual lights", "",
              "The scenes of `scripts/make-shadow-scenes.py` (`tests/data/shadows`: a ground plane, two spheres, a box "
              "and a thin pole under one light), yaw 20 / pitch 30, no environment. `fresnel render` with "
              f"`--shadows off` and with its default soft shadows against `fresnel trace` ({spp} spp, all bounces) and "
              "against `trace --max-bounces 1` (direct light alone: what the rasteriser computes for punctual lights)"
              + (", and against Blender Cycles (`cycles-ref --punctual`; spot lights: Blender's cone blend differs)"
                 if with_cycles else "") + ". PSNR / mean FLIP:", "",
              "| light | off vs trace | soft vs trace | off vs direct | soft vs direct |"
              + (" off vs Cycles | soft vs Cycles | trace vs Cycles |" if with_cycles else ""),
              "|---|---|---|---|---|" + ("---|---|---|" if with_cycles else "")]
        for r in shadows:
            line = (f"| {r['light']} | {pf(r['off_full'])} | {pf(r['soft_full'])} | {pf(r['off_b1'])} "
                    f"| {pf(r['soft_b1'])} |")
            if with_cycles:
                line += "".join(f" {pf(r[k])} |" if k in r else " – |"
                                for k in ("off_cycles", "soft_cycles", "trace_cycles"))
            L.append(line)
        L += ["", "What remains between soft shadows and the full trace is light the ground reflects into the "
              "shadows (the rasteriser has no interreflection of punctual light).", ""]
    L += ["## Thumbnails", "", "Each: raster | trace | FLIP of raster vs trace (magma: black = no visible difference, "
          f"yellow-white = large), {THUMB}² each, downscaled from {a.size}².", ""]
    for c in cases:
        L += [f"**{c['model']} × {c['env']}**: raster vs trace {pf(c['raster_full'])}", "",
              f"![{c['model']} {c['env']}: raster, trace, FLIP]({c['thumb']})", ""]
    with open(os.path.join(out, "report.md"), "w") as f:
        f.write("\n".join(L))


def update_readme(path, cases, spp, size, out):
    # The thumbnail's link, relative to the page written (docs/fidelity.md: fidelity/...).
    img = os.path.relpath(os.path.join(out, cases[0]['thumb']), os.path.dirname(os.path.abspath(path)))
    begin, end = "<!-- fidelity-report:begin -->", "<!-- fidelity-report:end -->"
    text = open(path).read()
    if begin not in text or end not in text or not cases:
        print(f"fidelity_report: {path} has no {begin} ... {end} section (or no cases); not updated")
        return
    L = [begin, f"| model × environment ({size}², IBL only, trace {spp} spp) | raster vs trace | raster vs 1-bounce "
         "| 1-bounce vs trace | trace noise floor |", "|---|---|---|---|---|"]
    for c in cases:
        L.append(f"| {c['model']} × {c['env']} | {pf(c['raster_full'])} | {pf(c['raster_b1'])} | {pf(c['b1_full'])} "
                 f"| {pf(c['noise'])} |")
    L += ["", f"![{cases[0]['model']} {cases[0]['env']}: raster, trace, FLIP]({img})", end]
    head, rest = text.split(begin, 1)
    with open(path, "w") as f:
        f.write(head + "\n".join(L) + rest.split(end, 1)[1])


if __name__ == "__main__":
    sys.exit(main())
