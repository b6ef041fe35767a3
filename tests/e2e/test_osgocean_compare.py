#!/usr/bin/env python3
"""The osgOcean comparison's tools (tools/bench/osgocean_compare.sh, tools/bench/osgocean/swap_timer.c).

Cases (chosen with --case, one ctest test each):
  swap-timer  swap_timer.so, built as the script builds it, times a GLX program it cannot change
              (osgocean/glx_spin.c, which like osgOcean's example never ends by itself) under xvfb-run: the
              program is ended after the warm-up and timed frames, the result file holds exactly that many
              positive frame times and their median; SWAP_TIMER_SHOT keeps the last timed frame as a PNG
              with the program's exact pixels (frame 10's colour, the white quarter, right side up) and
              its luma statistics on stderr; a bad SWAP_TIMER_FRAMES exits 2 naming it and writes nothing.
  stand-in   the script's whole path on a stand-in for osgOcean's source: a CMake project whose `oceanExample`
              is glx_spin.c, with a resources/ folder. The script builds it with CMake, builds swap_timer.so,
              alternates the timed example with the given pacifica-bench-frame (--bench, --skip-install) and
              writes compare.md: one row per round with the two medians and their ratio, matching the files
              it kept (the example's frame times and shot, the bench's frame.csv). A flat frame (no sky) and
              a black one are refused: exit 4 naming the fault and the shot, no compare.md (the flat run
              goes into the good run's folder, whose report it must remove).
  real       the script unchanged on osgOcean's real source, ../shared/peers/osgocean-f235e99.tar.gz
              ($PACIFICA_SHARED_DIR), extracted to a scratch folder; skipped (77) without it. First with the
              source's demo/ folder moved away: the example draws no sky and the run is refused (exit 4);
              then with it: the build needs the debug-library fix (said on stderr), one round lands, its
              shot is 1024x768 with a textured sky, and compare.md's row matches the files.
  no-source   without osgOcean's source (a missing --source directory) the script exits 3, says what it
              looked for and prints the recipe naming Debian's OpenSceneGraph package; bad arguments exit 2
              naming the option; nothing is written in either case.

Usage: test_osgocean_compare.py --case CASE SOURCE_DIR [XVFB_RUN | BENCH_EXE]   (python3 standard library, cc)
"""
import csv
import os
import shutil
import struct
import subprocess
import sys
import tarfile
import tempfile
import zlib


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def check(cond, what, detail=""):
    print(("ok   " if cond else "FAIL ") + what + (f" ({detail})" if detail and not cond else ""))
    if not cond:
        sys.exit(1)


def read_png(path):
    """(width, height, rows of RGB bytes) of an 8-bit RGB PNG whose rows all use filter 0, as swap_timer.c
    writes them."""
    data = open(path, "rb").read()
    check(data[:8] == b"\x89PNG\r\n\x1a\n", f"{path} is a PNG")
    pos, idat, w, h = 8, b"", 0, 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        check(zlib.crc32(kind + body) == struct.unpack(">I", data[pos + 8 + n:pos + 12 + n])[0],
              f"{path}: chunk {kind} CRC")
        if kind == b"IHDR":
            w, h, depth, colour = struct.unpack(">IIBB", body[:10])
            check(depth == 8 and colour == 2, f"{path}: 8-bit RGB", str((depth, colour)))
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw = zlib.decompress(idat)
    check(len(raw) == h * (3 * w + 1), f"{path}: {h} rows of {w} pixels")
    rows = [raw[y * (3 * w + 1):(y + 1) * (3 * w + 1)] for y in range(h)]
    check(all(r[0] == 0 for r in rows), f"{path}: filter 0 on every row")
    return w, h, [r[1:] for r in rows]


