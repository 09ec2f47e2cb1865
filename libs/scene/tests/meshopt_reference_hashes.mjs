// Prints the FNV-1a 64 hashes that GltfMeshoptFilters.MatchTheReferenceDecoderExactly
// (gltf_compressed_test.cpp) expects: the same inputs (one xorshift32 stream) encoded by
// meshoptimizer's encoder and decoded, filters included, by its reference decoder.
// usage: node meshopt_reference_hashes.mjs NODE_MODULES_DIR   (build/node-tools/node_modules,
// where scripts/setup-gltf-transform.sh installs meshoptimizer with @gltf-transform/cli)
import path from 'path';
import { pathToFileURL } from 'url';
const modules = path.resolve(process.argv[2] ?? 'build/node-tools/node_modules');
const load = (f) => import(pathToFileURL(path.join(modules, 'meshoptimizer', f)).href);
const { MeshoptDecoder: D } = await load('meshopt_decoder_reference.js');
const { MeshoptEncoder: E } = await load('index.js');
await E.ready;
function fnv(bytes) { let h = 0xcbf29ce484222325n; for (const b of bytes) { h ^= BigInt(b); h = (h * 0x100000001b3n) & 0xffffffffffffffffn; } return h.toString(16); }
// xorshift32 as in the C++ test
let st = 2463534242;
function rnd() { st ^= st << 13; st >>>= 0; st ^= st >>> 17; st ^= st << 5; st >>>= 0; return st; }
function run(name, raw, count, stride, filter) {
  const enc = E.encodeVertexBuffer(raw, count, stride);
  const out = new Uint8Array(count * stride);
  D.decodeVertexBuffer(out, count, stride, enc, filter);
  console.log(name, fnv(out), Array.from(out.slice(0, 16)).join(','));
}
// 8-bit octahedral: every x, y in [-127, 127], one = 127, w = 0x55
{ const n = 255 * 255; const raw = new Uint8Array(n * 4); let k = 0;
  for (let x = -127; x <= 127; ++x) for (let y = -127; y <= 127; ++y) { raw[k++] = x & 255; raw[k++] = y & 255; raw[k++] = 127; raw[k++] = 0x55; }
  run('oct8', raw, n, 4, 'OCTAHEDRAL'); }
// 16-bit octahedral: random x, y in [-one, one], one random in [1, 32767] (gltfpack writes smaller ones too)
{ const n = 20000; const raw = new Int16Array(n * 4);
  for (let i = 0; i < n; ++i) { const one = 1 + rnd() % 32767; raw[i*4] = (rnd() % (2*one+1)) - one; raw[i*4+1] = (rnd() % (2*one+1)) - one; raw[i*4+2] = one; raw[i*4+3] = rnd() & 0x7fff; }
  run('oct16', new Uint8Array(raw.buffer), n, 8, 'OCTAHEDRAL'); }
// quaternion: random components and scale word (hostile ones included)
{ const n = 20000; const raw = new Uint16Array(n * 4);
  for (let i = 0; i < n; ++i) for (let c = 0; c < 4; ++c) raw[i*4+c] = rnd() & 0xffff;
  run('quat', new Uint8Array(raw.buffer), n, 8, 'QUATERNION'); }
// exponential: random 32-bit words
{ const n = 20000; const raw = new Uint32Array(n * 3);
  for (let i = 0; i < n * 3; ++i) raw[i] = rnd();
  run('exp', new Uint8Array(raw.buffer), n, 12, 'EXPONENTIAL'); }
// hostile octahedral: random bytes (one may be 0 or negative)
{ const n = 20000; const raw = new Uint8Array(n * 4);
  for (let i = 0; i < n * 4; ++i) raw[i] = rnd() & 255;
  run('oct8_any', raw, n, 4, 'OCTAHEDRAL'); }
