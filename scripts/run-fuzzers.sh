#!/usr/bin/env bash
# Runs every libFuzzer target for SECONDS each, seeded from the regression corpus and,
# when present, ../shared (assets and the broken-glTF corpus). New crashes land in
# fuzz/findings/<target>/ with the run's whole log (log-<time>.txt: a finding's report, stack
# and the input's path); copy minimised ones into fuzz/regressions/<target>/.
# usage: scripts/run-fuzzers.sh BUILD_DIR SECONDS [TARGET...]
set -euo pipefail
build=$1; seconds=$2; shift 2
root=$(cd "$(dirname "$0")/.." && pwd)
shared="$root/../shared"
targets=("$@"); [[ ${#targets[@]} -eq 0 ]] && targets=(gltf obj image hdr exr scene_file meshopt draco webp ktx2 zstd)
for t in "${targets[@]}"; do
  work="$root/fuzz/work/$t"; findings="$root/fuzz/findings/$t"
  mkdir -p "$work" "$findings"
  seeds=("$root/fuzz/regressions/$t")
  if [[ -d $shared ]]; then
    case $t in
      gltf) seeds+=("$shared/corpus" "$shared/assets/models");;
      obj) mkdir -p "$work.seeds"; find "$shared/assets/obj" \( -name '*.obj' -o -name '*.mtl' \) -exec cp -n {} "$work.seeds/" \; ; seeds+=("$work.seeds");;
      image) mkdir -p "$work.seeds"; find "$shared/assets/models" -name '*.png' -size -200k -exec cp -n {} "$work.seeds/" \; ; find "$shared/assets/models" -name '*.jpg' -size -200k -exec cp -n {} "$work.seeds/" \; ; seeds+=("$work.seeds");;
      hdr) mkdir -p "$work.seeds"; for f in "$shared"/assets/env/*.hdr; do dd if="$f" of="$work.seeds/$(basename "$f")" bs=1 skip=2 count=200000 status=none || true; done; seeds+=("$work.seeds");;
      ktx2) seeds+=("$shared/assets/ktx2");;
      exr) mkdir -p "$work.seeds"; for f in "$shared"/assets/env/*.exr; do tail -c +5 "$f" > "$work.seeds/$(basename "$f")"; done; seeds+=("$work.seeds");;
    esac
  fi
  echo "== fuzz_$t for ${seconds}s"
  bin="$build/bin/fuzz_$t"
  [[ -x $bin ]] || { echo "missing $bin (build with make fuzz)"; exit 1; }
  log="$findings/log-$(date +%Y%m%d-%H%M%S).txt"
  status=0
  "$bin" "$work" "${seeds[@]}" -max_total_time="$seconds" -max_len=1048576 -rss_limit_mb=3072 \
      -timeout=60 -artifact_prefix="$findings/" -print_final_stats=1 > "$log" 2>&1 || status=$?
  # The end of the run, and a finding's report whole (from libFuzzer's or a sanitizer's first line).
  tail -15 "$log"
  if [[ $status -ne 0 ]]; then
    echo "fuzz_$t stopped with a finding (exit $status; the whole log: $log):"
    sed -n '/^==[0-9]*==\|^ERROR: libFuzzer\|^SUMMARY\|Deadly signal\|out-of-memory\|ALARM/,$p' "$log" | head -120
  else
    rm -f "$log"
  fi
done