def swap_timer(src, xvfb):
    tools = os.path.join(src, "tools", "bench", "osgocean")
    with tempfile.TemporaryDirectory() as tmp:
        shim = os.path.join(tmp, "swap_timer.so")
        spin = os.path.join(tmp, "glx_spin")
        subprocess.run(["cc", "-O2", "-shared", "-fPIC", os.path.join(tools, "swap_timer.c"), "-o", shim, "-ldl", "-lz", "-lm"],
                       check=True)
        subprocess.run(["cc", "-O2", os.path.join(tools, "glx_spin.c"), "-o", spin, "-lGL", "-lX11"], check=True)
        out = os.path.join(tmp, "frames.txt")

        shot = os.path.join(tmp, "shot.png")

        def run(frames):
            env = dict(os.environ, LIBGL_ALWAYS_SOFTWARE="1", LD_PRELOAD=shim, SWAP_TIMER_OUT=out,
                       SWAP_TIMER_WARMUP="3", SWAP_TIMER_FRAMES=frames, SWAP_TIMER_SHOT=shot)
            return subprocess.run([xvfb, "-a", "-f", os.path.join(tmp, "Xauthority"), "-s", "-screen 0 640x480x24",
                                   spin], env=env, capture_output=True, text=True, timeout=120)

        r = run("7")
        check(r.returncode == 0, "the timed program is ended after warm-up + timed frames, exit 0",
              r.stdout + r.stderr)
        lines = open(out).read().split("\n")
        lines = [l for l in lines if l]
        check(len(lines) == 8, "7 frame times and a median", str(lines))
        times = [float(l) for l in lines[:7]]
        check(all(t > 0.0 for t in times), "every frame time is positive", str(times))
        median = float(lines[7].split()[1])
        check(lines[7].startswith("median ") and abs(median - sorted(times)[3]) < 1e-3, "the median of the 7",
              lines[7])
        check("swap_timer: 7 frames" in r.stderr, "it reports the count on stderr", r.stderr)
        check(not os.path.exists(out + ".part"), "no partial file left")
        # The last timed swap is glx_spin's frame 3 + 7 = 10: red 10, the top-left quarter white.
        w, h, rows = read_png(shot)
        check((w, h) == (320, 180), "the shot is the window, 320x180", str((w, h)))
        px = lambda x, y: tuple(rows[y][3 * x:3 * x + 3])
        check(px(0, 0) == (255, 255, 255) and px(159, 89) == (255, 255, 255), "the white quarter at the top left",
              str((px(0, 0), px(159, 89))))
        check(px(160, 0) == (10, 51, 102) and px(0, 90) == (10, 51, 102) and px(319, 179) == (10, 51, 102),
              "the rest is frame 10's colour (10, 51, 102)", str((px(160, 0), px(0, 90), px(319, 179))))
        stats = [l for l in r.stderr.splitlines() if l.startswith("swap_timer: shot 320x180 ")]
        check(len(stats) == 1, "one statistics line for the shot", r.stderr)
        v = dict(zip(stats[0].split()[3::2], map(float, stats[0].split()[4::2])))
        luma = lambda c: 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
        mean = (luma((255, 255, 255)) + 3 * luma((10, 51, 102))) / 4
        top = [luma((255, 255, 255)), luma((10, 51, 102))]  # the top quarter: half white, half colour
        check(abs(v["mean"] - mean) < 0.01 and abs(v["top_mean"] - sum(top) / 2) < 0.01 and
              abs(v["top_stddev"] - (top[0] - top[1]) / 2) < 0.01, "mean, top quarter's mean and stddev",
              f"{v} vs {mean}, {sum(top) / 2}, {(top[0] - top[1]) / 2}")
        check(not os.path.exists(shot + ".part"), "no partial shot left")

        os.remove(out)
        os.remove(shot)
        r = run("seven")
        check(r.returncode == 2, "a bad SWAP_TIMER_FRAMES exits 2", r.stderr)
        check("SWAP_TIMER_FRAMES=seven" in r.stderr, "the error names the variable", r.stderr)
        check(not os.path.exists(out) and not os.path.exists(shot), "nothing written")


STAND_IN_CMAKE = """cmake_minimum_required(VERSION 3.16)
project(osgocean_stand_in C)
find_package(OpenGL REQUIRED COMPONENTS OpenGL GLX)
find_package(X11 REQUIRED)
add_executable(oceanExample glx_spin.c)
target_link_libraries(oceanExample PRIVATE OpenGL::GL OpenGL::GLX X11::X11)
"""


