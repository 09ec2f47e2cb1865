#!/usr/bin/env python3
"""Corpus test: every glTF file under CORPUS goes through `fresnel info` and a 64x64
`fresnel render`, each with a timeout. Fails on any crash (exit code other than 0/1),
hang, sanitizer report, or a file the Khronos validator calls valid (numErrors 0) that
we reject. Prints a summary table. Skips (exit 77) when the corpus folder is absent.

usage: run_corpus.py FRESNEL_BINARY CORPUS_DIR [--timeout S] [--jobs N] [--no-render]
"""
import argparse, concurrent.futures, json, os, subprocess, sys, tempfile, time

import sanitizer_report



def validator_errors(path):
    for report in (path + ".report.json", os.path.splitext(path)[0] + ".report.json"):
        if os.path.exists(report):
            try:
                with open(report) as f:
                    return json.load(f)["issues"]["numErrors"]
            except (ValueError, KeyError):
                return None
    return None


notes = []


def run(cmd, timeout):
    rc, err, secs, step_notes = sanitizer_report.run_step(cmd, timeout)
    notes.extend(step_notes)  # list.extend is atomic under the GIL
    return rc, err, secs


def check(binary, path, timeout, render, outdir):
    results = {}
    steps = [("info", [binary, "info", path])]
    if render:
        out = os.path.join(outdir, str(abs(hash(path))) + ".png")
        steps.append(("render", [binary, "render", path, "-o", out, "--size", "64x64"]))
    for name, cmd in steps:
        rc, err, secs = run(cmd, timeout)
        results[name] = (rc, err, secs)
    return path, results


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("binary")
    ap.add_argument("corpus")
    ap.add_argument("--timeout", type=float, default=10.0)
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    ap.add_argument("--no-render", action="store_true")
    a = ap.parse_args()
    if not os.path.isdir(a.corpus):
        print(f"SKIP: corpus folder {a.corpus} is absent")
        return 77
    files = sorted(os.path.join(d, f) for d, _, fs in os.walk(a.corpus) for f in fs
                   if f.endswith((".gltf", ".glb")))
    if not a.no_render:
        # Warm the environment cache once (the built-in studio lights models without lights),
        # so no timed render pays for the first bake, which a sanitizer build makes slow.
        with tempfile.TemporaryDirectory() as warm:
            run([a.binary, "render", "-o", os.path.join(warm, "warm.png"), "--size", "16x16"], 900)
    failures, rows = [], {"loaded": 0, "loaded with warnings": 0, "rejected with error": 0}
    slowest = (0.0, "")
    with tempfile.TemporaryDirectory() as outdir, concurrent.futures.ThreadPoolExecutor(a.jobs) as pool:
        for path, results in pool.map(lambda p: check(a.binary, p, a.timeout, not a.no_render, outdir), files):
            rel = os.path.relpath(path, a.corpus)
            nerr = validator_errors(path)
            for step, (rc, err, secs) in results.items():
                if secs > slowest[0]:
                    slowest = (secs, f"{step} {rel}")
                if rc == "timeout":
                    failures.append(f"HANG    {step} {rel} (> {a.timeout} s)")
                elif rc not in (0, 1):
                    failures.append(f"CRASH   {step} {rel} exit {rc}: {err.strip()[-300:]}")
                elif sanitizer_report.finding(err):
                    failures.append(f"SANITIZER {step} {rel}: {err.strip()[-600:]}")
                elif rc == 1 and nerr == 0:
                    failures.append(f"REJECTED {step} {rel} (validator: 0 errors): {err.strip()[-300:]}")
                elif rc == 1 and not err.startswith("fresnel: error:") and "\nfresnel: error:" not in err:
                    failures.append(f"UNCLEAR {step} {rel}: exit 1 without a 'fresnel: error:' message")
            rc, err, _ = results["info"]
            if rc == 0:
                rows["loaded with warnings" if "warning" in err else "loaded"] += 1
            elif rc == 1:
                rows["rejected with error"] += 1
    print(f"corpus: {len(files)} files in {a.corpus}")
    for k, v in rows.items():
        print(f"  {k:<22} {v:5d}")
    print(f"  slowest step: {slowest[1]} ({slowest[0]:.2f} s)")
    for note in notes:
        print(f"  note: {note}")
    for f in failures:
        print(f)
    print(f"{len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
