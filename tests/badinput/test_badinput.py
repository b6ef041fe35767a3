#!/usr/bin/env python3
"""Bad input to `pacifica replay`: every case must fail with the documented exit status (2 for usage errors,
1 otherwise), print a "pacifica: error: ..." line holding the specific expected text (the file and line, the
option, the valid names), and leave the output directory as it found it. Each case runs twice:
  absent    --out names a directory that does not exist: it must still not exist afterwards (and nothing else
            may appear next to it);
  existing  --out names a directory that already holds unrelated files (a file, a hidden file, a
            subdirectory): afterwards it must hold exactly those, byte for byte, with unchanged mtimes.

With --known-bugs it runs instead the cases that reproduce known CLI bugs (registered in CMake as a disabled
test until they are fixed; see tests/badinput/CMakeLists.txt).

Usage: test_badinput.py [--known-bugs] PACIFICA_EXE SOURCE_DIR     (python3 standard library only)
Temp dirs are removed on success and kept (path printed) on failure.
"""
import argparse
import hashlib
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from checks import Checks  # noqa: E402  (shared check counter)
from pngwrite import write_gray_png  # noqa: E402  (height-map images)

RUN_TIMEOUT_S = 120
HEADER = "time_s,x_m,y_m,z_m,heading_deg,pitch_deg,roll_deg"
VIEWS = ["ACES 1.0 - SDR Video", "Un-tone-mapped"]  # the embedded config's views of display "sRGB"
# Small and short, so that a CLI that wrongly accepts a case finishes fast (and the check still fails).
QUICK = ["--size", "160x90", "--start", "0", "--end", "0"]


def child_env(extra):
    env = dict(os.environ)
    env.pop("OCIO", None)  # hermetic: $OCIO would replace the embedded config
    env.setdefault("MESA_SHADER_CACHE_DISABLE", "true")
    env.update(extra)
    return env


def snapshot(root):
    """Everything under `root` (path -> kind, size, content hash, mode, mtime), or None if it does not exist."""
    if not os.path.lexists(root):
        return None
    state = {}
    for dirpath, dirnames, filenames in os.walk(root):
        for name in dirnames + filenames:
            path = os.path.join(dirpath, name)
            st = os.lstat(path)
            rel = os.path.relpath(path, root)
            if os.path.isdir(path):
                state[rel] = ("dir", st.st_mode)
            else:
                with open(path, "rb") as f:
                    digest = hashlib.sha256(f.read()).hexdigest()
                state[rel] = ("file", st.st_size, digest, st.st_mode, st.st_mtime_ns)
    return state


def populate(out_dir):
    """Unrelated content a user might keep in the output directory; none of it may be touched."""
    os.makedirs(os.path.join(out_dir, "notes"))
    with open(os.path.join(out_dir, "unrelated.txt"), "w") as f:
        f.write("not pacifica's: must survive a failed replay\n")
    with open(os.path.join(out_dir, ".hidden"), "w") as f:
        f.write("hidden, and also not pacifica's\n")
    with open(os.path.join(out_dir, "notes", "nested.txt"), "w") as f:
        f.write("nested\n")


def write(path, text):
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)
    return path


def flight_with_line4(inputs, name, line4):
    """A flight whose physical line 4 is `line4` (line 1 a comment, 2 the header, 3 and 5 good samples)."""
    return write(os.path.join(inputs, name),
                 f"# bad flight for test_badinput.py: line 4 is the culprit\n{HEADER}\n0.0,0,0,20,90,0,0\n"
                 f"{line4}\n2.0,300,0,20,90,0,0\n")


