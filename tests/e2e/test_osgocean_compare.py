#!/usr/bin/env python3
"""The osgOcean comparison's tools (tools/bench/osgocean_compare.sh, tools/bench/osgocean/swap_timer.c).

Cases (chosen with --case, one ctest test each):
  swap-timer  swap_timer.so, built as the script builds it, times a GLX program it cannot change
              (osgocean/glx_spin.c, which like osgOcean's example never ends by itself) under xvfb-run: the
              program is ended after the warm-up and timed frames, the result file holds exactly that many
              positive frame times and their median; a bad SWAP_TIMER_FRAMES exits 2 naming it and writes
              nothing.
  stand-in   the script's whole path on a stand-in for osgOcean's source: a CMake project whose `oceanExample`
              is glx_spin.c, with a resources/ folder. The script builds it with CMake, builds swap_timer.so,
              alternates the timed example with the given pacifica-bench-frame (--bench, --skip-install) and
              writes compare.md: one row per round with the two medians and their ratio, matching the files
              it kept (the example's frame times, the bench's frame.csv).
  no-source   without osgOcean's source (a missing --source directory) the script exits 3, says what it
              looked for and prints the recipe naming Debian's OpenSceneGraph package; bad arguments exit 2
              naming the option; nothing is written in either case.

Usage: test_osgocean_compare.py --case CASE SOURCE_DIR [XVFB_RUN | BENCH_EXE]   (python3 standard library, cc)
"""
import csv
import os
import subprocess
import sys
import tempfile


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def check(cond, what, detail=""):
    print(("ok   " if cond else "FAIL ") + what + (f" ({detail})" if detail and not cond else ""))
    if not cond:
        sys.exit(1)


def swap_timer(src, xvfb):
    tools = os.path.join(src, "tools", "bench", "osgocean")
    with tempfile.TemporaryDirectory() as tmp:
        shim = os.path.join(tmp, "swap_timer.so")
        spin = os.path.join(tmp, "glx_spin")
        subprocess.run(["cc", "-O2", "-shared", "-fPIC", os.path.join(tools, "swap_timer.c"), "-o", shim, "-ldl"],
                       check=True)
        subprocess.run(["cc", "-O2", os.path.join(tools, "glx_spin.c"), "-o", spin, "-lGL", "-lX11"], check=True)
        out = os.path.join(tmp, "frames.txt")

        def run(frames):
            env = dict(os.environ, LIBGL_ALWAYS_SOFTWARE="1", LD_PRELOAD=shim, SWAP_TIMER_OUT=out,
                       SWAP_TIMER_WARMUP="3", SWAP_TIMER_FRAMES=frames)
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

        os.remove(out)
        r = run("seven")
        check(r.returncode == 2, "a bad SWAP_TIMER_FRAMES exits 2", r.stderr)
        check("SWAP_TIMER_FRAMES=seven" in r.stderr, "the error names the variable", r.stderr)
        check(not os.path.exists(out), "nothing written")


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
        check(not os.path.exists(os.path.join(out, "compare.md.part")), "no partial report left")


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
        check("libopenscenegraph-dev" in r.stderr and "oceanExample" in r.stderr and "50.1" in r.stderr,
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
    elif case == "no-source":
        no_source(args[2])
    else:
        fail("unknown case " + case)
    print("PASS")


if __name__ == "__main__":
    main()
