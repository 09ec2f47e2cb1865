// The reference decode of a KTX2 file by the Basis Universal transcoder that npm's `three`
// package ships (examples/jsm/libs/basis/basis_transcoder.{js,wasm}), run under Node: what
// libs/core/tests/ktx2_test.cpp holds fresnel's own transcoders to, value for value.
//   node basis_reference.cjs NODE_MODULES_DIR in.ktx2 OUT_PREFIX
// Writes OUT_PREFIX_L<level>.rgba (RGBA8) or .rgbah (RGBA half floats, an HDR file) for every
// level (layer 0, face 0) and prints a JSON line describing the file.
const fs = require('fs');
const path = require('path');
const [modules, input, outPrefix] = process.argv.slice(2);
const dir = path.join(modules, 'three', 'examples', 'jsm', 'libs', 'basis');
const source = path.join(dir, 'basis_transcoder.js');
// The transcoder's script declares `var BASIS` for a browser worker; evaluate it as a function
// body that returns it (three's package is an ES module package, so require() does not take it).
const BASIS = new Function('module', 'exports', 'require', '__filename', '__dirname',
                           fs.readFileSync(source, 'utf8') + '\nreturn BASIS;')({}, undefined, require, source, dir);
BASIS({ wasmBinary: fs.readFileSync(path.join(dir, 'basis_transcoder.wasm')) }).then((M) => {
  M.initializeBasis();
  const file = new M.KTX2File(new Uint8Array(fs.readFileSync(input)));
  if (!file.isValid()) throw new Error(`${input}: not a valid KTX2 file for the transcoder`);
  const hdr = file.isHDR ? file.isHDR() : false;
  const format = hdr ? 25 : 13;  // cTFRGBA_HALF : cTFRGBA32
  if (!file.startTranscoding()) throw new Error(`${input}: startTranscoding failed`);
  const levels = [];
  for (let level = 0; level < file.getLevels(); ++level) {
    const info = file.getImageLevelInfo(level, 0, 0);
    const out = new Uint8Array(file.getImageTranscodedSizeInBytes(level, 0, 0, format));
    if (!file.transcodeImage(out, level, 0, 0, format, 0, -1, -1)) throw new Error(`${input}: level ${level} failed`);
    const name = `${outPrefix}_L${level}.${hdr ? 'rgbah' : 'rgba'}`;
    fs.writeFileSync(name, out);
    levels.push({ level, width: info.origWidth, height: info.origHeight, file: name });
  }
  console.log(JSON.stringify({ width: file.getWidth(), height: file.getHeight(), hdr, levels }));
  file.close();
  file.delete();
});
