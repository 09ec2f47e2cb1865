#!/usr/bin/env python3
"""Throughput of the Python module (printed figures, not a timed test): N views of one model.

The same N views of DamagedHelmet (yaw 0, 360/N, ... at 512x512, the studio_small_03_1k.hdr
environment, PNG files written), three ways, each a whole process timed from start to exit:
  python   one `python3` process: import fresnel, load the model once, render and save N views
  batch    one `fresnel batch` over a job list sweeping yaw over N values
  render   N `fresnel render` processes, one per view
Both sides share one environment cache, filled first. Target: python within 10 % of batch.

usage: python_bench.py FRESNEL_EXE BUILD_DIR SHARED_DIR [--views N] [--json]
"""
import json
import os
import subprocess
import sys
import tempfile
import time

PYTHON_JOB = r"""
import sys, fresnel
model, env, out, n = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
scene = fresnel.load(model)
job = fresnel.Job(size=(512, 512), env=env)
for i in range(n):
    fresnel.save(f"{out}/view-{i:03d}.png", fresnel.render(scene, job, yaw=360.0 * i / n))
"""


def timed(cmd, env):
    t = time.monotonic()
    subprocess.run(cmd, env=env, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.monotonic() - t


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    as_json = "--json" in sys.argv
    views = 24
    if "--views" in sys.argv:
        views = int(sys.argv[sys.argv.index("--views") + 1])
        args = [a for a in args if a != str(views)]
    if len(args) < 3:
        print(__doc__)
        return 2
    exe, build, shared = (os.path.abspath(a) for a in args[:3])
    model = os.path.join(shared, "assets", "models", "DamagedHelmet", "DamagedHelmet.glb")
    env_map = os.path.join(shared, "assets", "env", "studio_small_03_1k.hdr")
    package = os.path.join(build, "python")
    if not os.path.exists(model) or not os.path.exists(env_map):
        print("python_bench: no DamagedHelmet or studio_small_03_1k.hdr under", shared, "; nothing to measure")
        return 0
    if not os.path.isdir(os.path.join(package, "fresnel")):
        print("python_bench: no Python module in", package, "(make python); nothing to measure")
        return 0
    python = "/usr/bin/python3" if os.path.exists("/usr/bin/python3") else sys.executable
    work = tempfile.mkdtemp(prefix="fresnel-python-bench-")
    environ = dict(os.environ, XDG_CACHE_HOME=os.path.join(work, "cache"), PYTHONPATH=package)
    common = ["--size", "512x512", "--env", env_map, "--allow-external-files"]
    subprocess.run([exe, "render", model, "-o", os.path.join(work, "warm.png")] + common, env=environ, check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)

    results = {}
    for name in ("python", "batch", "render"):
        out = os.path.join(work, name)
        os.makedirs(out)
        if name == "python":
            results[name] = timed([python, "-c", PYTHON_JOB, model, env_map, out, str(views)], environ)
        elif name == "batch":
            jobs = os.path.join(work, "jobs.jsonl")
            with open(jobs, "w") as f:
                f.write(json.dumps({"model": model, "sweep": {"yaw": [0, 360, views]}, "output": "view.png"}) + "\n")
            results[name] = timed([exe, "batch", jobs, "--out", out] + common, environ)
        else:
            t = time.monotonic()
            for i in range(views):
                subprocess.run([exe, "render", model, "-o", os.path.join(out, f"view-{i:03d}.png"), "--yaw",
                                str(360.0 * i / views)] + common, env=environ, check=True, stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL)
            results[name] = time.monotonic() - t
        written = len([f for f in os.listdir(out) if f.endswith(".png")])
        assert written == views, f"{name} wrote {written} of {views} images"

    # The same pictures: Python's view 5 against batch's frame 5 and render's view 5.
    import importlib
    sys.path.insert(0, package)
    fresnel = importlib.import_module("fresnel")
    batch_files = sorted(f for f in os.listdir(os.path.join(work, "batch")) if f.endswith(".png"))
    k = min(5, views - 1)
    same_batch = fresnel.compare(os.path.join(work, "python", f"view-{k:03d}.png"),
                                 os.path.join(work, "batch", batch_files[k]))["psnr_db"]
    same_render = fresnel.compare(os.path.join(work, "python", f"view-{k:03d}.png"),
                                  os.path.join(work, "render", f"view-{k:03d}.png"))["psnr_db"]
    summary = {
        "views": views,
        "python_s": round(results["python"], 3),
        "batch_s": round(results["batch"], 3),
        "render_processes_s": round(results["render"], 3),
        "python_over_batch": round(results["python"] / results["batch"], 3),
        "render_processes_over_python": round(results["render"] / results["python"], 3),
        "psnr_python_vs_batch_db": round(same_batch, 2),
        "psnr_python_vs_render_db": round(same_render, 2),
    }
    if as_json:
        print(json.dumps(summary))
    else:
        print(f"Python module, {views} views of DamagedHelmet at 512x512 (whole processes, warm environment cache):")
        print(f"  python (one process)      {results['python']:7.2f} s  {views / results['python']:6.2f} images/s")
        print(f"  fresnel batch             {results['batch']:7.2f} s  {views / results['batch']:6.2f} images/s"
              f"   python/batch {summary['python_over_batch']:.3f} (target <= 1.10)")
        print(f"  fresnel render x{views:<3}       {results['render']:7.2f} s  {views / results['render']:6.2f} images/s"
              f"   {summary['render_processes_over_python']:.2f}x python's time")
        print(f"  same pictures: python vs batch {same_batch:.1f} dB, python vs render {same_render:.1f} dB")
    return 0


if __name__ == "__main__":
    sys.exit(main())
