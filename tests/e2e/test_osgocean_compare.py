#!/usr/bin/env python3
"""The osgOcean comparison's tools (tools/bench/osgocean_compare.sh, tools/bench/osgocean/swap_timer.c).

Cases (chosen with --case, one ctest test each):
  swap-timer  swap_timer.so, built as the script builds it, times a GLX program it cannot change
              (osgocean/glx_spin.c, which like osgOcean's example never ends by itself) under xvfb-run: the
              program is ended after the warm-up and timed frames, the result file holds exactly that many
              positive frame times and their median; a bad SWAP_TIMER_FRAMES exits 2 naming it and writes
              nothing.
  no-source   without osgOcean's source (a missing --source directory) the script exits 3, says what it
              looked for and prints the recipe naming Debian's OpenSceneGraph package; bad arguments exit 2
              naming the option; nothing is written in either case.

Usage: test_osgocean_compare.py --case CASE SOURCE_DIR XVFB_RUN     (python3 standard library, cc)
"""
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
    elif case == "no-source":
        no_source(args[2])
    else:
        fail("unknown case " + case)
    print("PASS")


if __name__ == "__main__":
    main()
