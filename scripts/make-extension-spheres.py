#!/usr/bin/python3
"""Writes the material-extension test scenes: one UV sphere per .gltf (embedded buffer and
PNG textures, TEXCOORD_0 and TANGENT along the parallels), each with one material that uses
KHR_materials_sheen, _anisotropy, _iridescence or _diffuse_transmission (one of them also with a
directional light).

Usage: make-extension-spheres.py OUT_DIR [NAME ...]   (no names: every scene)

tests/extensions/README.md says how the Khronos references were made from them; the
extension_fidelity_test renders them with fresnel and compares."""
import base64, json, math, os, struct, sys, zlib

SEG = 64


def png(width, height, pixel):
    """An 8-bit RGBA PNG; pixel(x, y) -> (r, g, b, a) in 0..255."""
    raw = b''.join(b'\0' + bytes(c for x in range(width) for c in pixel(x, y)) for y in range(height))
    def chunk(kind, data):
        return struct.pack('>I', len(data)) + kind + data + struct.pack('>I', zlib.crc32(kind + data) & 0xffffffff)
    return (b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', width, height, 8, 6, 0, 0, 0)) +
            chunk(b'IDAT', zlib.compress(raw, 9)) + chunk(b'IEND', b''))


def stripes(x, y):  # sheen colour (RGB, sRGB): bands along u
    return [(255, 200, 120), (120, 255, 160), (200, 160, 255)][(x // 8) % 3] + (255,)


def ramp(x, y):  # sheen roughness (A, linear): a ramp along v. Its own image: a renderer may
    # upload an image once, in one colour space, when two slots of different spaces share it.
    return (255, 255, 255, 40 + (215 * y) // 63)


def anisotropy_map(x, y):  # RG direction (tangent space, [-1,1] -> [0,255]), B strength
    a = 2.0 * math.pi * (x // 16) / 4.0
    return (int(127.5 + 127.5 * math.cos(a)), int(127.5 + 127.5 * math.sin(a)), 64 + (191 * y) // 63, 255)


def thickness_map(x, y):  # G: thickness between the minimum and the maximum
    return (0, (255 * x) // 63, 0, 255)


def primaries(x, y):  # diffuse transmission colour (RGB, sRGB): bands along u of 0 and 255 only, which
    # read the same through the sRGB curve and linearly; the Khronos renderer 1.1.0 samples this
    # slot linearly (its texture info keeps the default), where the extension says sRGB.
    return [(255, 255, 0), (0, 255, 255), (255, 0, 255), (255, 255, 255)][(x // 8) % 4] + (255,)


TEXTURES = {'stripes': stripes, 'ramp': ramp, 'anisotropy': anisotropy_map, 'thickness': thickness_map,
            'primaries': primaries}


# A directional light of 4 lux travelling towards the camera's side (+Z) and -X: the node turned
# 150 degrees about +Y (the light shines along the node's -Z).
BACKLIGHT = {'type': 'directional', 'intensity': 4.0, 'color': [1, 1, 1], 'rotation': [0.0, 0.9659258, 0.0, 0.2588190]}


def scenes():
    def mr(base, metallic, roughness):
        return {'baseColorFactor': list(base) + [1.0], 'metallicFactor': metallic, 'roughnessFactor': roughness}
    return {
        'sheen_velvet': ({'pbrMetallicRoughness': mr((0.05, 0.05, 0.3), 0.0, 0.9),
                          'extensions': {'KHR_materials_sheen': {'sheenColorFactor': [1.0, 0.5, 0.2],
                                                                 'sheenRoughnessFactor': 0.3}}}, []),
        'sheen_rough': ({'pbrMetallicRoughness': mr((0.6, 0.6, 0.6), 0.0, 0.5),
                         'extensions': {'KHR_materials_sheen': {'sheenColorFactor': [0.3, 0.9, 0.4],
                                                                'sheenRoughnessFactor': 0.8}}}, []),
        'sheen_textured': ({'pbrMetallicRoughness': mr((0.2, 0.02, 0.02), 0.0, 1.0),
                            'extensions': {'KHR_materials_sheen': {
                                'sheenColorFactor': [1.0, 1.0, 1.0], 'sheenColorTexture': {'index': 0},
                                'sheenRoughnessFactor': 1.0, 'sheenRoughnessTexture': {'index': 1}}}}, ['stripes', 'ramp']),
        # Clearcoat over sheen: the coat's Fresnel over the sheen layer over the base.
        'sheen_clearcoat': ({'pbrMetallicRoughness': mr((0.05, 0.05, 0.3), 0.0, 0.9),
                             'extensions': {'KHR_materials_sheen': {'sheenColorFactor': [1.0, 0.5, 0.2],
                                                                    'sheenRoughnessFactor': 0.3},
                                            'KHR_materials_clearcoat': {'clearcoatFactor': 1.0,
                                                                        'clearcoatRoughnessFactor': 0.1}}}, []),
        'sheen_clearcoat_rough': ({'pbrMetallicRoughness': mr((0.6, 0.6, 0.6), 0.0, 0.5),
                                   'extensions': {'KHR_materials_sheen': {'sheenColorFactor': [0.3, 0.9, 0.4],
                                                                          'sheenRoughnessFactor': 0.8},
                                                  'KHR_materials_clearcoat': {'clearcoatFactor': 0.6,
                                                                              'clearcoatRoughnessFactor': 0.4}}}, []),
        'anisotropy_metal': ({'pbrMetallicRoughness': mr((0.95, 0.9, 0.85), 1.0, 0.4),
                              'extensions': {'KHR_materials_anisotropy': {'anisotropyStrength': 0.8}}}, []),
        'anisotropy_textured': ({'pbrMetallicRoughness': mr((0.5, 0.2, 0.1), 0.0, 0.3),
                                 'extensions': {'KHR_materials_anisotropy': {
                                     'anisotropyStrength': 0.9, 'anisotropyRotation': 1.0,
                                     'anisotropyTexture': {'index': 0}}}}, ['anisotropy']),
        'iridescence_metal': ({'pbrMetallicRoughness': mr((0.9, 0.9, 0.9), 1.0, 0.2),
                               'extensions': {'KHR_materials_iridescence': {
                                   'iridescenceFactor': 1.0, 'iridescenceIor': 1.3,
                                   'iridescenceThicknessMinimum': 100, 'iridescenceThicknessMaximum': 400,
                                   'iridescenceThicknessTexture': {'index': 0}}}}, ['thickness']),
        'iridescence_dielectric': ({'pbrMetallicRoughness': mr((0.1, 0.1, 0.1), 0.0, 0.1),
                                    'extensions': {'KHR_materials_iridescence': {
                                        'iridescenceFactor': 1.0, 'iridescenceIor': 1.8,
                                        'iridescenceThicknessMaximum': 600}}}, []),
        'diffuse_transmission_leaf': ({'pbrMetallicRoughness': mr((0.2, 0.5, 0.1), 0.0, 0.6),
                                       'extensions': {'KHR_materials_diffuse_transmission': {
                                           'diffuseTransmissionFactor': 0.8,
                                           'diffuseTransmissionColorFactor': [0.4, 0.9, 0.2]}}}, []),
        'diffuse_transmission_textured': ({'pbrMetallicRoughness': mr((0.5, 0.5, 0.5), 0.0, 0.5),
                                           'extensions': {'KHR_materials_diffuse_transmission': {
                                               'diffuseTransmissionFactor': 1.0,
                                               'diffuseTransmissionTexture': {'index': 0},
                                               'diffuseTransmissionColorFactor': [1.0, 0.8, 0.6],
                                               'diffuseTransmissionColorTexture': {'index': 1}}}}, ['ramp', 'primaries']),
        # Lit from behind by a directional light (KHR_lights_punctual) as well as the environment:
        # the transmitted lobe of punctual lights. Rendered with the scene's light.
        'diffuse_transmission_backlit': ({'pbrMetallicRoughness': mr((0.5, 0.3, 0.2), 0.0, 0.5),
                                          'extensions': {'KHR_materials_diffuse_transmission': {
                                              'diffuseTransmissionFactor': 0.6,
                                              'diffuseTransmissionColorFactor': [1.0, 0.6, 0.3]}}}, [], BACKLIGHT),
        # Not tuned on (README: the "unseen" row): a weaker, reddish transmission on a blue base.
        'diffuse_transmission_unseen': ({'pbrMetallicRoughness': mr((0.1, 0.2, 0.6), 0.1, 0.3),
                                         'extensions': {'KHR_materials_diffuse_transmission': {
                                             'diffuseTransmissionFactor': 0.4,
                                             'diffuseTransmissionColorFactor': [1.0, 0.3, 0.3]}}}, []),
    }


def sphere():
    rings = SEG // 2
    pos, nor, tan, uv, idx = [], [], [], [], []
    for i in range(rings + 1):
        th = math.pi * i / rings
        for j in range(SEG + 1):
            ph = 2 * math.pi * j / SEG
            n = (math.sin(th) * math.sin(ph), math.cos(th), math.sin(th) * math.cos(ph))
            pos += n
            nor += n
            tan += (math.cos(ph), 0.0, -math.sin(ph), 1.0)
            uv += (j / SEG, i / rings)
    for i in range(rings):
        for j in range(SEG):
            a = i * (SEG + 1) + j
            b = a + SEG + 1
            idx += [a, b, a + 1, a + 1, b, b + 1]
    return pos, nor, tan, uv, idx


def write(out_dir, name, material, textures, light=None):
    pos, nor, tan, uv, idx = sphere()
    parts = [struct.pack(f'<{len(pos)}f', *pos), struct.pack(f'<{len(nor)}f', *nor),
             struct.pack(f'<{len(tan)}f', *tan), struct.pack(f'<{len(uv)}f', *uv), struct.pack(f'<{len(idx)}I', *idx)]
    views, offset = [], 0
    for k, p in enumerate(parts):
        views.append({'buffer': 0, 'byteOffset': offset, 'byteLength': len(p), 'target': 34963 if k == 4 else 34962})
        offset += len(p)
    buf = b''.join(parts)
    nv = len(pos) // 3
    used = sorted(set(material.get('extensions', {}).keys()))
    doc = {
        'asset': {'version': '2.0', 'generator': 'fresnel scripts/make-extension-spheres.py'},
        'extensionsUsed': used, 'scene': 0, 'scenes': [{'nodes': [0]}], 'nodes': [{'mesh': 0}],
        'meshes': [{'primitives': [{'attributes': {'POSITION': 0, 'NORMAL': 1, 'TANGENT': 2, 'TEXCOORD_0': 3},
                                    'indices': 4, 'material': 0}]}],
        'materials': [dict(material, name=name)],
        'buffers': [{'byteLength': len(buf), 'uri': 'data:application/octet-stream;base64,' + base64.b64encode(buf).decode()}],
        'bufferViews': views,
        'accessors': [{'bufferView': 0, 'componentType': 5126, 'count': nv, 'type': 'VEC3', 'min': [-1, -1, -1], 'max': [1, 1, 1]},
                      {'bufferView': 1, 'componentType': 5126, 'count': nv, 'type': 'VEC3'},
                      {'bufferView': 2, 'componentType': 5126, 'count': nv, 'type': 'VEC4'},
                      {'bufferView': 3, 'componentType': 5126, 'count': nv, 'type': 'VEC2'},
                      {'bufferView': 4, 'componentType': 5125, 'count': len(idx), 'type': 'SCALAR'}],
    }
    if textures:
        doc['images'] = [{'uri': 'data:image/png;base64,' + base64.b64encode(png(64, 64, TEXTURES[t])).decode()}
                         for t in textures]
        doc['samplers'] = [{'magFilter': 9729, 'minFilter': 9987, 'wrapS': 10497, 'wrapT': 10497}]
        doc['textures'] = [{'source': i, 'sampler': 0} for i in range(len(textures))]
    if light:
        doc['extensionsUsed'].append('KHR_lights_punctual')
        doc['extensions'] = {'KHR_lights_punctual': {'lights': [{k: v for k, v in light.items() if k != 'rotation'}]}}
        doc['nodes'].append({'rotation': light['rotation'], 'extensions': {'KHR_lights_punctual': {'light': 0}}})
        doc['scenes'][0]['nodes'].append(1)
    with open(os.path.join(out_dir, name + '.gltf'), 'w') as f:
        json.dump(doc, f)


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    out_dir = sys.argv[1]
    os.makedirs(out_dir, exist_ok=True)
    all_scenes = scenes()
    names = sys.argv[2:] or list(all_scenes)
    for n in names:
        if n not in all_scenes:
            sys.exit(f'make-extension-spheres.py: unknown scene {n}; known: {" ".join(all_scenes)}')
        write(out_dir, n, *all_scenes[n])


if __name__ == '__main__':
    main()
