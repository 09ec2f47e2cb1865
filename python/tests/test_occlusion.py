"""Baked occlusion through the Python module (`render_ao`, the settings registry's render.ao): the
shadow scene under a uniform sky renders darker where it hides the sky, the rest of the frame the
same; turning it off again gives the first picture back."""
import os

import numpy as np

import fresnel

SCENE = os.path.join(os.path.dirname(__file__), "..", "..", "tests", "data", "shadows", "shadow-environment.gltf")


def test_baked_occlusion_darkens_what_the_scene_hides():
    scene = fresnel.load(SCENE)
    plain = fresnel.Job(size=(96, 96), pitch=20, env="color:0.5,0.6,0.8")
    baked = fresnel.Job(size=(96, 96), pitch=20, env="color:0.5,0.6,0.8", render_ao="baked", render_ao_rays=64)
    a = fresnel.render(scene, plain).astype(np.float64)
    b = fresnel.render(scene, baked).astype(np.float64)
    assert a.shape == b.shape
    assert b.sum() < a.sum() * 0.999  # darker on the whole
    changed = np.abs(a - b).max(axis=-1) > 2
    assert 0 < changed.mean() < 0.5  # where the scene hides the sky, not everywhere
    again = fresnel.render(scene, plain).astype(np.float64)
    assert np.array_equal(again, a)
