#!/usr/bin/env bash
# Installs the independent readers and validators some tests use to check our files, into
# build/node-tools (never into the repository), from npm: ktx-parse (KTX2), three (its Basis Universal
# transcoder: the reference for our KTX2 decoders), ajv (JSON Schema:
# docs/scene.schema.json), js-yaml and kubernetes-models (docs/batch.md's Kubernetes manifest),
# gltf-validator (the Khronos glTF-Validator, for the glTF files `fresnel convert` writes),
# playwright-core (drives Debian's Chromium for the web page's test; the driver only, it downloads no browser).
# Best effort: without node/npm or the npm registry, those tests skip.
set -u
dir=${1:-build/node-tools}
# playwright-core 1.62 and later need Node.js 20; Debian 12's is 18, which 1.61.1 still runs.
playwright=1.65.1
if command -v node >/dev/null 2>&1 && ! node -e 'process.exit(+process.versions.node.split(".")[0] >= 20 ? 0 : 1)' 2>/dev/null; then
  playwright=1.61.1
fi
want=(ktx-parse@0.7 three@0.187 ajv@8 js-yaml@4 kubernetes-models@4 gltf-validator@2.0.0-dev.3.10 playwright-core@$playwright)
missing=()
for p in "${want[@]}"; do
  [[ -d $dir/node_modules/${p%@*} ]] || missing+=("$p")
done
# playwright-core at another version than this Node.js needs: that version instead.
if [[ -f $dir/node_modules/playwright-core/package.json ]] &&
   ! grep -q "\"version\": \"$playwright\"" "$dir/node_modules/playwright-core/package.json"; then
  missing+=("playwright-core@$playwright")
fi
# Another tool's install (scripts/setup-gltf-transform.sh shares this folder) can leave ajv 6
# at the top level, which has no JSON Schema 2020-12 (ajv/dist/2020): ask for ajv 8 again then.
if [[ -d $dir/node_modules/ajv && ! -f $dir/node_modules/ajv/dist/2020.js ]]; then missing+=(ajv@8); fi
[[ ${#missing[@]} -eq 0 ]] && exit 0
# A fresh Debian has node (web-packages.txt) but not npm: Debian's npm then (best effort; not in
# a package list, because a node from elsewhere, such as NodeSource's, brings its own npm and
# conflicts with Debian's).
if ! command -v npm >/dev/null 2>&1 && command -v apt-get >/dev/null 2>&1; then
  SUDO=""
  if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
  echo "install-test-tools: installing Debian's npm"
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends npm >/dev/null 2>&1 ||
    echo "install-test-tools: apt-get install npm failed"
fi
if ! command -v npm >/dev/null 2>&1; then
  echo "install-test-tools: npm not found; the KTX2 reader and docs format tests will skip"
  exit 0
fi
mkdir -p "$dir"
[[ -f $dir/package.json ]] || echo '{"name":"fresnel-test-tools","private":true}' > "$dir/package.json"
if ! (cd "$dir" && timeout 300 npm install --no-audit --no-fund --silent "${missing[@]}" >/dev/null 2>&1); then
  echo "install-test-tools: npm install ${missing[*]} failed; the tests that need them will skip"
fi
exit 0
