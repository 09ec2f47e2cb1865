"""Bakes, material evaluation, metrics and fits from Python, against the CLI's."""
import json
import subprocess

import numpy as np
import pytest

import fresnel


def test_bake_studio_and_an_array(tmp_path):
    seen = []
    baked = fresnel.bake("studio", tmp_path / "baked", size=16, samples=16, levels=3, progress=seen.append)
    assert len(baked["specular"]) == 3
    assert baked["specular"][0].shape == (6, 16, 16, 4) and baked["specular"][2].shape == (6, 4, 4, 4)
    assert baked["irradiance"].shape[0] == 6 and baked["irradiance_sh"].shape == (9, 3)
    assert baked["brdf_lut"].ndim == 3 and baked["brdf_lut"].shape[2] == 4
    assert (tmp_path / "baked" / "manifest.json").exists() and (tmp_path / "baked" / "specular.ktx2").exists()
    assert seen and seen[-1] == pytest.approx(1.0)
    # A uniform panorama of radiance 0.5 prefilters to 0.5 everywhere, at every level.
    uniform = np.full((32, 64, 3), 0.5, dtype=np.float32)
    u = fresnel.bake(uniform, size=8, samples=8, levels=2)
    assert np.allclose(u["specular"][1][..., :3], 0.5, atol=1e-3)
    assert np.allclose(u["irradiance"][..., :3], 0.5, atol=1e-2)
    # The baked folder is a job's environment.
    image = fresnel.render(fresnel.load(), size=(32, 24), env=str(tmp_path / "baked"))
    assert image.mean() > 10
    # A progress callback that raises stops calling; its exception reaches the caller, nothing is written.
    def fail(fraction):
        raise RuntimeError("stop")

    with pytest.raises(RuntimeError, match="stop"):
        fresnel.bake("studio", tmp_path / "failed", size=8, samples=8, levels=2, progress=fail)
    assert not (tmp_path / "failed").exists()
    with pytest.raises(ValueError, match="twice as wide"):
        fresnel.bake(np.zeros((10, 10, 3), np.float32))
    with pytest.raises(ValueError, match="power of two"):
        fresnel.bake("studio", size=20)


def test_evaluate_factors_and_textures(demo, helmet):
    uv = np.array([[0.5, 0.5], [0.1, 0.9]], dtype=np.float32)
    m0 = fresnel.evaluate(demo, 0, uv)
    m48 = fresnel.evaluate(demo, 48, uv)
    assert m0["base_color"].shape == (2, 4) and m0["roughness"].shape == (2,)
    # The demo's grid: roughness and metalness step with the sphere's column and row.
    assert m0["roughness"][0] != m48["roughness"][0] or m0["metallic"][0] != m48["metallic"][0]
    assert np.allclose(m0["normal"], [0, 0, 1])
    scene = fresnel.load(helmet)
    rng = np.random.default_rng(1)
    uvs = rng.random((500, 2), dtype=np.float32)
    m = fresnel.evaluate(scene, "Material_MR", uvs)
    assert m["base_color"].std() > 0.01  # read from the base colour texture
    assert 0 <= m["metallic"].min() and m["metallic"].max() <= 1 and m["roughness"].std() > 0.01
    assert m["emissive"].max() > 0.1  # the helmet's lit panels
    assert not m["discard"].any()
    with pytest.raises(fresnel.Error, match="no material"):
        fresnel.evaluate(scene, "Nope", uvs)
    with pytest.raises(ValueError, match="uv0"):
        fresnel.evaluate(scene, 0, np.zeros((3, 3), np.float32))


def test_compare(demo, tmp_path):
    a = fresnel.render(demo, size=(64, 48))
    same = fresnel.compare(a, a)
    assert same["psnr_db"] == 99.0 and same["ssim"] == pytest.approx(1.0) and same["flip"] == 0.0
    b = fresnel.render(demo, size=(64, 48), exposure=0.3)
    diff = fresnel.compare(b, a)
    assert 10 < diff["psnr_db"] < 60 and diff["flip"] > 0
    fresnel.save(tmp_path / "a.png", a)
    fresnel.save(tmp_path / "b.png", b)
    exe_result = subprocess.run(
        [__import__("os").environ["FRESNEL_EXE"], "compare", str(tmp_path / "b.png"), str(tmp_path / "a.png"), "--json"],
        check=True, capture_output=True, text=True).stdout
    cli = json.loads(exe_result)
    assert diff["psnr_db"] == pytest.approx(cli["psnr_db"], abs=1e-6)
    assert fresnel.compare(tmp_path / "b.png", tmp_path / "a.png")["psnr_db"] == pytest.approx(cli["psnr_db"], abs=1e-6)
    lin = fresnel.render(demo, size=(64, 48), dtype="float32")
    assert "hdr_flip" in fresnel.compare(lin, lin * 1.1, linear=True)
    with pytest.raises(fresnel.Error, match="one size"):
        fresnel.compare(a, a[:10])


def test_fit_matches_the_cli(exe):
    py = fresnel.fit(kd=0.8, ks=0.2, ns=32)
    cli = json.loads(subprocess.run([exe, "fit", "--phong", "0.8,0.2,32", "--json"], check=True, capture_output=True,
                                    text=True).stdout)
    assert py["pbr"]["roughness"] == pytest.approx(cli["fitted"]["roughness"], abs=1e-6)
    assert py["pbr"]["metallic"] == pytest.approx(cli["fitted"]["metallic"], abs=1e-6)
    back = fresnel.fit(base_color=(0.8, 0.1, 0.1), metallic=0, roughness=0.4)
    cli = json.loads(subprocess.run([exe, "fit", "--pbr", "0.8:0.1:0.1,0,0.4", "--json"], check=True, capture_output=True,
                                    text=True).stdout)
    assert back["phong"]["ns"] == pytest.approx(cli["fitted"]["Ns"], abs=1e-6)
    assert back["phong"]["kd"][0] == pytest.approx(cli["fitted"]["Kd"][0], abs=1e-6)
    with pytest.raises(fresnel.Error):
        fresnel.fit(kd=2.0, ks=0.5, ns=32)
    with pytest.raises(TypeError):
        fresnel.fit(kd=0.5, base_color=0.5)