def make_cases(inputs, demo):
    """(name, args before --out, extra args, env, exit status, texts that must all appear in the error line,
    texts of which at least one must appear)."""
    missing_flight = os.path.join(inputs, "no_such_flight.csv")
    six = flight_with_line4(inputs, "six_fields.csv", "1.0,150,0,20,90,0")
    nan = flight_with_line4(inputs, "nan_field.csv", "1.0,150,0,nan,90,0,0")
    word = flight_with_line4(inputs, "word_field.csv", "1.0,abc,0,20,90,0,0")
    unknown = flight_with_line4(inputs, "unknown_record.csv", "boat,a,1.0,500,0")
    weak = flight_with_line4(inputs, "zero_strength.csv", "explosion,1.0,500,0,0")
    lonely = flight_with_line4(inputs, "lonely_ship.csv", "ship,lonely,1.0,500,0")
    missing_ocio = os.path.join(inputs, "no_such_config.ocio")
    garbage_ocio = write(os.path.join(inputs, "garbage.ocio"), "this is not: [an OCIO config\n{{{ at all\n")
    missing_map = os.path.join(inputs, "no_such_map.png")
    garbage_map = write(os.path.join(inputs, "garbage_map.png"), "not a PNG at all\n")
    odd_map = write_gray_png(os.path.join(inputs, "odd_48x48.png"), 48, 48, lambda x, r: x / 47.0, 8)
    flat_map = write_gray_png(os.path.join(inputs, "flat_32x32.png"), 32, 32, lambda x, r: 0.25, 8)
    good_map = write_gray_png(os.path.join(inputs, "good_32x32.png"), 32, 32, lambda x, r: (x % 8) / 7.0, 8)
    return [
        ("missing flight file", [missing_flight], QUICK, {}, 1, [missing_flight, "cannot open flight file"], []),
        # Arguments are bytes: one that is not UTF-8 (a Linux file name may be any bytes) must not abort the
        # run key's JSON (tools/src/Commands.cpp argumentJson), as it once did.
        ("a flight path that is not UTF-8", [missing_flight[:-4] + "\udca1.csv"], QUICK, {}, 1,
         ["cannot open flight file"], []),
        ("CSV line 4 has 6 fields", [six], QUICK, {}, 1, [f"{six}:4:", "expected 7 fields, got 6"], []),
        ("NaN field", [nan], QUICK, {}, 1, [f"{nan}:4:", "'z_m'"], ["finite", "NaN"]),
        ("non-numeric field", [word], QUICK, {}, 1, [f"{word}:4:", "'x_m'", "not a number", "'abc'"], []),
        ("unknown record keyword", [unknown], QUICK, {}, 1, [f"{unknown}:4:", "unknown record 'boat'"], []),
        ("explosion strength 0", [weak], QUICK, {}, 1, [f"{weak}:4:", "'strength'", "must be > 0"], []),
        ("ship with one sample", [lonely], QUICK, {}, 1, [f"{lonely}:4:", "ship 'lonely'", "at least 2"], []),
        ("unknown OCIO view", [demo], QUICK + ["--view", "No Such View"], {}, 1,
         ["unknown view 'No Such View'", "'sRGB'"] + [f"'{v}'" for v in VIEWS], []),
        ("unknown OCIO display", [demo], QUICK + ["--display", "No Such Display"], {}, 1,
         ["unknown display 'No Such Display'", "valid displays: 'sRGB'"], []),
        ("missing --ocio-config file", [demo], QUICK + ["--ocio-config", missing_ocio], {}, 1,
         [missing_ocio, "does not exist"], []),
        ("malformed --ocio-config file", [demo], QUICK + ["--ocio-config", garbage_ocio], {}, 1,
         [garbage_ocio, "cannot load OCIO config"], []),
        ("--size abc", [demo], ["--start", "0", "--end", "0", "--size", "abc"], {}, 2, ["--size", "'abc'"], []),
        ("--size 0x0", [demo], ["--start", "0", "--end", "0", "--size", "0x0"], {}, 2, ["--size", "'0x0'"], []),
        ("--fps 0", [demo], QUICK + ["--fps", "0"], {}, 2, ["--fps must be in (0, 1000]"], []),
        ("--start after the flight end", [demo], ["--size", "160x90", "--start", "61"], {}, 2,
         ["--start 61", "outside the flight", "60"], []),
        # Lighting options: each bad value names its option (tools/src/OceanOptions.cpp).
        ("--sun-elevation 95", [demo], QUICK + ["--sun-elevation", "95"], {}, 2,
         ["--sun-elevation must be in [-90, 90] degrees, got 95"], []),
        ("--fog-density -1", [demo], QUICK + ["--fog-density", "-1"], {}, 2,
         ["--fog-density must be finite and >= 0", "got -1"], []),
        ("--subsurface 11", [demo], QUICK + ["--subsurface", "11"], {}, 2, ["--subsurface must be in [0, 10]", "got 11"],
         []),
        ("--fog-color 1,2", [demo], QUICK + ["--fog-color", "1,2"], {}, 2, ["--fog-color", "R,G,B", "'1,2'"], []),
        ("--foam-height-full below --foam-height-start", [demo], QUICK + ["--foam-height-full", "1"], {}, 2,
         ["--foam-height-full (1 m) must be > --foam-height-start (1.6 m)"], []),
        ("--water-color -1,0,0", [demo], QUICK + ["--water-color", "-1,0,0"], {}, 2,
         ["--water-color: expected R,G,B", "'-1,0,0'"], []),
        ("--octaves 9", [demo], QUICK + ["--octaves", "9"], {}, 2, ["--octaves must be in [1, 5], got 9"], []),
        # FFT spectrum options (tools/src/OceanOptions.cpp applyFftSpectrum).
        ("--wind-speed -1", [demo], QUICK + ["--model", "fft", "--wind-speed", "-1"], {}, 2,
         ["--wind-speed must be in (0, 60], got -1"], []),
        ("--fft-spectrum foo", [demo], QUICK + ["--model", "fft", "--fft-spectrum", "foo"], {}, 2,
         ["--fft-spectrum must be phillips or jonswap; got 'foo'"], []),
        ("--choppiness nan", [demo], QUICK + ["--model", "fft", "--choppiness", "nan"], {}, 2,
         ["--choppiness must be in [0, 3], got nan"], []),
        ("--fft-cascades 5", [demo], QUICK + ["--model", "fft", "--fft-cascades", "5"], {}, 2,
         ["--fft-cascades must be in [1, 4], got 5"], []),
        ("--sun-elevation with --env", [demo], QUICK + ["--sun-elevation", "30", "--env", missing_map], {}, 2,
         ["--sun-elevation/--sun-azimuth/--moon-elevation cannot be combined with --env"], []),
        # A moonlit night (--moon-*) and the pre-exposure that goes with it.
        ("--moon-phase 200", [demo], QUICK + ["--moon-elevation", "20", "--moon-phase", "200"], {}, 2,
         ["--moon-phase must be in [0, 180] degrees, got 200"], []),
        ("--moon-azimuth alone", [demo], QUICK + ["--moon-azimuth", "90"], {}, 2,
         ["--moon-azimuth/--moon-phase need --moon-elevation"], []),
        ("--moon-elevation with --sun-elevation", [demo], QUICK + ["--moon-elevation", "20", "--sun-elevation", "-10"],
         {}, 2, ["--moon-elevation cannot be combined with --sun-elevation/--sun-azimuth"], []),
        ("--exposure 50", [demo], QUICK + ["--exposure", "50"], {}, 2, ["--exposure", "50"], []),
        # --light: the spec and the key named.
        ("--light on no ship", [demo], QUICK + ["--light", "spot:tanker"], {}, 2,
         ["--light 'spot:tanker': no ship 'tanker' in the flight (ships: coaster, frigate)"], []),
        ("--light bad key", [demo], QUICK + ["--light", "spot:coaster,beam=3"], {}, 2,
         ["--light 'spot:coaster,beam=3': unknown key 'beam'"], []),
        ("--light bad angle", [demo], QUICK + ["--light", "spot:coaster,angle=120"], {}, 2,
         ["--light 'spot:coaster,angle=120': angle must be a number in [0.1, 90], got '120'"], []),
        ("--light fixed without y", [demo], QUICK + ["--light", "spot:fixed,x=3"], {}, 2,
         ["a fixed light needs x= and y="], []),
        ("--light under the sea", [demo], QUICK + ["--light", "spot:coaster,height=-5"], {}, 2,
         ["height must be a number in [0, 10000], got '-5'"], []),
        ("--light too bright once exposed", [demo],
         QUICK + ["--light", "spot:coaster,intensity=1e9", "--exposure", "17"], {}, 2,
         ["color x intensity x 2^exposure", "exceeds the spot lights' bound"], []),
        # Painted height maps: the message names the file; nothing is written.
        ("--height-map missing file", [demo], QUICK + ["--height-map", missing_map], {}, 1,
         [missing_map, "cannot open image"], []),
        ("--height-map not an image", [demo], QUICK + ["--height-map", garbage_map], {}, 1,
         [garbage_map, "cannot open image"], []),
        ("--height-map 48x48", [demo], QUICK + ["--height-map", odd_map], {}, 1,
         [odd_map, "width must be a power of two in [16, 1024], got 48x48"], []),
        ("--height-map flat", [demo], QUICK + ["--height-map", flat_map], {}, 1, [flat_map, "is flat"], []),
        ("--height-map with --model gerstner", [demo], QUICK + ["--height-map", good_map, "--model", "gerstner"],
         {}, 2, ["--height-map applies to --model octaves only"], []),
        ("--height-map more files than octaves", [demo],
         QUICK + ["--quality", "low"] + ["--height-map", good_map] * 9, {}, 2,
         ["--height-map given 9 times", "octaves"], []),
        # glvnd finds no EGL vendor library, so no EGL platform at all: the same as a machine without drivers.
        ("no headless EGL", [demo], QUICK, {"__EGL_VENDOR_LIBRARY_FILENAMES": "/nonexistent.json"}, 1,
         ["no headless OpenGL", "EGL"], []),
    ]