def stand_in(src, bench):
    script = os.path.join(src, "tools", "bench", "osgocean_compare.sh")
    with tempfile.TemporaryDirectory() as tmp:
        source = os.path.join(tmp, "osgocean")
        os.makedirs(os.path.join(source, "resources"))
        with open(os.path.join(source, "CMakeLists.txt"), "w") as f:
            f.write(STAND_IN_CMAKE)
        with open(os.path.join(src, "tools", "bench", "osgocean", "glx_spin.c")) as f_in, \
                open(os.path.join(source, "glx_spin.c"), "w") as f_out:
            f_out.write(f_in.read())
        out = os.path.join(tmp, "out")
        r = subprocess.run(["sh", script, "--source", source, "--out", out, "--bench", bench, "--skip-install",
                            "--frames", "3", "--rounds", "2"], capture_output=True, text=True, timeout=600)
        print(r.stdout[-3000:], r.stderr[-3000:])
        check(r.returncode == 0, "the comparison runs end to end: exit 0", f"{r.returncode}: {r.stderr[-1500:]}")
        md = open(os.path.join(out, "compare.md")).read()
        check("llvmpipe" in md and "1024x768" in md, "compare.md names the renderer and the size", md)
        rows = [l for l in md.splitlines() if l.startswith("| ") and l[2].isdigit()]
        check(len(rows) == 2, "one row per round", md)
        for i, row in enumerate(rows, start=1):
            cells = [c.strip() for c in row.strip("|").split("|")]
            check(cells[0] == str(i) and len(cells) == 6, f"round {i}: round, osgOcean, low, medium, high, ratio", row)
            osg, low, medium, high, ratio = (float(c) for c in cells[1:])
            frames = open(os.path.join(out, f"osgocean-{i}.txt")).read().split("\n")
            check(len([l for l in frames if l]) == 4 and frames[3] == f"median {cells[1]}",
                  f"round {i}: the example's 3 frame times and the median in the row", str(frames))
            with open(os.path.join(out, f"pacifica-{i}", "frame.csv")) as f:
                bench_rows = {r["setting"]: float(r["ms_median"]) for r in csv.DictReader(f)}
            check(sorted(bench_rows) == ["high", "low", "medium"] and
                  abs(bench_rows["medium"] - medium) < 1e-3 * medium, f"round {i}: the bench's medians in the row",
                  f"{bench_rows} vs {row}")
            check(all(x > 0 for x in (osg, low, medium, high)) and abs(ratio - osg / medium) < 0.01,
                  f"round {i}: positive times, ratio = osgOcean / medium", row)
            w, h, _ = read_png(os.path.join(out, f"osgocean-{i}.png"))
            look = open(os.path.join(out, f"osgocean-{i}.look")).read()
            check((w, h) == (320, 180) and look.startswith("320x180 mean "), f"round {i}: the example's shot kept",
                  f"{w}x{h}, {look}")
        check(not os.path.exists(os.path.join(out, "compare.md.part")), "no partial report left")

        # The flat run goes into the same OUT: the report of the good run above must not outlive it.
        for draw, why in (("flat", "no sky"), ("black", "nearly black")):
            bad = out if draw == "flat" else os.path.join(tmp, "out-" + draw)
            r = subprocess.run(["sh", script, "--source", source, "--out", bad, "--bench", bench, "--skip-install",
                                "--frames", "3", "--rounds", "1"], capture_output=True, text=True, timeout=600,
                               env=dict(os.environ, GLX_SPIN_DRAW=draw))
            check(r.returncode == 4 and why in r.stderr and "osgocean-1.png" in r.stderr,
                  f"a {draw} frame is refused: exit 4 saying '{why}' and naming the shot",
                  f"{r.returncode}: {r.stderr[-800:]}")
            check(not os.path.exists(os.path.join(bad, "compare.md")) and
                  not os.path.exists(os.path.join(bad, "osgocean-1.look")), f"{draw}: no report, no look")
            if draw == "black":
                check(not os.path.exists(os.path.join(bad, "pacifica-1")), "black: no bench run")


