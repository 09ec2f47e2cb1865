#!/usr/bin/env python3
"""The layers' dependencies, read from CMake's own graph (cmake --graphviz): the GL-free
libraries reach no OpenGL, EGL, epoxy, GLFW or GPU library, and no library reaches one above it.

usage: check_layers.py SOURCE_DIR SCRATCH_DIR [CMAKE]
Configures SOURCE_DIR into SCRATCH_DIR (no build) with --graphviz and checks the graph.
"""
import os
import re
import shutil
import subprocess
import sys

source, scratch = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
cmake = sys.argv[3] if len(sys.argv) > 3 else "cmake"
shutil.rmtree(scratch, ignore_errors=True)
os.makedirs(scratch)
dot = os.path.join(scratch, "graph", "fresnel.dot")
os.makedirs(os.path.dirname(dot))
r = subprocess.run([cmake, "-S", source, "-B", os.path.join(scratch, "build"), "-DFRESNEL_BENCH=OFF",
                    f"--graphviz={dot}"], capture_output=True, text=True)
if r.returncode != 0:
    print(r.stdout[-2000:], r.stderr[-2000:])
    sys.exit(1)

names, edges = {}, {}
for line in open(dot):
    m = re.match(r'\s*"(node\d+)" \[ label = "([^"]+)"', line)
    if m:
        names[m.group(1)] = m.group(2).split("\\n")[0]
        continue
    m = re.match(r'\s*"(node\d+)" -> "(node\d+)"', line)
    if m:
        edges.setdefault(m.group(1), set()).add(m.group(2))
by_name = {}
for node, name in names.items():
    by_name.setdefault(name, node)


def reach(name):
    """Every target `name` depends on, directly or not (names)."""
    start = by_name.get(name)
    if start is None:
        print(f"FAIL no target {name} in CMake's graph")
        sys.exit(1)
    seen, todo = set(), [start]
    while todo:
        n = todo.pop()
        for m in edges.get(n, ()):
            if m not in seen:
                seen.add(m)
                todo.append(m)
    return {names[n] for n in seen}


GL = re.compile(r"(epoxy|EGL|egl|glfw|GLFW|OpenGL|libGL|GLESv2|fresnel_gpu|fresnel_gui|fresnel_render|fresnel::gpu|"
                r"fresnel::gui|fresnel::render|imgui|IMGUI)", re.I)
failed = False
# The graph is read right: the rasteriser does reach the GPU library and epoxy.
if not {"fresnel_gpu", "PkgConfig::EPOXY"} <= reach("fresnel_render"):
    print(f"FAIL the graph shows fresnel_render without fresnel_gpu and epoxy: {sorted(reach('fresnel_render'))}")
    sys.exit(1)
# Layers bottom up; a library may depend only on layers below it.
# fresnel_viewer (the viewer's state, scripts, picking and files) sits above job beside the front ends:
# it may reach the job layer and what lies under it, and, GL-free, neither render, gpu nor gui.
layers = ["fresnel_core", "fresnel_material", "fresnel_scene", "fresnel_ibl", "fresnel_job", "fresnel_gpu",
          "fresnel_render", "fresnel_trace", "fresnel_viewer", "fresnel_gui"]
gl_free = ["fresnel_core", "fresnel_material", "fresnel_scene", "fresnel_ibl", "fresnel_job", "fresnel_trace",
           "fresnel_viewer"]
for lib in gl_free:
    bad = sorted(n for n in reach(lib) if GL.search(n))
    if bad:
        print(f"FAIL {lib} reaches {', '.join(bad)}")
        failed = True
    else:
        print(f"ok {lib}: no path to OpenGL, EGL, epoxy, GLFW or the GPU library")
for i, lib in enumerate(layers):
    above = {l for l in layers[i + 1:]} - ({"fresnel_gpu"} if lib == "fresnel_trace" else set())
    # fresnel_viewer sits beside trace, not above it: it may not reach the tracer.
    if lib == "fresnel_viewer":
        above |= {"fresnel_trace"}
    up = sorted(n for n in reach(lib) if n in above or n.replace("::", "_") in above)
    # fresnel_trace sits beside render (not above it): it may not reach render or gpu either.
    if up:
        print(f"FAIL {lib} depends on {', '.join(up)}, above it")
        failed = True
shutil.rmtree(scratch, ignore_errors=True)
sys.exit(1 if failed else 0)
