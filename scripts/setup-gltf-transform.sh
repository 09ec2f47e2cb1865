#!/usr/bin/env bash
# Installs @gltf-transform/cli (pinned) with npm into DIR (default build/node-tools), for
# compressed_models_test to make Draco, meshopt, quantised and WebP variants of the shared
# models. Best effort: without npm or the registry it says so and the test skips.
set -u
dir=${1:-build/node-tools}
version=4.5.1
bin="$dir/node_modules/.bin/gltf-transform"
[[ -x $bin ]] && exit 0
if ! command -v npm >/dev/null 2>&1; then echo "setup-gltf-transform: npm not found"; exit 0; fi
# @gltf-transform/cli 4.5 needs Node.js 20 (node:util's styleText); Debian 12's is 18.
if ! node -e 'process.exit(+process.versions.node.split(".")[0] >= 20 ? 0 : 1)' 2>/dev/null; then
  echo "setup-gltf-transform: @gltf-transform/cli $version needs Node.js 20, this is $(node --version 2>/dev/null)"
  exit 0
fi
mkdir -p "$dir"
(cd "$dir" && timeout 600 npm install --no-audit --no-fund --silent "@gltf-transform/cli@$version" >/dev/null 2>&1) ||
  echo "setup-gltf-transform: npm install @gltf-transform/cli@$version failed"
exit 0
