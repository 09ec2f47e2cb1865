// The page's environment bakes, off its thread: the same fresnel.wasm in a Web Worker bakes a
// panorama (or the studio) as load_lighting() would and hands back the baked folder's files
// (manifest.json, *.ktx2, irradiance_sh.json), which the page loads with load_baked().
// Messages in: { name, bytes (null: the studio), size, samples, quick (the first frame's bake:
// fewer irradiance and table samples too) }; out: { progress } while
// baking, then { files: [{ name, bytes }] } or { error }.
'use strict';
importScripts('fresnel.js');
const ready = createFresnel({
    print: t => console.log(t), printErr: t => console.warn(t),
    onBakeProgress: f => postMessage({ progress: f }),
});
let count = 0;
onmessage = async e => {
    const M = await ready;
    const { name, bytes, size, samples, quick } = e.data;
    const app = M.ccall('fresnel_create', 'number', ['string'], ['']);
    try {
        let source = 'studio';
        const dir = `/files/w${++count}`, out = `${dir}/baked`;
        M.FS.mkdirTree(dir);
        if (bytes) {
            source = `${dir}/${name}`;
            M.FS.writeFile(source, bytes);
        }
        if (!M.ccall('fresnel_bake', 'number', ['number', 'string', 'string', 'number', 'number', 'number'],
                     [app, source, out, size, samples, quick ? 1 : 0]))
            throw new Error(M.UTF8ToString(M._fresnel_error(app)).replace(/\/files\/w\d+\//g, ''));
        const files = M.FS.readdir(out).filter(n => n !== '.' && n !== '..').map(n => ({ name: n, bytes: M.FS.readFile(`${out}/${n}`) }));
        M.FS.unlink && files.forEach(f => M.FS.unlink(`${out}/${f.name}`));
        postMessage({ files }, files.map(f => f.bytes.buffer));
    } catch (err) {
        postMessage({ error: String(err && err.message || err) });
    } finally {
        M._fresnel_destroy(app);
    }
};
