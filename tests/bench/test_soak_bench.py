#!/usr/bin/env python3
"""bench_soak_short: the soak's short version. Runs `pacifica-bench-soak` for 160 frames of 1 s (160 s of sim
time: 160 explosions under a cap of 32, 11 ships appearing and leaving, the view count cycling 1-2-3) at 16x16 and checks its
report: every check passed (no GL object kind grows, every kind back to its baseline after the drain, resident
memory within 16 MiB; not under ASan, whose quarantine keeps freed memory), effects, ships and all three view counts were live, the CSV's columns and rows, GL_RENDERER
named, the plot drawn when gnuplot is installed. Frame time is reported, not asserted (--frame-time-ratio 0).
Then the checks' own test: with a texture kept every 5 frames a 60-frame run must exit 1 with the growth and the
drain checks failed, and a bad argument exits 2. Usage: test_soak_bench.py BENCH_EXE OUT_DIR"""
import csv
import json
import os
import shutil
import subprocess
import sys

exe, out = sys.argv[1], sys.argv[2]
failed = []


def check(ok, what):
    print(("  ok    " if ok else "  FAIL  ") + what)
    if not ok:
        failed.append(what)


# Under AddressSanitizer (the ASan pass exports ASAN_OPTIONS) resident memory says nothing about leaks: the
# quarantine holds freed memory by design (256 MiB), so RSS climbs with every allocation until it is full.
# There the RSS bound is lifted, and LeakSanitizer checks the heap at the soak's exit instead.
RSS_BOUND = ["--rss-growth-mib", "1000000"] if "ASAN_OPTIONS" in os.environ else []


def soak(folder, frames, *extra):
    shutil.rmtree(folder, ignore_errors=True)
    p = subprocess.run([exe, "--frames", str(frames), "--dt", "1", "--size", "16x16", "--samples", "40",
                        "--frame-time-ratio", "0", *RSS_BOUND, "--out", folder, *extra],
                       capture_output=True, text=True, timeout=900)
    print(p.stdout, p.stderr)
    return p


good = os.path.join(out, "good")
p = soak(good, 160)
check(p.returncode == 0, f"the soak exits 0 (got {p.returncode})")
report = json.load(open(os.path.join(good, "soak.json"))) if p.returncode in (0, 1) else {"checks": {}}
for name in ("gl_objects_do_not_grow", "gl_objects_return_after_drain", "rss_flat", "frame_time_flat"):
    c = report["checks"].get(name, {})
    check(c.get("passed") is True, f"check {name} passed: {c.get('detail')}")
check(report.get("gl_renderer", "") != "", "GL_RENDERER named")
rows = list(csv.DictReader(open(os.path.join(good, "soak.csv")))) if p.returncode == 0 else []
check(len(rows) == 40, f"40 samples (got {len(rows)})")
kinds = ["buffer", "texture", "framebuffer", "vertex_array", "program", "query", "sampler", "sync"]
check(rows != [] and list(rows[0].keys()) == ["frame", "sim_time_s", "rss_mib", "gpu_memory_used_mib",
                                              "frame_ms_median"] + ["gl_" + k for k in kinds] +
      ["gl_total", "explosions_active", "wakes_active", "ships", "views"], "the CSV's columns")
if rows:
    check(all(float(r["rss_mib"]) > 10 and float(r["frame_ms_median"]) > 0 for r in rows), "RSS and frame time > 0")
    check(all(int(r["gl_total"]) == sum(int(r["gl_" + k]) for k in kinds) for r in rows), "gl_total is the sum")
    check(min(int(r["gl_texture"]) for r in rows) > 0 and min(int(r["gl_program"]) for r in rows) > 0,
          "textures and programs are counted")
    check(max(int(r["explosions_active"]) for r in rows) >= 5, "explosions were live")
    check(max(int(r["wakes_active"]) for r in rows) >= 2 and max(int(r["ships"]) for r in rows) >= 4,
          "ships and their wakes were live")
    check({int(r["views"]) for r in rows} == {1, 2, 3}, "1, 2 and 3 views were rendered")
if shutil.which("gnuplot"):
    check(os.path.getsize(os.path.join(good, "soak.png")) > 10000, "soak.png drawn")

leaky = os.path.join(out, "leaky")
p = soak(leaky, 60, "--leak-textures-every", "5")
check(p.returncode == 1, f"a kept texture every 5 frames: exit 1 (got {p.returncode})")
report = json.load(open(os.path.join(leaky, "soak.json"))) if p.returncode == 1 else {"checks": {}}
for name in ("gl_objects_do_not_grow", "gl_objects_return_after_drain"):
    check(report["checks"].get(name, {}).get("passed") is False, f"the leak fails {name}")

p = subprocess.run([exe, "--frames", "0"], capture_output=True, text=True, timeout=60)
check(p.returncode == 2 and "--frames" in p.stderr, f"--frames 0 is refused with exit 2 naming it: {p.stderr.strip()}")
sys.exit(1 if failed else 0)
