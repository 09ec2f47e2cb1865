#!/usr/bin/env bash
# Paths per second of `fresnel trace` against Blender Cycles on the same scene, in one run
# (issue 11, item 6): DamagedHelmet, studio_small_03, 512^2, 256 spp, 16 bounces, 2 threads,
# black background, IBL only. Cycles runs through ../shared/tools/cycles-ref/render when
# `blender` is on PATH; otherwise the bench says it skipped it.
#   usage: bench/trace_bench.sh FRESNEL_BINARY [--spp N] [--size WxH] [--threads N] [--bounces N]
# Cycles' "N bounces" allow N bounces after the first hit (0 = direct light only); fresnel's
# --max-bounces counts every scattering event (1 = direct light only), so fresnel runs with
# N + 1 to do the same work. Times compared: fresnel's trace_ms + build_ms (BVH and textures)
# against Cycles' render_s (its render call: BVH, textures, sampling); scene loading apart.
set -euo pipefail
fresnel=$(realpath "$1"); shift
spp=256 size=512x512 threads=2 bounces=16
while [[ $# -gt 0 ]]; do
  case $1 in
    --spp) spp=$2; shift 2 ;;
    --size) size=$2; shift 2 ;;
    --threads) threads=$2; shift 2 ;;
    --bounces) bounces=$2; shift 2 ;;
    *) echo "trace_bench: unknown argument $1" >&2; exit 2 ;;
  esac
done
root=$(cd "$(dirname "$0")/.." && pwd)
shared=${FRESNEL_SHARED_DIR:-$root/../shared}
helmet=$shared/assets/models/DamagedHelmet/DamagedHelmet.glb
env=$shared/assets/env/studio_small_03_1k.hdr
if [[ ! -f $helmet || ! -f $env ]]; then
  echo "trace_bench: $shared/assets is absent; nothing to measure"
  exit 0
fi
py=/usr/bin/python3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

echo "machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
echo "scene: DamagedHelmet $size, $spp spp, $bounces bounces (fresnel --max-bounces $((bounces + 1))), $threads threads, studio_small_03"
"$fresnel" trace "$helmet" -o "$tmp/fresnel.png" --size "$size" --spp "$spp" --max-bounces $((bounces + 1)) \
  --threads "$threads" --env "$env" --background 0,0,0 --encoding gamma2.2 --no-scene-lights --json > "$tmp/fresnel.json"
have_cycles=0
if command -v blender > /dev/null; then
  if "$shared/tools/cycles-ref/render" --model "$helmet" --env "$env" --out "$tmp/cycles.png" --size "$size" \
       --samples "$spp" --bounces "$bounces" --threads "$threads" > "$tmp/cycles.json" 2> "$tmp/cycles.err"; then
    have_cycles=1
  else
    echo "trace_bench: cycles-ref/render failed:"; tail -5 "$tmp/cycles.err"
  fi
else
  echo "trace_bench: blender is not on PATH; Cycles skipped (apt-get install blender)"
fi
psnr=""
if [[ $have_cycles == 1 ]]; then
  psnr=$("$py" "$shared/tools/fidelity/compare.py" "$tmp/fresnel.png" "$tmp/cycles.png" | sed -n 's/.*psnr_db=\([^ ]*\).*/\1/p')
fi
"$py" - "$tmp/fresnel.json" "$tmp/cycles.json" "$have_cycles" "$psnr" <<'PY'
import json, sys
f = json.load(open(sys.argv[1]))
paths = f["camera_paths"]
t = (f["trace_ms"] + f["build_ms"]) / 1000.0
ours = paths / t / 1e6
print(f"fresnel trace: {f['trace_ms'] / 1000:.2f} s tracing + {f['build_ms'] / 1000:.2f} s BVH/textures, "
      f"{ours:.2f} M camera paths/s ({paths / f['trace_ms'] * 1e-3:.2f} tracing alone), {f['mrays_per_s']:.2f} M rays/s")
if sys.argv[3] == "1":
    c = json.load(open(sys.argv[2]))
    cpaths = c["width"] * c["height"] * c["samples"]
    theirs = cpaths / c["render_s"] / 1e6
    print(f"Cycles {c['blender_version']}: {c['render_s']:.2f} s render, {theirs:.2f} M camera paths/s")
    print(f"ratio fresnel / Cycles: {ours / theirs:.2f}x   (PSNR fresnel vs Cycles: {sys.argv[4]} dB)")
PY
