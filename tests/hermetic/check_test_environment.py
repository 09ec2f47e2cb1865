#!/usr/bin/env python3
"""Every CTest test of this build must run with XDG_CACHE_HOME inside the build folder,
so no test reads or writes the user's ~/.cache (see FRESNEL_TEST_ENVIRONMENT in the
top-level CMakeLists.txt). Reads the test list from `ctest --show-only=json-v1`."""
import json
import os
import subprocess
import sys


def main():
    ctest, build = sys.argv[1], os.path.realpath(sys.argv[2])
    out = subprocess.run([ctest, "--show-only=json-v1"], cwd=build, capture_output=True, text=True, check=True).stdout
    tests = json.loads(out)["tests"]
    bad = []
    for t in tests:
        env = {}
        for p in t.get("properties", []):
            if p["name"] == "ENVIRONMENT":
                env.update(v.split("=", 1) for v in p["value"] if "=" in v)
        cache = env.get("XDG_CACHE_HOME")
        if not cache:
            bad.append(f"{t['name']}: no XDG_CACHE_HOME in its ENVIRONMENT")
        elif os.path.commonpath([build, os.path.realpath(cache)]) != build:
            bad.append(f"{t['name']}: XDG_CACHE_HOME={cache} is outside the build folder {build}")
    print(f"{len(tests)} tests, {len(bad)} without a cache in the build folder")
    for b in bad:
        print("  " + b)
    if len(tests) < 2:
        print("expected more than one test in the list")
        return 1
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