def real(src, bench):
    """osgOcean's real source: refused without its sky, then one round with it."""
    peer = os.path.join(os.environ.get("PACIFICA_SHARED_DIR", ""), "peers", "osgocean-f235e99.tar.gz")
    if not os.path.isfile(peer):
        print(f"SKIP: no {peer}")
        sys.exit(77)
    script = os.path.join(src, "tools", "bench", "osgocean_compare.sh")
    with tempfile.TemporaryDirectory() as tmp:
        with tarfile.open(peer) as t:
            t.extractall(tmp, filter="data")
        source = os.path.join(tmp, "osgocean-f235e99")
        check(os.path.isdir(os.path.join(source, "demo", "textures", "sky_clear")), "the peer source has demo/")
        out = os.path.join(tmp, "out")
        cmd = ["sh", script, "--source", source, "--out", out, "--bench", bench, "--skip-install", "--frames", "5",
               "--rounds", "1"]
        shutil.move(os.path.join(source, "demo"), os.path.join(tmp, "demo"))
        r = subprocess.run(cmd, capture_output=True, text=True, timeout=1200)
        print(r.stdout[-2000:], r.stderr[-2000:])
        check("linking the release ones" in r.stderr, "Debian's OpenSceneGraph has no debug libraries: fixed up",
              r.stderr[-800:])
        check(r.returncode == 4 and "no sky" in r.stderr, "without demo/ the example draws no sky: refused, exit 4",
              f"{r.returncode}: {r.stderr[-800:]}")
        check(not os.path.exists(os.path.join(out, "compare.md")), "no report for a refused run")

        shutil.move(os.path.join(tmp, "demo"), os.path.join(source, "demo"))
        r = subprocess.run(cmd, capture_output=True, text=True, timeout=1200)
        print(r.stdout[-2000:], r.stderr[-2000:])
        check(r.returncode == 0, "with demo/: one round compared, exit 0", f"{r.returncode}: {r.stderr[-1500:]}")
        w, h, _ = read_png(os.path.join(out, "osgocean-1.png"))
        look = open(os.path.join(out, "osgocean-1.look")).read().split()
        v = dict(zip(look[1::2], map(float, look[2::2])))
        check((w, h) == (1024, 768) and look[0] == "1024x768", "the example's shot is its 1024x768 window",
              f"{w}x{h} {look}")
        print("the example's frame:", v)
        md = open(os.path.join(out, "compare.md")).read()
        rows = [l for l in md.splitlines() if l.startswith("| 1 |")]
        check(len(rows) == 1, "one round in compare.md", md)
        cells = [float(c) for c in rows[0].strip("|").split("|")[1:]]
        median = open(os.path.join(out, "osgocean-1.txt")).read().split("\n")[5]
        check(median == f"median {rows[0].split('|')[2].strip()}" and all(c > 0 for c in cells),
              "the row holds the example's median and positive times", f"{median} vs {rows[0]}")


def no_source(src):
    script = os.path.join(src, "tools", "bench", "osgocean_compare.sh")
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out")
        env = {k: v for k, v in os.environ.items() if k != "OSGOCEAN_SOURCE"}
        r = subprocess.run(["sh", script, "--source", os.path.join(tmp, "no-osgocean"), "--out", out], env=env,
                           capture_output=True, text=True, timeout=60)
        check(r.returncode == 3, "no source: exit 3", f"{r.returncode}: {r.stderr}")
        check("osgOcean source not found" in r.stderr and "no-osgocean" in r.stderr,
              "the error names the directory it looked in", r.stderr)
        check("libopenscenegraph-dev" in r.stderr and "oceanExample" in r.stderr and "102.8-125.3 ms" in r.stderr,
              "the recipe: Debian's OpenSceneGraph, the example, the baseline figures", r.stderr)
        check(not os.path.exists(out), "nothing written")
        for args, name in ((["--frames", "0"], "--frames"), (["--rounds", "x"], "--rounds"), (["--bogus"], "--bogus")):
            r = subprocess.run(["sh", script] + args + ["--out", out], env=env, capture_output=True, text=True,
                               timeout=60)
            check(r.returncode == 2 and name in r.stderr, f"bad argument {args}: exit 2 naming {name}",
                  f"{r.returncode}: {r.stderr}")
        check(not os.path.exists(out), "nothing written")


def main():
    args = sys.argv[1:]
    if len(args) < 3 or args[0] != "--case":
        fail(__doc__)
    case = args[1]
    if case == "swap-timer":
        swap_timer(args[2], args[3])
    elif case == "stand-in":
        stand_in(args[2], args[3])
    elif case == "real":
        real(args[2], args[3])
    elif case == "no-source":
        no_source(args[2])
    else:
        fail("unknown case " + case)
    print("PASS")


if __name__ == "__main__":
    main()
