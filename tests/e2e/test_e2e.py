#!/usr/bin/env python3
"""End-to-end tests of `pacifica replay`: run the real CLI on a slice of the demo flight and check what it
wrote from the outside, reading the images back with OpenImageIO's command-line tools (iinfo, oiiotool).

Cases (chosen with --case, one ctest test each):
  replay       the demo slice 0..3 s at 2 fps, 320x180: summary.json (frame count, times, poses against the
               flight CSV, files), the EXR/PNG files (resolution, channels, pixel types, header attributes),
               the EXR pixel hash recomputed from the decoded pixels, no leftover temp files; then the same
               slice with --view "Un-tone-mapped": different PNGs, identical scene-linear EXR pixels.
  studio-ocio  one frame through the ACES studio config (--ocio-config, display "sRGB - Display"): succeeds,
               and summary.json and the EXR header record that config, display and view.
  ocean-options  one frame with the defaults, then with lighting options (dense red fog: the frame turns red;
               a low western sun), --sea-state/--beaufort (a 20 m/s sea is brighter; 0 is refused) and painted
               --height-map PNGs (a still map and a 4-frame strip): each changes the EXR pixels, and the same
               maps render the same pixels twice.
  night        a moonlit night: the day frame x the Moon/Sun ratio, --exposure's 2^EV, the Moon's glitter path,
               not black through both OCIO views once exposed; a ship's searchlight and a fixed one in fog
               (--light): counted, no pass added, only light added, their beams seen.
  effects      the demo's 3.0 s explosion and two ships: per-frame counters in summary.json show the effect
               kinds active and drawn; with --no-events every effect counter is 0 and the frame costs exactly
               the plain ocean's passes, draws and uploads.

Usage: test_e2e.py --case CASE PACIFICA_EXE SOURCE_DIR     (python3 standard library only)
Temp dirs are removed on success and kept (path printed) on failure.
"""
import argparse
import json
import math
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from checks import Checks  # noqa: E402  (shared check counter)
from pngwrite import write_gray_png  # noqa: E402  (height-map images)

DEFAULT_VIEW = "ACES 1.0 - SDR Video"
UNTONEMAPPED_VIEW = "Un-tone-mapped"
EMBEDDED_DISPLAY = "sRGB"
STUDIO_CONFIG = "data/ocio/studio-config-v1.0.0_aces-v1.3_ocio-v2.1.ocio"  # relative to the shared dir
RUN_TIMEOUT_S = 180

# ---------------------------------------------------------------------------------------------------------
# Check bookkeeping: every check prints one line; a failed `require` also stops the current case.


class CaseAborted(Exception):
    pass


class E2eChecks(Checks):
    """The shared counter plus require(): a failed requirement aborts the current case."""

    def require(self, ok, what, detail=""):
        if not self.check(ok, what, detail):
            raise CaseAborted(what)


# ---------------------------------------------------------------------------------------------------------
# XXH64 (Yann Collet's xxHash, 64-bit variant, seed 0), used to recompute summary.json's exr_pixel_hash from
# the decoded EXR pixels. Reference: https://github.com/Cyan4973/xxHash/blob/dev/doc/xxhash_spec.md
# (section "XXH64 Algorithm Description"). Checked against the spec's values for "", "a" and "abc" below.

_M64 = (1 << 64) - 1
_P1, _P2, _P3 = 0x9E3779B185EBCA87, 0xC2B2AE3D27D4EB4F, 0x165667B19E3779F9
_P4, _P5 = 0x85EBCA77C2B2AE63, 0x27D4EB2F165667C5


def _rotl(x, r):
    return ((x << r) | (x >> (64 - r))) & _M64


def _round(acc, lane):
    acc = (acc + lane * _P2) & _M64
    return (_rotl(acc, 31) * _P1) & _M64


def _merge(acc, v):
    acc ^= _round(0, v)
    return (acc * _P1 + _P4) & _M64


def xxh64(data, seed=0):
    n = len(data)
    i = 0
    if n >= 32:
        v1, v2, v3, v4 = (seed + _P1 + _P2) & _M64, (seed + _P2) & _M64, seed, (seed - _P1) & _M64
        stripes = n // 32
        lanes = struct.unpack_from(f"<{stripes * 4}Q", data, 0)
        for j in range(0, stripes * 4, 4):
            v1 = _round(v1, lanes[j])
            v2 = _round(v2, lanes[j + 1])
            v3 = _round(v3, lanes[j + 2])
            v4 = _round(v4, lanes[j + 3])
        i = stripes * 32
        h = (_rotl(v1, 1) + _rotl(v2, 7) + _rotl(v3, 12) + _rotl(v4, 18)) & _M64
        for v in (v1, v2, v3, v4):
            h = _merge(h, v)
    else:
        h = (seed + _P5) & _M64
    h = (h + n) & _M64
    while i + 8 <= n:
        h ^= _round(0, struct.unpack_from("<Q", data, i)[0])
        h = (_rotl(h, 27) * _P1 + _P4) & _M64
        i += 8
    if i + 4 <= n:
        h ^= (struct.unpack_from("<I", data, i)[0] * _P1) & _M64
        h = (_rotl(h, 23) * _P2 + _P3) & _M64
        i += 4
    while i < n:
        h ^= (data[i] * _P5) & _M64
        h = (_rotl(h, 11) * _P1) & _M64
        i += 1
    h ^= h >> 33
    h = (h * _P2) & _M64
    h ^= h >> 29
    h = (h * _P3) & _M64
    h ^= h >> 32
    return h


assert xxh64(b"") == 0xEF46DB3751D8E999 and xxh64(b"a") == 0xD24EC4F1A98C6E5B
assert xxh64(b"abc") == 0x44BC2CF5AD770999

# ---------------------------------------------------------------------------------------------------------
# Running things.


def child_env(extra=None):
    env = dict(os.environ)
    env.pop("OCIO", None)  # hermetic: $OCIO would replace the embedded config
    env.setdefault("MESA_SHADER_CACHE_DISABLE", "true")
    env.update(extra or {})
    return env


