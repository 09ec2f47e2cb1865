#!/usr/bin/env python3
"""Every shared library fresnel's programs and tests load belongs to a package that
scripts/packages.txt (or scripts/web-packages.txt) names.

Two kinds of load are checked:
  - linked: the NEEDED entries of every ELF file under BUILD/bin (the programs and the test
    executables), resolved as ldd resolves them;
  - opened at run time (dlopen): what the dynamic loader reports (LD_DEBUG=files) while the
    programs do what the tests make them do: a headless frame on OpenGL 3.3 and on OpenGL ES 3.0,
    a window under Xvfb on both, a path-traced frame, ../shared/tools/ogl1-ref's renderer and
    fidelity/compare.py's Python (NumPy, Pillow).
A library whose package comes with every Debian system (the dependency closure of the Essential
and required packages, i.e. what `debootstrap --variant=minbase` installs) needs no line; every
other package must be named even where another listed package happens to pull it in today.
A library the programs try to open and that is not on this machine is a failure too: the
package that would provide it cannot be checked, and the program would fail for users.

usage: check_packages.py BUILD_DIR SOURCE_DIR SHARED_DIR
exit 0: all named; 1: a package is missing from the lists (each printed); 77: cannot check here
(no dpkg).
"""
import os
import re
import shutil
import socket
import subprocess
import sys
import tempfile
import time

build, source, shared = (os.path.abspath(a) for a in sys.argv[1:4])
if not shutil.which("dpkg-query") or not shutil.which("dpkg"):
    print("no dpkg on this machine: nothing to check")
    sys.exit(77)


def listed_packages():
    names = set()
    for f in ("packages.txt", "web-packages.txt"):
        with open(os.path.join(source, "scripts", f)) as fh:
            for line in fh:
                line = line.split("#", 1)[0].strip()
                if line:
                    names.add(line)
    return names


def base_packages():
    """Essential/required packages and everything they depend on (installed ones)."""
    out = subprocess.run(["dpkg-query", "-W", "-f", "${Package}\t${Essential}\t${Priority}\t${Pre-Depends}, ${Depends}\n"],
                         capture_output=True, text=True, check=True).stdout
    deps, roots = {}, set()
    for line in out.splitlines():
        name, essential, priority, rest = (line.split("\t") + ["", "", ""])[:4]
        alternatives = []
        for clause in rest.split(","):
            # "a (>= 1) | b" -> first alternative's name, without architecture qualifiers
            clause = clause.strip()
            if clause:
                alternatives.append([re.split(r"[\s(:]", a.strip())[0] for a in clause.split("|")])
        deps[name] = alternatives
        if essential == "yes" or priority == "required":
            roots.add(name)
    seen, todo = set(), list(roots)
    while todo:
        p = todo.pop()
        if p in seen:
            continue
        seen.add(p)
        for alts in deps.get(p, []):
            todo.extend(a for a in alts if a in deps)
    return seen


def owner(path):
    """The package that installed `path` (tries the merged-/usr twin too), or None."""
    real = os.path.realpath(path)
    candidates = []
    for p in (path, real):
        candidates.append(p)
        if p.startswith("/usr/lib/"):
            candidates.append(p[len("/usr"):])
        elif p.startswith("/lib/"):
            candidates.append("/usr" + p)
    for c in candidates:
        r = subprocess.run(["dpkg", "-S", c], capture_output=True, text=True)
        if r.returncode == 0:
            return r.stdout.split(":", 1)[0].strip()
    return None


def ldconfig_paths():
    out = subprocess.run(["/sbin/ldconfig", "-p"], capture_output=True, text=True).stdout
    paths = {}
    for line in out.splitlines():
        m = re.match(r"\s*(\S+) \((libc6,x86-64|libc6,AArch64|libc6)[^)]*\) => (\S+)", line)
        if m and m.group(1) not in paths:
            paths[m.group(1)] = m.group(3)
    return paths


def is_elf(path):
    try:
        with open(path, "rb") as f:
            return f.read(4) == b"\x7fELF"
    except OSError:
        return False


loads = {}  # library (path or soname) -> how it was loaded (first seen)
missing = {}  # soname that could not be found -> by whom


def note(lib, why):
    loads.setdefault(lib, why)


# 1. Linked: direct NEEDED of each ELF under bin/, resolved with ldd.
bindir = os.path.join(build, "bin")
elves = sorted(os.path.join(bindir, f) for f in os.listdir(bindir) if is_elf(os.path.join(bindir, f)))
for elf in elves:
    dyn = subprocess.run(["readelf", "-d", elf], capture_output=True, text=True).stdout
    needed = re.findall(r"\(NEEDED\)\s+Shared library: \[([^\]]+)\]", dyn)
    resolved = {}
    for line in subprocess.run(["ldd", elf], capture_output=True, text=True).stdout.splitlines():
        m = re.match(r"\s*(\S+) => (.+?) \(0x", line)
        if m:
            resolved[m.group(1)] = m.group(2)
        elif re.match(r"\s*(\S+) => not found", line):
            missing.setdefault(line.split()[0], os.path.basename(elf))
    for n in needed:
        if n in resolved and resolved[n] != "not found":
            note(resolved[n], f"linked by {os.path.basename(elf)}")

