"""Reading sanitizer output for the corpus and hostile-input runners.

Two things in a sanitizer build's stderr are not findings in fresnel's code:
- LeakSanitizer's own stop-the-world tracer dying at exit ("Tracer caught signal 11",
  "LeakSanitizer has encountered a fatal error"), a known intermittent fault of the tool
  (google/sanitizers#1353). The caller reruns the step.
- Leaks whose every stack frame above the allocator is "<unknown module>", or (with a
  working symboliser) a bare "(module+0xOFFSET)" without a function name: memory the GL
  driver allocated from code that is no longer mapped when the leak check runs (Mesa's
  driver is unloaded by eglTerminate; llvmpipe's JIT code has no module; an unloaded
  library that sat after the executable shows as the executable plus an offset past its
  end). fresnel's own code is linked into the executable and always symbolises, so such a
  leak cannot be ours; tests/lsan.supp covers the driver frames that still have a name.
Reports are read from stderr, never from the exit status: steps run with LeakSanitizer's
exitcode=0, so a leak report (counted or not) leaves the program's own status (0 or 1)
for the runners to judge.
Everything else (ASan errors, UBSan runtime errors, any leak with a named frame) is a
finding, except that a report of leaks alone is confirmed by running the step again:
the driver's threads make LeakSanitizer's view of exit timing-dependent, while a leak in
fresnel's code is deterministic and shows up again.
"""
import os
import re
import subprocess
import time

MARKERS = ("ERROR: AddressSanitizer", "ERROR: LeakSanitizer", "runtime error:", "UndefinedBehaviorSanitizer")
LSAN_TRACER_FAULT = "LeakSanitizer has encountered a fatal error"
_ALLOCATOR = re.compile(r"in (__interceptor_|__asan_|operator new|malloc|calloc|realloc)")
_UNNAMED = re.compile(r"\([^()\s]+\+0x[0-9a-f]+\)")


def tracer_fault(stderr):
    """True when LeakSanitizer itself failed and nothing else was reported."""
    return LSAN_TRACER_FAULT in stderr and not any(m in stderr for m in MARKERS)


def _leak_only_in_unknown_modules(stderr):
    if "ERROR: LeakSanitizer: detected memory leaks" not in stderr:
        return False
    if any(m in stderr for m in ("ERROR: AddressSanitizer", "runtime error:")):
        return False
    blocks = re.split(r"\n(?=(?:Direct|Indirect) leak of )", stderr)
    leaks = [b for b in blocks if re.match(r"(?:Direct|Indirect) leak of ", b)]
    if not leaks:
        return False
    for block in leaks:
        frames = [m.group(1).strip() for m in re.finditer(r"(?m)^\s*#\d+ 0x[0-9a-f]+ (.*)$", block)]
        # The symboliser works when the allocator's own frame has a name; then a frame with only
        # "(module+0xOFFSET)" is code no module maps any more (an unloaded driver placed after
        # the executable is reported as the executable plus an offset past its end).
        symbolised = any(_ALLOCATOR.search(f) for f in frames)
        for frame in frames:
            if frame == "(<unknown module>)" or _ALLOCATOR.search(frame):
                continue
            if symbolised and _UNNAMED.fullmatch(frame):
                continue
            return False
    return True


def finding(stderr):
    """The sanitizer report in stderr that counts as a finding, or None."""
    if not any(m in stderr for m in MARKERS):
        return None
    if _leak_only_in_unknown_modules(stderr):
        return None
    return stderr


def driver_leak(stderr):
    """True when the only report is a leak from unmapped driver code (see above)."""
    return _leak_only_in_unknown_modules(stderr)


def leak_only(stderr):
    """True when the report is LeakSanitizer's alone (no ASan error, no UBSan error)."""
    return ("ERROR: LeakSanitizer" in stderr and "ERROR: AddressSanitizer" not in stderr
            and "runtime error:" not in stderr)


def run_step(cmd, timeout):
    """Runs cmd, rerunning it when LeakSanitizer's tracer faulted (at most twice) and once
    to confirm a report of leaks alone. Returns (returncode or "timeout", stderr, seconds,
    notes): notes say what was rerun or not counted, for the runner to print. ASan and
    UBSan reports are never retried; finding(stderr) tells whether one remains."""
    notes, leak_report = [], None
    what = " ".join(str(c) for c in cmd[1:3])
    env = dict(os.environ)
    env["LSAN_OPTIONS"] = ":".join(o for o in [env.get("LSAN_OPTIONS", ""), "exitcode=0"] if o)
    for attempt in range(3):
        start = time.monotonic()
        try:
            p = subprocess.run(cmd, capture_output=True, text=True, errors="replace", timeout=timeout, env=env)
        except subprocess.TimeoutExpired:
            return "timeout", "", time.monotonic() - start, notes
        if tracer_fault(p.stderr) and attempt < 2:
            notes.append(f"rerun after a LeakSanitizer tracer fault: {what}")
            continue
        if finding(p.stderr) and leak_only(p.stderr) and leak_report is None and attempt < 2:
            leak_report = p.stderr
            continue
        if leak_report is not None and not finding(p.stderr):
            notes.append(f"leak report that a rerun did not reproduce, not counted: {what}\n{leak_report[-1500:]}")
        if driver_leak(p.stderr):
            notes.append(f"GL-driver leak from unmapped code, not counted: {what}")
        return p.returncode, p.stderr, time.monotonic() - start, notes