def run_replay(exe, args, extra_env=None):
    cmd = [exe, "replay", *args, "--no-progress"]
    print("  $ " + " ".join(f"'{a}'" if " " in a else a for a in cmd))
    t0 = time.monotonic()
    proc = subprocess.run(cmd, env=child_env(extra_env), capture_output=True, text=True, timeout=RUN_TIMEOUT_S)
    print(f"    exit {proc.returncode} after {time.monotonic() - t0:.1f} s")
    return proc


def oiio_tool(name):
    path = shutil.which(name)
    if not path:
        raise CaseAborted(f"'{name}' not found on PATH (install Debian's openimageio-tools)")
    return path


def iinfo_verbose(directory, names):
    """Runs `iinfo -v` once over `names` (relative to `directory`); returns {name: {"width", "height",
    "channels", "type", "format", "attrs": {name: text}}}."""
    proc = subprocess.run([oiio_tool("iinfo"), "-v", *names], cwd=directory, capture_output=True, text=True,
                          timeout=RUN_TIMEOUT_S)
    if proc.returncode != 0:
        raise CaseAborted(f"iinfo failed (exit {proc.returncode}): {proc.stderr.strip()}")
    header = re.compile(r"^(\S+)\s+:\s+(\d+)\s+x\s+(\d+),\s+(\d+)\s+channel,\s+(\S+)\s+(\S+)")
    info, current = {}, None
    for line in proc.stdout.splitlines():
        m = header.match(line)
        if m:
            current = {"width": int(m[2]), "height": int(m[3]), "channels": int(m[4]), "type": m[5],
                       "format": m[6], "attrs": {}}
            info[m[1]] = current
        elif current is not None and ": " in line:
            # "    name: value"; names may contain ':' themselves (pacifica:time_s), never ": ".
            key, value = line.strip().split(": ", 1)
            current["attrs"][key] = value.strip().strip('"')
    return info


def pixel_sha1(directory, names):
    """SHA-1 of the decoded pixels of each image (`iinfo --hash`), one process for all of them."""
    proc = subprocess.run([oiio_tool("iinfo"), "--hash", *names], cwd=directory, capture_output=True, text=True,
                          timeout=RUN_TIMEOUT_S)
    if proc.returncode != 0:
        raise CaseAborted(f"iinfo --hash failed (exit {proc.returncode}): {proc.stderr.strip()}")
    out, current = {}, None
    for line in proc.stdout.splitlines():
        if not line.startswith(" ") and " : " in line:
            current = line.split(" : ", 1)[0].strip()
        elif "SHA-1:" in line and current:
            out[current] = line.split("SHA-1:", 1)[1].strip()
    return out


def exr_xxh64(directory, names):
    """Recomputes the EXR pixel hash the way summary.json defines it (XXH64 of the half-float RGBA pixels,
    rows top-down): `oiiotool --dumpdata` prints every pixel, top row first, with 9 decimals, which is
    exact enough to recover each half value bit for bit (the smallest half step, 2^-24 = 6e-8, is far
    above 1e-9), and struct's 'e' format re-encodes it as IEEE half."""
    proc = subprocess.run([oiio_tool("oiiotool"), "--dumpdata", *names], cwd=directory, capture_output=True,
                          text=True, timeout=RUN_TIMEOUT_S)
    if proc.returncode != 0:
        raise CaseAborted(f"oiiotool --dumpdata failed (exit {proc.returncode}): {proc.stderr.strip()}")
    values = {}
    current = None
    for line in proc.stdout.splitlines():
        if line.startswith("    Pixel ("):
            values[current].extend(float(v) for v in line.split(":", 1)[1].split())
        elif " : " in line and not line.startswith(" "):
            current = line.split(" : ", 1)[0].strip()
            values[current] = []
    return {name: "%016x" % xxh64(struct.pack(f"<{len(v)}e", *v)) for name, v in values.items()}


def exr_pixels(directory, name):
    """Scene-linear (R, G, B) of every pixel of an EXR, from `oiiotool --dumpdata` (RGBA per pixel)."""
    proc = subprocess.run([oiio_tool("oiiotool"), "--dumpdata", name], cwd=directory, capture_output=True,
                          text=True, timeout=RUN_TIMEOUT_S)
    if proc.returncode != 0:
        raise CaseAborted(f"oiiotool --dumpdata failed (exit {proc.returncode}): {proc.stderr.strip()}")
    return [tuple(float(x) for x in line.split(":", 1)[1].split()[:3])
            for line in proc.stdout.splitlines() if line.startswith("    Pixel (")]


def exr_mean_rgb(directory, name):
    """Mean scene-linear (R, G, B) of an EXR."""
    px = exr_pixels(directory, name)
    return tuple(sum(p[i] for p in px) / max(len(px), 1) for i in range(3))


def read_flight(path):
    """time_s -> pose columns of a flight CSV (docs/FLIGHT_FORMAT.md; the demo file is well formed)."""
    rows, header = {}, None
    with open(path, encoding="utf-8-sig") as f:
        for line in f:
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            fields = [x.strip() for x in line.split(",")]
            if header is None:
                header = fields
                continue
            if fields[0] in ("explosion", "ship"):  # event records (docs/FLIGHT_FORMAT.md), not camera samples
                continue
            rows[float(fields[0])] = dict(zip(header[1:], map(float, fields[1:])))
    return rows


def close(a, b, rel=1e-9, abs_tol=1e-9):
    return math.isclose(float(a), float(b), rel_tol=rel, abs_tol=abs_tol)


def listing(directory):
    return sorted(os.listdir(directory))


# ---------------------------------------------------------------------------------------------------------
# Shared checks of one run's output.


