#!/usr/bin/env bash
# Prepares a copy of ../shared/tools/khronos-ref with its npm packages (the Khronos glTF
# Sample Renderer and playwright-core, pinned by its package-lock.json) in DIR, for
# `make bench` to time the Khronos renderer in the same run. Best effort: without the
# shared folder, npm or Debian's Chromium (`apt-get install chromium`) it says so and
# the bench prints the last measured figures instead.
set -u
dir=${1:-build/khronos-ref}
src="$(cd "$(dirname "$0")/.." && pwd)/../shared/tools/khronos-ref"
here="$(cd "$(dirname "$0")" && pwd)"
# Our copy takes `--time T [--animation K]` (scripts/khronos-ref-time.patch): animated models
# at a time, for the animation figures of docs/shading.md. The shared harness is left as it is.
add_time() { grep -q -- "'--time'" "$dir/render" || patch -s -d "$dir" -p0 < "$here/khronos-ref-time.patch" || echo "setup-khronos-ref: time patch failed"; }
if [[ -x $dir/render && -d $dir/node_modules ]]; then add_time; exit 0; fi
if [[ ! -d $src ]]; then echo "setup-khronos-ref: $src is absent"; exit 0; fi
if [[ ! -x /usr/bin/chromium ]]; then echo "setup-khronos-ref: /usr/bin/chromium not installed (apt-get install chromium)"; exit 0; fi
if ! command -v npm >/dev/null 2>&1; then echo "setup-khronos-ref: npm not found"; exit 0; fi
rm -rf "$dir" && mkdir -p "$(dirname "$dir")" && cp -r "$src" "$dir" && chmod -R u+w "$dir"
(cd "$dir" && timeout 300 npm ci --no-audit --no-fund --silent >/dev/null 2>&1) || echo "setup-khronos-ref: npm ci failed"
add_time
exit 0
