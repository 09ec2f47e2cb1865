// The fresnel page: the C++ renderer (fresnel.js / fresnel.wasm, apps/web/main.cpp) on a
// WebGL 2 canvas. Files (picked, dropped, or named by URL parameters from the same origin)
// are written into Emscripten's in-memory file system and loaded by the same loaders as
// `fresnel render`. URL parameters use the CLI's names and meanings:
//   ?model=URL&env=URL&light=SPEC (repeatable, as --light)&no-ibl, and every setting the
//   registry offers the page by its flag's name or its key (urlSettings: ?yaw=DEG&size=WxH&tonemap=NAME
//   &env-rotation=DEG&no-scene-lights&render.exposure=EV ...; `fresnel settings` lists them)
//   ?scene=URL: a *.fresnel.json scene file (same origin; the files it names are fetched beside it),
//   read as `fresnel render SCENE.fresnel.json` reads it; the other parameters then override it as flags do.
// window.fresnelReady becomes true once the first complete frame of what was asked is on the
// canvas; window.fresnelError holds the message when loading failed. window.fresnel is the
// page's interface for scripts and tests (set, openFiles, openUrl, draw, screenshot).
// Long (~700 lines): the page's whole behaviour (files, URL parameters, panel, editor, input) in
// one script with no build step, as the page is served as plain files.
'use strict';
(() => {
const $ = id => document.getElementById(id);
const canvas = $('canvas');
const params = new URLSearchParams(location.search);
const DEFAULT_MODEL = 'models/DamagedHelmet.glb';  // copied here by `make web` when ../shared has it

let M = null, app = 0, frames = 0, drawPending = false;

const status = text => { $('status').textContent = text; };
function showError(message) {
    $('error').hidden = !message;
    $('error').textContent = message || '';
}
// The loaders name files by their place in the in-memory file system (/files/N/NAME): show NAME.
const plain = text => text.replace(/\/files\/\d+\//g, '');
function lastError() { return plain(M.UTF8ToString(M._fresnel_error(app))); }
function fail(message) {
    showError(message);
    window.fresnelError = message;
    status('failed');
    throw new Error(message);
}
// The URL parameters that are settings, as [key, value] in the registry's order: every setting
// the registry offers the page, named by its flag without dashes (?env-rotation=30, and for a
// negated boolean flag its presence: ?no-energy-compensation) or by its key
// (?environment.rotation=30). The page reads ?env= (a file to fetch), ?scene= (a scene file)
// and ?light= (repeated) itself.
let registryCache = null;
const registry = () => registryCache || (registryCache = JSON.parse(M.ccall('fresnel_settings', 'string', [], [])));
function urlSettings() {
    const out = [];
    for (const s of registry()) {
        if (!s.frontEnds.includes('web') || s.key === 'environment' || s.key === 'scene') continue;
        const flag = s.flag.replace(/^--/, '');
        if (params.has(s.key)) out.push([s.key, params.get(s.key)]);
        else if (flag && params.has(flag))
            out.push([s.key, s.type === 'bool' && params.get(flag) === '' ? String(!flag.startsWith('no-')) : params.get(flag)]);
    }
    return out;
}
// The canvas fills the window beside the panel, in device pixels, and follows resizes — unless a
// size was asked for (?size=, or a scene file's render.size), which the canvas then keeps.
let fitWindow = !params.has('size') && !params.has('render.size') && !params.has('scene');
function fitCanvas() {
    canvas.classList.toggle('fit', fitWindow);
    if (!fitWindow || !app) return;
    const r = $('view').getBoundingClientRect(), dpr = window.devicePixelRatio || 1;
    const w = Math.max(16, Math.round(r.width * dpr)), h = Math.max(16, Math.round(r.height * dpr));
    if (w === canvas.width && h === canvas.height) return;
    try { set('size', `${w}x${h}`); } catch (e) { showError(e.message); return; }
    if (frames > 0) scheduleDraw();  // before the first frame, the load draws at this size
}
function set(key, value) {
    if (!M.ccall('fresnel_set', 'number', ['number', 'string', 'string'], [app, key, String(value)]))
        throw new Error(lastError());
}
// Writes files ({name, bytes}) under a fresh folder of the in-memory file system; returns its path.
let folders = 0;
function writeFiles(files) {
    const dir = `/files/${++folders}`;
    M.FS.mkdirTree(dir);
    for (const f of files) {
        const path = `${dir}/${f.name}`;
        M.FS.mkdirTree(path.substring(0, path.lastIndexOf('/')));
        M.FS.writeFile(path, f.bytes);
    }
    return dir;
}
const isModel = name => /\.(glb|gltf)$/i.test(name);
const isEnv = name => /\.(hdr|exr)$/i.test(name);
const baseName = name => name.split('/').pop();
const dirName = name => name.includes('/') ? name.substring(0, name.lastIndexOf('/')) : '';
const join = (dir, name) => (dir && name ? `${dir}/${name}` : dir || name);
// A `fresnel bake` folder's manifest, and scene files (any other .json).
const isBakeManifest = name => baseName(name) === 'manifest.json';
const isScene = name => /\.json$/i.test(name) && !isBakeManifest(name) && baseName(name) !== 'irradiance_sh.json';
const exists = path => { try { M.FS.stat(path); return true; } catch (e) { return false; } };
function writeFile(path, bytes) {
    M.FS.mkdirTree(dirName(path));
    M.FS.writeFile(path, bytes);
}
// The files a scene file names, relative to its folder: its models and its environment file
// (a panorama or a `fresnel bake` folder). The C++ parser checks the rest.
function sceneReferences(doc) {
    const models = [];
    if (doc && typeof doc.model === 'string' && doc.model !== 'demo') models.push(doc.model);
    for (const m of (doc && Array.isArray(doc.models) ? doc.models : []))
        if (m && typeof m.path === 'string' && m.path && m.path !== 'demo' && m.visible !== false) models.push(m.path);
    const e = doc && doc.environment;
    let env = typeof e === 'string' ? e : e && typeof e === 'object' && typeof e.file === 'string' ? e.file : null;
    if (env && (/^(studio|none|auto)$/.test(env) || env.startsWith('color:'))) env = null;
    return { models, env };
}

// Draws one frame now (baking the environment first when it changed). Throws the error.
function drawNow() {
    if (!M.ccall('fresnel_prepare', 'number', ['number'], [app])) throw new Error(lastError());
    if (!M.ccall('fresnel_draw', 'number', ['number'], [app])) throw new Error(lastError());
    frames++;
    const [yaw, pitch] = M.UTF8ToString(M._fresnel_camera(app)).split(' ').map(Number);
    $('stats').textContent = `frame ${M._fresnel_frame_ms(app).toFixed(1)} ms · yaw ${yaw.toFixed(1)} pitch ${pitch.toFixed(1)}`;
}
// Environments bake in a Web Worker (fresnel_bake_worker.js) so that the page stays responsive;
// without workers (or when the worker fails to start) they bake here, in fresnel_prepare.
let worker = null;
// One bake at a time: a bake asked for while another runs waits for it (the worker answers its
// messages in order, through one onmessage).
let workerQueue = Promise.resolve();
function bakeInWorker(message) {
    const p = workerQueue.then(() => bakeInWorkerNow(message));
    workerQueue = p.catch(() => {});
    return p;
}
function bakeInWorkerNow(message) {
    if (worker === null) {
        try { worker = new Worker('fresnel_bake_worker.js'); } catch (e) { worker = false; }
    }
    if (!worker) return Promise.resolve(null);
    return new Promise(resolve => {
        worker.onmessage = e => {
            if (e.data.progress !== undefined) { $('progress').value = e.data.progress; return; }
            resolve(e.data);
        };
        worker.onerror = e => { e.preventDefault(); worker = false; resolve(null); };
        worker.postMessage(message, message.bytes ? [message.bytes.buffer] : []);
    });
}
// Hands a worker's bake to fresnel: its folder (written under `tag`), or its error.
function handBake(r, name, tag, provisional) {
    const baked = (folder, error) =>
        M.ccall('fresnel_baked', null, ['number', 'string', 'string', 'number'], [app, folder, error, provisional ? 1 : 0]);
    if (!r) return baked('', 'the bake worker did not start');
    if (r.error) return baked('', r.error.replace(/^[^:]*: /, ''));
    const dir = writeFiles(r.files.map(f => ({ name: `${name}.${tag}/${f.name}`, bytes: f.bytes })));
    baked(`${dir}/${name}.${tag}`, '');
}
// The full bake that replaces the first frame's quick one (a promise while it runs; see below).
let refining = null;
// The quick bake started before the model loads (bakeEarly): { source, bake (its promise) }.
let early = null;
// Starts the first frame's quick bake of `source` (studio, or a panorama in the page's file system:
// what fresnel_pending_bake will name) in the worker while the model loads on the page's thread.
function bakeEarly(source) {
    const bytes = source === 'studio' ? null : M.FS.readFile(source).slice();
    early = { source, bake: bakeInWorker({ name: source.split('/').pop(), bytes, ...QUICK_BAKE }) };
}
// The quick bake of the first frame: small cube faces and few samples (a tenth of the full bake's
// time natively), so that the page shows the model lit by its environment seconds sooner.
const QUICK_BAKE = { size: 32, samples: 64, quick: true };
// Bakes what the next frame needs in the worker (if anything), and hands the result to fresnel.
// The page's first frame is lit by a quick bake while the full one runs; it is drawn again when
// the full bake arrives (`refining`, which main() waits for before window.fresnelReady).
async function ensureLighting() {
    const pending = M.UTF8ToString(M._fresnel_pending_bake(app));
    if (!pending) return;
    const [source, size, samples] = pending.split('\n');
    status('baking the environment…');
    $('progress').hidden = false;
    $('progress').value = 0;
    const bytes = source === 'studio' ? null : M.FS.readFile(source).slice();
    const name = source.split('/').pop();
    const t = performance.now();
    const full = { name, bytes, size: Number(size), samples: Number(samples) };
    if (!window.fresnelReady && !refining && full.size > QUICK_BAKE.size) {
        const quick = await (early && early.source === source ? early.bake : bakeInWorker({ name, bytes: bytes && bytes.slice(), ...QUICK_BAKE }));
        if (quick && !quick.error) {
            handBake(quick, name, 'quick', true);
            console.log(`environment: quick bake in the worker ${Math.round(performance.now() - t)} ms`);
            refining = bakeInWorker(full).then(r => {
                handBake(r, name, 'baked', false);
                console.log(`environment baked in the worker: ${Math.round(performance.now() - t)} ms`);
                refining = null;
            });
            return;
        }
    }
    handBake(await bakeInWorker(full), name, 'baked', false);
    console.log(`environment baked in the worker: ${Math.round(performance.now() - t)} ms`);
}
// After the first frame: waits for the full bake (when the first frame had the quick one) and
// draws with it. window.fresnelFirstFrame: ms from navigation to the first frame.
async function refineFirstFrame() {
    window.fresnelFirstFrame = Math.round(performance.now());
    if (!refining) return;
    status('refining the environment…');
    await refining;
    try {
        drawNow();
    } catch (e) {
        showError(e.message);
    }
}
// Lets the page paint (status, progress) before a long synchronous step.
const paint = () => new Promise(r => requestAnimationFrame(() => setTimeout(r, 0)));
// Draws after the environment (if it is new) has baked; errors go to the page.
async function draw() {
    try {
        await ensureLighting();
        status('drawing…');
        await paint();
        drawNow();
        showError('');
        status('ready');
    } catch (e) {
        showError(e.message);
        status('error (the last good scene and environment stay)');
        try { drawNow(); } catch (e2) { /* nothing drawable yet */ }
    } finally {
        $('progress').hidden = true;
    }
}
function scheduleDraw() {
    if (drawPending) return;
    drawPending = true;
    requestAnimationFrame(() => {
        drawPending = false;
        try { drawNow(); } catch (e) { showError(e.message); }
    });
}

// Opens picked or dropped files: the model among them (its .bin and textures beside it),
// or the environment. Throws (and shows) the loader's message; what was shown stays.
async function openFiles(files) {
    try {
        await openFilesOrThrow(files);
    } catch (e) {
        showError(e.message);
        status('error (the last good scene and environment stay)');
        throw e;
    }
}
async function openFilesOrThrow(files) {
    const scene = files.find(f => isScene(f.name));
    if (scene) return openSceneFiles(scene, files);
    const manifest = files.find(f => isBakeManifest(f.name));
    if (manifest && !files.some(f => isModel(f.name))) {  // a folder written by `fresnel bake`
        const dir = writeFiles(files);
        set('env', join(dir, dirName(manifest.name)) || dir);
        await draw();
        syncPanel();
        if (!$('error').hidden) throw new Error($('error').textContent);
        return;
    }
    const model = files.find(f => isModel(f.name)), env = files.find(f => isEnv(f.name));
    if (!model && !env) throw new Error(`${files.map(f => f.name).join(', ')}: not a .glb, .gltf, .hdr, .exr, scene (.json) file or bake folder`);
    const dir = writeFiles(files);
    if (model) {
        status(`loading ${model.name}…`);
        await paint();
        if (!M.ccall('fresnel_open', 'number', ['number', 'string'], [app, `${dir}/${model.name}`]))
            throw new Error(lastError());
        $('warnings').textContent = plain(M.UTF8ToString(M._fresnel_warnings(app)));
        $('warnings').hidden = !$('warnings').textContent;
    }
    if (env) set('env', `${dir}/${env.name}`);
    await draw();
    syncPanel();
    if (model) play(true);  // an animated model plays as it opens
    if (!$('error').hidden) throw new Error($('error').textContent);
}
// A scene file among picked or dropped files (a folder, or the files it names picked with it):
// every file is written at its place under a fresh folder; a file the scene names but that
// was picked without its folder is found by its name (and its neighbours put beside it).
async function openSceneFiles(scene, files) {
    const dir = writeFiles(files);
    let doc = null;
    try { doc = JSON.parse(new TextDecoder().decode(scene.bytes)); } catch (e) { /* the parser says why */ }
    const { models, env } = sceneReferences(doc);
    const sceneDir = join(dir, dirName(scene.name));
    const others = files.filter(f => f !== scene);
    for (const ref of models) {
        const path = join(sceneDir, ref);
        if (exists(path)) continue;
        for (const f of others) if (!exists(join(dirName(path), baseName(f.name)))) writeFile(join(dirName(path), baseName(f.name)), f.bytes);
    }
    if (env) {
        const path = join(sceneDir, env);
        if (!exists(path)) {
            if (isEnv(env)) { const f = others.find(f => baseName(f.name) === baseName(env)); if (f) writeFile(path, f.bytes); }
            else for (const f of others) if (/\.(ktx2|json)$/i.test(f.name)) writeFile(join(path, baseName(f.name)), f.bytes);
        }
    }
    await openScenePath(join(dir, scene.name));
}
// Loads the scene file at `path` (in the page's file system) and draws it.
async function openScenePath(path, afterOpen) {
    fitWindow = false;  // the scene file's size
    canvas.classList.remove('fit');
    status(`loading ${baseName(path)}…`);
    await paint();
    if (!M.ccall('fresnel_open_scene', 'number', ['number', 'string'], [app, path])) throw new Error(lastError());
    if (afterOpen) afterOpen();
    $('warnings').textContent = plain(M.UTF8ToString(M._fresnel_warnings(app)));
    $('warnings').hidden = !$('warnings').textContent;
    await draw();
    syncPanel();
    if (!$('error').hidden) throw new Error($('error').textContent);
}
// A scene file by URL (same origin): it and the files it names, fetched beside it (a .gltf with
// its buffers and images; a bake folder by its manifest's "files").
async function fetchScene(url) {
    const abs = new URL(url, location.href);
    const name = decodeURIComponent(abs.pathname.split('/').pop());
    const bytes = await fetchBytes(abs.href);
    const dir = writeFiles([{ name, bytes }]);
    let doc = null;
    try { doc = JSON.parse(new TextDecoder().decode(bytes)); } catch (e) { return `${dir}/${name}`; }  // the parser says why
    const { models, env } = sceneReferences(doc);
    const safe = ref => !ref.startsWith('/') && !ref.split('/').includes('..') && !/^[a-z][a-z0-9+.-]*:/i.test(ref);
    for (const ref of models.filter(safe)) {
        try {
            for (const f of await fetchFiles(new URL(ref, abs).href)) writeFile(join(dir, join(dirName(ref), f.name)), f.bytes);
        } catch (e) { /* the parser names the missing file */ }
    }
    if (env && safe(env)) {
        try {
            if (isEnv(env)) writeFile(join(dir, env), await fetchBytes(new URL(env, abs).href));
            else await fetchBakeFolder(new URL(env, abs).href, join(dir, env));
        } catch (e) { /* the parser names the missing file */ }
    }
    return `${dir}/${name}`;
}
// A `fresnel bake` folder by URL: its manifest and the files the manifest lists (previews left
// out), written into the folder `into`; returns `into`.
async function fetchBakeFolder(url, into) {
    const folder = new URL(url.replace(/\/?$/, '/'), location.href);
    const manifest = await fetchBytes(new URL('manifest.json', folder).href);
    writeFile(join(into, 'manifest.json'), manifest);
    let listed = [];
    try { listed = JSON.parse(new TextDecoder().decode(manifest)).files || []; } catch (e) { /* load_baked says why */ }
    const safe = f => typeof f === 'string' && !f.startsWith('/') && !f.split('/').includes('..') && !f.startsWith('preview/');
    for (const f of listed.filter(safe))
        try { writeFile(join(into, f), await fetchBytes(new URL(f, folder).href)); } catch (e) { /* reported on load */ }
    return into;
}
// An environment by URL: a panorama, or a `fresnel bake` folder (a URL without .hdr/.exr); its path here.
async function fetchEnvironment(url) {
    const name = decodeURIComponent(new URL(url, location.href).pathname.replace(/\/$/, '').split('/').pop());
    if (!isEnv(name)) return fetchBakeFolder(url, `/files/${++folders}/${name || 'baked'}`);
    const dir = writeFiles(await fetchFiles(url));
    return `${dir}/${name}`;
}
async function openScene(url) {
    try {
        await openScenePath(await fetchScene(url));
    } catch (e) {
        showError(e.message);
        status('error (the last good scene and environment stay)');
        throw e;
    }
}
async function fetchBytes(url) {
    const r = await fetch(url);
    if (!r.ok) throw new Error(`${url}: HTTP ${r.status} ${r.statusText}`);
    return new Uint8Array(await r.arrayBuffer());
}
// A model or environment by URL (same origin); a .gltf brings the files its buffers and images name.
async function fetchFiles(url) {
    const name = decodeURIComponent(new URL(url, location.href).pathname.split('/').pop());
    const files = [{ name, bytes: await fetchBytes(url) }];
    if (/\.gltf$/i.test(name)) {
        let doc;
        try { doc = JSON.parse(new TextDecoder().decode(files[0].bytes)); } catch (e) { return files; }  // the loader says why
        const uris = [...(doc.buffers || []), ...(doc.images || [])].map(x => x && x.uri).filter(u => typeof u === 'string' && !u.startsWith('data:'));
        for (const u of new Set(uris)) {
            const rel = decodeURIComponent(u);
            if (rel.startsWith('/') || rel.split('/').includes('..')) continue;  // the loader refuses these
            try { files.push({ name: rel, bytes: await fetchBytes(new URL(u, new URL(url, location.href)).href) }); } catch (e) { /* reported by the loader */ }
        }
    }
    return files;
}
async function openUrl(url) { return openFiles(await fetchFiles(url)); }
// Picked files, by their path in a picked folder (webkitdirectory) or their name.
async function readPicked(list) {
    return Promise.all([...list].map(async f => ({ name: f.webkitRelativePath || f.name, bytes: new Uint8Array(await f.arrayBuffer()) })));
}
// Dropped files and folders (each file by its path under the dropped folder).
async function readDropped(dt) {
    const entries = [...dt.items].map(i => i.webkitGetAsEntry && i.webkitGetAsEntry()).filter(Boolean);
    if (!entries.some(e => e.isDirectory)) return readPicked(dt.files);
    const out = [];
    const walk = async (entry, prefix) => {
        if (entry.isFile) {
            const f = await new Promise((res, rej) => entry.file(res, rej));
            out.push({ name: prefix + f.name, bytes: new Uint8Array(await f.arrayBuffer()) });
        } else if (entry.isDirectory) {
            const reader = entry.createReader();
            for (;;) {
                const batch = await new Promise((res, rej) => reader.readEntries(res, rej));
                if (!batch.length) break;
                for (const e of batch) await walk(e, `${prefix}${entry.name}/`);
            }
        }
    };
    for (const e of entries) await walk(e, '');
    return out;
}
function screenshot() {
    canvas.toBlob(blob => {
        const a = document.createElement('a');
        a.href = URL.createObjectURL(blob);
        a.download = `fresnel-${new Date().toISOString().replace(/[:.]/g, '-')}.png`;
        a.click();
        setTimeout(() => URL.revokeObjectURL(a.href), 1000);
    }, 'image/png');
}

// Linear RGB (0..1) <-> the colour picker's sRGB hex.
const toHex = rgb => '#' + rgb.map(c => {
    c = Math.min(Math.max(c, 0), 1);
    const e = c <= 0.0031308 ? 12.92 * c : 1.055 * Math.pow(c, 1 / 2.4) - 0.055;
    return Math.round(e * 255).toString(16).padStart(2, '0');
}).join('');
const fromHex = hex => [1, 3, 5].map(i => {
    const e = parseInt(hex.substr(i, 2), 16) / 255;
    return e <= 0.04045 ? e / 12.92 : Math.pow((e + 0.055) / 1.055, 2.4);
});
const num = v => String(+Number(v).toFixed(4));
const state = () => JSON.parse(M.UTF8ToString(M._fresnel_state(app)));
const materials = () => JSON.parse(M.UTF8ToString(M._fresnel_materials(app)));
function setMaterial(index, key, value) {
    if (!M.ccall('fresnel_set_material', 'number', ['number', 'number', 'string', 'string'], [app, index, key, String(value)]))
        throw new Error(lastError());
}
// A small labelled control: a range, number, colour or checkbox input calling `change(value)`.
function field(parent, label, attrs, change) {
    const l = document.createElement('label');
    l.append(`${label} `);
    const el = document.createElement('input');
    Object.assign(el, attrs);
    l.append(el);
    const out = attrs.type === 'range' ? document.createElement('output') : null;
    if (out) { out.textContent = num(el.value); l.append(out); }
    el.addEventListener('input', () => {
        if (out) out.textContent = num(el.value);
        try { change(el.type === 'checkbox' ? el.checked : el.value); } catch (e) { showError(e.message); return; }
        scheduleDraw();
    });
    parent.append(l);
    return el;
}

// The lights of the frame: the scene's and the default pair (listed), the job's extra ones
// (--light, a scene file's "lights"; edited, removed), and the switches of the CLI's flags.
function buildLights(st) {
    const box = $('lights');
    box.textContent = '';
    $('ibl').checked = st.ibl;
    const describe = l => l.type === 'directional' ? `from azimuth ${num(l.azimuth)}, elevation ${num(l.elevation)}, ${num(l.intensity)} lux`
                                                   : `at ${l.position.map(num).join(', ')}, ${num(l.intensity)} cd`;
    const extras = st.lights.filter(l => l.origin === 'extra');
    for (const l of [...st.lights, ...st.hiddenSceneLights]) {
        const row = document.createElement('div');
        row.className = 'light' + (l.origin === 'scene-off' ? ' off' : '');
        const title = { scene: 'scene', 'scene-off': 'scene (off)', default: 'default', extra: `light ${l.index + 1}` }[l.origin];
        row.append(`${title}: ${l.type} ${l.origin === 'extra' ? '' : describe(l)}`);
        if (l.origin === 'extra') {
            const spec = () => {
                const [r, g, b] = fromHex(color.value).map(num);
                return l.type === 'directional' ? `dir:${a.value},${e.value},${i.value},${r},${g},${b}`
                                                : `point:${x.value},${y.value},${z.value},${i.value},${r},${g},${b}`;
            };
            const apply = () => set(`light:${l.index}`, spec());
            let a, e, x, y, z;
            if (l.type === 'directional') {
                a = field(row, 'azimuth', { type: 'range', min: -180, max: 180, step: 1, value: num(l.azimuth) }, apply);
                e = field(row, 'elevation', { type: 'range', min: -90, max: 90, step: 1, value: num(l.elevation) }, apply);
            } else if (l.type === 'point') {
                x = field(row, 'x', { type: 'number', step: 0.1, value: num(l.position[0]) }, apply);
                y = field(row, 'y', { type: 'number', step: 0.1, value: num(l.position[1]) }, apply);
                z = field(row, 'z', { type: 'number', step: 0.1, value: num(l.position[2]) }, apply);
            }
            let color = { value: toHex(l.color) }, i = { value: num(l.intensity) };
            if (l.type === 'directional' || l.type === 'point') {
                color = field(row, 'colour', { type: 'color', value: toHex(l.color) }, apply);
                i = field(row, l.type === 'directional' ? 'lux' : 'candela', { type: 'number', min: 0, step: 0.1, value: num(l.intensity) }, apply);
            } else {  // spot and area lights: edited as their --light text (rect:X,Y,Z,AZ,EL,W,H,NITS[,R,G,B], ...)
                const t = field(row, '--light', { type: 'text', size: 48, value: l.spec }, () => {});
                t.addEventListener('change', () => { try { set(`light:${l.index}`, t.value); } catch (err) { showError(err.message); } scheduleDraw(); });
            }
            const remove = document.createElement('button');
            remove.textContent = 'remove';
            remove.addEventListener('click', () => { try { set('light-remove', l.index); } catch (err) { showError(err.message); } draw().then(syncPanel); });
            row.append(' ', remove);
        }
        box.append(row);
    }
    $('add-dir').dataset.next = $('add-point').dataset.next = $('add-rect').dataset.next = String(extras.length);
}

// The material editor, built from the material property registry (fresnel_material_properties:
// libs/material/src/properties.cpp): the core's properties and those of the extension blocks
// the material has, and a list to add another block (with its defaults, which change nothing).
// Edits show at the next frame; revert restores the material as loaded.
let materialRegistry = null;
const materialProperties = () =>
    materialRegistry || (materialRegistry = JSON.parse(M.UTF8ToString(M._fresnel_material_properties())));
function buildMaterial(list) {
    const box = $('material-controls'), select = $('material');
    const keep = select.value;
    select.textContent = '';
    list.forEach(m => select.add(new Option(`${m.index}: ${m.name || '(unnamed)'}`, String(m.index))));
    if (list.some(m => String(m.index) === keep)) select.value = keep;
    box.textContent = '';
    const m = list.find(x => String(x.index) === select.value);
    if (!m) { box.textContent = list.length ? '' : 'no materials (the default material)'; return; }
    const registry = materialProperties();
    const put = name => value => setMaterial(m.index, name, value);
    const control = p => {
        const v = m.values[p.name];
        if (p.type === 'bool') return field(box, p.name, { type: 'checkbox', checked: v }, x => put(p.name)(x ? 'true' : 'false'));
        if (p.type === 'choice') {
            const l = document.createElement('label'), el = document.createElement('select');
            l.append(`${p.name} `, el);
            p.choices.forEach(c => el.add(new Option(c, c)));
            el.value = v;
            el.addEventListener('input', () => { try { put(p.name)(el.value); } catch (e) { showError(e.message); return; } scheduleDraw(); });
            box.append(l);
            return el;
        }
        if (p.type === 'color') {
            let alpha = null;
            const rgb = field(box, p.name, { type: 'color', value: toHex(v.slice(0, 3)) },
                              x => put(p.name)((alpha ? [...fromHex(x), alpha.value] : fromHex(x)).join(',')));
            if (p.width === 4)
                alpha = field(box, `${p.name} alpha`, { type: 'range', min: 0, max: 1, step: 0.01, value: v[3] },
                              x => put(p.name)([...fromHex(rgb.value), x].join(',')));
            return rgb;
        }
        const lo = p.sliderMin, hi = p.sliderMax;
        return field(box, p.name + (p.unit ? ` (${p.unit})` : ''),
                     { type: 'range', min: lo, max: hi, step: (hi - lo) / 200, value: v === null ? hi : v }, put(p.name));
    };
    registry.properties.filter(p => !p.block && p.name in m.values).forEach(control);
    for (const block of m.blocks) {
        const h = document.createElement('h2');
        h.textContent = block;
        box.append(h);
        registry.properties.filter(p => p.block === block && p.name in m.values).forEach(control);
    }
    const addable = registry.blocks.filter(b => !m.blocks.includes(b.name) && registry.properties.some(p => p.block === b.name));
    if (addable.length) {
        const l = document.createElement('label'), el = document.createElement('select');
        l.append('add ', el);
        el.add(new Option('an extension…', ''));
        addable.forEach(b => el.add(new Option(`${b.name}: ${b.doc}`, b.name)));
        el.addEventListener('input', () => {
            const first = registry.properties.find(p => p.block === el.value);
            try { put(first.name)(first.default); } catch (e) { showError(e.message); return; }
            buildMaterial(materials());
            scheduleDraw();
        });
        box.append(l);
    }
}

// The panel's controls from the job (after a scene file, a model, URL parameters): each
// control names its setting (data-setting, a key of the settings registry) and shows the
// job's value in the registry's text.
function showSetting(el, value) {
    if (el.type === 'checkbox') {
        el.checked = value === 'true';
        return;
    }
    if (el.tagName === 'SELECT' && ![...el.options].some(o => o.value === value)) el.add(new Option(value, value));
    el.value = value;
    const out = el.parentElement.querySelector('output');
    if (out) out.textContent = el.dataset.unit ? `${el.value} ${el.dataset.unit}` : el.value;
}
// Animation playback: the page's clock advances the job's animation.time (the settings
// registry's; the C++ side poses the scene at it, as `fresnel render --time` does) while
// playing; the time slider scrubs, the speed may be negative, looping wraps at the end.
const playback = { playing: false, speed: 1, loop: true, last: 0, lo: 0, hi: 0, time: null };
function showPlayback() {
    $('play').textContent = playback.playing ? 'pause' : 'play';
    const t = $('anim-time');
    t.min = playback.lo;
    t.max = playback.hi;
    t.value = playback.time === null ? playback.lo : playback.time;
    t.parentElement.querySelector('output').textContent = playback.time === null ? 'rest pose'
        : `${playback.time.toFixed(3)} s of ${playback.hi.toFixed(3)} s`;
}
function buildAnimation(st) {
    const list = st.animations;
    $('animation-panel').hidden = !list.length;
    if (!list.length) { playback.playing = false; return; }
    const sel = $('animation');
    const index = st.settings['animation.index'];
    if (sel.options.length !== list.length + 1) {
        sel.replaceChildren(new Option(`all (${list.length})`, 'all'));
        list.forEach((a, i) => sel.add(new Option(`${i}: ${a.name || '(unnamed)'}`, String(i))));
    }
    sel.value = index;
    const chosen = index === 'all' ? list : [list[Number(index)]];
    playback.lo = Math.min(...chosen.map(a => a.start));
    playback.hi = Math.max(...chosen.map(a => a.end));
    const time = st.settings['animation.time'];
    playback.time = time === 'rest' ? null : Number(time);
    showPlayback();
}
function tick(now) {
    if (!playback.playing) return;
    const dt = playback.last ? (now - playback.last) / 1000 : 0;
    playback.last = now;
    const { lo, hi } = playback, length = hi - lo;
    let t = (playback.time === null ? lo : playback.time) + dt * playback.speed;
    if (t > hi || t < lo) {
        if (playback.loop && length > 0) t = lo + (((t - lo) % length) + length) % length;
        else { t = Math.min(Math.max(t, lo), hi); playback.playing = false; }
    }
    try {
        set('animation.time', t);
        playback.time = t;
        drawNow();
    } catch (e) { showError(e.message); playback.playing = false; }
    showPlayback();
    if (playback.playing) requestAnimationFrame(tick);
}
function play(on) {
    playback.playing = on && !$('animation-panel').hidden;
    playback.last = 0;
    if (playback.playing) {
        if (playback.time === null || playback.time >= playback.hi || playback.time < playback.lo) playback.time = playback.lo;
        requestAnimationFrame(tick);
    }
    showPlayback();
}

// Environment presets: the built-in studio and every environment opened on this page, each a
// button with its picture (fresnel_env_thumbnail: the panorama box-filtered, exposed, tone
// mapped); a click makes it the environment.
const envPresets = ['studio'];
function rememberEnvironment(path) {
    if (path && !envPresets.includes(path) && /\.(hdr|exr)$/i.test(path)) envPresets.push(path);
}
function buildEnvPresets(st) {
    const box = $('env-presets');
    const current = st.environment;
    for (const preset of envPresets) {
        let b = [...box.children].find(c => c.dataset.preset === preset);
        if (!b) {
            b = document.createElement('button');
            b.dataset.preset = preset;
            const c = document.createElement('canvas');
            c.width = 96;
            c.height = 48;
            const ptr = M.ccall('fresnel_env_thumbnail', 'number', ['number', 'string', 'number'], [app, preset, 96]);
            if (ptr) c.getContext('2d').putImageData(new ImageData(new Uint8ClampedArray(M.HEAPU8.buffer, ptr, 96 * 48 * 4).slice(), 96, 48), 0, 0);
            b.append(c, preset === 'studio' ? 'studio' : baseName(preset));
            b.title = preset === 'studio' ? 'the built-in studio' : plain(preset);
            b.addEventListener('click', async () => {
                try { set('env', preset); } catch (e) { showError(e.message); return; }
                await draw();
                syncPanel();
            });
            box.append(b);
        }
        b.classList.toggle('current', current === preset);
    }
}

// The file's parts that can be switched off (skinning, morphing, occlusion, material extensions):
// a checkbox each, setting the registry's `disable` list (the model loads again without them).
function buildFeatures(st) {
    $('features-panel').hidden = !st.features.length;
    const box = $('features');
    box.replaceChildren();
    for (const f of st.features) {
        const label = document.createElement('label');
        const input = document.createElement('input');
        input.type = 'checkbox';
        input.checked = f.on;
        input.dataset.feature = f.name;
        input.addEventListener('input', async () => {
            const off = [...box.querySelectorAll('input')].filter(i => !i.checked).map(i => i.dataset.feature);
            try { set('disable', off.length ? off.join(',') : 'none'); } catch (e) { showError(e.message); }
            await draw();
            syncPanel();
        });
        label.append(input, ` ${f.name.replace(/^KHR_materials_/, '')}`);
        label.title = f.name;
        box.append(label);
    }
}

function syncPanel() {
    const st = state();
    rememberEnvironment(st.environment);
    buildEnvPresets(st);
    buildAnimation(st);
    buildFeatures(st);
    $('variant-label').hidden = !st.variants.length;
    // The file's cameras, and the orbit camera.
    $('camera-label').hidden = !st.cameras.length;
    if (st.cameras.length && $('camera-select').options.length !== st.cameras.length + 1) {
        $('camera-select').replaceChildren(new Option('orbit camera', 'orbit'));
        st.cameras.forEach((name, i) => $('camera-select').add(new Option(`${i}: ${name}`, String(i))));
        showSetting($('camera-select'), st.settings['camera.index']);
    }
    if (st.variants.length && $('variant').options.length !== st.variants.length + 1) {
        $('variant').replaceChildren(new Option('(default materials)', ''));
        for (const v of st.variants) $('variant').add(new Option(v, v));
    }
    for (const el of document.querySelectorAll('#panel [data-setting]')) showSetting(el, st.settings[el.dataset.setting]);
    for (const term of st.settings['render.brdf'].split(',')) {
        const [key, value] = term.split('=');
        if ($(`brdf-${key}`)) showSetting($(`brdf-${key}`), value);
    }
    buildLights(st);
    buildMaterial(materials());
}

function bindPanel() {
    // Every control that names a setting takes its range (sliders), its choices (empty
    // drop-downs) and its doc (tooltip) from the settings registry, and sets it by its key.
    for (const el of document.querySelectorAll('#panel [data-setting]')) {
        const s = registry().find(r => r.key === el.dataset.setting);
        if (!s) continue;
        el.title = s.doc;
        if (el.type === 'range') {
            el.min = s.sliderMin;
            el.max = s.sliderMax;
            el.step = s.type === 'int' ? 1 : (s.sliderMax - s.sliderMin) / 160;
            el.dataset.unit = s.unit === 'degrees' ? '°' : s.unit;
        }
        // (Less the choices the registry does not offer the page: --ao baked needs the tracer.)
        const offered = c => !s.choicesNotOffered.some(x => x.choice === c && x.frontEnds.includes('web'));
        if (el.tagName === 'SELECT' && !el.options.length) for (const c of s.choices.filter(offered)) el.add(new Option(c, c));
        showSetting(el, s.default);
        el.addEventListener('input', async () => {
            if (el.type !== 'checkbox') showSetting(el, el.value);
            try { set(s.key, el.type === 'checkbox' ? String(el.checked) : el.value); } catch (e) { showError(e.message); return; }
            if (el.type === 'checkbox' || s.key === 'background') {
                await draw();
                syncPanel();
            } else {
                scheduleDraw();
            }
        });
    }
    for (const key of ['D', 'G', 'F', 'diffuse']) {
        const el = $(`brdf-${key}`);
        for (const n of M.UTF8ToString(M.ccall('fresnel_brdf_names', 'number', ['number', 'string'], [app, key])).split(' ')) el.add(new Option(n, n));
        el.addEventListener('input', () => {
            const terms = ['D', 'G', 'F', 'diffuse'].map(k => `${k}=${$(`brdf-${k}`).value}`).join(',');
            try { set('brdf', terms); } catch (e) { showError(e.message); return; }
            scheduleDraw();
        });
    }
    const toggle = (id, apply) => $(id).addEventListener('input', async () => {
        try { apply($(id).checked); } catch (e) { showError(e.message); }
        await draw();
        syncPanel();
    });
    toggle('ibl', on => set('no-ibl', on ? 0 : 1));
    const add = spec => async () => {
        try { set(`light:${$('add-dir').dataset.next || 0}`, spec); } catch (e) { showError(e.message); }
        await draw();
        syncPanel();
    };
    $('add-dir').addEventListener('click', add('dir:30,45,3'));
    $('add-point').addEventListener('click', add('point:0,1,1,5'));
    $('add-rect').addEventListener('click', add('rect:0,1.5,1.5,0,45,1,1,5'));
    $('play').addEventListener('click', () => play(!playback.playing));
    $('rest-pose').addEventListener('click', async () => {
        play(false);
        try { set('animation.time', 'rest'); set('animation.index', 'all'); } catch (e) { showError(e.message); }
        await draw();
        syncPanel();
    });
    $('loop').addEventListener('input', () => { playback.loop = $('loop').checked; });
    $('anim-speed').addEventListener('input', () => {
        playback.speed = Number($('anim-speed').value);
        $('anim-speed').parentElement.querySelector('output').textContent = `${playback.speed}×`;
    });
    $('anim-time').addEventListener('input', () => {  // scrubbing; playing goes on from there
        try { set('animation.time', $('anim-time').value); } catch (e) { showError(e.message); return; }
        playback.time = Number($('anim-time').value);
        showPlayback();
        scheduleDraw();
    });
    $('animation').addEventListener('input', async () => {
        try {
            set('animation.index', $('animation').value);
            buildAnimation(state());
            if (playback.playing || playback.time === null) set('animation.time', playback.lo);
            else set('animation.time', Math.min(Math.max(playback.time, playback.lo), playback.hi));
        } catch (e) { showError(e.message); }
        await draw();
        syncPanel();
    });
    canvas.addEventListener('keydown', e => { if (e.key === ' ') { e.preventDefault(); play(!playback.playing); } });
    $('material').addEventListener('input', () => buildMaterial(materials()));
    $('material-revert').addEventListener('click', () => {
        try { setMaterial(Number($('material').value), 'reset', ''); } catch (e) { showError(e.message); }
        buildMaterial(materials());
        scheduleDraw();
    });
    // One way in: files (a model with its files, an environment, a scene file with its files, a
    // bake folder's files) or a folder; openFiles tells them apart.
    for (const id of ['open-files', 'open-folder'])
        $(id).addEventListener('change', async e => {
            try { await openFiles(await readPicked(e.target.files)); } catch (err) { showError(err.message); }
            e.target.value = '';
        });
    $('open').addEventListener('click', () => $('open-files').click());
    $('open-dir').addEventListener('click', () => $('open-folder').click());
    $('screenshot').addEventListener('click', screenshot);
    $('frame-all').addEventListener('click', () => { M._fresnel_frame_all(app); scheduleDraw(); });

    // Orbit (left drag), pan (right or middle drag, shift + left), dolly (wheel, pinch).
    const pointers = new Map();
    let pinch = 0;
    canvas.addEventListener('contextmenu', e => e.preventDefault());
    canvas.addEventListener('pointerdown', e => { canvas.setPointerCapture(e.pointerId); pointers.set(e.pointerId, { x: e.clientX, y: e.clientY, button: e.button, shift: e.shiftKey }); });
    const end = e => { pointers.delete(e.pointerId); pinch = 0; };
    canvas.addEventListener('pointerup', end);
    canvas.addEventListener('pointercancel', end);
    canvas.addEventListener('pointermove', e => {
        const p = pointers.get(e.pointerId);
        if (!p) return;
        const scale = canvas.width / canvas.getBoundingClientRect().width;  // CSS pixels to framebuffer pixels
        const dx = (e.clientX - p.x) * scale, dy = (e.clientY - p.y) * scale;
        p.x = e.clientX; p.y = e.clientY;
        if (pointers.size === 2) {  // pinch: dolly by the change of the fingers' distance
            const [a, b] = [...pointers.values()];
            const d = Math.hypot(a.x - b.x, a.y - b.y);
            if (pinch) M._fresnel_dolly(app, (d - pinch) / 40);
            pinch = d;
        } else if (p.button === 2 || p.button === 1 || p.shift) M._fresnel_pan(app, dx, dy);
        else M._fresnel_orbit(app, dx, dy);
        scheduleDraw();
    });
    canvas.addEventListener('wheel', e => { e.preventDefault(); M._fresnel_dolly(app, -Math.sign(e.deltaY)); scheduleDraw(); }, { passive: false });
    const view = $('view');
    new ResizeObserver(fitCanvas).observe(view);
    view.addEventListener('dragover', e => { e.preventDefault(); view.classList.add('dragging'); });
    view.addEventListener('dragleave', () => view.classList.remove('dragging'));
    view.addEventListener('drop', async e => {
        e.preventDefault();
        view.classList.remove('dragging');
        try { await openFiles(await readDropped(e.dataTransfer)); } catch (err) { showError(err.message); }
    });
}

async function main() {
    if (typeof createFresnel !== 'function') fail('fresnel.js did not load');
    M = await createFresnel({
        print: t => console.log(t), printErr: t => console.warn(t),
        onBakeProgress: f => { $('progress').value = f; },
    });
    app = M.ccall('fresnel_create', 'number', ['string'], ['#canvas']);
    const err = lastError();
    if (err && !document.createElement('canvas').getContext('webgl2')) {  // say what to do, not only what failed
        $('no-webgl').hidden = false;
        $('no-webgl-reason').textContent = `(${err})`;
    }
    $('gl-info').textContent = M.UTF8ToString(M._fresnel_info(app));
    const gl = canvas.getContext('webgl2'), dbg = gl && gl.getExtension('WEBGL_debug_renderer_info');
    if (dbg) $('gl-info').textContent += ` | ${gl.getParameter(dbg.UNMASKED_RENDERER_WEBGL)}`;
    if (err) fail(err);
    try {
        for (const [key, value] of urlSettings()) set(key, value);
    } catch (e) { fail(e.message); }
    // The CLI's light flags (--light replaces a scene file's lights, as on the command line).
    const lightParams = () => {
        const lights = params.getAll('light');
        if (lights.length) set('lights-clear', '');
        lights.forEach((spec, i) => set(`light:${i}`, spec));
        if (params.has('no-ibl')) set('no-ibl', 1);
    };
    try { lightParams(); } catch (e) { fail(e.message); }
    bindPanel();
    fitCanvas();
    const redraw = async () => { await draw(); syncPanel(); };
    window.fresnel = { set: (k, v) => { set(k, v); return redraw(); }, openFiles, openUrl, openScene, draw, drawNow, screenshot,
                       state, materials, materialProperties, setMaterial: (i, k, v) => { setMaterial(i, k, v); return draw(); },
                       addLight: spec => { set(`light:${state().lights.filter(l => l.origin === 'extra').length}`, spec); return redraw(); },
                       removeLight: i => { set('light-remove', i); return redraw(); },
                       frames: () => frames, error: () => ($('error').hidden ? '' : $('error').textContent),
                       // The settings registry (key, flag, type, default, example, doc, ...), and a
                       // setting changed without drawing (tests set many at once).
                       settings: registry,
                       // Animation playback (play(true|false), and its state: playing, time, range).
                       play, playback: () => ({ ...playback }),
                       setOnly: (k, v) => set(k, v) };
    if (params.has('scene')) {  // a scene file: read as `fresnel render SCENE` reads it, then the other parameters as flags
        try {
            status('loading the scene file…');
            const path = await fetchScene(params.get('scene'));
            let env = null;  // ?env= overrides the file's environment, as --env does
            if (params.has('env')) env = /^(studio|none|auto)$|^color:/.test(params.get('env')) ? params.get('env') : await fetchEnvironment(params.get('env'));
            await openScenePath(path, () => {
                if (env) set('env', env);
                for (const [key, value] of urlSettings()) set(key, value);
                lightParams();
            });
            await refineFirstFrame();
        } catch (e) {
            fail(e.message);
        }
        status('ready');
        requestAnimationFrame(() => { window.fresnelReady = true; });
        return;
    }
    try {
        if (params.has('env') && /^(studio|none|auto)$|^color:/.test(params.get('env'))) set('env', params.get('env'));
        else if (params.has('env')) {
            status('loading the environment…');
            const path = await fetchEnvironment(params.get('env'));
            set('env', path);
            if (isEnv(path)) bakeEarly(path);
        }
        if (!params.has('env') || /^(studio|auto)$/.test(params.get('env'))) bakeEarly('studio');
        let model = params.get('model');
        if (model === null) model = (await fetch(DEFAULT_MODEL, { method: 'HEAD' }).then(r => r.ok, () => false)) ? DEFAULT_MODEL : '';
        status('loading the model…');
        if (model) {
            const files = await fetchFiles(model);
            const dir = writeFiles(files);
            if (!M.ccall('fresnel_open', 'number', ['number', 'string'], [app, `${dir}/${files[0].name}`])) fail(lastError());
        } else if (!M.ccall('fresnel_open', 'number', ['number', 'string'], [app, ''])) fail(lastError());  // the built-in demo
        // A model opens at its rest pose: ?time= and ?animation= apply to it.
        for (const [key, value] of urlSettings()) if (key.startsWith('animation.')) set(key, value);
        $('warnings').textContent = plain(M.UTF8ToString(M._fresnel_warnings(app)));
        $('warnings').hidden = !$('warnings').textContent;
        await ensureLighting();
        status('drawing…');
        await paint();
        drawNow();
        $('progress').hidden = true;
        syncPanel();
        await refineFirstFrame();
        // An animated model plays as it opens (as in other glTF viewers), unless ?time= asked for a pose.
        if (!params.has('time') && !params.has('animation.time')) play(true);
    } catch (e) {
        fail(e.message);
    }
    status('ready');
    requestAnimationFrame(() => { window.fresnelReady = true; });
}
main().catch(e => { if (!window.fresnelError) { window.fresnelError = String(e && e.message || e); showError(window.fresnelError); } });
})();