def check_run_output(c, out_dir, summary, start, fps, expected_count, size, flight_rows, view, display):
    frames = summary.get("frames", [])
    c.require(len(frames) == expected_count, f"summary.json lists {expected_count} frames",
              f"got {len(frames)}")
    c.check(summary.get("size") == list(size), f"summary size is {list(size)}", f"got {summary.get('size')}")
    c.check(close(summary.get("fps", -1), fps), f"summary fps is {fps}", f"got {summary.get('fps')}")
    renderer = summary.get("gl", {}).get("renderer", "")
    c.check(isinstance(renderer, str) and renderer.strip() != "", "gl.renderer is non-empty", repr(renderer))
    print(f"    gl.renderer = {renderer!r}")
    ocio = summary.get("ocio", {})
    c.check(ocio.get("view") == view, f"ocio.view is '{view}'", f"got {ocio.get('view')!r}")
    c.check(ocio.get("display") == display, f"ocio.display is '{display}'", f"got {ocio.get('display')!r}")
    c.check(bool(ocio.get("config")), "ocio.config is non-empty", repr(ocio.get("config")))

    times = [f.get("time_s") for f in frames]
    c.check([f.get("index") for f in frames] == list(range(expected_count)), "frame indices are 0..n-1",
            str([f.get("index") for f in frames]))
    # Frame k is at exactly start + k/fps (Replay.cpp computes it from the index, not by accumulation);
    # 1e-9 s only absorbs the printing of doubles in JSON.
    expected_times = [start + k / fps for k in range(expected_count)]
    c.check(all(close(t, e) for t, e in zip(times, expected_times)), "frame times are start + k/fps",
            f"got {times}, expected {expected_times}")
    c.check(all(b > a for a, b in zip(times, times[1:])), "frame times strictly increase", str(times))

    # The slice's times fall on the CSV's own samples, so the pose must be that sample (up to the quaternion
    # round trip of the attitude, 89.99999999999999 for 90: 1e-6 is far below anything visible).
    pose_ok, pose_detail = True, ""
    for f in frames:
        row = flight_rows.get(f["time_s"])
        if row is None:  # every case here picks times on the CSV's 0.5 s grid
            pose_ok, pose_detail = False, f"frame {f['index']} t={f['time_s']} is not a CSV sample time"
            continue
        for key in ("x_m", "y_m", "z_m", "heading_deg", "pitch_deg", "roll_deg"):
            if not close(f["pose"][key], row[key], rel=1e-9, abs_tol=1e-6):
                pose_ok = False
                pose_detail = f"frame {f['index']} {key}: {f['pose'][key]} vs CSV {row[key]}"
    c.check(pose_ok, "poses match the flight CSV samples at those times", pose_detail)

    exrs = [f.get("exr", "") for f in frames]
    pngs = [f.get("png", "") for f in frames]
    c.check(exrs == [f"frame_{k:05d}.exr" for k in range(expected_count)], "EXR names are frame_NNNNN.exr",
            str(exrs))
    c.check(pngs == [f"frame_{k:05d}.png" for k in range(expected_count)], "PNG names are frame_NNNNN.png",
            str(pngs))
    missing = [n for n in exrs + pngs if not os.path.isfile(os.path.join(out_dir, n))]
    c.require(not missing, "every listed EXR and PNG exists", f"missing {missing}")
    files = listing(out_dir)
    hidden = [n for n in files if n.startswith(".")]
    c.check(not hidden, "no leftover temp files (names starting with '.')", str(hidden))
    c.check(files == sorted(exrs + pngs + ["summary.json"]), "DIR holds exactly the listed files + summary.json",
            str(files))

    info = iinfo_verbose(out_dir, exrs + pngs)
    unread = [n for n in exrs + pngs if n not in info]
    c.require(not unread, f"OIIO reads back all {len(exrs)} EXRs and {len(pngs)} PNGs", f"unreadable: {unread}")
    w, h = size
    problems = {}  # check description -> offending files, so each check prints one line for all frames

    def expect(ok, what, detail):
        problems.setdefault(what, [])
        if not ok:
            problems[what].append(detail)

    for f in frames:
        exr, png, a = info[f["exr"]], info[f["png"]], info[f["exr"]]["attrs"]
        expect((exr["width"], exr["height"], exr["channels"], exr["type"], exr["format"]) ==
               (w, h, 4, "half", "openexr"), f"EXRs are {w}x{h} half 4-channel OpenEXR",
               f"{f['exr']}: {exr['width']}x{exr['height']} {exr['channels']} ch {exr['type']} {exr['format']}")
        expect(a.get("channel list") == "R, G, B, A", "EXR channels are R, G, B, A",
               f"{f['exr']}: {a.get('channel list')!r}")
        expect((png["width"], png["height"], png["channels"], png["type"], png["format"]) ==
               (w, h, 4, "uint8", "png"), f"PNGs are {w}x{h} 8-bit 4-channel PNG",
               f"{f['png']}: {png['width']}x{png['height']} {png['channels']} ch {png['type']} {png['format']}")
        expect(a.get("pacifica:frame") == str(f["index"]), "EXR pacifica:frame == summary index",
               f"{f['exr']}: {a.get('pacifica:frame')!r} vs {f['index']}")
        # iinfo prints double attributes with %g (6 significant digits): compare to that precision.
        tv = a.get("pacifica:time_s")
        expect(tv is not None and close(tv, f["time_s"], rel=1e-5, abs_tol=1e-9),
               "EXR pacifica:time_s == summary time_s", f"{f['exr']}: {tv!r} vs {f['time_s']}")
        xv = a.get("pacifica:camera_x_m")
        expect(xv is not None and close(xv, f["pose"]["x_m"], rel=1e-5, abs_tol=1e-3),
               "EXR pacifica:camera_x_m == summary pose.x_m", f"{f['exr']}: {xv!r} vs {f['pose']['x_m']}")
        expect(a.get("pacifica:ocio_display") == display and a.get("pacifica:ocio_view") == view,
               f"EXR pacifica:ocio_display/ocio_view == '{display}'/'{view}'",
               f"{f['exr']}: {a.get('pacifica:ocio_display')!r}/{a.get('pacifica:ocio_view')!r}")
        expect(a.get("pacifica:gl_renderer") == renderer, "EXR pacifica:gl_renderer == summary gl.renderer",
               f"{f['exr']}: {a.get('pacifica:gl_renderer')!r}")
    for what, bad in problems.items():
        c.check(not bad, f"{what} ({len(frames)} frames)", "; ".join(bad))
    return info


def load_summary(c, out_dir):
    path = os.path.join(out_dir, "summary.json")
    c.require(os.path.isfile(path), "summary.json exists")
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except ValueError as e:
        c.require(False, "summary.json is valid JSON", str(e))


