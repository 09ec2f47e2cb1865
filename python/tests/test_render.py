"""The GPU renderer from Python: the same images as `fresnel render` for the same job."""
import numpy as np
import pytest

import fresnel
from conftest import psnr, run_cli

SMALL = dict(size=(160, 120))


def test_demo_equals_the_cli_png(exe, demo, tmp_path):
    out = tmp_path / "demo.png"
    run_cli(exe, "render", "-o", str(out), "--size", "160x120", "--yaw", "25", "--pitch", "10")
    image = fresnel.render(demo, yaw=25, pitch=10, **SMALL)
    assert image.dtype == np.uint8 and image.shape == (120, 160, 3)
    cli = fresnel.read(out)[:, :, :3]
    assert psnr(image, cli) >= 60.0


def test_damaged_helmet_equals_the_cli_png(exe, helmet, tmp_path):
    out = tmp_path / "helmet.png"
    run_cli(exe, "render", str(helmet), "-o", str(out), "--size", "256x192", "--yaw", "40")
    scene = fresnel.load(helmet)
    image = fresnel.render(scene, fresnel.Job(size=(256, 192), yaw=40))
    assert psnr(image, fresnel.read(out)[:, :, :3]) >= 60.0


def test_float_output_equals_the_cli_exr(exe, demo, tmp_path):
    out = tmp_path / "demo.exr"
    run_cli(exe, "render", "-o", str(out), "--size", "160x120", "--exposure", "0.5")
    image = fresnel.render(demo, dtype="float32", exposure=0.5, **SMALL)
    assert image.dtype == np.float32 and image.shape == (120, 160, 4)
    cli = fresnel.read(out)
    # The EXR holds half floats: compare at their precision.
    assert np.allclose(image, cli, rtol=2e-3, atol=2e-3)


def test_transparent_background_gives_rgba(demo):
    image = fresnel.render(demo, background="transparent", **SMALL)
    assert image.shape == (120, 160, 4)
    assert image[0, 0, 3] == 0 and image[60, 80, 3] == 255


def test_scene_files_keep_their_settings(exe, tmp_path):
    (tmp_path / "look.fresnel.json").write_text('{"fresnel": 1, "camera": {"yaw": 60, "pitch": 20}, "render": {"size": [96, 64]}}')
    scene = fresnel.load(tmp_path / "look.fresnel.json")
    assert scene.job["yaw"] == 60.0 and scene.job["size"] == (96, 64)
    image = fresnel.render(scene)
    assert image.shape == (64, 96, 3)
    run_cli(exe, "render", str(tmp_path / "look.fresnel.json"), "-o", str(tmp_path / "look.png"))
    assert psnr(image, fresnel.read(tmp_path / "look.png")[:, :, :3]) >= 60.0
    # A job given replaces the file's settings; keywords apply on top of either.
    assert fresnel.render(scene, fresnel.Job(size=(32, 24))).shape == (24, 32, 3)
    assert fresnel.render(scene, size=(48, 32)).shape == (32, 48, 3)
    assert fresnel.render(scene, {"render.size": (40, 30)}).shape == (30, 40, 3)
    with pytest.raises(TypeError, match="job"):
        fresnel.render(scene, 42)


def test_channels(demo):
    names = fresnel.debug_channels()
    assert {"normal", "basecolor", "roughness", "metallic"} <= set(names)
    normal = fresnel.channel(demo, "normal", background="transparent", **SMALL)
    assert normal.dtype == np.float32 and normal.shape == (120, 160, 4)
    covered = normal[:, :, 3] > 0.5
    n = normal[:, :, :3][covered] * 2.0 - 1.0
    assert covered.sum() > 1000
    assert np.allclose(np.linalg.norm(n, axis=1), 1.0, atol=0.02)
    # The demo's spheres grow rougher left to right and more metallic bottom to top (7x7).
    rough = fresnel.channel(demo, "roughness", background="transparent", **SMALL)[:, :, 0]
    row = rough[60][covered[60]]
    assert row[0] < row[-1]
    with pytest.raises(fresnel.Error, match="debug"):
        fresnel.channel(demo, "no-such-channel")


def test_a_renderer_reuses_its_upload_and_closes(demo):
    with fresnel.Renderer() as r:
        a = r.render(demo, size=(64, 64), yaw=0)
        b = r.render(demo, size=(64, 64), yaw=90)
        assert not np.array_equal(a, b)
        info = r.info()
        assert info["api"] == "OpenGL 3.3 core" and info["texture_bytes"] > 0
        assert r.stats["draw_calls"] > 0
    assert r.closed
    with pytest.raises(fresnel.Error, match="closed"):
        r.render(demo, size=(64, 64))


def test_opengl_es_renderer_agrees(demo):
    with fresnel.Renderer(api="gles") as r:
        es = r.render(demo, **SMALL)
    assert psnr(es, fresnel.render(demo, **SMALL)) >= 40.0
    with pytest.raises(ValueError):
        fresnel.Renderer(api="vulkan")


