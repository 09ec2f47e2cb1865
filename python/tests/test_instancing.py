"""EXT_mesh_gpu_instancing end to end: a file whose node instances a box three times renders and
traces as the same file with three plain nodes does."""
import base64
import json
import struct

import numpy as np

import fresnel

BOX = [(-0.5, -0.5, 0.5), (0.5, -0.5, 0.5), (0.5, 0.5, 0.5), (-0.5, 0.5, 0.5),
       (-0.5, -0.5, -0.5), (0.5, -0.5, -0.5), (0.5, 0.5, -0.5), (-0.5, 0.5, -0.5)]
FACES = [0, 1, 2, 0, 2, 3, 5, 4, 7, 5, 7, 6, 4, 0, 3, 4, 3, 7, 1, 5, 6, 1, 6, 2, 3, 2, 6, 3, 6, 7, 4, 5, 1, 4, 1, 0]
T = [(-1.5, 0, 0), (0, 0.3, 0), (1.5, 0, 0)]
R = [(0, 0, 0, 1), (0, 0.3826834, 0, 0.9238795), (0.258819, 0, 0, 0.9659258)]
S = [(1, 1, 1), (0.7, 1.4, 0.7), (1, 1, 1)]


def write(path, instanced):
    blob = b"".join(struct.pack("<3f", *p) for p in BOX) + struct.pack(f"<{len(FACES)}H", *FACES)
    views = [{"buffer": 0, "byteOffset": 0, "byteLength": 96}, {"buffer": 0, "byteOffset": 96, "byteLength": 72}]
    accessors = [{"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3", "min": [-0.5] * 3, "max": [0.5] * 3},
                 {"bufferView": 1, "componentType": 5123, "count": 36, "type": "SCALAR"}]
    doc = {"asset": {"version": "2.0"}, "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
           "scene": 0}
    if instanced:
        offset = len(blob) + (-len(blob)) % 4
        blob += b"\0" * (offset - len(blob))
        for name, rows, kind in (("TRANSLATION", T, "VEC3"), ("ROTATION", R, "VEC4"), ("SCALE", S, "VEC3")):
            data = b"".join(struct.pack(f"<{len(r)}f", *r) for r in rows)
            views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data)})
            accessors.append({"bufferView": len(views) - 1, "componentType": 5126, "count": 3, "type": kind})
            blob += data
        doc["nodes"] = [{"mesh": 0, "extensions": {"EXT_mesh_gpu_instancing": {
            "attributes": {"TRANSLATION": 2, "ROTATION": 3, "SCALE": 4}}}}]
        doc["extensionsUsed"] = doc["extensionsRequired"] = ["EXT_mesh_gpu_instancing"]
        doc["scenes"] = [{"nodes": [0]}]
    else:
        doc["nodes"] = [{"mesh": 0, "translation": list(t), "rotation": list(r), "scale": list(s)} for t, r, s in zip(T, R, S)]
        doc["scenes"] = [{"nodes": [0, 1, 2]}]
    doc["bufferViews"] = views
    doc["accessors"] = accessors
    doc["buffers"] = [{"byteLength": len(blob), "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}]
    path.write_text(json.dumps(doc))
    return path


def test_instances_render_and_trace_as_nodes(tmp_path):
    instanced = fresnel.load(write(tmp_path / "instanced.gltf", True))
    plain = fresnel.load(write(tmp_path / "plain.gltf", False))
    assert instanced.triangle_count == plain.triangle_count == 12
    assert instanced.bounds == plain.bounds
    job = fresnel.Job(size=(160, 120), pitch=20, yaw=15)
    assert np.array_equal(fresnel.render(instanced, job), fresnel.render(plain, job))
    a = fresnel.trace(instanced, job, spp=4, radiance=True)
    b = fresnel.trace(plain, job, spp=4, radiance=True)
    assert np.allclose(a, b, atol=1e-5)
    ids = fresnel.surfaces(instanced, job)["node"]
    assert len(set(np.unique(ids)) - {-1}) == 3  # three instances, three nodes
    # One instanced draw and three Embree instances, or every placement on its own: the same picture.
    flat = fresnel.Job(size=(160, 120), pitch=20, yaw=15, render_instancing=False)
    assert np.array_equal(fresnel.render(instanced, flat), fresnel.render(instanced, job))
    assert np.allclose(fresnel.trace(instanced, flat, spp=4, radiance=True), a, atol=1e-5)


def test_convert_keeps_the_extension(exe, tmp_path):
    """`fresnel convert` carries EXT_mesh_gpu_instancing into a .glb and back to a .gltf (the JSON
    key by key), and the converted file still renders the three instances."""
    import subprocess
    source = write(tmp_path / "instanced.gltf", True)
    glb, back = tmp_path / "instanced.glb", tmp_path / "back.gltf"
    subprocess.run([exe, "convert", str(source), str(glb)], check=True, capture_output=True)
    subprocess.run([exe, "convert", str(glb), str(back)], check=True, capture_output=True)
    doc = json.loads(back.read_text())
    assert "EXT_mesh_gpu_instancing" in doc["extensionsUsed"]
    assert doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"].keys() == {"TRANSLATION", "ROTATION", "SCALE"}
    job = fresnel.Job(size=(96, 72), pitch=20, yaw=15)
    assert np.array_equal(fresnel.render(fresnel.load(back), job), fresnel.render(fresnel.load(source), job))