# ---------------------------------------------------------------------------------------------------------
# Cases.


def case_replay(c, exe, source_dir, tmp):
    flight = os.path.join(source_dir, "tools", "data", "demo_flight.csv")
    start, end, fps, size = 0.0, 3.0, 2.0, (320, 180)
    expected = int(math.floor((end - start) * fps + 1e-9)) + 1  # 7: 0, 0.5, ..., 3.0
    slice_args = ["--start", "0", "--end", "3", "--fps", "2", "--size", "320x180"]
    rows = read_flight(flight)

    print("[run A] default view")
    out_a = os.path.join(tmp, "run_a")  # does not exist yet: the CLI must create it
    proc = run_replay(exe, [flight, "--out", out_a, *slice_args])
    c.require(proc.returncode == 0, "run A exits 0", proc.stderr.strip()[-2000:])
    c.check("pacifica: error" not in proc.stderr, "run A prints no error", proc.stderr.strip()[-2000:])
    summary_a = load_summary(c, out_a)
    check_run_output(c, out_a, summary_a, start, fps, expected, size, rows, DEFAULT_VIEW, EMBEDDED_DISPLAY)

    frames_a = summary_a["frames"]
    exrs = [f["exr"] for f in frames_a]
    recomputed = exr_xxh64(out_a, exrs)
    bad = [(f["exr"], f["exr_pixel_hash"], recomputed.get(f["exr"])) for f in frames_a
           if recomputed.get(f["exr"]) != f["exr_pixel_hash"]]
    c.check(not bad, "exr_pixel_hash == XXH64 of the EXR's decoded half RGBA pixels, rows top-down", str(bad))
    hashes_a = [f["exr_pixel_hash"] for f in frames_a]
    # A moving camera over a moving sea: consecutive frames must differ (guards against a stuck renderer).
    c.check(len(set(hashes_a)) == len(hashes_a), "every frame's EXR pixels differ", str(hashes_a))

    print(f"[run B] --view '{UNTONEMAPPED_VIEW}'")
    out_b = os.path.join(tmp, "run_b")
    proc = run_replay(exe, [flight, "--out", out_b, *slice_args, "--view", UNTONEMAPPED_VIEW])
    c.require(proc.returncode == 0, "run B exits 0", proc.stderr.strip()[-2000:])
    summary_b = load_summary(c, out_b)
    check_run_output(c, out_b, summary_b, start, fps, expected, size, rows, UNTONEMAPPED_VIEW, EMBEDDED_DISPLAY)
    hashes_b = [f["exr_pixel_hash"] for f in summary_b["frames"]]
    # The view only changes the display transform; scene-linear data must be bit-identical.
    c.check(hashes_a == hashes_b, "same exr_pixel_hash per frame as run A (tonemap leaves scene-linear alone)",
            f"A {hashes_a} B {hashes_b}")
    sha_a = pixel_sha1(out_a, exrs + [f["png"] for f in frames_a])
    sha_b = pixel_sha1(out_b, exrs + [f["png"] for f in frames_a])
    c.check(all(sha_a.get(n) and sha_a.get(n) == sha_b.get(n) for n in exrs),
            "decoded EXR pixels identical to run A (iinfo --hash)",
            str([(n, sha_a.get(n), sha_b.get(n)) for n in exrs if sha_a.get(n) != sha_b.get(n)]))
    same_png = [f["png"] for f in frames_a if not sha_a.get(f["png"]) or sha_a.get(f["png"]) == sha_b.get(f["png"])]
    c.check(not same_png, "every PNG differs from run A's (decoded pixels)", f"identical: {same_png}")


def case_studio_ocio(c, exe, source_dir, tmp):
    flight = os.path.join(source_dir, "tools", "data", "demo_flight.csv")
    shared = os.environ.get("PACIFICA_SHARED_DIR", "")  # set by ctest (tests/README.md)
    config = os.path.normpath(os.path.join(shared, STUDIO_CONFIG))
    c.require(os.path.isfile(config), f"studio config present at {config}")
    with open(config, encoding="utf-8") as f:
        m = re.search(r"^name:\s*(.+?)\s*$", f.read(), re.MULTILINE)
    c.require(m is not None, "studio config has a name: line")
    config_name = m[1]
    display, view = "sRGB - Display", DEFAULT_VIEW
    rows = read_flight(flight)
    args = ["--start", "8", "--end", "8", "--size", "320x180"]

    print(f"[studio] --ocio-config {config} --display '{display}' --view '{view}'")
    out_s = os.path.join(tmp, "studio")
    proc = run_replay(exe, [flight, "--out", out_s, *args, "--ocio-config", config, "--display", display,
                            "--view", view])
    c.require(proc.returncode == 0, "studio-config run exits 0", proc.stderr.strip()[-2000:])
    summary = load_summary(c, out_s)
    info = check_run_output(c, out_s, summary, 8.0, summary.get("fps", 10.0), 1, (320, 180), rows, view, display)
    # summary.json names the config by its `name:` (ColorPipeline::configDescription), not by path.
    c.check(summary["ocio"].get("config") == config_name, f"summary ocio.config is '{config_name}'",
            f"got {summary['ocio'].get('config')!r}")
    exr = summary["frames"][0]["exr"]
    c.check(info[exr]["attrs"].get("pacifica:ocio_config") == config_name,
            f"{exr} pacifica:ocio_config is '{config_name}'", repr(info[exr]["attrs"].get("pacifica:ocio_config")))

    print("[embedded] same frame with the embedded config, for comparison")
    out_e = os.path.join(tmp, "embedded")
    proc = run_replay(exe, [flight, "--out", out_e, *args])
    c.require(proc.returncode == 0, "embedded-config run exits 0", proc.stderr.strip()[-2000:])
    summary_e = load_summary(c, out_e)
    c.check(summary_e["ocio"].get("config") != config_name, "embedded run records a different config",
            repr(summary_e["ocio"].get("config")))
    # The OCIO config only drives the display transform: the scene-linear EXR must not depend on it.
    c.check(summary_e["frames"][0]["exr_pixel_hash"] == summary["frames"][0]["exr_pixel_hash"],
            "same exr_pixel_hash as with the embedded config",
            f"{summary_e['frames'][0]['exr_pixel_hash']} vs {summary['frames'][0]['exr_pixel_hash']}")
    # The frames are linear Rec.709: the studio config (scene_linear = ACEScg) is entered through its
    # "Linear Rec.709 (sRGB)" space, so its ACES SDR view gives the embedded config's picture (the embedded
    # config mirrors it) to within one 8-bit code.
    c.check(summary["ocio"].get("input") == "Linear Rec.709 (sRGB)", "studio config entered from linear Rec.709",
            repr(summary["ocio"].get("input")))
    png = summary["frames"][0]["png"]
    diff = subprocess.run([oiio_tool("idiff"), "-abs", "-fail", "0.0045", "-failpercent", "0",
                           os.path.join(out_s, png), os.path.join(out_e, png)], capture_output=True, text=True)
    c.check(diff.returncode in (0, 1), "studio vs embedded PNG within one 8-bit code",
            (diff.stdout + diff.stderr)[-600:])


