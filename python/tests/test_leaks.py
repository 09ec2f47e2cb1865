"""200 renders in one process hold no more GPU or host memory than the first few."""
import resource

import fresnel


def rss_mib():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * resource.getpagesize() / 2**20


def test_two_hundred_renders_do_not_grow(demo):
    scenes = [demo, fresnel.load()]  # two scenes in turn: each render uploads again
    with fresnel.Renderer() as r:
        seen = set()
        for i in range(10):  # every kind of frame below, twice: their targets and programs
            r.render(scenes[i % 2], size=(64, 48), yaw=i, dtype="float32" if i % 3 == 0 else "uint8")
            if i % 5 == 0:
                r.channel(scenes[0], "normal", size=(64, 48))
            seen.add(r.info()["texture_bytes"])
        warm = r.info()
        # The targets of the frame formats in use come and go (a renderer keeps two formats' targets).
        warm_bytes = warm["texture_bytes"]
        before = rss_mib()
        for i in range(200):
            image = r.render(scenes[i % 2], size=(64, 48), yaw=i, exposure=(i % 5) * 0.1,
                             dtype="float32" if i % 3 == 0 else "uint8")
            assert image.shape[:2] == (48, 64)
            if i % 50 == 0:
                r.channel(scenes[0], "normal", size=(64, 48))
            assert r.info()["texture_bytes"] <= max(seen)
        after = rss_mib()
        info = r.info()
    assert info["texture_bytes"] in seen and warm_bytes in seen  # GPU objects: none left behind
    assert info["programs"] == warm["programs"]
    assert after - before < 24.0, f"resident memory grew {after - before:.1f} MiB over 200 renders"
