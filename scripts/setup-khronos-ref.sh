#!/usr/bin/env bash
# Prepares a copy of ../shared/tools/khronos-ref with its npm packages (the Khronos glTF
# Sample Renderer and playwright-core, pinned by its package-lock.json) in DIR, for
# `make bench` to time the Khronos renderer in the same run. Best effort: without the
# shared folder, npm or Debian's Chromium (`apt-get install chromium`) it says so and
# the bench prints the last measured figures instead.
set -u
dir=${1:-build/khronos-ref}
src="$(cd "$(dirname "$0")/.." && pwd)/../shared/tools/khronos-ref"
[[ -x $dir/render && -d $dir/node_modules ]] && exit 0
if [[ ! -d $src ]]; then echo "setup-khronos-ref: $src is absent"; exit 0; fi
if [[ ! -x /usr/bin/chromium ]]; then echo "setup-khronos-ref: /usr/bin/chromium not installed (apt-get install chromium)"; exit 0; fi
if ! command -v npm >/dev/null 2>&1; then echo "setup-khronos-ref: npm not found"; exit 0; fi
rm -rf "$dir" && mkdir -p "$(dirname "$dir")" && cp -r "$src" "$dir" && chmod -R u+w "$dir"
(cd "$dir" && timeout 300 npm ci --no-audit --no-fund --silent >/dev/null 2>&1) || echo "setup-khronos-ref: npm ci failed"
exit 0
