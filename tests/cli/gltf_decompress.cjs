// Reference decoding for compressed_models_test: reads a glTF with reference decoders and
// writes it back without the compression extension, as plain (possibly quantised) accessors.
// meshopt: meshoptimizer's js/meshopt_decoder_reference.js, the extension's reference decoder
// (its filters round exactly as fresnel's libs/scene/src/meshopt_filters.cpp; the WebAssembly
// decoder rounds some 8-bit normals one step differently); Draco: Draco's JavaScript build.
// usage: node gltf_decompress.cjs NODE_MODULES_DIR IN.glb OUT.glb
const path = require('path');
const [modules, input, output] = process.argv.slice(2);
const req = (m) => require(path.resolve(modules, m));
const { NodeIO } = req('@gltf-transform/core');
const { ALL_EXTENSIONS } = req('@gltf-transform/extensions');
const draco3d = req('draco3dgltf');
(async () => {
  const { pathToFileURL } = require('url');
  const reference = path.resolve(modules, 'meshoptimizer', 'meshopt_decoder_reference.js');
  const { MeshoptDecoder } = await import(pathToFileURL(reference).href);
  await MeshoptDecoder.ready;
  const io = new NodeIO().registerExtensions(ALL_EXTENSIONS).registerDependencies({
    'meshopt.decoder': MeshoptDecoder,
    'draco3d.decoder': await draco3d.createDecoderModule(),
  });
  const doc = await io.read(input);
  for (const e of doc.getRoot().listExtensionsUsed())
    if (e.extensionName === 'EXT_meshopt_compression' || e.extensionName === 'KHR_draco_mesh_compression') e.dispose();
  await io.write(output, doc);
})().catch((e) => { console.error(e); process.exit(1); });
