// The web page (make web -> build-web/) in headless Debian Chromium (WebGL 2 on SwiftShader),
// driven by npm playwright-core (the driver only; no browser is downloaded):
//   1. DamagedHelmet with studio_small_03 by URL parameters: the canvas read back matches
//      `fresnel render` for the same camera and settings at >= 30 dB PSNR (`fresnel compare`);
//   1b. the environment bakes in the page's Web Worker (the page's thread stays free);
//   2. a broken file shows an error in the page, and the page keeps working (the next frame draws);
//   3. debug channels switch (normal, basecolor): each matches `fresnel render --debug` at >= 30 dB;
//   4. a .gltf by URL (its buffer and texture fetched beside it) matches `fresnel render` at >= 30 dB.
// Exit 77 (skipped) when build-web, Chromium, playwright-core or the shared assets are missing.
// usage: node web_page_test.mjs WEB_DIR FRESNEL_EXE SHARED_DIR NODE_TOOLS_DIR OUT_DIR
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';

import { chromiumPath, launch, loadChromium, openPage, serve } from './web_harness.mjs';

const [webDir, fresnel, shared, nodeTools, outDir] = process.argv.slice(2);
const skip = why => { console.log(`web_page_test: skipped: ${why}`); process.exit(77); };
if (!webDir || !outDir) { console.error('usage: web_page_test.mjs WEB_DIR FRESNEL_EXE SHARED_DIR NODE_TOOLS_DIR OUT_DIR'); process.exit(2); }
if (!fs.existsSync(path.join(webDir, 'fresnel.wasm'))) skip(`${webDir}/fresnel.wasm is missing (run make web)`);
if (!fs.existsSync(chromiumPath)) skip(`${chromiumPath} is missing (apt-get install chromium)`);
const model = path.join(shared, 'assets/models/DamagedHelmet/DamagedHelmet.glb');
const env = path.join(shared, 'assets/env/studio_small_03_1k.hdr');
if (!fs.existsSync(model) || !fs.existsSync(env)) skip(`the shared assets are missing (${model}, ${env})`);
const chromium = loadChromium(nodeTools);
if (!chromium) skip(`playwright-core is not in ${nodeTools} (scripts/install-test-tools.sh)`);
fs.mkdirSync(outDir, { recursive: true });

