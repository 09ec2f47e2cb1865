#!/usr/bin/env bash
# Installs the independent readers some tests use to check our files, into
# build/node-tools (never into the repository): the npm packages ktx-parse (KTX2) and
# gltf-validator (the Khronos glTF-Validator, for the glTF files `fresnel convert` writes).
# Best effort: without node/npm or the npm registry, those tests skip.
set -u
dir=${1:-build/node-tools}
[[ -d $dir/node_modules/ktx-parse && -d $dir/node_modules/gltf-validator ]] && exit 0
if ! command -v npm >/dev/null 2>&1; then
  echo "install-test-tools: npm not found; the KTX2 independent-reader test will skip"
  exit 0
fi
mkdir -p "$dir"
[[ -f $dir/package.json ]] || echo '{"name":"fresnel-test-tools","private":true}' > "$dir/package.json"
if ! (cd "$dir" && timeout 120 npm install --no-audit --no-fund --silent ktx-parse@0.7 >/dev/null 2>&1); then
  echo "install-test-tools: npm install ktx-parse failed; the KTX2 independent-reader test will skip"
fi
if ! (cd "$dir" && timeout 120 npm install --no-audit --no-fund --silent gltf-validator@2.0.0-dev.3.10 >/dev/null 2>&1); then
  echo "install-test-tools: npm install gltf-validator failed; the glTF validation test will skip"
fi
exit 0
