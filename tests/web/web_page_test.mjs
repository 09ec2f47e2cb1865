// The web page (make web -> build-web/) in headless Debian Chromium (WebGL 2 on SwiftShader),
// driven by npm playwright-core (the driver only; no browser is downloaded):
//   1. DamagedHelmet with studio_small_03 by URL parameters: the canvas read back matches
//      `fresnel render` for the same camera and settings at >= 30 dB PSNR (`fresnel compare`);
//   1b. the environment bakes in the page's Web Worker (the page's thread stays free); a quick bake,
//      started while the model loads, lights the first frame, and the full bake the one compared;
//   2. a broken file shows an error in the page, and the page keeps working (the next frame draws);
//   3. debug channels switch (normal, basecolor): each matches `fresnel render --debug` at >= 30 dB;
//   4. a .gltf by URL (its buffer and texture fetched beside it) matches `fresnel render` at >= 30 dB;
//      so does one whose texture is a KHR_texture_basisu KTX2 (UASTC with Zstandard);
//   5. the debug channel list holds every `render --debug` name, the --brdf lists every term;
//   6. a scene file by ?scene= (DamagedHelmet, a light, a `fresnel bake` folder as environment,
//      tone mapping, exposure, camera, size) matches `fresnel render SCENE.fresnel.json` at >= 30 dB;
//   7. a material edit changes the frame and reverting restores it; adding a light changes the
//      frame and removing it restores it;
//   8. every setting of the registry the page offers round-trips through its fresnel_set;
//   9. an animated model opened at ?time= is posed on the GPU and matches `fresnel render --time`; played, the page's clock
//      moves the time and draws; paused, the frame matches `fresnel render` at the time reached;
//  10. without ?size= the canvas fills the window beside the panel and follows a resize.
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

