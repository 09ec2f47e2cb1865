"""What the Cycles benches share (occlusion_fidelity.py, shadow_fidelity.py): where ../shared's tools
and the Cycles images are, one Blender Cycles image made by ../shared/tools/cycles-ref/render into
`truth` unless it is there already, and the fidelity tool's metrics of an image against another."""
import json
import os
import shutil
import subprocess
import sys


def cycles_image(cycles, truth, args, label):
    """Makes `truth` (a PNG) with cycles-ref's `args` when it is absent; False when it cannot
    (no Blender, no cycles-ref), after saying so."""
    if os.path.exists(truth):
        return True
    if not os.path.exists(cycles) or not shutil.which("blender"):
        print(f"  no Cycles image for {label} (needs Debian's blender)", file=sys.stderr)
        return False
    print(f"  Cycles: {label}...", file=sys.stderr, flush=True)
    # Blender and cycles-ref's post-processing want Debian's python3 (numpy, PIL), not one a
    # version manager put first on the PATH.
    env_vars = {k: v for k, v in os.environ.items() if not k.startswith("PYENV")}
    env_vars["PATH"] = os.pathsep.join(p for p in os.environ.get("PATH", "").split(os.pathsep) if ".pyenv" not in p)
    subprocess.run([cycles, *args, "--out", truth + ".tmp.png"], check=True, stdout=subprocess.DEVNULL, env=env_vars)
    os.replace(truth + ".tmp.png", truth)
    return True


def locations(bench_file, fresnel_binary, refs):
    """(shared, cycles-ref's render, the fidelity compare.py, the refs folder, made): ../shared
    beside the repository (FRESNEL_SHARED_DIR overrides), refs beside the binary's build folder
    unless given."""
    root = os.path.dirname(os.path.dirname(os.path.abspath(bench_file)))
    shared = os.environ.get("FRESNEL_SHARED_DIR", os.path.join(root, "..", "shared"))
    refs = refs or os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(fresnel_binary))), "cycles-refs")
    return shared, os.path.join(shared, "tools/cycles-ref/render"), os.path.join(shared, "tools/fidelity/compare.py"), refs


def metrics(compare, test, ref):
    """compare.py's JSON for `test` against `ref` (psnr_db, mv_rms_db, ...)."""
    out = subprocess.run(["/usr/bin/python3", compare, test, ref, "--json"], capture_output=True, text=True, check=True).stdout
    return json.loads(out)
