#!/usr/bin/env bash
# How close `fresnel trace` and `fresnel render` come to Blender Cycles' ground truth: every
# view in ../shared/tools/cycles-ref/examples/results.jsonl (model, environment, camera,
# samples, bounces) is traced and rendered with the same settings and compared with Cycles'
# PNG by ../shared/tools/fidelity/compare.py (PSNR over the model's pixels).
#   usage: bench/trace_agreement.sh FRESNEL_BINARY [--spp N] [--threads N]
# cycles-ref's --env-rotation 90 is fresnel's 0 (both: +Z the panorama's centre column).
set -euo pipefail
fresnel=$(realpath "$1"); shift
spp="" threads=0
while [[ $# -gt 0 ]]; do
  case $1 in
    --spp) spp=$2; shift 2 ;;
    --threads) threads=$2; shift 2 ;;
    *) echo "trace_agreement: unknown argument $1" >&2; exit 2 ;;
  esac
done
root=$(cd "$(dirname "$0")/.." && pwd)
shared=${FRESNEL_SHARED_DIR:-$root/../shared}
examples=$shared/tools/cycles-ref/examples
if [[ ! -f $examples/results.jsonl ]]; then
  echo "trace_agreement: $examples is absent; nothing to compare"
  exit 0
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
/usr/bin/python3 - "$fresnel" "$shared" "$examples" "$tmp" "$spp" "$threads" <<'PY'
import json, os, subprocess, sys
fresnel, shared, examples, tmp, spp, threads = sys.argv[1:7]
compare = os.path.join(shared, "tools/fidelity/compare.py")
def psnr(a, b):
    out = subprocess.run(["/usr/bin/python3", compare, a, b], capture_output=True, text=True, check=True).stdout
    return float(out.split("psnr_db=")[1].split()[0])
rows = []
for line in open(os.path.join(examples, "results.jsonl")):
    r = json.loads(line)
    model = os.path.join(shared, "assets/models", r["model"].rsplit(".", 1)[0], r["model"])
    env = os.path.join(shared, "assets/env", r["env"])
    ref = os.path.join(examples, r["out"])
    if not (os.path.exists(model) and os.path.exists(env) and os.path.exists(ref)) or r.get("punctual") or r.get("background") != "black":
        continue
    cam = r["camera"]
    common = [model, "--size", f"{r['width']}x{r['height']}", "--yaw", str(cam["yaw_deg"]), "--pitch", str(cam["pitch_deg"]),
              "--fov", str(cam["yfov_deg"]), "--env", env, "--env-rotation", str(r["env_rotation_deg"] - 90.0),
              "--env-intensity", str(r["ibl_intensity"]), "--background", "0,0,0", "--tonemap", r["tonemap"],
              "--encoding", "gamma2.2", "--no-scene-lights"]
    t_out, r_out = os.path.join(tmp, "trace_" + r["out"]), os.path.join(tmp, "render_" + r["out"])
    samples = spp or str(r["samples"])
    j = json.loads(subprocess.run([fresnel, "trace", *common, "-o", t_out, "--spp", samples, "--max-bounces", str(r["bounces"] + 1),
                                   "--threads", threads, "--json"], capture_output=True, text=True, check=True).stdout)
    subprocess.run([fresnel, "render", *common, "-o", r_out], capture_output=True, check=True)
    rows.append((r["out"], psnr(t_out, ref), psnr(r_out, ref), j["trace_ms"] / 1000.0, j["spp"]))
    print(f"{r['out']:42s} trace {rows[-1][1]:6.2f} dB  render {rows[-1][2]:6.2f} dB  gain {rows[-1][1] - rows[-1][2]:+6.2f} dB"
          f"  ({j['spp']} spp, {rows[-1][3]:.1f} s)", flush=True)
if rows:
    gain = sum(t - r for _, t, r, _, _ in rows) / len(rows)
    print(f"mean: trace {sum(t for _, t, _, _, _ in rows) / len(rows):.2f} dB, render {sum(r for _, _, r, _, _ in rows) / len(rows):.2f} dB,"
          f" trace closer by {gain:+.2f} dB; every view closer: {all(t > r for _, t, r, _, _ in rows)}")
PY
