#!/usr/bin/env python3
"""bench_frame_quick: runs `pacifica-bench-frame --quick` (the 3 presets at 160x90, 3 frames) and checks its
report: one row per preset, finite positive frame times, the per-pass split measured (sea and the compute shading
pass, which lights the sky too, > 0; no effect time above the frame), vertices growing low < medium < high, the
compute, sea and shading passes and the one draw counted, GL_RENDERER
and both clocks named, CSV and Markdown written; a bad --size is refused with exit 2; --only runs the named settings only;
eight spot lights with their beams add no pass or draw. Asserts nothing about speed
(docs/PERFORMANCE.md has the figures). Usage: test_frame_bench.py BENCH_EXE OUT_DIR"""
import csv
import json
import math
import os
import shutil
import subprocess
import sys

exe, out = sys.argv[1], sys.argv[2]
shutil.rmtree(out, ignore_errors=True)
p = subprocess.run([exe, "--quick", "--out", out], capture_output=True, text=True, timeout=240)
print(p.stdout, p.stderr)
failed = []


def check(ok, what):
    print(("  ok    " if ok else "  FAIL  ") + what)
    if not ok:
        failed.append(what)


check(p.returncode == 0, "the benchmark exits 0")
report = json.load(open(os.path.join(out, "frame.json"))) if p.returncode == 0 else {"rows": []}
rows = {r["setting"]: r for r in report["rows"]}
check(sorted(rows) == ["high", "low", "medium"], f"one row per preset (got {sorted(rows)})")
for name, r in rows.items():
    check(r["width"] == 160 and r["height"] == 90 and r["samples"] >= 1, f"{name}: 160x90, frames timed")
    check(math.isfinite(r["ms_median"]) and r["ms_median"] > 0 and r["ms_p90"] >= r["ms_median"],
          f"{name}: frame ms median {r['ms_median']} > 0, p90 >= median")
    check(r["shade_ms"] > 0 and r["sea_ms"] > 0,
          f"{name}: shading {r['shade_ms']} and sea {r['sea_ms']} ms measured")
    check(0 <= r["effects_ms"] < r["sea_ms"], f"{name}: no effects: effects span {r['effects_ms']} below the sea's")
    # The presets shade in one compute pass (OceanDesc::computeShading): the sky is no draw of its own. On a
    # software renderer (OceanDesc::shadeTiles Auto) by tiles: the sorting pass and one dispatch per kind of tile.
    software = "llvmpipe" in report.get("renderer", "") or "softpipe" in report.get("renderer", "")
    check(r["shade_tiled"] == software, f"{name}: shaded by tiles on a software renderer only (got {r['shade_tiled']})")
    want = 3 + (4 if r["shade_tiled"] else 0)
    check(r["passes"] == want and r["draws"] == 1,
          f"{name}: lighting-map compute + sea + shading = {want} passes, 1 draw (got {r['passes']}, {r['draws']})")
if len(rows) == 3:
    check(rows["low"]["vertices"] < rows["medium"]["vertices"] < rows["high"]["vertices"],
          "vertices grow low < medium < high")
check(report.get("renderer", "") != "" and report.get("clock", "") != "" and report.get("pass_clock", "") != "",
      "renderer, frame clock and pass clock named")
with open(os.path.join(out, "frame.csv")) as f:
    check(len(list(csv.DictReader(f))) == 3, "frame.csv has the 3 rows")
check(os.path.exists(os.path.join(out, "frame.md")), "Markdown table written")
p2 = subprocess.run([exe, "--out", out, "--size", "huge"], capture_output=True, text=True, timeout=60)
check(p2.returncode == 2 and "--size" in p2.stderr, "a bad --size is refused")
p3 = subprocess.run([exe, "--quick"], capture_output=True, text=True, timeout=60)
check(p3.returncode == 2 and "--out" in p3.stderr, "a missing --out is refused")
only_out = os.path.join(out, "only")
p4 = subprocess.run([exe, "--quick", "--only", "low", "--out", only_out], capture_output=True, text=True, timeout=120)
only_rows = json.load(open(os.path.join(only_out, "frame.json")))["rows"] if p4.returncode == 0 else []
check([r["setting"] for r in only_rows] == ["low"], "--only low runs just the low preset")
p5 = subprocess.run([exe, "--quick", "--only", "lowest", "--out", only_out], capture_output=True, text=True,
                    timeout=60)
check(p5.returncode == 2 and "--only" in p5.stderr, "--only naming no setting is refused")
# The spot rows (a full run's): eight lamps with their beams run inside the same passes and draws as the fog
# without lamps.
spot_out = os.path.join(out, "spots")
p6 = subprocess.run([exe, "--size", "160x90", "--frames", "1", "--only", "high/fog-1e-3", "--only", "high/spots-8",
                     "--out", spot_out], capture_output=True, text=True, timeout=240)
spot_rows = {r["setting"]: r for r in json.load(open(os.path.join(spot_out, "frame.json")))["rows"]} \
    if p6.returncode == 0 else {}
check(sorted(spot_rows) == ["high/fog-1e-3", "high/spots-8"], f"the spot rows run (got {sorted(spot_rows)})")
if len(spot_rows) == 2:
    fog, spots = spot_rows["high/fog-1e-3"], spot_rows["high/spots-8"]
    check(spots["passes"] == fog["passes"] and spots["draws"] == fog["draws"],
          f"lamps and beams add no pass or draw ({spots['passes']}/{spots['draws']} vs {fog['passes']}/{fog['draws']})")
    check(math.isfinite(spots["ms_median"]) and spots["ms_median"] > 0, "the spot row's frame time measured")
print("FAILED: " + "; ".join(failed) if failed else "all checks passed")
sys.exit(1 if failed else 0)
