#!/usr/bin/env node
// Validates glTF files with the Khronos glTF-Validator (npm gltf-validator, installed by
// scripts/install-test-tools.sh into build/node-tools). usage: validate-gltf.js NODE_TOOLS FILE...
// Prints one JSON line per file ({file, errors, warnings, infos, messages}); exit 1 when any
// file has errors or warnings, 2 when the validator is missing.
const path = require('path');
const fs = require('fs');
let validator;
try {
  validator = require(path.join(path.resolve(process.argv[2]), 'node_modules', 'gltf-validator'));
} catch (e) {
  console.error('validate-gltf: gltf-validator not installed under ' + process.argv[2]);
  process.exit(2);
}
(async () => {
  let bad = false;
  for (const file of process.argv.slice(3)) {
    const dir = path.dirname(file);
    const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)), {
      uri: path.basename(file),
      externalResourceFunction: (uri) =>
        new Promise((resolve, reject) => {
          fs.readFile(path.join(dir, decodeURIComponent(uri)), (err, data) => (err ? reject(err.toString()) : resolve(new Uint8Array(data))));
        }),
    });
    const i = report.issues;
    console.log(JSON.stringify({file, errors: i.numErrors, warnings: i.numWarnings, infos: i.numInfos,
                                messages: i.messages.filter((m) => m.severity < 2)}));
    if (i.numErrors > 0 || i.numWarnings > 0) bad = true;
  }
  process.exit(bad ? 1 : 0);
})();
