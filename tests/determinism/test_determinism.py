#!/usr/bin/env python3
"""Determinism of `pacifica replay`: the same slice of the demo flight (t = 8, 13, 18, 23 s at 320x180: two
frames of the 20 m low pass, two of the climb) rendered by separate processes must produce bit-identical
scene-linear EXR pixels and display PNG pixels:
  run1, run2   default environment, twice (run-to-run)
  lp1, lp2     LP_NUM_THREADS=1 and =2 (llvmpipe's rasteriser thread count; bins are split differently)
  device       PACIFICA_EGL_PLATFORM=device (EGL device platform instead of Mesa surfaceless); compared only
               when it reports the same GL_RENDERER, since on a machine with a GPU it picks the hardware.
Per frame it compares summary.json's exr_pixel_hash and the SHA-1 of the decoded pixels (`iinfo --hash`) of
both EXR and PNG. A mismatch writes a difference image with idiff. It also asserts the frames differ from
one another (at least 2 distinct hashes), so a renderer that draws nothing, or always the same image, fails.

Usage: test_determinism.py PACIFICA_EXE SOURCE_DIR     (python3 standard library + OIIO's iinfo/idiff)
Temp dirs are removed on success and kept (path printed) on failure.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from checks import Checks  # noqa: E402  (shared check counter)

SLICE = ["--start", "8", "--end", "26", "--fps", "0.2", "--size", "320x180"]
EXPECTED_TIMES = [8.0, 13.0, 18.0, 23.0]  # 8 + k / 0.2 while <= 26
RUN_TIMEOUT_S = 180
VARIANTS = [  # name, extra environment, must match the reference renderer
    ("run1", {}, True),
    ("run2", {}, True),
    ("lp1", {"LP_NUM_THREADS": "1"}, True),
    ("lp2", {"LP_NUM_THREADS": "2"}, True),
    ("device", {"PACIFICA_EGL_PLATFORM": "device"}, False),
]


def child_env(extra):
    env = dict(os.environ)
    env.pop("OCIO", None)  # hermetic: $OCIO would replace the embedded config
    for key in ("LP_NUM_THREADS", "PACIFICA_EGL_PLATFORM"):
        env.pop(key, None)  # each variant sets exactly what it tests
    env.setdefault("MESA_SHADER_CACHE_DISABLE", "true")
    env.update(extra)
    return env


def iinfo_hashes(directory, names):
    """SHA-1 of the decoded pixels of each image, one iinfo process for all of them."""
    proc = subprocess.run([shutil.which("iinfo") or "iinfo", "--hash", *names], cwd=directory,
                          capture_output=True, text=True, timeout=RUN_TIMEOUT_S)
    out, current = {}, None
    for line in proc.stdout.splitlines():
        if not line.startswith(" ") and " : " in line:
            current = line.split(" : ", 1)[0].strip()
        elif "SHA-1:" in line and current:
            out[current] = line.split("SHA-1:", 1)[1].strip()
    return proc.returncode, out, proc.stderr.strip()


def write_diff(reference, other, diff_path):
    """On a mismatch: idiff's report and a difference image (|a - b| x 20) for a human to look at."""
    proc = subprocess.run(["idiff", "-fail", "0", "-failpercent", "0", "-o", diff_path, "-abs", "-scale", "20",
                           reference, other], capture_output=True, text=True, timeout=RUN_TIMEOUT_S)
    print("    idiff: " + " | ".join(proc.stdout.strip().splitlines()[-4:]))
    print(f"    difference image: {diff_path}")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("pacifica_exe")
    ap.add_argument("source_dir")
    ns = ap.parse_args()
    flight = os.path.join(os.path.abspath(ns.source_dir), "tools", "data", "demo_flight.csv")
    c = Checks()
    tmp = tempfile.mkdtemp(prefix="pacifica-determinism-")
    t0 = time.monotonic()
    print(f"determinism: {ns.pacifica_exe} (temp dir {tmp})")
    if not shutil.which("iinfo") or not shutil.which("idiff"):
        c.check(False, "OIIO's iinfo and idiff are on PATH (Debian package openimageio-tools)")

    runs = {}  # name -> {"summary", "dir", "sha"}
    for name, extra, must_match in VARIANTS if not c.failed else []:
        out = os.path.join(tmp, name)
        cmd = [ns.pacifica_exe, "replay", flight, "--out", out, *SLICE, "--no-progress"]
        print(f"[{name}] {' '.join(f'{k}={v}' for k, v in extra.items()) or '(default environment)'}")
        print("  $ " + " ".join(cmd))
        t = time.monotonic()
        try:
            proc = subprocess.run(cmd, env=child_env(extra), capture_output=True, text=True,
                                  timeout=RUN_TIMEOUT_S)
        except subprocess.TimeoutExpired:
            c.check(False, f"{name}: finishes within {RUN_TIMEOUT_S} s")
            continue
        print(f"    exit {proc.returncode} after {time.monotonic() - t:.1f} s")
        if not c.check(proc.returncode == 0, f"{name}: exits 0", proc.stderr.strip()[-2000:]):
            continue
        try:
            with open(os.path.join(out, "summary.json"), encoding="utf-8") as f:
                summary = json.load(f)
        except (OSError, ValueError) as e:
            c.check(False, f"{name}: summary.json readable", str(e))
            continue
        frames = summary.get("frames", [])
        times = [fr.get("time_s") for fr in frames]
        if not c.check(times == EXPECTED_TIMES, f"{name}: frames at t = {EXPECTED_TIMES}", f"got {times}"):
            continue
        renderer = summary.get("gl", {}).get("renderer", "")
        print(f"    gl.renderer = {renderer!r}, platform = {summary.get('gl', {}).get('platform')!r}, "
              f"camera z_m = {[round(fr['pose']['z_m'], 1) for fr in frames]}")
        ref_renderer = runs["run1"]["renderer"] if "run1" in runs else None
        if name != "run1" and renderer != ref_renderer:
            if must_match:
                c.check(False, f"{name}: same GL_RENDERER as run1", f"{renderer!r} vs {ref_renderer!r}")
            else:
                print(f"  skip  {name}: different GL_RENDERER than run1, its pixels may legitimately differ")
            continue
        names = [fr["exr"] for fr in frames] + [fr["png"] for fr in frames]
        rc, sha, err = iinfo_hashes(out, names)
        if not c.check(rc == 0 and all(n in sha for n in names), f"{name}: iinfo --hash reads every image", err):
            continue
        runs[name] = {"summary": summary, "dir": out, "sha": sha, "renderer": renderer,
                      "hashes": [fr["exr_pixel_hash"] for fr in frames]}

    ref = runs.get("run1")
    if ref:
        print("[compare] against run1")
        distinct = set(ref["hashes"])
        # The four frames see different water from different heights: identical frames would mean the
        # camera or the time is ignored, and would make every comparison below trivially pass.
        c.check(len(distinct) >= 2, "run1's frames are not all the same image (>= 2 distinct exr_pixel_hash)",
                str(ref["hashes"]))
        c.check(len({ref["sha"][fr["exr"]] for fr in ref["summary"]["frames"]}) >= 2,
                "run1's frames are not all the same image (>= 2 distinct decoded-EXR SHA-1)")
        for name, run in runs.items():
            if name == "run1":
                continue
            c.check(run["hashes"] == ref["hashes"], f"{name}: exr_pixel_hash identical to run1 for every frame",
                    f"{run['hashes']} vs {ref['hashes']}")
            for kind in ("exr", "png"):
                bad = [fr[kind] for fr in ref["summary"]["frames"] if run["sha"][fr[kind]] != ref["sha"][fr[kind]]]
                c.check(not bad, f"{name}: decoded {kind.upper()} pixels identical to run1 (iinfo --hash)",
                        f"differ: {bad}")
                for file in bad:
                    write_diff(os.path.join(ref["dir"], file), os.path.join(run["dir"], file),
                               os.path.join(tmp, f"diff_{name}_{file}"))
        compared = [n for n in runs if n != "run1"]
        print(f"    compared {len(compared)} runs with run1: {', '.join(compared)}")
        c.check(all(n in runs for n in ("run2", "lp1", "lp2")), "run2, lp1 and lp2 were all compared",
                f"compared {compared}")

    return c.finish("determinism", t0, tmp)


if __name__ == "__main__":
    sys.exit(main())
