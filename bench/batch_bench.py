#!/usr/bin/env python3
"""Batch throughput and memory of `fresnel batch` (printed figures, not a timed test).

1. Thumbnails of the shared models (../shared/assets/models, every .gltf/.glb) at 512x512 with
   image-based light (studio_small_03_1k.hdr): one `fresnel render` process per image against
   one `fresnel batch` over the folder, in the same run, as images per hour and their ratio
   (target: batch at least 3x).
2. Memory over a batch of 100 jobs cycling through those models: the resident memory each job's
   result line reports (`rss_mib`) after the first round against the last, and the process's
   peak (ru_maxrss); flat means no growth per job.

usage: batch_bench.py FRESNEL_EXE SHARED_DIR [--quick] [--json]
Both runs share one environment cache, filled first, so neither pays for the bake.
"""
import json
import os
import resource
import subprocess
import sys
import tempfile
import time


def models_under(folder):
    out = []
    for root, _, files in os.walk(folder):
        for f in files:
            if f.lower().endswith((".gltf", ".glb")):
                out.append(os.path.join(root, f))
    return sorted(out)


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    quick = "--quick" in sys.argv
    as_json = "--json" in sys.argv
    if len(args) < 2:
        print(__doc__)
        return 2
    exe, shared = os.path.abspath(args[0]), os.path.abspath(args[1])
    models_dir = os.path.join(shared, "assets", "models")
    env = os.path.join(shared, "assets", "env", "studio_small_03_1k.hdr")
    if not os.path.isdir(models_dir) or not os.path.exists(env):
        print(f"batch_bench: {shared} has no models or studio_small_03_1k.hdr; nothing to measure")
        return 0
    models = models_under(models_dir)
    if quick:
        models = models[:6]
    size = "512x512"
    work = tempfile.mkdtemp(prefix="fresnel-batch-bench-")
    environ = dict(os.environ, XDG_CACHE_HOME=os.path.join(work, "cache"))
    common = ["--size", size, "--env", env, "--allow-external-files"]

    # Fill the environment cache (and Mesa's shader cache) once, for both sides.
    subprocess.run([exe, "render", models[0], "-o", os.path.join(work, "warm.png")] + common,
                   env=environ, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)

    # 1a. One process per image.
    failed_separate = 0
    t = time.monotonic()
    for i, m in enumerate(models):
        r = subprocess.run([exe, "render", m, "-o", os.path.join(work, f"sep-{i}.png")] + common,
                           env=environ, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        failed_separate += r.returncode != 0
    separate_s = time.monotonic() - t

    # 1b. One batch over the same models (a job list, so the set is exactly the same).
    jobs = os.path.join(work, "jobs.jsonl")
    with open(jobs, "w") as f:
        for i, m in enumerate(models):
            f.write(json.dumps({"model": m, "output": f"b-{i}.png"}) + "\n")
    t = time.monotonic()
    r = subprocess.run([exe, "batch", jobs, "--out", os.path.join(work, "batch"), "--json"] + common,
                       env=environ, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    batch_s = time.monotonic() - t
    results = [json.loads(l) for l in r.stdout.splitlines() if l.strip()]
    failed_batch = sum(1 for j in results if j.get("status") != "ok")

    n = len(models)
    sep_rate = (n - failed_separate) / separate_s * 3600 if separate_s > 0 else 0
    batch_rate = (n - failed_batch) / batch_s * 3600 if batch_s > 0 else 0

    # 2. 100 jobs cycling through the models (more than the model cache holds: every job
    #    loads and uploads again), memory after each.
    count = 30 if quick else 100
    with open(jobs, "w") as f:
        for i in range(count):
            f.write(json.dumps({"model": models[i % n], "output": f"m-{i}.png"}) + "\n")
    before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    t = time.monotonic()
    r = subprocess.run([exe, "batch", jobs, "--out", os.path.join(work, "mem"), "--json"] + common,
                       env=environ, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    mem_s = time.monotonic() - t
    peak_kib = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    lines = [json.loads(l) for l in r.stdout.splitlines() if l.strip()]
    rss = [j.get("rss_mib", 0.0) for j in sorted(lines, key=lambda j: j["index"])]
    rounds = [rss[k:k + n] for k in range(0, len(rss), n) if len(rss[k:k + n]) == n]
    round_max = [max(r) for r in rounds]
    round_end = [r[-1] for r in rounds]
    first_round = round_max[0] if round_max else 0.0
    last_round = round_max[-1] if round_max else 0.0

    out = {
        "models": n, "size": size, "environment": os.path.basename(env),
        "separate_processes": {"seconds": separate_s, "images_per_hour": sep_rate, "failed": failed_separate},
        "batch": {"seconds": batch_s, "images_per_hour": batch_rate, "failed": failed_batch},
        "ratio": batch_rate / sep_rate if sep_rate > 0 else 0.0,
        "memory": {"jobs": count, "seconds": mem_s, "rss_mib_first_round_max": first_round,
                   "rss_mib_last_round_max": last_round, "rss_mib_round_max": round_max,
                   "rss_mib_round_end": round_end, "peak_rss_mib": peak_kib / 1024.0,
                   "peak_rss_earlier_children_mib": before / 1024.0},
    }
    subprocess.run(["rm", "-rf", work])
    if as_json:
        print(json.dumps(out, indent=2))
        return 0
    print(f"thumbnails of {n} shared models, {size}, studio IBL (environment cache warm):")
    print(f"  one `fresnel render` per image: {separate_s:6.1f} s, {sep_rate:7.0f} images/hour"
          f"{f' ({failed_separate} failed)' if failed_separate else ''}")
    print(f"  one `fresnel batch`:            {batch_s:6.1f} s, {batch_rate:7.0f} images/hour"
          f"{f' ({failed_batch} failed)' if failed_batch else ''}")
    print(f"  batch / separate processes: {out['ratio']:.2f}x  [target 3x]")
    growth = last_round - first_round
    print(f"memory over a batch of {count} jobs cycling through the {n} models ({mem_s:.1f} s), resident after each job:")
    print("  largest in each pass over the models: " + ", ".join(f"{v:.0f}" for v in round_max) + " MiB"
          f" (last - first {growth:+.0f} MiB)")
    print("  after the last job of each pass:      " + ", ".join(f"{v:.0f}" for v in round_end) + " MiB"
          f"; process peak {peak_kib / 1024.0:.0f} MiB")
    return 0


if __name__ == "__main__":
    sys.exit(main())
