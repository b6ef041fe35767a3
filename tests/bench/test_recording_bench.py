#!/usr/bin/env python3
"""bench_recording_quick: runs `pacifica-bench-recording --mb 2 --runs 1` and checks its report: both inputs
(text and zip) parsed to the same objects, samples and decoded size, finite positive MB/s and peak memory, the
Markdown table written, and the generated recordings removed. Asserts nothing about speed (the benchmark
reports it; docs/RECORDINGS.md has the figures).
Usage: test_recording_bench.py BENCH_EXE OUT_DIR"""
import json
import math
import os
import shutil
import subprocess
import sys

exe, out = sys.argv[1], sys.argv[2]
shutil.rmtree(out, ignore_errors=True)
p = subprocess.run([exe, "--out", out, "--mb", "2", "--runs", "1"], capture_output=True, text=True, timeout=240)
print(p.stdout, p.stderr)
failed, passed = [], []


def check(ok, what):
    print(("  ok    " if ok else "  FAIL  ") + what)
    (passed if ok else failed).append(what)


check(p.returncode == 0, "the benchmark exits 0")
report = json.load(open(os.path.join(out, "recording_bench.json"))) if p.returncode == 0 else {"results": []}
r = report["results"]
check([x["input"] for x in r] == ["generated.txt.acmi", "generated.zip.acmi"], "text and zip results")
if len(r) == 2:
    a, b = r
    check(a["decoded_mb"] >= 2.0 and a["decoded_mb"] == b["decoded_mb"], "both decode the same >= 2 MB")
    check(a["samples"] == b["samples"] > 0 and a["objects"] == b["objects"] > 100, "same objects and samples")
    check(b["file_mb"] < a["file_mb"], "the zip is smaller than the text")
    for x in r:
        check(math.isfinite(x["mb_per_s"]) and x["mb_per_s"] > 0, f"{x['input']}: MB/s finite and > 0")
        check(math.isfinite(x["peak_over_tracks"]) and x["peak_over_tracks"] > 0, f"{x['input']}: peak memory")
check(os.path.exists(os.path.join(out, "recording_bench.md")), "Markdown table written")
check(not any(n.startswith("generated.") for n in os.listdir(out)) if os.path.isdir(out) else False,
      "the generated recordings are removed")
print(f"{len(passed)} passed, {len(failed)} failed")
sys.exit(1 if failed else 0)