def test_bad_input_raises_fresnel_error_naming_the_file(tmp_path):
    with pytest.raises(fresnel.Error) as e:
        fresnel.load(tmp_path / "missing.glb")
    assert e.value.file.endswith("missing.glb")
    junk = tmp_path / "junk.gltf"
    junk.write_bytes(b"\x89PNG\r\n\x1a\n not a model")
    with pytest.raises(fresnel.Error) as e:
        fresnel.load(junk)
    assert e.value.file.endswith("junk.gltf")
    with pytest.raises(fresnel.Error):
        fresnel.render(fresnel.load(), dtype="uint8", camera=3)  # the demo has no cameras
    with pytest.raises(ValueError, match="dtype"):
        fresnel.render(fresnel.load(), dtype="int16")


def test_load_settings_belong_to_load(helmet):
    scene = fresnel.load(helmet)
    with pytest.raises(fresnel.Error, match="load setting"):
        fresnel.render(scene, variant="midnight", size=(32, 32))


def test_display_and_png(demo):
    image = fresnel.render(demo, size=(32, 24))
    png = fresnel.display(image)._repr_png_()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    assert fresnel.display(image.astype(np.float32) / 255.0)._repr_png_()[:4] == b"\x89PNG"


def test_save_and_read_round_trip(demo, tmp_path):
    image = fresnel.render(demo, size=(32, 24))
    fresnel.save(tmp_path / "a.png", image)
    assert np.array_equal(fresnel.read(tmp_path / "a.png")[:, :, :3], image)
    linear = fresnel.render(demo, size=(32, 24), dtype="float32")
    fresnel.save(tmp_path / "a.exr", linear)
    assert np.allclose(fresnel.read(tmp_path / "a.exr"), linear, rtol=2e-3, atol=2e-3)
    with pytest.raises(fresnel.Error):
        fresnel.save(tmp_path / "a.jpg", image)
    with pytest.raises(fresnel.Error):
        fresnel.save(tmp_path / "no-such-dir" / "a.png", image)


def test_scene_properties(helmet):
    scene = fresnel.load(helmet)
    assert scene.path.endswith("DamagedHelmet.glb")
    assert len(scene.materials) == 1 and scene.triangle_count == 15452
    lo, hi = scene.bounds
    assert all(l < h for l, h in zip(lo, hi))
    cam = scene.camera(size=(200, 100))
    assert cam["view"].shape == (4, 4) and cam["width"] == 200 and cam["near"] < cam["far"]
    assert "DamagedHelmet" in repr(scene)


def test_with_material_and_pose(helmet, shared):
    scene = fresnel.load(helmet)
    red = scene.with_material("Material_MR", baseColorFactor=(1, 0, 0, 1), roughnessFactor=0.2, clearcoatFactor=1)
    m = fresnel.evaluate(red, 0, [[0.5, 0.5]])
    assert m["clearcoat"][0] == 1.0
    assert fresnel.evaluate(scene, 0, [[0.5, 0.5]])["clearcoat"][0] == 0.0  # the original is untouched
    a, b = fresnel.render(scene, size=(64, 64)), fresnel.render(red, size=(64, 64))
    assert (b[..., 0].astype(int) - b[..., 1]).mean() > (a[..., 0].astype(int) - a[..., 1]).mean() + 5
    with pytest.raises(TypeError, match="did you mean 'roughnessFactor'"):
        scene.with_material(roughnesFactor=0.5)
    with pytest.raises(fresnel.Error, match="roughnessFactor"):
        scene.with_material(roughnessFactor=2.0)
    with pytest.raises(fresnel.Error, match="no material"):
        scene.with_material(5, roughnessFactor=0.5)
    man = fresnel.load(shared / "assets" / "models" / "CesiumMan" / "CesiumMan.glb")
    assert len(man.animations) == 1
    posed = man.pose(0.5)
    assert not np.array_equal(fresnel.render(man, size=(48, 48)), fresnel.render(posed, size=(48, 48)))


def test_load_at_a_time_equals_render_time(exe, shared, tmp_path):
    """The animation time is a load setting (the registry's animation.time): the scene posed at it
    renders as `fresnel render --time` does, and another time is another picture."""
    model = shared / "assets" / "models" / "CesiumMan" / "CesiumMan.glb"
    if not model.exists():
        pytest.skip(f"{model} is absent")
    out = tmp_path / "walk.png"
    run_cli(exe, "render", str(model), "-o", str(out), "--size", "160x120", "--time", "0.75", "--posing", "cpu")
    job = fresnel.Job(**SMALL)
    posed = fresnel.render(fresnel.load(model, time=0.75), job)
    assert psnr(posed, fresnel.read(out)[:, :, :3]) >= 60
    assert psnr(posed, fresnel.render(fresnel.load(model, time=1.5), job)) < 35
    with pytest.raises(fresnel.Error):
        fresnel.render(fresnel.load(model), fresnel.Job(time=1.0, **SMALL))  # a load setting: given to load()
