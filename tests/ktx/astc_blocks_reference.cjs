// The reference decode of single ASTC 4x4 blocks (UASTC HDR 4x4) by the Basis Universal
// transcoder that npm's `three` ships, run under Node: what libs/core/tests/basisu_modes_test.cpp
// holds fresnel's ASTC HDR decoder to, block by block.
//   node astc_blocks_reference.cjs NODE_MODULES_DIR blocks.bin OUT_PREFIX
// blocks.bin holds N 16-byte blocks. Each is wrapped in a 4x4 UASTC HDR KTX2 file of its own (the
// transcoder fails a whole image when one of its blocks is illegal) and transcoded to RGBA half
// floats. Writes OUT_PREFIX.rgbah (N x 16 texels x RGBA FP16, little-endian, rows top to bottom;
// zeros for a refused block) and OUT_PREFIX.valid (N bytes: 1 decoded, 0 refused), and prints a
// JSON line with the counts.
const fs = require('fs');
const path = require('path');
const [modules, input, outPrefix] = process.argv.slice(2);
if (!outPrefix) throw new Error('usage: node astc_blocks_reference.cjs NODE_MODULES_DIR blocks.bin OUT_PREFIX');
const dir = path.join(modules, 'three', 'examples', 'jsm', 'libs', 'basis');
const source = path.join(dir, 'basis_transcoder.js');
// As tests/ktx/basis_reference.cjs loads it: the script's `var BASIS`, returned from a function body.
const BASIS = new Function('module', 'exports', 'require', '__filename', '__dirname',
                           fs.readFileSync(source, 'utf8') + '\nreturn BASIS;')({}, undefined, require, source, dir);

// A KTX2 file (KTX 2.0 specification) of one 4x4 UASTC HDR 4x4 image: vkFormat 0, no
// supercompression, one level; the data format descriptor is a basic block with colour model
// 167 (KHR_DF_MODEL_UASTC_HDR_4X4), BT.709 primaries, linear transfer, a 4x4 texel block of 16
// bytes and one 128-bit sample. The block goes at byte 160 (levels align to the 16-byte block).
const kDfdOffset = 80 + 24, kDfdLength = 44, kDataOffset = 160;
const file = Buffer.alloc(kDataOffset + 16);
Buffer.from([0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32, 0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A]).copy(file, 0);
// vkFormat, typeSize, width, height, depth, layers, faces, levels, supercompression
[0, 1, 4, 4, 0, 0, 1, 1, 0].forEach((v, i) => file.writeUInt32LE(v, 12 + 4 * i));
file.writeUInt32LE(kDfdOffset, 48);
file.writeUInt32LE(kDfdLength, 52);  // key/value data and global data: none (zeros)
file.writeBigUInt64LE(BigInt(kDataOffset), 80);
file.writeBigUInt64LE(16n, 88);
file.writeBigUInt64LE(16n, 96);
const dfd = [kDfdLength, 0, (40 << 16) | 2,    // total size; vendor 0, type 0; version 2, block size 40
             167 | (1 << 8) | (1 << 16),       // model, primaries, transfer, flags 0
             3 | (3 << 8),                     // texel block 4x4 (dimensions minus one)
             16, 0,                            // bytesPlane0 = 16
             127 << 16,                        // sample: bit offset 0, 128 bits, channel 0
             0, 0, 0xFFFFFFFF];                // sample position, lower, upper
dfd.forEach((v, i) => file.writeUInt32LE(v >>> 0, kDfdOffset + 4 * i));

BASIS({ wasmBinary: fs.readFileSync(path.join(dir, 'basis_transcoder.wasm')) }).then((M) => {
  M.initializeBasis();
  const kRgbaHalf = 25;  // transcoder_texture_format cTFRGBA_HALF
  const blocks = fs.readFileSync(input);
  if (blocks.length % 16 !== 0) throw new Error(`${input}: ${blocks.length} bytes, not whole 16-byte blocks`);
  const n = blocks.length / 16;
  const out = Buffer.alloc(n * 128), valid = Buffer.alloc(n);
  const dst = new Uint8Array(128);
  let decoded = 0;
  for (let i = 0; i < n; ++i) {
    blocks.copy(file, kDataOffset, 16 * i, 16 * i + 16);
    const ktx = new M.KTX2File(new Uint8Array(file));
    if (!ktx.isValid() || !ktx.isHDR() || !ktx.startTranscoding() ||
        ktx.getImageTranscodedSizeInBytes(0, 0, 0, kRgbaHalf) !== 128)
      throw new Error('the transcoder does not take the 4x4 UASTC HDR file');
    dst.fill(0);
    if (ktx.transcodeImage(dst, 0, 0, 0, kRgbaHalf, 0, -1, -1)) {
      valid[i] = 1;
      ++decoded;
      out.set(dst, 128 * i);
    }
    ktx.close();
    ktx.delete();
  }
  fs.writeFileSync(`${outPrefix}.rgbah`, out);
  fs.writeFileSync(`${outPrefix}.valid`, valid);
  console.log(JSON.stringify({ blocks: n, valid: decoded, refused: n - decoded }));
});
