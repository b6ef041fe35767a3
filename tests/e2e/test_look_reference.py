#!/usr/bin/env python3
"""The near sea against the look reference: `pacifica replay` renders the reference's 2 m and 50 m views (U10 =
9 m/s, sun 30 degrees up and 30 degrees right of the view, the camera looking downwind, 1280x720, vertical fov
60 degrees, pitch -5 degrees; docs/LOOK.md, "The clear sky") with the default model and with the FFT sea
(`--model fft`, its cascades: docs/LOOK.md, "The FFT sea"), and the sparkle of each one's glitter must be at
least half the reference frame's.

Sparkle: in the glitter region (the right half of the 640x360 frame from 6 rows below the horizon down), the
RMS of the luminance minus its 3x3 box mean (the high-frequency energy), over the mean luminance; luminance of
the 8-bit display values (Rec. 709 weights). A sea whose glitter is a smooth BRDF lobe scores ~0.006; one whose
glitter breaks into glints as many as the reference's scores like it.

The reference frames are renders of the demo of Bruneton, Neyret & Holzschuch, "Real-time Realistic Ocean
Lighting using Seamless Transitions from Geometry to BRDF" (Eurographics 2010), at 640x360, looked for as
look-reference/bruneton_{2m,50m}.png in the shared data directory ($PACIFICA_SHARED_DIR, set by ctest);
without them the test is skipped (exit 77) with a message.

Usage: test_look_reference.py PACIFICA_EXE SOURCE_DIR     (python3 standard library + oiiotool)
"""
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from pngread import read_png  # noqa: E402

SKIP = 77
VIEWS = {"2m": 2.0, "50m": 50.0}
MODELS = {"default": [], "fft": ["--model", "fft"]}
HORIZON_ROW = 150  # pitch -5 degrees in a 60-degree, 360-row frame: 180 - 5 / 30 * 180
MIN_RATIO = 0.5


def sparkle(path):
    width, height, channels, rows = read_png(path)
    if (width, height) != (640, 360):
        raise ValueError(f"{path}: expected 640x360, got {width}x{height}")

    def lum(x, y):
        r = rows[y]
        i = x * channels
        return (0.2126 * r[i] + 0.7152 * r[i + 1] + 0.0722 * r[i + 2]) / 255.0

    grid = [[lum(x, y) for x in range(width)] for y in range(height)]
    energy = total = 0.0
    n = 0
    for y in range(HORIZON_ROW + 7, height - 1):
        for x in range(width // 2 + 1, width - 1):
            box = sum(grid[yy][xx] for yy in (y - 1, y, y + 1) for xx in (x - 1, x, x + 1)) / 9.0
            d = grid[y][x] - box
            energy += d * d
            total += grid[y][x]
            n += 1
    return (energy / n) ** 0.5 / (total / n)


def main():
    if len(sys.argv) != 3:
        print(__doc__)
        return 2
    exe, source = sys.argv[1], os.path.abspath(sys.argv[2])
    shared = os.environ.get("PACIFICA_SHARED_DIR", "")  # set by ctest (tests/README.md)
    refs = {v: os.path.join(shared, "look-reference", f"bruneton_{v}.png") for v in VIEWS}
    missing = [p for p in refs.values() if not os.path.isfile(p)]
    if missing:
        print(f"skipped: the look reference frames are absent ({', '.join(missing)})")
        return SKIP
    tmp = tempfile.mkdtemp(prefix="pacifica-look-reference-")
    failed = []
    cases = 0
    for model, extra in MODELS.items():
        for view, z in VIEWS.items():
            flight = os.path.join(tmp, f"view_{view}.csv")
            with open(flight, "w", encoding="utf-8") as f:
                f.write("time_s,x_m,y_m,z_m,heading_deg,pitch_deg,roll_deg\n")
                f.write(f"0.0,0,0,{z},60,-5,0\n1.0,0,0,{z},60,-5,0\n")
            out = os.path.join(tmp, f"{model}_{view}")
            proc = subprocess.run([exe, "replay", flight, "--out", out, "--size", "1280x720", "--sea-state", "9",
                                   "--sun-elevation", "30", "--sun-azimuth", "90", "--no-events", "--start", "0",
                                   "--end", "0", "--no-progress"] + extra,
                                  capture_output=True, text=True, timeout=300)
            cases += 1
            if proc.returncode != 0:
                failed.append(f"{model} {view}: replay exited {proc.returncode}: {proc.stderr[-1500:]}")
                continue
            small = os.path.join(tmp, f"{model}_{view}_640.png")
            subprocess.run(["oiiotool", os.path.join(out, "frame_00000.png"), "--ch", "R,G,B", "--resize",
                            "640x360", "-d", "uint8", "-o", small], check=True)
            ours, ref = sparkle(small), sparkle(refs[view])
            ok = ours >= MIN_RATIO * ref
            print(f"  {'ok  ' if ok else 'FAIL'}  {model} {view}: sparkle {ours:.4f}, reference {ref:.4f} "
                  f"(ratio {ours / ref:.2f}, bound {MIN_RATIO})")
            if not ok:
                failed.append(f"{model} {view}: sparkle {ours:.4f} < {MIN_RATIO} x reference {ref:.4f}")
    if failed:
        print("FAILED:\n  " + "\n  ".join(failed) + f"\n(temp dir kept: {tmp})")
        return 1
    shutil.rmtree(tmp, ignore_errors=True)
    print(f"{cases} passed, 0 failed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
