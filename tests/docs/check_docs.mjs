// Checks the published formats with independent validators (npm, installed under the build
// folder by scripts/install-test-tools.sh; exit 77 = skipped when they are absent):
//   - docs/scene.schema.json is a valid JSON Schema (ajv, draft 2020-12), the examples in
//     docs/examples validate against it, and broken scene files do not;
//   - every Kubernetes manifest (```yaml block) of docs/batch.md validates against the
//     Kubernetes API schema (kubernetes-models), and its Indexed Job sets the shard count;
//   - the Slurm script (```bash block with #SBATCH) passes bash -n and is an array job.
// usage: node check_docs.mjs TOOL_DIR SOURCE_DIR
import { createRequire } from 'module';
import { readFileSync, readdirSync, writeFileSync, mkdtempSync } from 'fs';
import { spawnSync } from 'child_process';
import { tmpdir } from 'os';
import { join, resolve } from 'path';

const [toolDir, sourceDir] = process.argv.slice(2);
const require = createRequire(join(resolve(toolDir), 'package.json'));
let Ajv2020, yaml, models;
try {
  Ajv2020 = require('ajv/dist/2020').default;
  yaml = require('js-yaml');
  models = { Job: require('kubernetes-models/batch/v1/Job').Job };
} catch (e) {
  console.log(`validators not installed under ${toolDir} (scripts/install-test-tools.sh): ${e.message}`);
  process.exit(77);
}
let failed = false;
const fail = (m) => { console.log(`FAIL ${m}`); failed = true; };

// Scene schema.
const schema = JSON.parse(readFileSync(join(sourceDir, 'docs', 'scene.schema.json'), 'utf8'));
const ajv = new Ajv2020({ allErrors: true, strict: false });
const validate = ajv.compile(schema);
const examples = join(sourceDir, 'docs', 'examples');
for (const f of readdirSync(examples).filter((n) => n.endsWith('.fresnel.json'))) {
  const doc = JSON.parse(readFileSync(join(examples, f), 'utf8'));
  if (!validate(doc)) fail(`${f}: ${ajv.errorsText(validate.errors)}`);
  else console.log(`ok ${f}`);
}
for (const line of readFileSync(join(examples, 'jobs.jsonl'), 'utf8').split('\n')) {
  if (!line.trim() || line.startsWith('#')) continue;
  const job = JSON.parse(line);
  if (typeof job !== 'string' && typeof job !== 'object') fail(`jobs.jsonl: ${line}`);
}
const broken = [
  {},                                               // no version
  { fresnel: 2 },                                   // newer version
  { fresnel: 1, camera: { pitch: 120 } },           // out of range
  { fresnel: 1, render: { size: [0, 10] } },
  { fresnel: 1, lights: [{ type: 'area' }] },
  { fresnel: 1, lights: [{ type: 'point' }] },      // no position
  { fresnel: 1, model: 'a.glb', models: [{ path: 'b.glb' }] },
  { fresnel: 1, models: [{ path: 'a.glb', matrix: new Array(16).fill(0), scale: [1, 1, 1] }] },
  { fresnel: 1, output: 'x.jpg' },
];
for (const b of broken) if (validate(b)) fail(`the schema accepts ${JSON.stringify(b)}`);
console.log(`ok ${broken.length} broken scene files rejected by the schema`);

// Kubernetes manifests in docs/batch.md.
const md = readFileSync(join(sourceDir, 'docs', 'batch.md'), 'utf8');
const blocks = [...md.matchAll(/```yaml\n([\s\S]*?)```/g)].map((m) => m[1]);
if (blocks.length === 0) fail('docs/batch.md has no ```yaml manifest');
let indexed = 0;
for (const block of blocks) {
  for (const doc of yaml.loadAll(block)) {
    if (!doc) continue;
    if (doc.kind !== 'Job' || doc.apiVersion !== 'batch/v1') { console.log(`(not checked: ${doc.kind})`); continue; }
    try {
      new models.Job(doc).validate();
      console.log(`ok Job ${doc.metadata.name}`);
    } catch (e) {
      fail(`Job ${doc.metadata && doc.metadata.name}: ${e.message}`);
      continue;
    }
    if (doc.spec.completionMode === 'Indexed') {
      ++indexed;
      const c = doc.spec.template.spec.containers[0];
      const env = (c.env || []).find((e) => e.name === 'FRESNEL_SHARD_COUNT');
      if (!env || String(env.value) !== String(doc.spec.completions))
        fail('the Indexed Job must set FRESNEL_SHARD_COUNT to its completions');
      if (!(c.args || c.command || []).join(' ').includes('--shard auto')) fail('the Indexed Job must run --shard auto');
    }
  }
}
if (indexed === 0) fail('docs/batch.md has no Indexed Job');

// The Slurm script (```bash block with #SBATCH) parses, and runs --shard auto.
const scripts = [...md.matchAll(/```bash\n([\s\S]*?)```/g)].map((m) => m[1]).filter((b) => b.includes('#SBATCH'));
if (scripts.length === 0) fail('docs/batch.md has no Slurm script');
for (const script of scripts) {
  const file = join(mkdtempSync(join(tmpdir(), 'fresnel-docs-')), 'job.sbatch');
  writeFileSync(file, script);
  const r = spawnSync('bash', ['-n', file], { encoding: 'utf8' });
  if (r.status !== 0) fail(`Slurm script: bash -n: ${r.stderr}`);
  else if (!script.includes('--shard auto') || !script.includes('--array')) fail('the Slurm script must be an array job with --shard auto');
  else console.log('ok Slurm script');
}
process.exit(failed ? 1 : 0);
