// The fresnel page: the C++ renderer (fresnel.js / fresnel.wasm, apps/web/main.cpp) on a
// WebGL 2 canvas. Files (picked, dropped, or named by URL parameters from the same origin)
// are written into Emscripten's in-memory file system and loaded by the same loaders as
// `fresnel render`. URL parameters use the CLI's names and meanings:
//   ?model=URL&env=URL&yaw=DEG&pitch=DEG&size=WxH&tonemap=NAME&debug=CHANNEL&exposure=EV
//   &env-intensity=X&env-rotation=DEG&background=env|blur|transparent|R,G,B&distance=K&fov=DEG&msaa=N
// window.fresnelReady becomes true once the first complete frame of what was asked is on the
// canvas; window.fresnelError holds the message when loading failed. window.fresnel is the
// page's interface for scripts and tests (set, openFiles, openUrl, draw, screenshot).
'use strict';
(() => {
const $ = id => document.getElementById(id);
const canvas = $('canvas');
const params = new URLSearchParams(location.search);
const SETTINGS = ['size', 'yaw', 'pitch', 'distance', 'fov', 'msaa', 'anisotropy', 'tonemap', 'encoding', 'exposure',
                  'debug', 'env-intensity', 'env-rotation', 'background'];
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
function bakeInWorker(message) {
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
// Bakes what the next frame needs in the worker (if anything), and hands the result to fresnel.
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
    const r = await bakeInWorker({ name, bytes, size: Number(size), samples: Number(samples) });
    if (!r) { M.ccall('fresnel_baked', null, ['number', 'string', 'string'], [app, '', 'the bake worker did not start']); return; }
    if (r.error) { M.ccall('fresnel_baked', null, ['number', 'string', 'string'], [app, '', r.error.replace(/^[^:]*: /, '')]); return; }
    const dir = writeFiles(r.files.map(f => ({ name: `${name}.baked/${f.name}`, bytes: f.bytes })));
    M.ccall('fresnel_baked', null, ['number', 'string', 'string'], [app, `${dir}/${name}.baked`, '']);
    console.log(`environment baked in the worker: ${Math.round(performance.now() - t)} ms`);
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
    const model = files.find(f => isModel(f.name)), env = files.find(f => isEnv(f.name));
    if (!model && !env) throw new Error(`${files.map(f => f.name).join(', ')}: not a .glb, .gltf, .hdr or .exr file`);
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
    if (!$('error').hidden) throw new Error($('error').textContent);
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
async function readPicked(list) {
    return Promise.all([...list].map(async f => ({ name: f.name, bytes: new Uint8Array(await f.arrayBuffer()) })));
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

function bindPanel() {
    const control = (id, key, format) => {
        const el = $(id), out = el.parentElement.querySelector('output');
        const show = () => { if (out) out.textContent = format ? format(el.value) : el.value; };
        show();
        el.addEventListener('input', () => {
            show();
            try { set(key, el.value); } catch (e) { showError(e.message); return; }
            if (key === 'background') draw(); else scheduleDraw();
        });
    };
    const debug = $('debug');
    debug.add(new Option('none', 'none'));
    for (const n of M.UTF8ToString(M._fresnel_debug_channels(app)).split(' ')) debug.add(new Option(n, n));
    control('env-intensity', 'env-intensity');
    control('env-rotation', 'env-rotation', v => `${v}°`);
    control('background', 'background');
    control('tonemap', 'tonemap');
    control('exposure', 'exposure');
    control('debug', 'debug');
    for (const [key, id] of [['tonemap', 'tonemap'], ['debug', 'debug'], ['exposure', 'exposure'],
                             ['env-intensity', 'env-intensity'], ['env-rotation', 'env-rotation'], ['background', 'background']])
        if (params.has(key)) $(id).value = params.get(key);
    for (const el of document.querySelectorAll('#panel input[type=range]')) el.dispatchEvent(new Event('show'));
    $('model-file').addEventListener('change', async e => { try { await openFiles(await readPicked(e.target.files)); } catch (err) { showError(err.message); } });
    $('env-file').addEventListener('change', async e => { try { await openFiles(await readPicked(e.target.files)); } catch (err) { showError(err.message); } });
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
    view.addEventListener('dragover', e => { e.preventDefault(); view.classList.add('dragging'); });
    view.addEventListener('dragleave', () => view.classList.remove('dragging'));
    view.addEventListener('drop', async e => {
        e.preventDefault();
        view.classList.remove('dragging');
        try { await openFiles(await readPicked(e.dataTransfer.files)); } catch (err) { showError(err.message); }
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
    $('gl-info').textContent = M.UTF8ToString(M._fresnel_info(app));
    const gl = canvas.getContext('webgl2'), dbg = gl && gl.getExtension('WEBGL_debug_renderer_info');
    if (dbg) $('gl-info').textContent += ` | ${gl.getParameter(dbg.UNMASKED_RENDERER_WEBGL)}`;
    if (err) fail(err);
    try {
        for (const key of SETTINGS) if (params.has(key)) set(key, params.get(key));
    } catch (e) { fail(e.message); }
    bindPanel();
    window.fresnel = { set: (k, v) => { set(k, v); return draw(); }, openFiles, openUrl, draw, drawNow, screenshot,
                       frames: () => frames, error: () => ($('error').hidden ? '' : $('error').textContent) };
    try {
        if (params.has('env')) {
            status('loading the environment…');
            const dir = writeFiles(await fetchFiles(params.get('env')));
            set('env', `${dir}/${decodeURIComponent(new URL(params.get('env'), location.href).pathname.split('/').pop())}`);
        }
        let model = params.get('model');
        if (model === null) model = (await fetch(DEFAULT_MODEL, { method: 'HEAD' }).then(r => r.ok, () => false)) ? DEFAULT_MODEL : '';
        status('loading the model…');
        if (model) {
            const files = await fetchFiles(model);
            const dir = writeFiles(files);
            if (!M.ccall('fresnel_open', 'number', ['number', 'string'], [app, `${dir}/${files[0].name}`])) fail(lastError());
        } else if (!M.ccall('fresnel_open', 'number', ['number', 'string'], [app, ''])) fail(lastError());  // the built-in demo
        $('warnings').textContent = plain(M.UTF8ToString(M._fresnel_warnings(app)));
        $('warnings').hidden = !$('warnings').textContent;
        await ensureLighting();
        status('drawing…');
        await paint();
        drawNow();
        $('progress').hidden = true;
    } catch (e) {
        fail(e.message);
    }
    status('ready');
    requestAnimationFrame(() => { window.fresnelReady = true; });
}
main().catch(e => { if (!window.fresnelError) { window.fresnelError = String(e && e.message || e); showError(window.fresnelError); } });
})();
