// Reads KTX2 files with the independent npm reader `ktx-parse` and checks their
// layout. usage: node check_ktx2.mjs TOOL_DIR FILE WIDTH FACES LEVELS [FILE WIDTH FACES LEVELS ...]
import { createRequire } from 'module';
import { readFileSync } from 'fs';
import { join } from 'path';
const [toolDir, ...rest] = process.argv.slice(2);
const require = createRequire(join(toolDir, 'package.json'));
const { read } = require('ktx-parse');
let failed = false;
for (let i = 0; i < rest.length; i += 4) {
  const [file, width, faces, levels] = [rest[i], +rest[i + 1], +rest[i + 2], +rest[i + 3]];
  const c = read(new Uint8Array(readFileSync(file)));
  const problems = [];
  if (c.vkFormat !== 97) problems.push(`vkFormat ${c.vkFormat} != 97 (R16G16B16A16_SFLOAT)`);
  if (c.pixelWidth !== width) problems.push(`width ${c.pixelWidth} != ${width}`);
  if (c.faceCount !== faces) problems.push(`faceCount ${c.faceCount} != ${faces}`);
  if (c.levels.length !== levels) problems.push(`levels ${c.levels.length} != ${levels}`);
  c.levels.forEach((lv, l) => {
    const w = Math.max(1, width >> l);
    const expect = w * Math.max(1, (faces === 6 ? width : c.pixelHeight) >> l) * 8 * faces;
    if (lv.levelData.byteLength !== expect) problems.push(`level ${l}: ${lv.levelData.byteLength} bytes != ${expect}`);
  });
  const dfd = c.dataFormatDescriptor[0];
  if (!dfd || dfd.samples.length !== 4) problems.push('data format descriptor does not list 4 samples');
  console.log(`${file}: ${problems.length ? problems.join('; ') : 'ok'}`);
  failed = failed || problems.length > 0;
}
process.exit(failed ? 1 : 0);
