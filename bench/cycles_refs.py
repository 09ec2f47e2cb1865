"""What the Cycles benches share (occlusion_fidelity.py, shadow_fidelity.py): one Blender Cycles
image made by ../shared/tools/cycles-ref/render into `truth`, unless it is there already."""
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
