"""fresnel: physically based rendering of glTF, OBJ and scene files from Python.

    import fresnel
    scene = fresnel.load("DamagedHelmet.glb")
    image = fresnel.render(scene, size=(512, 512), yaw=30)   # uint8 (H, W, 3), as `fresnel render` writes
    truth = fresnel.trace(scene, size=(512, 512), yaw=30, spp=64)  # the path tracer, float32 (H, W, 4)

Settings are the settings registry's (fresnel.settings(); the same names, ranges and messages as
the command line and scene files). docs/python.md has the whole API.
"""
from ._fresnel import (  # noqa: F401  (the C++ module: every call below is one of these)
    Error,
    Job,
    Renderer,
    Scene,
    __version__,
    bake,
    compare,
    debug_channels,
    evaluate,
    fit,
    load,
    read,
    save,
    settings,
    surfaces,
    to_png,
    trace,
)

__all__ = [
    "Error", "Job", "Renderer", "Scene", "bake", "channel", "close", "compare", "debug_channels", "default_renderer",
    "display", "evaluate", "fit", "load", "read", "render", "save", "settings", "surfaces", "to_png", "trace",
]

_renderer = None  # the process's renderer (one OpenGL context), made by the first render()


def default_renderer() -> Renderer:
    """The renderer render() and channel() use: made on first use, kept for the process."""
    global _renderer
    if _renderer is None or _renderer.closed:
        _renderer = Renderer()
    return _renderer


def render(scene, job=None, *, dtype="uint8", progress=None, **settings):
    """Renders `scene` on the GPU with the default renderer: see Renderer.render."""
    return default_renderer().render(scene, job, dtype, progress, **settings)


def channel(scene, name, job=None, **settings):
    """A debug channel of `scene` as float32 (H, W, 4) with the default renderer: see Renderer.channel."""
    return default_renderer().channel(scene, name, job, **settings)


def close():
    """Frees the default renderer's GPU context (the next render() makes another)."""
    global _renderer
    if _renderer is not None:
        _renderer.close()
        _renderer = None


class _Png:
    """An image Jupyter shows inline (its _repr_png_)."""

    def __init__(self, data: bytes):
        self.data = data

    def _repr_png_(self) -> bytes:
        return self.data


def display(image):
    """An object Jupyter (IPython) displays as the image: a uint8 array as it is, a float array as
    display values clamped to [0, 1]. Outside a notebook, save() writes files."""
    import numpy as np

    a = np.asarray(image)
    if a.dtype != np.uint8:
        a = (np.clip(a, 0.0, 1.0) * 255.0 + 0.5).astype(np.uint8)
    if a.ndim == 2:
        a = a[:, :, None]
    return _Png(to_png(a))