# 2. Opened at run time: run the programs under LD_DEBUG=files.
dlopen_re = re.compile(r"file=(\S+) \[0\];\s+dynamically loaded by (\S+)")
fail_re = re.compile(r"cannot open shared object file|error while loading shared libraries: (\S+):")
scratch = tempfile.mkdtemp(prefix="fresnel_packages_")
fresnel = os.path.join(bindir, "fresnel")
# Debian's Python, as the tools' #! lines name it (not another one first on PATH).
python = "/usr/bin/python3" if os.path.exists("/usr/bin/python3") else sys.executable
env = dict(os.environ, XDG_CACHE_HOME=os.path.join(scratch, "cache"))
runs = [
    ("render on OpenGL 3.3", [fresnel, "render", "-o", f"{scratch}/a.png", "--size", "32x24", "--gl", "gl33"]),
    ("render on OpenGL ES 3.0", [fresnel, "render", "-o", f"{scratch}/b.png", "--size", "32x24", "--gl", "es3"]),
    ("trace", [fresnel, "trace", "-o", f"{scratch}/c.png", "--size", "16x12", "--spp", "1"]),
]
xvfb = shutil.which("Xvfb")
ogl1 = os.path.join(shared, "tools", "ogl1-ref")
if os.path.exists(os.path.join(ogl1, "render")):
    scenes = os.path.join(scratch, "scenes")
    runs.append(("ogl1-ref make-scenes", [python, os.path.join(ogl1, "make-scenes"), scenes]))
    runs.append(("ogl1-ref render", [python, os.path.join(ogl1, "render"), os.path.join(scenes, "spheres.obj"),
                                     "-o", f"{scratch}/d.png", "--size", "32x32"]))
runs.append(("Python with NumPy and Pillow", [python, "-c", "import numpy, PIL.Image, PIL.PngImagePlugin"]))
# The Python module (python/): its frame, and the pytest that runs its tests.
if os.path.isdir(os.path.join(build, "python", "fresnel")):
    runs.append(("the Python module", [python, "-c",
                 f"import sys; sys.path.insert(0, {os.path.join(build, 'python')!r}); import pytest, fresnel; "
                 "fresnel.render(fresnel.load(), size=(32, 24))"]))

display_proc = None
display_pipe = None
if xvfb and os.path.exists(fresnel):
    r, w = os.pipe()
    # As view_test starts its server: -noreset keeps it up between the two windows.
    display_proc = subprocess.Popen([xvfb, "-displayfd", str(w), "-screen", "0", "320x240x24", "-nolisten", "tcp",
                                     "-noreset"], pass_fds=(w,), stderr=open(os.path.join(scratch, "xvfb.log"), "w"))
    os.close(w)
    number = os.read(r, 16).decode().strip()
    # The read end stays open while the server runs: Xvfb writes the number again at times and
    # dies ("Cannot write display number") when nobody is there to read it.
    display_pipe = r
    # Wait until the server answers on its socket (the number can come before it accepts).
    for _ in range(100):
        try:
            with socket.socket(socket.AF_UNIX) as probe:
                probe.connect(f"/tmp/.X11-unix/X{number}")
            break
        except OSError:
            time.sleep(0.1)
    if number:
        for api in ("gl33", "es3"):
            runs.append((f"view on {api} under Xvfb",
                         [fresnel, "view", "--exit-after", "2", "--size", "64x48", "--gl", api], {"DISPLAY": ":" + number}))
else:
    print("(no Xvfb: the viewer's libraries are checked as linked only)")

ran_any = False
try:
    for entry in runs:
        what, cmd = entry[0], entry[1]
        extra = entry[2] if len(entry) > 2 else {}
        if not os.path.exists(cmd[0]):
            continue
        p = subprocess.run(cmd, env=dict(env, LD_DEBUG="files", **extra), capture_output=True, text=True, timeout=300)
        ran_any = True
        for line in p.stderr.splitlines():
            m = dlopen_re.search(line)
            if m:
                note(m.group(1), f"opened at run time by {os.path.basename(m.group(2))} ({what})")
        if p.returncode != 0:
            tail = "\n".join(l for l in p.stderr.splitlines() if "file=" not in l and not re.match(r"\s*\d+:", l))[-600:]
            print(f"FAIL {what} exited {p.returncode}: {' '.join(cmd)}\n{tail}")
            if extra and os.path.exists(os.path.join(scratch, "xvfb.log")):
                print("Xvfb: " + open(os.path.join(scratch, "xvfb.log")).read()[-800:])
            missing.setdefault(f"(a run: {what})", tail.strip().splitlines()[-1] if tail.strip() else "")
finally:
    if display_proc:
        display_proc.terminate()
        display_proc.wait()
    if display_pipe is not None:
        os.close(display_pipe)
    shutil.rmtree(scratch, ignore_errors=True)

listed, base = listed_packages(), base_packages()
sonames = ldconfig_paths()
problems = []
ok = 0
for lib, why in sorted(loads.items()):
    path = lib if lib.startswith("/") else sonames.get(lib)
    if not path or not os.path.exists(path):
        # Opened at run time and absent: an optional probe (Mesa's libd3d12, TBB's libirml, the
        # loader's tls/ folders) when the run went on; a run that failed for it is reported above.
        if "opened at run time" in why:
            continue
        problems.append(f"{lib} ({why}) is not on this machine")
        continue
    pkg = owner(path)
    if pkg is None:
        # Not from a package: the project's own build outputs (under the build folder).
        if os.path.realpath(path).startswith(os.path.realpath(build)):
            continue
        problems.append(f"{path} ({why}) belongs to no Debian package")
        continue
    if pkg in listed or pkg in base:
        ok += 1
        continue
    problems.append(f"{path} ({why}) comes from package {pkg}, which scripts/packages.txt does not name")
for soname, by in sorted(missing.items()):
    problems.append(f"{soname}: not found ({by})")

print(f"{len(elves)} executables, {len(loads)} libraries linked or opened at run time; "
      f"{ok} from packages the lists name or every Debian has")
for p in problems:
    print("FAIL " + p)
sys.exit(1 if problems else 0)