def shown(text):
    """Text for the log: bytes that are not UTF-8 (surrogate escapes) as \\xNN."""
    return text.encode("utf-8", "surrogateescape").decode("utf-8", "backslashreplace")


def run_case(c, exe, tmp, index, case, mode):
    name, flight_args, extra, env, want_rc, must, any_of = case
    parent = os.path.join(tmp, f"case{index:02d}-{mode}")  # holds only `out` (or nothing)
    os.makedirs(parent)
    out = os.path.join(parent, "out")
    if mode == "existing":
        populate(out)
    before_out, before_parent = snapshot(out), sorted(os.listdir(parent))
    cmd = [exe, "replay", *flight_args, "--out", out, *extra, "--no-progress"]
    print(f"[{name} / DIR {mode}]")
    print("  $ " + " ".join(f"{k}={v}" for k, v in env.items()) + (" " if env else "") +
          shown(" ".join(f"'{a}'" if " " in a or not a else a for a in cmd)))
    t = time.monotonic()
    try:
        proc = subprocess.run(cmd, env=child_env(env), capture_output=True, text=True, errors="surrogateescape",
                              timeout=RUN_TIMEOUT_S)
    except subprocess.TimeoutExpired:
        c.check(False, f"{name} / {mode}: finishes within {RUN_TIMEOUT_S} s")
        return
    error_lines = [line for line in proc.stderr.splitlines() if line.startswith("pacifica: error: ")]
    error = error_lines[-1] if error_lines else ""
    print(f"    exit {proc.returncode} after {time.monotonic() - t:.1f} s; {shown(error or proc.stderr.strip()[-500:])}")
    c.check(proc.returncode == want_rc, f"{name} / {mode}: exit status {want_rc}", f"got {proc.returncode}")
    c.check(bool(error), f"{name} / {mode}: prints a 'pacifica: error: ' line", repr(proc.stderr[-500:]))
    missing = [m for m in must if m not in error]
    c.check(not missing, f"{name} / {mode}: message names {must}", f"missing {missing} in {error!r}")
    if any_of:
        c.check(any(a in error for a in any_of), f"{name} / {mode}: message says one of {any_of}", repr(error))
    after_out, after_parent = snapshot(out), sorted(os.listdir(parent))
    if mode == "absent":
        c.check(after_out is None, f"{name} / {mode}: DIR still does not exist",
                f"it holds {sorted(after_out or {})}")
    else:
        added = sorted(set(after_out or {}) - set(before_out))
        removed = sorted(set(before_out) - set(after_out or {}))
        changed = sorted(k for k in before_out if k in (after_out or {}) and after_out[k] != before_out[k])
        c.check(after_out == before_out, f"{name} / {mode}: DIR holds exactly what it held before",
                f"added {added}, removed {removed}, changed {changed}")
    c.check(after_parent == before_parent, f"{name} / {mode}: nothing written next to DIR",
            f"{before_parent} -> {after_parent}")


