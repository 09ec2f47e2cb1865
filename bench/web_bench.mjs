// The web build's size and speed (printed, not asserted): fresnel.wasm raw and gzip, time to the
// first frame of DamagedHelmet under studio_small_03 in headless Debian Chromium (WebGL 2 on
// SwiftShader, as the page's test runs it), and the frame time in the page; then the Khronos glTF
// Sample Renderer (../shared/tools/khronos-ref, same browser and backend) on the same model,
// environment and size in the same run, when its copy is prepared (scripts/setup-khronos-ref.sh).
// usage: node bench/web_bench.mjs [WEB_DIR=build-web] [SHARED_DIR=../shared] [NODE_TOOLS=build/node-tools]
//                                 [KHRONOS_REF=build/khronos-ref] [SIZE=512x512]
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import zlib from 'node:zlib';

import { launch, loadChromium, openPage, serve } from '../tests/web/web_harness.mjs';

const [webDir = 'build-web', shared = '../shared', nodeTools = 'build/node-tools', khronos = 'build/khronos-ref',
       size = '512x512'] = process.argv.slice(2);
const wasm = path.join(webDir, 'fresnel.wasm'), js = path.join(webDir, 'fresnel.js');
if (!fs.existsSync(wasm)) { console.error(`web_bench: ${wasm} is missing (make web)`); process.exit(1); }
const kib = n => `${(n / 1024).toFixed(1)} KiB`;
const gz = f => zlib.gzipSync(fs.readFileSync(f), { level: 9 }).length;
console.log(`machine: ${os.cpus().length} threads, ${os.cpus()[0].model}; ${new Date().toISOString()}`);
console.log(`fresnel.wasm ${kib(fs.statSync(wasm).size)} raw, ${kib(gz(wasm))} gzip -9; ` +
            `fresnel.js ${kib(fs.statSync(js).size)} raw, ${kib(gz(js))} gzip -9`);

const model = 'models/DamagedHelmet/DamagedHelmet.glb', env = 'env/studio_small_03_1k.hdr';
const chromium = loadChromium(nodeTools);
if (!chromium || !fs.existsSync(path.join(shared, 'assets', model))) {
    console.log('web_bench: no playwright-core or shared assets: no timings');
    process.exit(0);
}
const server = await serve(webDir, path.join(shared, 'assets'));
const browser = await launch(chromium);
try {
    const page = await browser.newPage({ viewport: { width: 1200, height: 900 } });
    const log = [];
    page.on('console', m => log.push(m.text()));
    const { ms, error } = await openPage(page, server.base, `?model=/assets/${model}&env=/assets/${env}&size=${size}`);
    if (error) throw new Error(error);
    const bake = log.find(l => l.startsWith('environment ')) || '';
    // The first frame (lit by the quick bake) and the complete one (the full bake's lighting).
    const first = await page.evaluate(() => window.fresnelFirstFrame || 0);
    // Frames: each drawn, then one pixel read back so that the GPU has finished it.
    const frames = await page.evaluate(() => {
        const gl = document.getElementById('canvas').getContext('webgl2');
        const px = new Uint8Array(4), out = [];
        for (let i = 0; i < 6; i++) {
            const t = performance.now();
            window.fresnel.drawNow();
            gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
            out.push(performance.now() - t);
        }
        return out.slice(1);
    });
    const median = a => [...a].sort((x, y) => x - y)[Math.floor(a.length / 2)];
    console.log(`fresnel page, DamagedHelmet, studio_small_03, ${size}, 4x MSAA:`);
    console.log(`  first frame ${first} ms from navigation (wasm load, model, the quick bake, first frame); ` +
                `complete frame ${ms} ms (${log.filter(l => l.startsWith('environment')).join('; ') || 'environment bake'})`);
    console.log(`  frame ${median(frames).toFixed(1)} ms median of ${frames.length} (${frames.map(f => f.toFixed(0)).join(' ')})`);
} finally {
    await browser.close();
    server.close();
}

const render = path.join(khronos, 'render');
if (!fs.existsSync(render) || !fs.existsSync(path.join(khronos, 'node_modules'))) {
    console.log(`Khronos Sample Renderer: ${khronos} is not prepared (scripts/setup-khronos-ref.sh ${khronos})`);
    process.exit(0);
}
const out = path.join(os.tmpdir(), `web-bench-khronos-${process.pid}.png`);
const r = spawnSync(render, ['--model', path.join(shared, 'assets', model), '--env', path.join(shared, 'assets', env),
                             '--size', size, '--frames', '5', '--out', out], { encoding: 'utf8', timeout: 1800000 });
fs.rmSync(out, { force: true });
const line = (r.stdout || '').trim().split('\n').pop();
let k;
try { k = JSON.parse(line); } catch (e) { console.log(`Khronos Sample Renderer failed: ${r.stderr}`); process.exit(0); }
console.log(`Khronos Sample Renderer ${k.gltf_viewer} (same browser, SwiftShader), ${k.width}x${k.height}, ${k.msaa_samples}x MSAA:`);
console.log(`  first frame ${Math.round(k.env_ms + k.load_ms + k.first_frame_ms)} ms after the page loaded ` +
            `(environment ${Math.round(k.env_ms)}, model ${Math.round(k.load_ms)}, first frame ${Math.round(k.first_frame_ms)})`);
console.log(`  frame ${k.frame_ms_median} ms median of ${k.frame_ms.length}`);
