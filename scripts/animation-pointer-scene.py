#!/usr/bin/env python3
"""Writes a KHR_animation_pointer test scene: the shared Suzanne with one animation, over
0..2 s, of its base colour factor, emissive factor, roughness factor and the base colour
texture's KHR_texture_transform offset (the keyframes in a second, data-URI buffer).

    scripts/animation-pointer-scene.py OUT_DIR [SHARED_DIR]

OUT_DIR gets Suzanne_pointer.gltf plus copies of Suzanne's buffer and textures (the model
folder is not written to). Used to compare `fresnel render --time T` with the Khronos Sample
Renderer at the same times (docs in docs/shading.md, "Animation").
"""
import base64
import json
import shutil
import struct
import sys
from pathlib import Path


def main() -> int:
    if len(sys.argv) < 2:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    out = Path(sys.argv[1])
    shared = Path(sys.argv[2]) if len(sys.argv) > 2 else Path(__file__).resolve().parent.parent.parent / "shared"
    src = shared / "assets" / "models" / "Suzanne"
    if not (src / "Suzanne.gltf").is_file():
        print(f"{src / 'Suzanne.gltf'}: not found", file=sys.stderr)
        return 1
    out.mkdir(parents=True, exist_ok=True)
    doc = json.loads((src / "Suzanne.gltf").read_text())
    for f in ["Suzanne.bin", "Suzanne_BaseColor.png", "Suzanne_MetallicRoughness.png"]:
        shutil.copyfile(src / f, out / f)

    times = [0.0, 1.0, 2.0]
    tracks = [  # (pointer, type, keyframe values)
        ("/materials/0/pbrMetallicRoughness/baseColorFactor", "VEC4", [[1, 1, 1, 1], [1, 0.35, 0.2, 1], [0.2, 0.5, 1, 1]]),
        ("/materials/0/emissiveFactor", "VEC3", [[0, 0, 0], [0.3, 0.15, 0], [0, 0, 0.25]]),
        ("/materials/0/pbrMetallicRoughness/roughnessFactor", "SCALAR", [[1], [0.35], [0.6]]),
        ("/materials/0/pbrMetallicRoughness/baseColorTexture/extensions/KHR_texture_transform/offset", "VEC2",
         [[0, 0], [0.25, 0], [0.25, 0.5]]),
    ]
    data = bytearray()
    buffer = len(doc["buffers"])
    views, accessors = doc.setdefault("bufferViews", []), doc.setdefault("accessors", [])

    def accessor(values, type_, minmax=False):
        flat = [float(x) for v in values for x in v]
        while len(data) % 4:
            data.append(0)
        views.append({"buffer": buffer, "byteOffset": len(data), "byteLength": 4 * len(flat)})
        data.extend(struct.pack(f"<{len(flat)}f", *flat))
        a = {"bufferView": len(views) - 1, "componentType": 5126, "count": len(values), "type": type_}
        if minmax:
            a["min"], a["max"] = [min(times)], [max(times)]
        accessors.append(a)
        return len(accessors) - 1

    t = accessor([[x] for x in times], "SCALAR", minmax=True)
    samplers, channels = [], []
    for pointer, type_, values in tracks:
        samplers.append({"input": t, "output": accessor(values, type_), "interpolation": "LINEAR"})
        channels.append({"sampler": len(samplers) - 1,
                         "target": {"path": "pointer", "extensions": {"KHR_animation_pointer": {"pointer": pointer}}}})
    doc["buffers"].append({"byteLength": len(data),
                           "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(data)).decode()})
    doc["animations"] = [{"name": "pointer", "samplers": samplers, "channels": channels}]
    # The animated texture transform needs the extension on the texture it moves.
    doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"] = {
        "KHR_texture_transform": {"offset": [0, 0]}}
    used = doc.setdefault("extensionsUsed", [])
    for e in ["KHR_animation_pointer", "KHR_texture_transform"]:
        if e not in used:
            used.append(e)
    (out / "Suzanne_pointer.gltf").write_text(json.dumps(doc, indent=1))
    print(out / "Suzanne_pointer.gltf")
    return 0


if __name__ == "__main__":
    sys.exit(main())
