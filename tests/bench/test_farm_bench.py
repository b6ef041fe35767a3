#!/usr/bin/env python3
"""The farm's scaling benchmark (tools/bench/bench_farm.py) on a tiny run: it completes, writes its table with
the one-process row and one row per workers x chunk size, every farm row's frames equal to the one-process
run's, and sane figures (positive wall time and frames/s, as many chunks as the sizes make). It asserts nothing
about speed (docs/BENCHMARKS.md).

Usage: test_farm_bench.py PACIFICA_EXE SOURCE_DIR
"""
import csv
import os
import subprocess
import sys
import tempfile


def main():
    exe, source = sys.argv[1], sys.argv[2]
    out = tempfile.mkdtemp(prefix="pacifica-farm-bench-")
    cmd = [sys.executable, os.path.join(source, "tools", "bench", "bench_farm.py"), "--pacifica", exe, "--out", out,
           "--workers", "1,2", "--chunk-frames", "3", "--", "--start", "218", "--end", "223", "--fps", "1",
           "--size", "160x90"]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    print(p.stdout + p.stderr)
    failed = []
    if p.returncode != 0:
        failed.append(f"bench_farm.py exits {p.returncode}")
    with open(os.path.join(out, "farm-scaling.csv")) as f:
        rows = list(csv.DictReader(f))
    want = [("1", "6", "1"), ("1", "3", "2"), ("2", "3", "2")]
    got = [(r["workers"], r["chunk_frames"], r["chunks"]) for r in rows]
    if got != want:
        failed.append(f"rows (workers, chunk frames, chunks) {got}, expected {want}")
    if [r["identical"] for r in rows[1:]] != ["yes", "yes"]:
        failed.append(f"farm rows' frames equal the one-process run's: {[r['identical'] for r in rows]}")
    if not all(float(r["wall_s"]) > 0 and float(r["frames_per_s"]) > 0 for r in rows):
        failed.append("positive wall time and frames/s in every row")
    if not os.path.isfile(os.path.join(out, "farm-scaling.md")):
        failed.append("farm-scaling.md written")
    for f in failed:
        print("FAIL  " + f)
    print("farm bench: " + ("FAILED" if failed else "ok") + f" (output in {out})")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