def non_utf8_flight_name(c, exe, tmp, demo):
    """A flight whose file name is not UTF-8 (byte 0xA1; a Linux name may be any bytes) renders and writes its
    summary, the bad byte as U+FFFD there; before, the summary's JSON threw after the last frame."""
    flight = os.path.join(tmp, "flight\udca1.csv")
    shutil.copyfile(demo, flight)
    out = os.path.join(tmp, "non-utf8")
    cmd = [exe, "replay", flight, "--out", out, *QUICK, "--no-progress"]
    print("[a flight file whose name is not UTF-8]\n  $ " + shown(" ".join(cmd)))
    proc = subprocess.run(cmd, env=child_env({}), capture_output=True, text=True, errors="surrogateescape",
                          timeout=RUN_TIMEOUT_S)
    c.check(proc.returncode == 0, "a non-UTF-8 flight name: the replay succeeds", shown(proc.stderr[-500:]))
    summary = os.path.join(out, "summary.json")
    if c.check(os.path.isfile(summary), "a non-UTF-8 flight name: summary.json written"):
        with open(summary, encoding="utf-8") as f:
            flight_in_summary = json.load(f)["flight"]
        c.check(flight_in_summary.endswith("flight\ufffd.csv"), "the bad byte is U+FFFD in the summary",
                flight_in_summary)
    # The farm's plan.json must hold the path to run its chunks: refused before anything is written.
    run_dir = os.path.join(tmp, "farm-non-utf8")
    proc = subprocess.run([exe, "farm", "run", flight, "--out", run_dir], env=child_env({}), capture_output=True,
                          text=True, errors="surrogateescape", timeout=RUN_TIMEOUT_S)
    c.check(proc.returncode == 2 and "is not UTF-8, and plan.json (JSON) cannot hold it" in proc.stderr,
            "farm run: a non-UTF-8 recording name is refused (exit 2), naming why", shown(proc.stderr[-500:]))
    c.check(not os.path.exists(run_dir), "farm run: nothing written for it")