let failures = 0;
const check = (ok, what) => { console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`); if (!ok) failures++; };

const server = await serve(webDir, path.join(shared, 'assets'));
const base = server.base;

const size = '384x288', yaw = 30, pitch = 15;
const cliArgs = [model, '--env', env, '--size', size, '--yaw', String(yaw), '--pitch', String(pitch)];
function render(out, extra = [], args = cliArgs) {
    const r = spawnSync(fresnel, ['render', ...args, ...extra, '-o', out], { encoding: 'utf8' });
    if (r.status !== 0) throw new Error(`fresnel render failed: ${r.stderr}`);
}
function psnr(a, b) {
    const r = spawnSync(fresnel, ['compare', a, b, '--json'], { encoding: 'utf8' });
    if (r.status !== 0) throw new Error(`fresnel compare failed: ${r.stderr}`);
    return JSON.parse(r.stdout).psnr_db;
}
const t0 = Date.now();
render(path.join(outDir, 'cli.png'));
render(path.join(outDir, 'cli_normal.png'), ['--debug', 'normal']);
render(path.join(outDir, 'cli_basecolor.png'), ['--debug', 'basecolor']);
const gltfRel = 'models/BoxTextured/specular-glossiness/BoxTextured.gltf';  // .gltf + .bin + .png, specular-glossiness
render(path.join(outDir, 'cli_gltf.png'), [], [path.join(shared, 'assets', gltfRel), ...cliArgs.slice(1)]);
console.log(`fresnel render x3: ${Date.now() - t0} ms`);

const browser = await launch(chromium);
try {
    const page = await browser.newPage({ viewport: { width: 1000, height: 700 }, deviceScaleFactor: 1 });
    const log = [];
    page.on('console', m => log.push(`[${m.type()}] ${m.text()}`));
    page.on('pageerror', e => log.push(`[exception] ${e.message}`));
    const canvasPng = async file => {
        const url = await page.evaluate(() => document.getElementById('canvas').toDataURL('image/png'));
        fs.writeFileSync(file, Buffer.from(url.split(',')[1], 'base64'));
    };
    const query = `?model=/assets/models/DamagedHelmet/DamagedHelmet.glb&env=/assets/env/studio_small_03_1k.hdr` +
                  `&size=${size}&yaw=${yaw}&pitch=${pitch}&tonemap=neutral`;
    const { ms: firstFrameMs, error } = await openPage(page, base, query);
    check(!error, `page loads DamagedHelmet + studio_small_03 (${firstFrameMs} ms to the first frame)${error ? ': ' + error : ''}`);
    if (error) throw new Error(log.join('\n'));
    console.log(`renderer: ${await page.evaluate(() => document.getElementById('gl-info').textContent)}`);
    const worker = log.find(l => /baked in the worker/.test(l));
    check(worker, `the environment baked in the page's Web Worker (${worker || 'no'})`);

    await canvasPng(path.join(outDir, 'web.png'));
    const p = psnr(path.join(outDir, 'web.png'), path.join(outDir, 'cli.png'));
    check(p >= 30, `canvas vs fresnel render: ${p.toFixed(2)} dB (>= 30)`);

    // A broken file: an error in the page, the scene stays and the page keeps drawing.
    const broken = await page.evaluate(async () => {
        const bytes = new TextEncoder().encode('glTF this is not a binary glTF file');
        try { await window.fresnel.openFiles([{ name: 'broken.glb', bytes }]); return { thrown: '' }; } catch (e) {
            return { thrown: e.message, shown: window.fresnel.error() };
        }
    });
    check(/broken\.glb/.test(broken.thrown) && /broken\.glb/.test(broken.shown || ''),
          `a broken .glb shows its error in the page: "${broken.shown}"`);
    // What the web build leaves out is an error naming it, not a silent gap: an OpenEXR environment.
    const exr = await page.evaluate(async () => {
        const bytes = new Uint8Array([0x76, 0x2f, 0x31, 0x01, 2, 0, 0, 0, 0]);
        try { await window.fresnel.openFiles([{ name: 'sky.exr', bytes }]); return ''; } catch (e) { return window.fresnel.error(); }
    });
    check(/sky\.exr/.test(exr) && /OpenEXR/.test(exr), `an .exr environment (no OpenEXR on the web) says so: "${exr}"`);
    const frames = await page.evaluate(() => window.fresnel.frames());
    await page.evaluate(() => window.fresnel.set('yaw', 30));
    check(await page.evaluate(() => window.fresnel.frames()) > frames && !(await page.evaluate(() => window.fresnel.error())),
          'the page keeps working after the broken file (the next frame draws, no error)');
    await canvasPng(path.join(outDir, 'web_after_broken.png'));
    const again = psnr(path.join(outDir, 'web_after_broken.png'), path.join(outDir, 'cli.png'));
    check(again >= 30, `the model shown is still DamagedHelmet: ${again.toFixed(2)} dB`);

    // Debug channels switch.
    for (const channel of ['normal', 'basecolor']) {
        await page.evaluate(c => window.fresnel.set('debug', c), channel);
        const err = await page.evaluate(() => window.fresnel.error());
        await canvasPng(path.join(outDir, `web_${channel}.png`));
        const d = psnr(path.join(outDir, `web_${channel}.png`), path.join(outDir, `cli_${channel}.png`));
        const vsShaded = psnr(path.join(outDir, `web_${channel}.png`), path.join(outDir, 'cli.png'));
        check(!err && d >= 30 && vsShaded < d - 5,
              `--debug ${channel}: ${d.toFixed(2)} dB against fresnel render --debug ${channel} (${vsShaded.toFixed(2)} dB against the shaded frame)${err ? ': ' + err : ''}`);
    }
    // Another model by URL: a .gltf whose buffer and texture the page fetches beside it.
    await page.evaluate(() => window.fresnel.set('debug', 'none'));
    const gltfError = await page.evaluate(async u => {
        try { await window.fresnel.openUrl(u); return ''; } catch (e) { return e.message; }
    }, `/assets/${gltfRel}`);
    await canvasPng(path.join(outDir, 'web_gltf.png'));
    const g = psnr(path.join(outDir, 'web_gltf.png'), path.join(outDir, 'cli_gltf.png'));
    check(!gltfError && g >= 30, `${gltfRel} by URL (its .bin and .png fetched): ${g.toFixed(2)} dB against fresnel render${gltfError ? ': ' + gltfError : ''}`);
    if (failures) console.log(log.join('\n'));
} finally {
    await browser.close();
    server.close();
}
console.log(failures ? `web_page_test: ${failures} check(s) failed` : 'web_page_test: all checks passed');
process.exit(failures ? 1 : 0);
