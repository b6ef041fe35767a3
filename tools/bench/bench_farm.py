#!/usr/bin/env python3
"""Scaling of a sharded replay (docs/SCALE.md): frames/s of `pacifica farm` (local pool) against workers and
chunk size, against one process rendering the same run, with the per-chunk overhead (start-up and shader
compile, pre-roll) measured from the chunks' own summaries.

  bench_farm.py --pacifica EXE --out DIR [--flight FILE] [--workers 1,2] [--chunk-frames 25,100] [--gpus N]
                [--repeat N] -- REPLAY OPTIONS

Writes DIR/farm-scaling.csv and DIR/farm-scaling.md (a table), and prints the table. Every farm run's frames
are compared with the one-process run's (EXR pixel hashes in the summaries): a row whose frames differ says so.
Times: wall clock (time.monotonic) around each command; the medians of --repeat runs (default 1). With
--gpus N the pool gives worker slot s the GPU s mod N (CUDA_VISIBLE_DEVICES).
"""
import argparse
import csv
import json
import os
import shutil
import statistics
import subprocess
import sys
import time


def timed(cmd, env=None):
    t = time.monotonic()
    p = subprocess.run(cmd, capture_output=True, text=True, env=env)
    wall = time.monotonic() - t
    if p.returncode != 0:
        sys.exit(f"bench_farm: `{' '.join(cmd)}` failed (exit {p.returncode}):\n{p.stderr[-2000:]}")
    return wall


def hashes(summary):
    return [[f["exr_pixel_hash"] for f in v["frames"]] for v in summary["views"]]


def load(path):
    with open(path) as f:
        return json.load(f)


def one_process(exe, flight, replay, out, repeat):
    walls = []
    for _ in range(repeat):
        shutil.rmtree(out, ignore_errors=True)
        walls.append(timed([exe, "replay", flight, *replay, "--no-progress", "--out", out]))
    s = load(os.path.join(out, "summary.json"))
    return statistics.median(walls), s


def farm(exe, flight, replay, out, workers, chunk, gpus, repeat):
    walls = []
    for _ in range(repeat):
        shutil.rmtree(out, ignore_errors=True)
        cmd = [exe, "farm", "run", flight, "--out", out, "--chunk-frames", str(chunk), "--workers", str(workers)]
        if gpus:
            cmd += ["--gpus", str(gpus)]
        walls.append(timed(cmd + ["--", *replay]))
    name = [d for d in os.listdir(out) if os.path.isfile(os.path.join(out, d, "summary.json"))][0]
    return statistics.median(walls), load(os.path.join(out, name, "summary.json"))


def chunk_overheads(s):
    """Per chunk: its start-up beyond a steady frame (context, shaders, first frame; the pre-roll, which the
    time to the first frame includes, taken out) and its pre-roll, s."""
    start, pre = [], []
    for c in s["chunks"]:
        start.append(max(0.0, c.get("time_to_first_frame_s", 0.0) - c.get("frame_wall_ms_median", 0.0) / 1000.0 -
                         c.get("preroll_s", 0.0)))
        pre.append(c.get("preroll_s", 0.0))
    return statistics.mean(start), statistics.mean(pre)


def main():
    argv = sys.argv[1:]
    replay = []
    if "--" in argv:
        i = argv.index("--")
        argv, replay = argv[:i], argv[i + 1:]
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--pacifica", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--flight", default=os.path.join(os.path.dirname(__file__), "..", "data", "sortie.txt.acmi"))
    ap.add_argument("--workers", default="1,2")
    ap.add_argument("--chunk-frames", default="25,100")
    ap.add_argument("--gpus", type=int, default=0)
    ap.add_argument("--repeat", type=int, default=1)
    a = ap.parse_args(argv)
    if not replay:
        replay = ["--start", "200", "--end", "229", "--fps", "4", "--size", "320x180"]
    os.makedirs(a.out, exist_ok=True)
    flight = os.path.abspath(a.flight)
    base_wall, base = one_process(a.pacifica, flight, replay, os.path.join(a.out, "one-process"), a.repeat)
    frames = len(base["frames"])
    renderer = base["gl"]["renderer"]
    rows = [{"workers": 1, "chunk_frames": frames, "chunks": 1, "wall_s": round(base_wall, 2),
             "frames_per_s": round(frames / base_wall, 2), "speedup": 1.0, "efficiency": 1.0,
             "startup_s_per_chunk": round(max(0.0, base["timings"]["time_to_first_frame_s"] -
                                              base["timings"]["frame_wall_ms_median"] / 1000.0), 3),
             "preroll_s_per_chunk": 0.0, "identical": "reference (one process)"}]
    for w in [int(x) for x in a.workers.split(",")]:
        for c in [int(x) for x in a.chunk_frames.split(",")]:
            wall, s = farm(a.pacifica, flight, replay, os.path.join(a.out, f"farm-w{w}-c{c}"), w, c, a.gpus,
                           a.repeat)
            start, pre = chunk_overheads(s)
            speedup = base_wall / wall
            rows.append({"workers": w, "chunk_frames": c, "chunks": len(s["chunks"]), "wall_s": round(wall, 2),
                         "frames_per_s": round(frames / wall, 2), "speedup": round(speedup, 2),
                         "efficiency": round(speedup / w, 2), "startup_s_per_chunk": round(start, 3),
                         "preroll_s_per_chunk": round(pre, 4),
                         "identical": "yes" if hashes(s) == hashes(base) else "NO: frames differ"})
    with open(os.path.join(a.out, "farm-scaling.csv"), "w", newline="") as f:
        wr = csv.DictWriter(f, fieldnames=list(rows[0]))
        wr.writeheader()
        wr.writerows(rows)
    head = (f"{frames} frames x {len(base['views'])} view(s) of {os.path.basename(flight)} "
            f"({' '.join(replay)}), GL_RENDERER {renderer}, {os.cpu_count()} CPUs; wall clock "
            f"(time.monotonic) per command, median of {a.repeat}")
    lines = [head, "", "| " + " | ".join(rows[0]) + " |", "|" + "---|" * len(rows[0])]
    lines += ["| " + " | ".join(str(r[k]) for k in rows[0]) + " |" for r in rows]
    text = "\n".join(lines) + "\n"
    with open(os.path.join(a.out, "farm-scaling.md"), "w") as f:
        f.write(text)
    print(text)
    return 0 if all(r["identical"] != "NO: frames differ" for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
