// Shared by tests/web/web_page_test.mjs and bench/web_bench.mjs: a static server for the web
// build (and the shared assets under /assets/), and Debian's Chromium through playwright-core
// (the driver only; never a downloaded browser) with WebGL 2 on SwiftShader, as
// ../shared/tools/khronos-ref runs it.
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import { createRequire } from 'node:module';

export const chromiumPath = process.env.CHROMIUM_PATH || '/usr/bin/chromium';

// playwright-core's chromium from NODE_TOOLS_DIR (scripts/install-test-tools.sh), or null.
export function loadChromium(nodeTools) {
    try {
        return createRequire(path.resolve(nodeTools, 'package.json'))('playwright-core').chromium;
    } catch (e) {
        return null;
    }
}

const TYPES = { '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.css': 'text/css',
                '.wasm': 'application/wasm', '.json': 'application/json', '.png': 'image/png' };

// Serves webDir at / and assetsDir at /assets/ on 127.0.0.1 (a free port), and each folder of
// `mounts` ({ '/test/': dir }) at its prefix; resolves to { base, close() }.
export async function serve(webDir, assetsDir, mounts = {}) {
    const roots = Object.entries({ ...mounts, ...(assetsDir ? { '/assets/': assetsDir } : {}) });
    const server = http.createServer((req, res) => {
        const url = decodeURIComponent(new URL(req.url, 'http://x').pathname);
        const [prefix, dir] = roots.find(([p]) => url.startsWith(p)) || ['/', webDir];
        const root = path.resolve(dir);
        const file = path.resolve(root, url.slice(prefix.length) || 'index.html');
        if (!file.startsWith(root + path.sep) || !fs.existsSync(file) || !fs.statSync(file).isFile()) {
            res.writeHead(404);
            res.end('not found');
            return;
        }
        res.writeHead(200, { 'Content-Type': TYPES[path.extname(file)] || 'application/octet-stream' });
        fs.createReadStream(file).pipe(res);
    });
    await new Promise(r => server.listen(0, '127.0.0.1', r));
    return { base: `http://127.0.0.1:${server.address().port}`, close: () => server.close() };
}

export function launch(chromium) {
    return chromium.launch({
        executablePath: chromiumPath, headless: true,
        args: ['--no-sandbox', '--use-gl=angle', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
               '--disable-gpu-watchdog', '--force-color-profile=srgb', '--disable-background-networking',
               '--disable-component-update', '--no-first-run'],
    });
}

// Opens the page with `query`, waits for window.fresnelReady or window.fresnelError; resolves to
// { ms (navigation to the first frame), error }.
export async function openPage(page, base, query, timeout = 300000) {
    const t = Date.now();
    await page.goto(base + '/' + query);
    await page.waitForFunction(() => window.fresnelReady || window.fresnelError, null, { timeout, polling: 50 });
    return { ms: Date.now() - t, error: await page.evaluate(() => window.fresnelError || '') };
}