# ---------------------------------------------------------------------------------------------------------
# Known bugs (run with --known-bugs; the ctest test that does so is disabled until they are fixed).


def known_bug_midrun_failure(c, exe, tmp, demo):
    """A failure after some frames were written must not delete files that were in DIR before the run.
    Replay's OutputTransaction removes every path this run wrote, including frame files that a previous run
    had left there and this run overwrote: a failed re-run destroys the earlier (complete) output and leaves
    a summary.json that lists deleted frames. The failure is forced deterministically by putting a directory
    where frame 1's EXR goes (the rename into place fails)."""
    out = os.path.join(tmp, "midrun", "out")
    args = [exe, "replay", demo, "--out", out, "--size", "160x90", "--start", "0", "--end", "0.5", "--fps", "2",
            "--no-progress"]
    print("[mid-run failure after a previous run / DIR holds that run's output]")
    print("  $ " + " ".join(args))
    first = subprocess.run(args, env=child_env({}), capture_output=True, text=True, timeout=RUN_TIMEOUT_S)
    if not c.check(first.returncode == 0, "previous run succeeds", first.stderr[-500:]):
        return
    os.remove(os.path.join(out, "frame_00001.exr"))
    os.makedirs(os.path.join(out, "frame_00001.exr", "blocker"))
    before = snapshot(out)
    print("  (frame_00001.exr replaced by a directory) $ " + " ".join(args))
    second = subprocess.run(args, env=child_env({}), capture_output=True, text=True, timeout=RUN_TIMEOUT_S)
    print(f"    exit {second.returncode}; {second.stderr.strip().splitlines()[-1] if second.stderr.strip() else ''}")
    c.check(second.returncode == 1, "re-run fails with exit status 1", f"got {second.returncode}")
    c.check("frame_00001.exr" in second.stderr, "its message names frame_00001.exr", second.stderr[-500:])
    after = snapshot(out)
    removed = sorted(set(before) - set(after or {}))
    changed = sorted(k for k in before if k in (after or {}) and after[k] != before[k])
    c.check(after == before, "DIR holds exactly what it held before the failed re-run",
            f"removed {removed}, changed {changed}")