// The scene file and what it names, in a folder the server mounts at /test/ (paths relative to it).
const sceneDir = path.join(outDir, 'scene');
fs.rmSync(sceneDir, { recursive: true, force: true });
fs.mkdirSync(sceneDir, { recursive: true });
fs.copyFileSync(model, path.join(sceneDir, 'DamagedHelmet.glb'));
const sceneDoc = {
    fresnel: 1, model: 'DamagedHelmet.glb',
    camera: { type: 'orbit', yaw: -35, pitch: 10 },
    lights: [{ type: 'directional', azimuth: 60, elevation: 30, intensity: 2, color: [1, 0.9, 0.8] }],
    environment: { file: 'studio.baked', rotation: 45, intensity: 0.8 },
    render: { size: [320, 240], toneMapping: 'aces', exposure: 0.3 },
};
fs.writeFileSync(path.join(sceneDir, 'helmet.fresnel.json'), JSON.stringify(sceneDoc, null, 2));
const server = await serve(webDir, path.join(shared, 'assets'), { '/test/': outDir });
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
{
    const b = spawnSync(fresnel, ['bake', env, '-o', path.join(sceneDir, 'studio.baked'), '--no-previews'], { encoding: 'utf8' });
    if (b.status !== 0) throw new Error(`fresnel bake failed: ${b.stderr}`);
}
render(path.join(outDir, 'cli_scene.png'), [], [path.join(sceneDir, 'helmet.fresnel.json')]);
// Every `render --debug` channel, from the settings registry (`fresnel settings --json`).
const registry = JSON.parse(spawnSync(fresnel, ['settings', '--json'], { encoding: 'utf8' }).stdout);
const debugNames = registry.find(s => s.key === 'render.debug').choices.filter(n => n !== 'none');
console.log(`fresnel render x5, bake: ${Date.now() - t0} ms`);

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
    const { ms: firstFrameMs, error } = await openPage(page, base, query);  // the complete frame
    check(!error, `page loads DamagedHelmet + studio_small_03 (${firstFrameMs} ms to the first frame)${error ? ': ' + error : ''}`);
    if (error) throw new Error(log.join('\n'));
    console.log(`renderer: ${await page.evaluate(() => document.getElementById('gl-info').textContent)}`);
    const worker = log.find(l => /baked in the worker/.test(l));
    check(worker, `the environment baked in the page's Web Worker (${worker || 'no'})`);
    // The first frame is lit by a quick bake started while the model loaded; the frame compared
    // below (window.fresnelReady) is the one lit by the full bake.
    const quick = log.find(l => /quick bake in the worker/.test(l));
    const firstMs = await page.evaluate(() => window.fresnelFirstFrame || 0);
    check(quick && firstMs > 0 && firstMs < firstFrameMs,
          `a quick bake lit the first frame at ${firstMs} ms, before the complete frame (${quick || 'no quick bake'})`);

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
    await page.evaluate(() => window.fresnel.set('debug', 'none'));
    // A `fresnel bake` folder picked (its files), instead of the page's own bake.
    const bakedFiles = fs.readdirSync(path.join(sceneDir, 'studio.baked')).map(f => path.join(sceneDir, 'studio.baked', f));
    const pick = async (p, selector, files, done) => {
        const before = await p.evaluate(() => window.fresnel.frames());
        await p.setInputFiles(selector, files);
        await p.waitForFunction(([n, d]) => window.fresnel.error() || (window.fresnel.frames() > n && new Function('s', d)(window.fresnel.state())),
                                [before, done], { timeout: 60000, polling: 50 });
        return p.evaluate(() => window.fresnel.error());
    };
    const bakeError = await pick(page, '#open-files', bakedFiles, 'return !s.environment.endsWith(".hdr")');
    await canvasPng(path.join(outDir, 'web_baked.png'));
    const pb = psnr(path.join(outDir, 'web_baked.png'), path.join(outDir, 'cli.png'));
    const bakedEnv = await page.evaluate(() => window.fresnel.state().environment);
    check(!bakeError && pb >= 30 && !/\.hdr$/.test(bakedEnv),
          `a picked fresnel bake folder as the environment (${bakedEnv}): ${pb.toFixed(2)} dB against fresnel render${bakeError ? ': ' + bakeError : ''}`);
    // Another model by URL: a .gltf whose buffer and texture the page fetches beside it.
    const gltfError = await page.evaluate(async u => {
        try { await window.fresnel.openUrl(u); return ''; } catch (e) { return e.message; }
    }, `/assets/${gltfRel}`);
    await canvasPng(path.join(outDir, 'web_gltf.png'));
    const g = psnr(path.join(outDir, 'web_gltf.png'), path.join(outDir, 'cli_gltf.png'));
    check(!gltfError && g >= 30, `${gltfRel} by URL (its .bin and .png fetched): ${g.toFixed(2)} dB against fresnel render${gltfError ? ': ' + gltfError : ''}`);
    // A glTF whose texture is a KHR_texture_basisu KTX2 (UASTC, Zstandard: the page's own Zstandard
    // decoder, since the web build has no libzstd) renders as fresnel render draws it.
    const ktx2 = path.join(shared, 'assets/ktx2/kodim23_uastc_zstd_mips.ktx2');
    if (fs.existsSync(ktx2)) {
        fs.copyFileSync(ktx2, path.join(sceneDir, 'kodim23.ktx2'));
        const quad = Buffer.alloc(92);
        [-1.5, -1, 0, 1.5, -1, 0, 1.5, 1, 0, -1.5, 1, 0, 0, 1, 1, 1, 1, 0, 0, 0].forEach((v, i) => quad.writeFloatLE(v, 4 * i));
        [0, 1, 2, 0, 2, 3].forEach((v, i) => quad.writeUInt16LE(v, 80 + 2 * i));
        const doc = {
            asset: { version: '2.0' }, extensionsUsed: ['KHR_texture_basisu'], extensionsRequired: ['KHR_texture_basisu'],
            scenes: [{ nodes: [0] }], nodes: [{ mesh: 0 }],
            buffers: [{ byteLength: 92, uri: 'data:application/octet-stream;base64,' + quad.toString('base64') }],
            bufferViews: [{ buffer: 0, byteLength: 48 }, { buffer: 0, byteOffset: 48, byteLength: 32 }, { buffer: 0, byteOffset: 80, byteLength: 12 }],
            accessors: [{ bufferView: 0, componentType: 5126, count: 4, type: 'VEC3', min: [-1.5, -1, 0], max: [1.5, 1, 0] },
                        { bufferView: 1, componentType: 5126, count: 4, type: 'VEC2' }, { bufferView: 2, componentType: 5123, count: 6, type: 'SCALAR' }],
            meshes: [{ primitives: [{ attributes: { POSITION: 0, TEXCOORD_0: 1 }, indices: 2, material: 0 }] }],
            materials: [{ pbrMetallicRoughness: { baseColorTexture: { index: 0 }, metallicFactor: 0 } }],
            images: [{ uri: 'kodim23.ktx2', mimeType: 'image/ktx2' }],
            textures: [{ extensions: { KHR_texture_basisu: { source: 0 } } }],
        };
        const quadPath = path.join(sceneDir, 'ktx2quad.gltf');
        fs.writeFileSync(quadPath, JSON.stringify(doc));
        render(path.join(outDir, 'cli_ktx2.png'), [], [quadPath, '--env', env, '--size', size, '--yaw', String(yaw), '--pitch', String(pitch)]);
        const quadError = await page.evaluate(async u => {
            try { await window.fresnel.openUrl(u); return ''; } catch (e) { return e.message; }
        }, '/test/scene/ktx2quad.gltf');
        const quadWarnings = await page.evaluate(() => document.getElementById('warnings').textContent);
        await canvasPng(path.join(outDir, 'web_ktx2.png'));
        const k = psnr(path.join(outDir, 'web_ktx2.png'), path.join(outDir, 'cli_ktx2.png'));
        check(!quadError && !/basisu|ktx2/i.test(quadWarnings) && k >= 30,
              `a KHR_texture_basisu UASTC+Zstandard texture: ${k.toFixed(2)} dB against fresnel render${quadError ? ': ' + quadError : ''}${quadWarnings ? ' (warnings: ' + quadWarnings + ')' : ''}`);
    }

    // The panel's lists: every --debug channel of `fresnel render --help`, every --brdf term.
    const lists = await page.evaluate(() => Object.fromEntries(['debug', 'brdf-D', 'brdf-G', 'brdf-F', 'brdf-diffuse']
        .map(id => [id, [...document.getElementById(id).options].map(o => o.value)])));
    const missing = debugNames.filter(n => !lists.debug.includes(n));
    check(debugNames.length >= 20 && !missing.length, `the debug list holds all ${debugNames.length} render --debug channels${missing.length ? ' (missing: ' + missing.join(' ') + ')' : ''}`);
    check(lists['brdf-D'].includes('beckmann') && lists['brdf-G'].includes('kelemen') && lists['brdf-F'].includes('schlick') &&
          lists['brdf-diffuse'].includes('burley'), `the --brdf terms are listed (D: ${lists['brdf-D'].join(' ')})`);
    // The panel's controls are the registry's: the exposure slider's range and tooltip, and the
    // value a set() gives it.
    const panel = await page.evaluate(async () => {
        const el = document.getElementById('exposure');
        const s = window.fresnel.settings().find(r => r.key === 'render.exposure');
        const before = [Number(el.min), Number(el.max), s.sliderMin, s.sliderMax, el.title === s.doc];
        await window.fresnel.set('render.exposure', '1.5');
        const shown = el.value;
        await window.fresnel.set('render.exposure', '0');
        return [...before, shown];
    });
    check(panel[0] === panel[2] && panel[1] === panel[3] && panel[4] && panel[5] === '1.5',
          `the exposure slider is the registry's (range ${panel[0]}..${panel[1]}, tooltip ${panel[4]}, shows ${panel[5]} after set 1.5)`);

    // A scene file by URL: read by the library's parser as `fresnel render SCENE.fresnel.json` reads it.
    const scenePage = await browser.newPage({ viewport: { width: 1000, height: 700 }, deviceScaleFactor: 1 });
    scenePage.on('console', m => log.push(`[scene ${m.type()}] ${m.text()}`));
    scenePage.on('pageerror', e => log.push(`[scene exception] ${e.message}`));
    // URL parameters are the settings registry's: by key (render.anisotropy), by flag name, and a
    // negated boolean flag by its presence (no-energy-compensation); both are set back to their
    // defaults (the scene file sets neither) before the comparison with fresnel render.
    const sceneOpen = await openPage(scenePage, base,
                                     '?scene=/test/scene/helmet.fresnel.json&render.anisotropy=4&no-energy-compensation');
    check(!sceneOpen.error, `?scene=helmet.fresnel.json loads (${sceneOpen.ms} ms to the first frame)${sceneOpen.error ? ': ' + sceneOpen.error : ''}`);
    const shot = async file => {
        const url = await scenePage.evaluate(() => document.getElementById('canvas').toDataURL('image/png'));
        fs.writeFileSync(path.join(outDir, file), Buffer.from(url.split(',')[1], 'base64'));
        return path.join(outDir, file);
    };
    if (!sceneOpen.error) {
        const st = await scenePage.evaluate(() => window.fresnel.state());
        check(st.settings['render.anisotropy'] === '4' && st.settings['render.energyCompensation'] === 'false',
              `URL parameters by registry key and negated flag (render.anisotropy ${st.settings['render.anisotropy']}, ` +
              `energy compensation ${st.settings['render.energyCompensation']})`);
        await scenePage.evaluate(() => { window.fresnel.setOnly('render.anisotropy', '6'); return window.fresnel.set('render.energyCompensation', 'true'); });
        const sceneShot = await shot('web_scene.png');
        const ps = psnr(sceneShot, path.join(outDir, 'cli_scene.png'));
        check(ps >= 30 && st.settings['render.toneMapping'] === 'aces' && st.settings['render.size'].startsWith('320x') && st.lights.some(l => l.origin === 'extra'),
              `scene file vs fresnel render SCENE.fresnel.json: ${ps.toFixed(2)} dB (>= 30; tone mapping ${st.settings['render.toneMapping']}, ${st.settings['render.size']}, ` +
              `${st.lights.length} light(s), environment ${st.environment.replace(/\/files\/\d+\//, '')})`);

        // The material editor: an edit changes the frame, revert restores it.
        const mats = await scenePage.evaluate(() => window.fresnel.materials());
        await scenePage.evaluate(() => window.fresnel.setMaterial(0, 'baseColorFactor', '1,0.1,0.1,1'));
        const edited = await shot('web_scene_material.png');
        await scenePage.evaluate(() => window.fresnel.setMaterial(0, 'reset', ''));
        const reverted = await shot('web_scene_reverted.png');
        const pe = psnr(edited, sceneShot), pr = psnr(reverted, sceneShot);
        check(mats.length >= 1 && pe < 30 && pr >= 50, `material ${mats[0] && mats[0].name}: base colour edit ${pe.toFixed(2)} dB (< 30), revert ${pr.toFixed(2)} dB (>= 50)`);
        // The editor offers every property of the material property registry: an extension the
        // material lacks (iridescence) is added by setting one of its properties, and shows.
        const registry = await scenePage.evaluate(() => window.fresnel.materialProperties());
        await scenePage.evaluate(() => window.fresnel.setMaterial(0, 'iridescenceFactor', '1'));
        const added = (await scenePage.evaluate(() => window.fresnel.materials()))[0];
        await scenePage.evaluate(() => window.fresnel.setMaterial(0, 'reset', ''));
        check(registry.properties.some(p => p.name === 'diffuseTransmissionFactor') &&
              added.blocks.includes('KHR_materials_iridescence') && added.values.iridescenceFactor === 1,
              `material registry: ${registry.properties.length} properties offered; iridescence added by an edit ` +
              `(${added.blocks.join(', ')})`);

        // Lights: adding one changes the frame, removing it restores it.
        await scenePage.evaluate(() => window.fresnel.addLight('point:0,0,2,80,0.3,0.5,1'));
        const lit = await shot('web_scene_light.png');
        const n = await scenePage.evaluate(() => window.fresnel.state().lights.filter(l => l.origin === 'extra').length);
        await scenePage.evaluate(k => window.fresnel.removeLight(k - 1), n);
        const unlit = await shot('web_scene_unlit.png');
        const pl = psnr(lit, sceneShot), pu = psnr(unlit, sceneShot);
        check(n === 2 && pl < 35 && pu >= 50, `an added point light: ${pl.toFixed(2)} dB (< 35), removed ${pu.toFixed(2)} dB (>= 50)`);

        // Shadows toggled live (the registry's render.shadows): a light from the side casts the
        // helmet's own shadows; off changes the frame, soft again restores it.
        await scenePage.evaluate(() => window.fresnel.addLight('point:1.5,1,0.5,60'));
        const shadowed = await shot('web_scene_shadowed.png');
        await scenePage.evaluate(() => window.fresnel.set('render.shadows', 'off'));
        const unshadowed = await shot('web_scene_unshadowed.png');
        await scenePage.evaluate(() => window.fresnel.set('render.shadows', 'soft'));
        const reshadowed = await shot('web_scene_reshadowed.png');
        const extra = await scenePage.evaluate(() => window.fresnel.state().lights.filter(l => l.origin === "extra").length);
        await scenePage.evaluate(k => window.fresnel.removeLight(k - 1), extra);
        const pOff = psnr(shadowed, unshadowed), pBack = psnr(shadowed, reshadowed);
        check(pOff < 45 && pBack >= 50, `shadows off changes the frame: ${pOff.toFixed(2)} dB (< 45), soft again ${pBack.toFixed(2)} dB (>= 50)`);

        // The scene file picked with the files it names (without their folder): found by name.
        await scenePage.evaluate(() => window.fresnel.set('yaw', 120));
        const pickError = await pick(scenePage, '#open-files', [path.join(sceneDir, 'helmet.fresnel.json'), path.join(sceneDir, 'DamagedHelmet.glb'), ...bakedFiles],
                                     'return s.settings["camera.yaw"] === "-35"');
        const pp = psnr(await shot('web_scene_picked.png'), path.join(outDir, 'cli_scene.png'));
        check(!pickError && pp >= 30, `the scene file picked with its files: ${pp.toFixed(2)} dB against fresnel render SCENE.fresnel.json${pickError ? ': ' + pickError : ''}`);
        const err = await scenePage.evaluate(() => window.fresnel.error());
        check(!err, `no error in the scene page${err ? ': ' + err : ''}`);

        // 8. Every setting of the registry the page offers, set by its key through fresnel_set,
        //    reads back in the registry's text (the C++ round trip test does the same for the
        //    flags, scene files and view scripts).
        const round = await scenePage.evaluate(() => {
            const bad = [];
            let n = 0;
            for (const s of window.fresnel.settings().filter(s => s.frontEnds.includes('web'))) {
                try { window.fresnel.setOnly(s.key, s.example); } catch (e) { bad.push(`${s.key}: ${e.message}`); continue; }
                const got = window.fresnel.state().settings[s.key];
                if (got !== s.example) bad.push(`${s.key}: set ${s.example}, reads ${got}`);
                // Back to the default: each setting's example alone (a variant the model lacks
                // would make the next reload of the model, `disable`'s, fail).
                try { window.fresnel.setOnly(s.key, s.default); } catch (e) { bad.push(`${s.key} back to ${s.default}: ${e.message}`); }
                ++n;
            }
            return { n, bad };
        });
        check(round.n >= 25 && !round.bad.length, `${round.n} registry settings round-trip through the page's set${round.bad.length ? ': ' + round.bad.join('; ') : ''}`);
    }
    // 9. Animation: CesiumMan opened at ?time=0.75 matches `fresnel render --time 0.75`; played, the
    //    page's clock moves animation.time and draws; paused, the frame matches `fresnel render` at
    //    the time the playback reached.
    const walker = path.join(shared, 'assets/models/CesiumMan/CesiumMan.glb');
    if (fs.existsSync(walker)) {
        const animPage = await browser.newPage({ viewport: { width: 1000, height: 700 }, deviceScaleFactor: 1 });
        animPage.on('pageerror', e => log.push(`[animation exception] ${e.message}`));
        const animArgs = [walker, '--size', '256x192', '--yaw', '30', '--env', 'color:0.6,0.6,0.6', '--env-size', '64'];
        const opened = await openPage(animPage, base, '?model=/assets/models/CesiumMan/CesiumMan.glb&time=0.75&size=256x192&yaw=30&env=color:0.6,0.6,0.6&env-size=64');
        check(!opened.error, `CesiumMan at ?time=0.75 loads${opened.error ? ': ' + opened.error : ''}`);
        if (!opened.error) {
            const animShot = async file => {
                const url = await animPage.evaluate(() => document.getElementById('canvas').toDataURL('image/png'));
                fs.writeFileSync(path.join(outDir, file), Buffer.from(url.split(',')[1], 'base64'));
                return path.join(outDir, file);
            };
            render(path.join(outDir, 'cli_walk.png'), ['--time', '0.75'], animArgs);
            const still = await animPage.evaluate(() => ({ ...window.fresnel.playback(), panel: !document.getElementById('animation-panel').hidden }));
            const pa = psnr(await animShot('web_walk.png'), path.join(outDir, 'cli_walk.png'));
            check(pa >= 30 && !still.playing && still.panel && still.hi === 2,
                  `?time=0.75 opens paused (${still.playing ? 'playing' : 'paused'}, range ${still.lo}..${still.hi}): ${pa.toFixed(2)} dB against render --time 0.75 (>= 30)`);
            // WebGL 2 poses it in the vertex shader (joint matrices read from a float texture), not on the CPU.
            const posedOnGpu = await animPage.evaluate(() => window.fresnel.state().posedOnGpu);
            check(posedOnGpu === true, `CesiumMan is posed on the GPU (posedOnGpu: ${posedOnGpu})`);
            const before = await animPage.evaluate(() => window.fresnel.frames());
            await animPage.evaluate(() => window.fresnel.play(true));
            await animPage.waitForTimeout(1500);
            const played = await animPage.evaluate(() => { window.fresnel.play(false); return { ...window.fresnel.playback(), frames: window.fresnel.frames() }; });
            await animPage.evaluate(() => window.fresnel.draw());
            const t = played.time;
            render(path.join(outDir, 'cli_walk_played.png'), ['--time', String(t)], animArgs);
            const pp = psnr(await animShot('web_walk_played.png'), path.join(outDir, 'cli_walk_played.png'));
            check(played.frames - before >= 2 && Math.abs(t - 0.75) > 0.05 && t >= 0 && t <= 2 && pp >= 30,
                  `playing drew ${played.frames - before} frames and reached t = ${t.toFixed(3)}; paused there: ${pp.toFixed(2)} dB against render --time (>= 30)`);
        }
        await animPage.close();
    } else {
        console.log(`skipped the animation checks: ${walker} is missing`);
    }
    // 9b. The file's cameras in the camera picker: choosing one shows what `render --camera N` renders.
    const camModel = path.join(shared, 'assets/models/Cameras/Cameras.gltf');
    if (fs.existsSync(camModel)) {
        const camPage = await browser.newPage({ viewport: { width: 1000, height: 700 }, deviceScaleFactor: 1 });
        const opened = await openPage(camPage, base, '?model=/assets/models/Cameras/Cameras.gltf&size=256x192&env=color:0.5,0.5,0.5&env-size=64');
        if (!opened.error) {
            const names = await camPage.evaluate(() => window.fresnel.state().cameras);
            const before = await camPage.evaluate(() => window.fresnel.frames());
            await camPage.selectOption('#camera-select', '0');
            await camPage.waitForFunction(n => window.fresnel.frames() > n, before, { timeout: 20000, polling: 50 }).catch(() => {});
            const url = await camPage.evaluate(() => document.getElementById('canvas').toDataURL('image/png'));
            fs.writeFileSync(path.join(outDir, 'web_camera0.png'), Buffer.from(url.split(',')[1], 'base64'));
            render(path.join(outDir, 'cli_camera0.png'), ['--camera', '0'], [camModel, '--size', '256x192', '--env', 'color:0.5,0.5,0.5', '--env-size', '64']);
            const pc = psnr(path.join(outDir, 'web_camera0.png'), path.join(outDir, 'cli_camera0.png'));
            const setting = await camPage.evaluate(() => window.fresnel.state().settings['camera.index']);
            check(names.length >= 1 && setting === '0' && pc >= 30,
                  `the camera picker lists the file's ${names.length} camera(s); camera 0 chosen: ${pc.toFixed(2)} dB against render --camera 0`);
        } else {
            check(false, `Cameras.gltf loads: ${opened.error}`);
        }
        await camPage.close();
    }
    // 9c. Environment presets: the studio and the environment the URL opened, each a button with
    //     its picture; a click on the studio shows what `render --env studio` renders.
    {
        const envPage = await browser.newPage({ viewport: { width: 1000, height: 700 }, deviceScaleFactor: 1 });
        const opened = await openPage(envPage, base, '?model=/assets/models/BoxTextured/BoxTextured.glb&env=/assets/env/studio_small_03_1k.hdr&size=256x192&yaw=30');
        if (!opened.error) {
            const presets = await envPage.evaluate(() => [...document.querySelectorAll('#env-presets button')].map(b => {
                const px = b.querySelector('canvas').getContext('2d').getImageData(0, 0, 96, 48).data;
                let lo = 255, hi = 0;
                for (let i = 0; i < px.length; i += 4) { lo = Math.min(lo, px[i + 1]); hi = Math.max(hi, px[i + 1]); }
                return { preset: b.dataset.preset, current: b.classList.contains('current'), spread: hi - lo };
            }));
            const before = await envPage.evaluate(() => window.fresnel.frames());
            await envPage.click('#env-presets button[data-preset="studio"]');
            await envPage.waitForFunction(n => window.fresnel.frames() > n && window.fresnel.state().environment === 'studio', before,
                                          { timeout: 60000, polling: 50 }).catch(() => {});
            const url = await envPage.evaluate(() => document.getElementById('canvas').toDataURL('image/png'));
            fs.writeFileSync(path.join(outDir, 'web_preset_studio.png'), Buffer.from(url.split(',')[1], 'base64'));
            const box = path.join(shared, 'assets/models/BoxTextured/BoxTextured.glb');
            render(path.join(outDir, 'cli_preset_studio.png'), [], [box, '--env', 'studio', '--size', '256x192', '--yaw', '30']);
            const ps = psnr(path.join(outDir, 'web_preset_studio.png'), path.join(outDir, 'cli_preset_studio.png'));
            check(presets.length === 2 && presets[0].preset === 'studio' && presets[1].current && presets.every(p => p.spread > 30) && ps >= 30,
                  `environment presets: ${presets.map(p => `${p.preset.split('/').pop()} (picture spread ${p.spread}${p.current ? ', current' : ''})`).join(', ')}; ` +
                  `the studio clicked: ${ps.toFixed(2)} dB against render --env studio`);
        } else {
            check(false, `the presets page loads: ${opened.error}`);
        }
        await envPage.close();
    }
    // 10. Without ?size= the canvas fills the window beside the panel, in device pixels, and
    //     follows a resize; the page has one Open control (files, or a folder) and no WebGL notice.
    {
        const fitPage = await browser.newPage({ viewport: { width: 1000, height: 700 }, deviceScaleFactor: 1 });
        const opened = await openPage(fitPage, base, '?model=/assets/models/BoxTextured/BoxTextured.glb&env=color:0.5,0.5,0.5&env-size=64');
        const size = async () => fitPage.evaluate(() => {
            const c = document.getElementById('canvas'), v = document.getElementById('view').getBoundingClientRect();
            return { w: c.width, h: c.height, vw: Math.round(v.width), vh: Math.round(v.height), setting: window.fresnel.state().settings['render.size'],
                     opens: document.querySelectorAll('#panel input[type=file]').length, notice: !document.getElementById('no-webgl').hidden };
        });
        const a = await size();
        await fitPage.setViewportSize({ width: 900, height: 600 });
        await fitPage.waitForFunction(() => document.getElementById('canvas').height === 600, null, { timeout: 20000, polling: 50 }).catch(() => {});
        const frames0 = await fitPage.evaluate(() => window.fresnel.frames());
        await fitPage.waitForTimeout(500);
        const b = await size();
        const drew = (await fitPage.evaluate(() => window.fresnel.frames())) >= frames0;
        check(!opened.error && a.w === a.vw && a.h === a.vh && a.setting === `${a.w}x${a.h}` && b.w === b.vw && b.h === 600 && b.w < a.w &&
              drew && a.opens === 2 && !a.notice,
              `the canvas fills the window beside the panel: ${a.w}x${a.h} in a 1000x700 window, ${b.w}x${b.h} after a resize to 900x600 ` +
              `(render.size ${b.setting}); ${a.opens} file inputs (files, folder) behind one Open group`);
        await fitPage.close();
    }
    if (failures) console.log(log.join('\n'));
} finally {
    await browser.close();
    server.close();
}
console.log(failures ? `web_page_test: ${failures} check(s) failed` : 'web_page_test: all checks passed');
process.exit(failures ? 1 : 0);
