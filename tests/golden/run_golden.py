#!/usr/bin/env python3
"""Golden-image test: render each case of cases.json with `pacifica replay` at a fixed camera and time and
compare the tonemapped PNG with the committed reference tests/golden/<name>.png using OpenImageIO's idiff.

Threshold (why): the reference and the test both come from Mesa llvmpipe, which is bit-deterministic on one
machine, but a different CPU (AVX2 vs AVX-512 code paths) or a Mesa point release can change float rounding
in the rasteriser and in texture filtering. After the 8-bit quantisation that shows up as differences of
1-2 code values (0.004-0.008) on a few pixels, mostly along the sun glitter and the horizon. So a pixel fails
above 0.02 (5 code values), the test fails when more than 0.2 % of pixels fail, and any single pixel off by
more than 0.1 fails outright (a real change: wrong waves, lighting or tonemap moves many pixels by far more).

On failure the new image and a difference image (|a-b| x 20) are written next to the test's working dir
and their paths printed. Usage: run_golden.py PACIFICA_CLI SOURCE_DIR WORK_DIR
"""
import json
import os
import shutil
import subprocess
import sys

FAIL = "0.02"
FAIL_PERCENT = "0.2"
HARD_FAIL = "0.1"


def main():
    cli, source_dir, work_dir = sys.argv[1:4]
    golden_dir = os.path.join(source_dir, "tests", "golden")
    cases = json.load(open(os.path.join(golden_dir, "cases.json")))["cases"]
    shutil.rmtree(work_dir, ignore_errors=True)
    os.makedirs(work_dir)
    failed = []
    for case in cases:
        out = os.path.join(work_dir, case["name"])
        t = str(case["time"])
        cmd = [cli, "replay", os.path.join(golden_dir, case["flight"]), "--out", out, "--start", t, "--end", t,
               "--size", case["size"], "--no-progress", *case.get("args", [])]
        subprocess.run(cmd, check=True)
        new = os.path.join(out, "frame_00000.png")
        ref = os.path.join(golden_dir, case["name"] + ".png")
        if not os.path.exists(ref):
            print(f"golden {case['name']}: no reference {ref}; run tests/golden/bless.sh")
            failed.append(case["name"])
            continue
        r = subprocess.run(["idiff", "-fail", FAIL, "-failpercent", FAIL_PERCENT, "-hardfail", HARD_FAIL, ref, new],
                           capture_output=True, text=True)
        print(f"golden {case['name']}: idiff exit {r.returncode}\n{r.stdout.strip()}")
        if r.returncode not in (0, 1):  # 0 = identical/pass, 1 = warning, 2+ = failure
            diff = os.path.join(work_dir, case["name"] + "-diff.png")
            subprocess.run(["idiff", "-o", diff, "-abs", "-scale", "20", ref, new], capture_output=True)
            print(f"golden {case['name']}: FAILED; new image {new}, difference image {diff}")
            failed.append(case["name"])
    print(f"{len(cases) - len(failed)} passed, {len(failed)} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