def known_bug_cli11_errors(c, exe, tmp, demo):
    """Command-line errors caught by CLI11 itself (an unconvertible number, an unknown option) bypass main()'s
    "pacifica: error:" reporting and exit with CLI11's own codes (104, 109, ...) instead of 2."""
    for extra, text in ((["--fps", "abc"], "--fps"), (["--bogus-option"], "--bogus-option")):
        out = os.path.join(tmp, "cli11-" + extra[0].strip("-"), "out")
        cmd = [exe, "replay", demo, "--out", out, *QUICK, *extra, "--no-progress"]
        print(f"[CLI11 parse error: {' '.join(extra)}]")
        print("  $ " + " ".join(cmd))
        proc = subprocess.run(cmd, env=child_env({}), capture_output=True, text=True, timeout=RUN_TIMEOUT_S)
        print(f"    exit {proc.returncode}; {proc.stderr.strip()!r}")
        c.check(proc.returncode == 2, f"{' '.join(extra)}: exit status 2 (usage error)", f"got {proc.returncode}")
        c.check(any(line.startswith("pacifica: error: ") and text in line for line in proc.stderr.splitlines()),
                f"{' '.join(extra)}: a 'pacifica: error: ' line naming {text}", repr(proc.stderr))
        c.check(not os.path.lexists(out), f"{' '.join(extra)}: DIR not created")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--known-bugs", action="store_true", help="run the known-bug reproductions instead")
    ap.add_argument("pacifica_exe")
    ap.add_argument("source_dir")
    ns = ap.parse_args()
    demo = os.path.join(os.path.abspath(ns.source_dir), "tools", "data", "demo_flight.csv")
    c = Checks()
    tmp = tempfile.mkdtemp(prefix="pacifica-badinput-")
    t0 = time.monotonic()
    print(f"badinput{' (known bugs)' if ns.known_bugs else ''}: {ns.pacifica_exe} (temp dir {tmp})")
    if ns.known_bugs:
        known_bug_midrun_failure(c, ns.pacifica_exe, tmp, demo)
        known_bug_cli11_errors(c, ns.pacifica_exe, tmp, demo)
    else:
        inputs = os.path.join(tmp, "inputs")
        os.makedirs(inputs)
        cases = make_cases(inputs, demo)
        for i, case in enumerate(cases):
            for mode in ("absent", "existing"):
                run_case(c, ns.pacifica_exe, tmp, i, case, mode)
        print(f"\n{len(cases)} cases x 2 DIR states")
        non_utf8_flight_name(c, ns.pacifica_exe, tmp, demo)
    return c.finish("badinput known bugs" if ns.known_bugs else "badinput", t0, tmp)


if __name__ == "__main__":
    sys.exit(main())