def case_ocean_options(c, exe, source_dir, tmp):
    """Lighting and painted-height-map options of `pacifica replay` change what is rendered: one frame (t = 8 s,
    the low pass over the sea) with the defaults, then with each option; summary.json's exr_pixel_hash and the
    EXR's mean colour tell them apart."""
    flight = os.path.join(source_dir, "tools", "data", "demo_flight.csv")
    args = ["--start", "8", "--end", "8", "--size", "160x90"]

    def run(name, extra):
        # The output format itself is the replay case's subject; here: one frame, its EXR present.
        out = os.path.join(tmp, name)
        proc = run_replay(exe, [flight, "--out", out, *args, *extra])
        c.require(proc.returncode == 0, f"{name}: exits 0", proc.stderr.strip()[-2000:])
        summary = load_summary(c, out)
        frames = summary.get("frames", [])
        c.require(len(frames) == 1 and os.path.isfile(os.path.join(out, frames[0].get("exr", ""))),
                  f"{name}: summary.json lists one frame whose EXR exists", str(frames)[:500])
        return out, frames[0]

    print("[default] no ocean options")
    out_d, frame_d = run("default", [])
    mean_d = exr_mean_rgb(out_d, frame_d["exr"])
    print(f"    mean RGB {mean_d}")
    # The default sky and sea are blue: blue above red on average.
    c.check(mean_d[2] > mean_d[0], "default frame: mean blue > mean red", str(mean_d))

    print("[fog] --fog-density 0.01 --fog-height-falloff 5000 --fog-color 1,0,0")
    out_f, frame_f = run("fog", ["--fog-density", "0.01", "--fog-height-falloff", "5000", "--fog-color", "1,0,0"])
    mean_f = exr_mean_rgb(out_f, frame_f["exr"])
    print(f"    mean RGB {mean_f}")
    # rho = 0.01/m: 1/e within 100 m of sea and sky (the sky's column rho H = 50 is opaque), so the frame is
    # the fog's red in-scatter: red at least 5x green and blue.
    c.check(mean_f[0] > 5.0 * max(mean_f[1], mean_f[2]), "dense red fog: mean red > 5x green and blue",
            str(mean_f))
    c.check(frame_f["exr_pixel_hash"] != frame_d["exr_pixel_hash"], "fog options change the EXR pixels")

    print("[sun] --sun-elevation 5 --sun-azimuth 250")
    _, frame_s = run("sun", ["--sun-elevation", "5", "--sun-azimuth", "250"])
    c.check(frame_s["exr_pixel_hash"] != frame_d["exr_pixel_hash"], "sun options change the EXR pixels",
            frame_s["exr_pixel_hash"])

    print("[water] --water-color 0.03,0.005,0.002 (a red-brown water body)")
    out_w, frame_w = run("water", ["--water-color", "0.03,0.005,0.002"])
    mean_w = exr_mean_rgb(out_w, frame_w["exr"])
    print(f"    mean RGB {mean_w}")
    c.check(frame_w["exr_pixel_hash"] != frame_d["exr_pixel_hash"] and mean_w[0] > mean_d[0],
            "--water-color changes the EXR pixels and adds red", f"{mean_w} vs {mean_d}")

    print("[shading] --forward-shading: the grids' fragment stage lights the sea instead of the compute pass")
    out_fw, frame_fw = run("forward", ["--forward-shading"])
    mean_fw = exr_mean_rgb(out_fw, frame_fw["exr"])
    print(f"    mean RGB {mean_fw}")
    shaded = (frame_d.get("counters", {}).get("compute_shaded"), frame_fw.get("counters", {}).get("compute_shaded"))
    c.check(shaded == (True, False), "compute shading by default, forward with --forward-shading (counters)",
            str(shaded))
    # The same picture (test_compute_shading_gl measures the per-pixel difference): mean colour within 0.1%.
    c.check(all(abs(a - b) <= 1e-3 * b for a, b in zip(mean_fw, mean_d)),
            "--forward-shading: mean RGB within 0.1% of the compute-shaded frame", f"{mean_fw} vs {mean_d}")

    print("[shading] --shade-tiles on / off: compute shading by tiles, the same pixels")
    _, frame_ton = run("tiles_on", ["--shade-tiles", "on"])
    _, frame_toff = run("tiles_off", ["--shade-tiles", "off"])
    tiled = (frame_ton.get("counters", {}).get("shade_tiled"), frame_toff.get("counters", {}).get("shade_tiled"))
    c.check(tiled == (True, False), "--shade-tiles on / off (counters)", str(tiled))
    c.check(frame_ton["exr_pixel_hash"] == frame_toff["exr_pixel_hash"] == frame_d["exr_pixel_hash"],
            "by tiles or not, and by default: the same EXR pixels",
            f'{frame_ton["exr_pixel_hash"]} {frame_toff["exr_pixel_hash"]} {frame_d["exr_pixel_hash"]}')
    r = run_replay(exe, [flight, "--out", os.path.join(tmp, "tiles_bad"), *args, "--shade-tiles", "some"])
    c.check(r.returncode != 0 and "--shade-tiles" in r.stderr and not os.path.exists(os.path.join(tmp, "tiles_bad")),
            "--shade-tiles some: refused naming the option, nothing written", r.stderr)

    print("[octaves] --octaves 2 --displaced-octaves 1")
    _, frame_o = run("octaves", ["--octaves", "2", "--displaced-octaves", "1"])
    c.check(frame_o["exr_pixel_hash"] != frame_d["exr_pixel_hash"], "octave count options change the EXR pixels",
            frame_o["exr_pixel_hash"])

    print("[fft spectrum] --model fft, then with --fft-spectrum phillips --wind-speed 20 --choppiness 0.5")
    _, frame_fft = run("fft", ["--model", "fft"])
    _, frame_ph = run("fft_phillips", ["--model", "fft", "--fft-spectrum", "phillips", "--wind-speed", "20",
                                       "--choppiness", "0.5"])
    c.check(frame_ph["exr_pixel_hash"] != frame_fft["exr_pixel_hash"],
            "FFT spectrum options change the EXR pixels", frame_ph["exr_pixel_hash"])
    print("[fft cascades] --model fft --fft-cascades 2, and --no-fft-mix")
    _, frame_c2 = run("fft_cascades", ["--model", "fft", "--fft-cascades", "2"])
    _, frame_nm = run("fft_no_mix", ["--model", "fft", "--no-fft-mix"])
    c.check(len({frame_c2["exr_pixel_hash"], frame_nm["exr_pixel_hash"], frame_fft["exr_pixel_hash"]}) == 3,
            "--fft-cascades and --no-fft-mix change the EXR pixels", frame_c2["exr_pixel_hash"])

    print("[sea state] --sea-state 20, --beaufort 3, and a bad value")
    out_ss, frame_ss = run("sea_state", ["--sea-state", "20"])
    _, frame_bf = run("beaufort", ["--beaufort", "3"])
    c.check(frame_ss["exr_pixel_hash"] != frame_d["exr_pixel_hash"] and
            frame_bf["exr_pixel_hash"] not in (frame_d["exr_pixel_hash"], frame_ss["exr_pixel_hash"]),
            "--sea-state and --beaufort change the EXR pixels", f"{frame_ss['exr_pixel_hash']}")
    mean_ss = exr_mean_rgb(out_ss, frame_ss["exr"])
    print(f"    mean RGB {mean_ss}")
    # 20 m/s: ~10 % whitecaps (Monahan) and a wider glitter: a brighter sea than the default.
    c.check(sum(mean_ss) > sum(mean_d), "a 20 m/s sea is brighter on average (whitecaps, glitter)",
            f"{mean_ss} vs {mean_d}")
    bad = subprocess.run([exe, "replay", flight, "--out", os.path.join(tmp, "bad_sea"), *args, "--sea-state", "0",
                          "--no-progress"], env=child_env(), capture_output=True, text=True, timeout=RUN_TIMEOUT_S)
    c.check(bad.returncode != 0 and "--sea-state" in bad.stderr and not os.path.exists(os.path.join(tmp, "bad_sea")),
            "--sea-state 0: refused naming the option, nothing written", bad.stderr.strip()[-300:])

    print("[height maps] --height-map still.png --height-map strip.png (4 frames)")
    still = write_gray_png(os.path.join(tmp, "still.png"), 64, 64, lambda x, r: 0.5 + 0.5 * math.cos(
        2 * math.pi * (3 * (x + 0.5) / 64 + 2 * (r + 0.5) / 64)))
    strip = write_gray_png(os.path.join(tmp, "strip.png"), 64, 256, lambda x, r: 0.5 + 0.5 * math.cos(
        2 * math.pi * (2 * (x + 0.5) / 64 + (r % 64 + 0.5) / 64) - 2 * math.pi * (r // 64) / 4))
    _, frame_h = run("maps", ["--height-map", still, "--height-map", strip])
    c.check(frame_h["exr_pixel_hash"] != frame_d["exr_pixel_hash"], "painted height maps change the EXR pixels",
            frame_h["exr_pixel_hash"])
    _, frame_h2 = run("maps_again", ["--height-map", still, "--height-map", strip])
    c.check(frame_h2["exr_pixel_hash"] == frame_h["exr_pixel_hash"], "the same maps render the same pixels",
            f"{frame_h['exr_pixel_hash']} vs {frame_h2['exr_pixel_hash']}")


def case_effects(c, exe, source_dir, tmp):
    """The demo flight's events reach the picture and the per-frame counters (summary.json frames[i].counters):
    the 3.0 s explosion is flat at t = 3.0 and active and drawn after; both ships' wakes are active; with
    --no-events every effect counter is 0 and the frame costs exactly the plain ocean's passes, draws and
    uploads (with events: that plus the effects field's compute pass and uploads, and one pass and draw per
    kind of secondary grid drawn)."""
    flight = os.path.join(source_dir, "tools", "data", "demo_flight.csv")
    args = ["--start", "3", "--end", "5", "--fps", "2", "--size", "160x90", "--no-images"]

    def run(name, extra):
        out = os.path.join(tmp, name)
        proc = run_replay(exe, [flight, "--out", out, *args, *extra])
        c.require(proc.returncode == 0, f"{name}: exits 0", proc.stderr.strip()[-2000:])
        summary = load_summary(c, out)
        frames = summary.get("frames", [])
        c.require(len(frames) == 5 and all("counters" in f for f in frames),
                  f"{name}: 5 frames, each with counters", str(frames)[:500])
        return summary, frames

    print("[events] demo slice 3..5 s with the flight's explosions and ships")
    s_fx, f_fx = run("events", [])
    ev = s_fx.get("events", {})
    c.check(ev.get("applied") is True and ev.get("explosions") == 3 and ev.get("ships") == 2,
            "summary.events: applied, 3 explosions, 2 ships", str(ev))
    first = f_fx[0]["counters"]
    c.check(first["explosions"]["active"] == 0, "t = 3.0 (the blast's own instant): no explosion to draw",
            str(first["explosions"]))
    for f in f_fx[1:]:
        k = f["counters"]
        print(f"    t={f['time_s']}: explosions {k['explosions']}, wakes {k['wakes']}")
        x = k["explosions"]
        c.check(x["active"] == 1 and k["effect_field"]["tiles"] > 0 and x["drawn"] <= 1 and
                x["draws"] == x["drawn"] and (x["vertices"] > 0) == (x["drawn"] == 1),
                f"t={f['time_s']}: the explosion is active and in the effects field (a grid only if near)",
                str(x) + " " + str(k["effect_field"]))
        c.check(k["wakes"]["active"] == 2, f"t={f['time_s']}: both ships' wakes are active", str(k["wakes"]))
        c.check(k["programs_built"] == 0 or f["time_s"] == 3.5, f"t={f['time_s']}: no shader built in steady state",
                str(k["programs_built"]))

    print("[no events] the same slice with --no-events")
    s_plain, f_plain = run("plain", ["--no-events"])
    c.check(s_plain.get("events", {}).get("applied") is False, "summary.events.applied is false")
    for fp, fe in zip(f_plain, f_fx):
        kp, ke = fp["counters"], fe["counters"]
        zero = all(kp[kind][field] == 0 for kind in ("explosions", "wakes")
                   for field in ("active", "drawn", "passes", "draws", "uploads", "vertices")) and \
            all(v == 0 for v in kp["effect_field"].values())
        c.check(zero, f"t={fp['time_s']}: no effect counter is non-zero without events", str(kp))
        field = ke["effect_field"]
        c.check(field["passes"] == 1 and field["tiles"] > 0 and field["texels"] == 64 * field["tiles"],
                f"t={fe['time_s']}: the effects field is evaluated once, over the tiles the effects touch",
                str(field))
        extra_passes = ke["explosions"]["passes"] + ke["wakes"]["passes"] + field["passes"]
        extra_draws = ke["explosions"]["draws"] + ke["wakes"]["draws"]
        extra_uploads = ke["explosions"]["uploads"] + ke["wakes"]["uploads"] + field["uploads"]
        c.check(ke["passes"] == kp["passes"] + extra_passes and ke["draws"] == kp["draws"] + extra_draws and
                ke["uploads"] == kp["uploads"] + extra_uploads,
                f"t={fp['time_s']}: effects add exactly their own passes, draws and uploads",
                f"events {ke} vs plain {kp}")
        if fe["counters"]["explosions"]["drawn"] or fe["counters"]["wakes"]["drawn"]:
            c.check(fp["exr_pixel_hash"] != fe["exr_pixel_hash"], f"t={fp['time_s']}: the effects change the pixels")


    print("[profile] the events slice again with --profile: per-pass times, the same pixels")
    c.check(all("pass_ms" not in f for f in f_fx), "without --profile no frame has pass_ms")
    s_prof, f_prof = run("profiled", ["--profile"])
    medians = s_prof.get("timings", {}).get("passes_ms_median", {})
    want = {"compute", "sky", "sea", "effects", "shade", "objects", "tonemap", "readback", "encode"}
    c.check(want <= set(medians), "summary timings.passes_ms_median names every pass", str(medians))
    c.check("glFinish" in s_prof.get("timings", {}).get("pass_clock", "") or
            "GL_TIMESTAMP" in s_prof.get("timings", {}).get("pass_clock", ""),
            "summary timings.pass_clock names the clock", str(s_prof.get("timings")))
    for fp, fe in zip(f_prof, f_fx):
        pm = fp.get("pass_ms", {})
        c.check(fp["exr_pixel_hash"] == fe["exr_pixel_hash"], f"t={fp['time_s']}: --profile changes no pixel")
        c.check(all(isinstance(pm.get(k), (int, float)) and pm[k] >= 0 for k in want),
                f"t={fp['time_s']}: pass_ms has every pass, none negative", str(pm))
        # Compute shading (the default, counters.compute_shaded) lights the sky in its shading pass.
        sky_pass = "shade" if fp["counters"]["compute_shaded"] else "sky"
        c.check(pm.get("sea", 0) > 0 and pm.get(sky_pass, 0) > 0 and pm.get("tonemap", 0) > 0,
                f"t={fp['time_s']}: {sky_pass}, sea and tonemap take time", str(pm))
        if fe["counters"]["wakes"]["drawn"] or fe["counters"]["explosions"]["drawn"]:
            c.check(pm.get("effects", 0) > 0, f"t={fp['time_s']}: drawn effects take time", str(pm))





def png_mean(directory, name):
    """Mean of the R, G, B code values (0..255) of an 8-bit PNG, from `oiiotool --dumpdata`."""
    proc = subprocess.run([oiio_tool("oiiotool"), "--dumpdata", name], cwd=directory, capture_output=True,
                          text=True, timeout=RUN_TIMEOUT_S)
    if proc.returncode != 0:
        raise CaseAborted(f"oiiotool --dumpdata failed (exit {proc.returncode}): {proc.stderr.strip()}")
    values = [sum(int(v) for v in line.split(":", 1)[1].split()[:3]) / 3.0
              for line in proc.stdout.splitlines() if line.startswith("    Pixel (")]
    return sum(values) / max(len(values), 1)


def case_night(c, exe, source_dir, tmp):
    """A moonlit night (--moon-*) and its pre-exposure (--exposure): one frame at t = 0 (20 m up, heading 90),
    the full Moon 12 degrees up straight ahead. The same frame by day (the Sun where the Moon is) is the night
    frame times the Sun/Moon illuminance ratio (Krisciunas & Schaefer: 2.34e-6 for a full Moon); --exposure 15
    scales every pixel by 2^15; the Moon's glitter path lies in the middle column; through both OCIO views the
    exposed night is not black, unexposed it is."""
    flight = os.path.join(source_dir, "tools", "data", "demo_flight.csv")
    args = ["--start", "0", "--end", "0", "--size", "160x90", "--view", DEFAULT_VIEW, "--view", UNTONEMAPPED_VIEW]

    def run(name, extra, base=args):
        out = os.path.join(tmp, name)
        proc = run_replay(exe, [flight, "--out", out, *base, *extra])
        c.require(proc.returncode == 0, f"{name}: exits 0", proc.stderr.strip()[-2000:])
        summary = load_summary(c, out)
        frames = summary.get("frames", [])
        c.require(len(frames) == 1, f"{name}: one frame", str(frames)[:300])
        return out, summary, frames[0]

    moon = ["--moon-elevation", "12", "--moon-azimuth", "90"]
    out_day, _, f_day = run("day", ["--sun-elevation", "12", "--sun-azimuth", "90"])
    out_n0, _, f_n0 = run("night-ev0", moon)
    out_n, s_n, f_n = run("night-ev15", moon + ["--exposure", "15"])
    c.check(s_n.get("exposure_ev") == 15, "summary.json records exposure_ev 15", str(s_n.get("exposure_ev")))
    day, night0, night = (exr_pixels(o, f["exr"]) for o, f in ((out_day, f_day), (out_n0, f_n0), (out_n, f_n)))

    def lum(p):
        return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]

    mean = [sum(lum(p) for p in px) / len(px) for px in (day, night0, night)]
    print(f"    mean luminance: day {mean[0]:.4g}, night {mean[1]:.4g}, night +15 EV {mean[2]:.4g}")
    c.check(all(math.isfinite(v) for px in (night0, night) for p in px for v in p), "night EXRs finite")
    ratio = 0.313 / 133800.0  # the full Moon's illuminance over the Sun's (ocean/Lighting.h)
    c.check(abs(mean[2] / mean[0] / (ratio * 32768.0) - 1.0) < 0.01,
            "night +15 EV = day x Moon/Sun x 2^15 within 1 %", f"{mean[2] / mean[0]:.5g} vs {ratio * 32768.0:.5g}")
    c.check(abs(mean[2] / mean[1] / 32768.0 - 1.0) < 0.03, "--exposure 15 scales the frame by 2^15 within 3 %",
            f"{mean[2] / mean[1]:.1f}")
    # The glitter: the brightest column of the sea (the lower half, below the level horizon) is the middle one.
    cols = [sum(lum(night[y * 160 + x]) for y in range(50, 90)) for x in range(160)]
    brightest = max(range(160), key=lambda x: cols[x])
    c.check(abs(brightest - 79.5) <= 4, "the Moon's glitter path lies in the middle column", f"column {brightest}")
    pngs = [(DEFAULT_VIEW, f_n.get("png"))] + [(e.get("view"), e.get("png")) for e in f_n.get("extra_views", [])]
    c.check([v for v, _ in pngs] == [DEFAULT_VIEW, UNTONEMAPPED_VIEW], "a PNG per OCIO view", str(pngs))
    for view, name in pngs:
        exposed = png_mean(out_n, name)
        unexposed = png_mean(out_n0, name)
        c.check(exposed > 15.0 and unexposed < 2.0,
                f"{view}: the exposed night is not black (mean code {exposed:.1f}), unexposed it is ({unexposed:.2f})")
    # Searchlights in fog (--light): one on the demo's coaster (ahead, 1.2 km), one fixed; at t = 10 s.
    fog = ["--fog-density", "6e-4", "--exposure", "17"]
    at10 = ["--start", "10", "--end", "10", "--size", "160x90"]
    lamps = ["--light", "spot:coaster,height=15,azimuth=-60,elevation=-6,angle=5,intensity=2000",
             "--light", "spot:fixed,x=2000,y=-400,height=30,azimuth=20,elevation=4,angle=4,intensity=5000"]
    out_dark, _, f_dark = run("fog", moon + fog, at10)
    out_lit, _, f_lit = run("searchlights", moon + fog + lamps, at10)
    c.check(f_lit["counters"].get("spots") == 2 and f_dark["counters"].get("spots") == 0,
            "summary.json counts the two lights (none without --light)", str(f_lit["counters"].get("spots")))
    c.check(f_lit["counters"]["passes"] == f_dark["counters"]["passes"], "the lights add no pass")
    dark_px, lit_px = exr_pixels(out_dark, f_dark["exr"]), exr_pixels(out_lit, f_lit["exr"])
    gained = [lum(b) - lum(a) for a, b in zip(dark_px, lit_px)]
    c.check(all(math.isfinite(v) for p in lit_px for v in p), "the lit frame is finite")
    # Above the horizon (the level camera's upper 40 rows of 90) only the beams in the fog add light.
    sky_gain = sum(1 for i, g in enumerate(gained) if i // 160 < 40 and g > 0.05)
    c.check(min(gained) > -1e-3 * max(gained) and sky_gain > 40,
            f"the lights only add light, and their beams show in the sky ({sky_gain} pixels above the horizon "
            "gain 0.05, 119 measured; > 40 wanted)",
            f"min {min(gained):.3g}, max {max(gained):.3g}, {sky_gain} pixels")


CASES = {"replay": case_replay, "studio-ocio": case_studio_ocio, "ocean-options": case_ocean_options,
         "effects": case_effects,
         "night": case_night}


def main(cases=None, label="e2e", doc=None):
    """Runs one --case of `cases` (this file's CASES by default); shared by test_recordings.py."""
    cases = cases or CASES
    ap = argparse.ArgumentParser(description=doc or __doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--case", choices=sorted(cases), required=True)
    ap.add_argument("pacifica_exe")
    ap.add_argument("source_dir")
    ns = ap.parse_args()

    c = E2eChecks()
    tmp = tempfile.mkdtemp(prefix=f"pacifica-{label}-{ns.case}-")
    t0 = time.monotonic()
    print(f"{label} case '{ns.case}': {ns.pacifica_exe} (temp dir {tmp})")
    try:
        cases[ns.case](c, ns.pacifica_exe, os.path.abspath(ns.source_dir), tmp)
    except CaseAborted as e:
        if not c.failed:
            c.failed.append(str(e))
        print(f"  case aborted: {e}")
    except subprocess.TimeoutExpired as e:
        c.failed.append(f"timed out: {e}")
        print(f"  FAIL  timed out: {e}")
    return c.finish(f"{label}/{ns.case}", t0, tmp)


if __name__ == "__main__":
    sys.exit(main())
