#!/usr/bin/env python3
"""bench_tonemap_quick: runs `pacifica-bench-tonemap --frames 3 --cpu-frames 1 --size 320x180` and checks its
report: the 8 transforms (6 shipped + the embedded config's 2 sRGB views), finite positive GPU and CPU medians,
GL_RENDERER and the clock named, the Markdown table written. Asserts nothing about speed (docs/TONEMAP.md has
the figures). Usage: test_tonemap_bench.py BENCH_EXE OUT_DIR"""
import json
import math
import os
import shutil
import subprocess
import sys

exe, out = sys.argv[1], sys.argv[2]
shutil.rmtree(out, ignore_errors=True)
p = subprocess.run([exe, "--out", out, "--frames", "3", "--cpu-frames", "1", "--size", "320x180"],
                   capture_output=True, text=True, timeout=240)
print(p.stdout, p.stderr)
failed = []


def check(ok, what):
    print(("  ok    " if ok else "  FAIL  ") + what)
    if not ok:
        failed.append(what)


check(p.returncode == 0, "the benchmark exits 0")
report = json.load(open(os.path.join(out, "tonemap_bench.json"))) if p.returncode == 0 else {"transforms": []}
rows = report["transforms"]
check(len(rows) == 8, f"8 transforms timed (got {len(rows)})")
check(sum(r["transform"].startswith("pacifica: ") for r in rows) == 6, "the 6 shipped tonemappers")
for r in rows:
    check(math.isfinite(r["gpu_ms_per_frame_median"]) and r["gpu_ms_per_frame_median"] > 0, f"{r['transform']}: GPU ms")
    check(math.isfinite(r["cpu_ms_per_frame_median"]) and r["cpu_ms_per_frame_median"] > 0, f"{r['transform']}: CPU ms")
check(report.get("gl_renderer", "") != "" and "steady_clock" in report.get("clock", ""), "renderer and clock named")
check(os.path.exists(os.path.join(out, "tonemap_bench.md")), "Markdown table written")
p2 = subprocess.run([exe, "--out", out, "--size", "huge"], capture_output=True, text=True, timeout=60)
check(p2.returncode == 2 and "error" in p2.stderr, "a bad --size is refused")
print("FAILED: " + "; ".join(failed) if failed else "all checks passed")
sys.exit(1 if failed else 0)
