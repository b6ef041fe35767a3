#!/usr/bin/env python3
"""The game end to end (pacifica-game under Xvfb), one ctest test per case:
  sortie     the autopilot's scripted input flies a sortie: take-off from the carrier's deck, climb, a bomb run,
             a hit that sinks a target; screenshots checked from the outside (the HUD is drawn, the splash is
             visible), no GL errors, no gamepad present handled; the session recorded as ACMI and replayed by
             `pacifica replay`: the same explosions at the same times and places, the ships with their wakes.
  keys       the real input path: keys typed into the window with xdotool (XTEST) under Xvfb -- Backspace
             starts a new sortie (the recording of the first is saved), then throttle up
             on the deck (the jet rolls ahead of the carrier), C cycles the camera, T slow motion, P pause,
             Escape quits cleanly and the summary says so.
  night      --night (headless): a moonlit, hazy sea and the carrier's four lamps: counted, dark but not black
             against the same moment by day, the lamps' beams and lit water bright.
  bad-input  bad command-line values exit 2 naming the option; no display exits 1 with a clear message.
Usage: test_game.py --case CASE XVFB_RUN GAME_EXE PACIFICA_EXE     (python3 standard library only)"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from checks import Checks  # noqa: E402
from pngread import luminance, read_png  # noqa: E402

ap = argparse.ArgumentParser()
ap.add_argument("--case", required=True, choices=["sortie", "keys", "night", "bad-input"])
ap.add_argument("xvfb")
ap.add_argument("game")
ap.add_argument("pacifica")
args = ap.parse_args()
tmp = tempfile.mkdtemp(prefix=f"pacifica-game-{args.case}-")
started = time.monotonic()
c = Checks()
W, H = 640, 360


def env():
    e = dict(os.environ)
    e.pop("OCIO", None)
    e.setdefault("MESA_SHADER_CACHE_DISABLE", "true")
    return e


def xvfb_run():
    """xvfb-run with its X authority file in this test's directory (-f): without one it makes and removes a
    temporary directory of its own, and that removal failed twice in a row under ctest -j2 ("problem while
    cleaning up temporary directory", its exit 5 replacing the game's)."""
    return [args.xvfb, "-a", "-f", os.path.join(tmp, "Xauthority"), "-s", "-screen 0 1280x720x24"]


def game(*a, xvfb=True, timeout=600):
    cmd = (xvfb_run() if xvfb else []) + [args.game, *a]
    print("  $ " + " ".join(cmd))
    return subprocess.run(cmd, cwd=tmp, env=env(), capture_output=True, text=True, timeout=timeout)


def region(png, x0, y0, x1, y1):
    """(mean luminance, fraction of pixels brighter than 0.85) of a rectangle of a screenshot."""
    w, h, ch, rows = png
    lum = [luminance(rows, ch, x, y) for y in range(y0, y1) for x in range(x0, x1)]
    return sum(lum) / len(lum), sum(v > 0.85 for v in lum) / len(lum)


if args.case == "sortie":
    # Time 0 is the start on the deck; the autopilot's first bomb lands at ~44 s; the weapon camera follows it
    # down, then watches the impact point for 10 s from the same place (so 44.5 s and 50.5 s differ by the
    # splash: its plume lasts 6 s).
    g = game("--autopilot", "--frames", "202", "--fps", "4", "--quality", "low", "--size", f"{W}x{H}",
             "--camera", "weapon", "--screenshot", "1:deck.png", "--screenshot", "44.5:hit.png",
             "--screenshot", "50.5:after.png", "--summary", "s.json", "--record", "s.txt.acmi")
    print(g.stdout[-800:])
    c.check(g.returncode == 0, "the scripted sortie runs (exit 0, no GL errors)", g.stderr[-800:])
    s = json.load(open(os.path.join(tmp, "s.json"))) if os.path.exists(os.path.join(tmp, "s.json")) else {}
    ev = s.get("events", [])
    kinds = [e["kind"] for e in ev]
    c.check(s.get("gl_errors") == 0, "no GL errors in any frame", str(s.get("gl_errors")))
    c.check(s.get("frames") == 202 and abs(s.get("time_s", 0) - 50.5) < 1e-6, "202 frames of 0.25 s game time",
            f"{s.get('frames')} frames, t = {s.get('time_s')}")
    c.check(s.get("gamepad") is None, "no gamepad present: keyboard and mouse, no error", str(s.get("gamepad")))
    p = s.get("player", {})
    c.check(not p.get("on_deck", True) and p.get("z", 0) > 200, "took off and climbed above 200 m", str(p))
    c.check("launch" in kinds and "impact" in kinds and "ship_sunk" in kinds,
            "a bomb run: launch, impact, a target sunk", str(kinds))
    impacts = [e for e in ev if e["kind"] == "impact"]
    if impacts:
        c.check(35.0 < impacts[0]["time_s"] < 46.0 and impacts[0]["strength"] == 1.0,
                "the bomb lands ~44 s into the sortie with a 500 kg charge's strength", str(impacts[0]))
    c.check(any("sunk" in m for m in s.get("messages", [])), "the HUD announced the sinking", str(s.get("messages")))
    c.check(s.get("score") == 1200, "score 1200: a hit (200) that sank the ship (1000)", str(s.get("score")))
    c.check(s.get("hud", {}).get("vertices", 0) > 500, "the HUD drew (ImGui vertices)", str(s.get("hud")))
    c.check(len(s.get("screenshots", [])) == 3, "three screenshots taken", str(s.get("screenshots")))
    c.check(s.get("counters", {}).get("wakes", 0) >= 1, "ship wakes drawn in the last frame", str(s.get("counters")))

    shots = {}
    for name in ("deck", "hit", "after"):
        path = os.path.join(tmp, f"{name}.png")
        if c.check(os.path.exists(path), f"{name}.png written"):
            shots[name] = read_png(path)
            c.check(shots[name][:2] == (W, H), f"{name}.png is {W}x{H}", str(shots[name][:2]))
    if "deck" in shots:
        # The HUD's flight panel (top left, 10..310 x 10..~160): dark translucent panel with white text. Without
        # it this is bright sky and sea (mean luminance ~0.5, no pure white).
        mean, bright = region(shots["deck"], 14, 30, 300, 150)
        c.check(mean < 0.35 and bright > 0.01, "the HUD's flight panel is drawn (dark panel, white text)",
                f"mean {mean:.3f}, white fraction {bright:.4f}")
        # The carrier's flight deck fills the lower middle of the chase view at the start.
        mean, _ = region(shots["deck"], 240, 250, 400, 320)
        c.check(0.25 < mean < 0.8, "the carrier's deck is drawn under the aircraft", f"mean {mean:.3f}")
    if "hit" in shots and "after" in shots:
        # Same camera (watching the impact point) 0.7 s and 6.7 s after the impact: the splash's white column
        # stands in the first only.
        _, _, ch, a = shots["hit"]
        _, _, _, b = shots["after"]
        brighter = sum(1 for y in range(170, H) for x in range(0, W)
                       if luminance(a, ch, x, y) - luminance(b, ch, x, y) > 0.25)
        c.check(brighter > 150, "the splash is visible at the impact (pixels >0.25 brighter than 6 s later)",
                f"{brighter} pixels")

    # Record -> replay: the replay's readers and sea drivers see what the game did.
    acmi = os.path.join(tmp, "s.txt.acmi")
    if c.check(os.path.exists(acmi) and not os.path.exists(acmi + ".tmp"), "the session was recorded (ACMI)"):
        out = os.path.join(tmp, "replay")
        r = subprocess.run([args.pacifica, "replay", acmi, "--rig", "chase:Player", "--out", out, "--size",
                            "160x90", "--fps", "1", "--start", "215", "--end", "230", "--no-progress"],
                           env=env(), capture_output=True, text=True, timeout=600)
        c.check(r.returncode == 0, "pacifica replay reads the game's recording", r.stderr[-600:])
        if r.returncode == 0:
            rs = json.load(open(os.path.join(out, "summary.json")))
            x = rs["recording"]["explosions"]
            c.check(len(x) == len(impacts) and all(e["type"] == "Weapon+Bomb" for e in x),
                    "the replay's explosions are the game's bomb impacts", f"{x} vs {impacts}")
            for e, gi in zip(x, impacts):
                c.check(abs(e["time_s"] - gi["record_time_s"]) <= 1e-3, "at the game's time (1 ms)",
                        f"{e['time_s']} vs {gi['record_time_s']}")
                c.check(abs(e["latitude_deg"] - gi["latitude_deg"]) < 1e-6 and
                        abs(e["longitude_deg"] - gi["longitude_deg"]) < 1e-6, "at the game's place (~0.1 m)",
                        f"{e} vs {gi}")
            ships = rs["recording"]["ships"]
            c.check(len(ships) == 4, "the carrier and three targets are ships in the replay", str(ships))
            last = rs["frames"][-1]["counters"]
            c.check(last["wakes"]["active"] >= 1 and last["explosions"]["active"] >= 1,
                    "wakes and the explosion are alive in the replay", str(last))
        # Each ship's recorded track ends where the game's ship was at the end (the tracks replay's wakes
        # follow); ACMI T= fields are relative to the reference point and left empty when unchanged.
        ref_lat = ref_lon = 0.0
        track_end = {}
        with open(acmi, encoding="utf-8") as f:
            for line in f:
                line = line.rstrip("\n")
                if line.startswith("0,ReferenceLatitude="):
                    ref_lat = float(line.split("=")[1])
                elif line.startswith("0,ReferenceLongitude="):
                    ref_lon = float(line.split("=")[1])
                elif ",T=" in line and not line.startswith(("#", "0,")):
                    oid = int(line.split(",")[0], 16)
                    fields = line.split(",T=")[1].split(",")[0].split("|")
                    lon, lat = track_end.get(oid, (None, None))
                    lon = float(fields[0]) + ref_lon if fields[0] else lon
                    lat = float(fields[1]) + ref_lat if fields[1] else lat
                    track_end[oid] = (lon, lat)
        for sh in s.get("ships", []):
            lon, lat = track_end.get(sh["id"], (None, None))
            c.check(lat is not None and abs(lat - sh["latitude_deg"]) < 1e-7 and
                    abs(lon - sh["longitude_deg"]) < 1e-7,
                    f"{sh['name']}'s recorded track ends where the game's ship was",
                    f"{lat}, {lon} vs {sh.get('latitude_deg')}, {sh.get('longitude_deg')}")

elif args.case == "keys":
    # A shell script under one Xvfb: start the game (real-time stepping), wait until its window is mapped (the
    # game shows it at its first swap, once its programs are built: seconds here, tens of seconds under ASan
    # with other tests beside it), focus it, then type. The holds are generous: a frame takes ~0.3 s here in
    # Release, several under a sanitizer, and the game steps at most 0.25 s of game time a frame. P comes
    # right after R: at full throttle the jet rolls off the bow ~8.6 s of game time after R goes down (the
    # recorded track of a 16 s hold), and on a quiet machine game time keeps up with the wall clock, so the
    # throttle is held for 6 s and the game paused before the camera and slow-motion keys.
    script = os.path.join(tmp, "keys.sh")
    with open(script, "w") as f:
        f.write(f"""#!/bin/sh
"{args.game}" --quality low --size 480x270 --summary k.json --record k.txt.acmi &
pid=$!
wid=$(timeout 240 xdotool search --sync --onlyvisible --name '^Pacifica$' | head -1)
xdotool windowfocus --sync "$wid"
xdotool mousemove --window "$wid" 240 200
xdotool key BackSpace; sleep 2
xdotool keydown r; sleep 6; xdotool keyup r
xdotool key p; sleep 2
xdotool key c; sleep 2
xdotool key t; sleep 2
xdotool key Escape
( sleep 60; kill $pid ) >/dev/null 2>&1 &
watchdog=$!
wait $pid
status=$?
kill $watchdog 2>/dev/null
exit $status
""")
    os.chmod(script, 0o755)
    print("  $ xvfb-run " + script)
    r = subprocess.run(xvfb_run() + [script], cwd=tmp, env=env(),
                       capture_output=True, text=True, timeout=300)
    print(r.stdout[-600:])
    c.check(r.returncode == 0, "the game ran under typed keys and quit on Escape (exit 0)", r.stderr[-600:])
    path = os.path.join(tmp, "k.json")
    if c.check(os.path.exists(path), "its summary was written on quitting"):
        s = json.load(open(path))
        # How far it spools depends on how much game time the slow frames let pass (CI runs tests in
        # parallel): any clear rise from 0 shows the key reached the game.
        c.check(s["throttle"] > 0.1, "R throttled up (from 0; the engine spools at 60 % per game second)",
                str(s["throttle"]))
        # Started 115 m aft of the carrier's centre, riding it; throttle up rolls the jet forward on the deck.
        ev = s["player"]
        c.check(ev["on_deck"] or ev["z"] > 20.0, "still on the deck or flying (not ditched)", str(ev))
        c.check(s["camera"] == "orbit", "C switched the chase camera to the orbit camera", s["camera"])
        c.check(s["slow_motion"] and s["paused"], "T slowed the game down and P paused it",
                f"slow {s['slow_motion']}, paused {s['paused']}")
        c.check(s["gl_errors"] == 0 and s["gamepad"] is None, "no GL errors, no gamepad needed", str(s))
        c.check(any(m.startswith("New sortie") and "saved" in m for m in s["messages"]) and
                os.path.exists(os.path.join(tmp, "k.txt.acmi")),
                "Backspace started a new sortie and saved the recording of the first", str(s["messages"]))
        c.check(s["speed_over_deck_mps"] > 0.5, "the jet rolled forward over the deck (> 0.5 m/s; idle: < 0.1)",
                str(s["speed_over_deck_mps"]))

elif args.case == "night":
    # --night: the same scripted start by day and by night, seen from the orbit camera over the carrier at 2 s.
    shots = {}
    for name, extra in (("day", []), ("night", ["--night"])):
        g = game("--headless", "--autopilot", "--frames", "12", "--fps", "4", "--quality", "low", "--size",
                 f"{W}x{H}", "--camera", "orbit", "--no-hud", "--screenshot", f"2:{name}.png", "--summary",
                 f"{name}.json", *extra, xvfb=False)
        c.check(g.returncode == 0, f"{name}: the scripted start runs (exit 0)", g.stderr[-800:])
        path = os.path.join(tmp, f"{name}.json")
        s = json.load(open(path)) if os.path.exists(path) else {}
        c.check(s.get("gl_errors") == 0, f"{name}: no GL errors", str(s.get("gl_errors")))
        lamps = 4 if extra else 0
        c.check(s.get("counters", {}).get("spots") == lamps,
                f"{name}: {lamps} of the carrier's lamps light the sea", str(s.get("counters")))
        if os.path.exists(os.path.join(tmp, f"{name}.png")):
            png = read_png(os.path.join(tmp, f"{name}.png"))
            w, h, ch, rows = png
            lum = [luminance(rows, ch, x, y) for y in range(h) for x in range(w)]
            shots[name] = (sum(lum) / len(lum), sum(v > 0.85 for v in lum) / len(lum))
    print(f"  mean luminance, share brighter than 0.85: {shots}")
    if len(shots) == 2:
        day, night = shots["day"], shots["night"]
        c.check(0.005 < night[0] < day[0] / 3.0, "the night is dark but not black (a third of the day's mean at most)",
                str(shots))
        # Measured 0.14 % of the night's pixels above 0.85, none by day.
        c.check(night[1] > 0.0007 and day[1] < night[1] / 10.0,
                "the lamps' beams and lit water show (> 0.07 % of the pixels above 0.85, 10x the day's)", str(shots))

elif args.case == "bad-input":
    for bad, needle in [(["--frames", "-3"], "--frames"), (["--quality", "ultra"], "--quality"),
                        (["--size", "10x10"], "--size"), (["--screenshot", "soon.png"], "--screenshot"),
                        (["--camera", "drone"], "--camera"), (["--wind", "99"], "--wind"),
                        (["--model", "waves"], "--model"), (["--fps", "0"], "--fps"),
                        (["--bogus"], "--bogus"), (["--view", "No Such View", "--frames", "1"], "--view"),
                        (["--no-hud=x"], "--no-hud")]:  # found by fuzz_game_options: it aborted
        r = game(*bad)
        c.check(r.returncode == 2 and needle in r.stderr and "error" in r.stderr,
                f"{' '.join(bad)}: exit 2 naming {needle}", f"exit {r.returncode}: {r.stderr[-300:]}")
    e = env()
    e.pop("DISPLAY", None)
    e.pop("WAYLAND_DISPLAY", None)
    r = subprocess.run([args.game, "--frames", "1"], cwd=tmp, env=e, capture_output=True, text=True, timeout=120)
    c.check(r.returncode == 1 and "window" in r.stderr.lower(), "no display: exit 1 with a clear message",
            f"exit {r.returncode}: {r.stderr[-300:]}")
    r = game("--help", xvfb=False)
    c.check(r.returncode == 0 and "--autopilot" in r.stdout, "--help lists the options", r.stdout[-300:])
    # Screenshots go through libpng: OpenImageIO (and the GDAL, OpenVDB, ffmpeg and OpenCV behind it, ~340 MB
    # of shared libraries) stays out of the game's process.
    r = subprocess.run(["ldd", args.game], capture_output=True, text=True, timeout=60)
    libs = [line.split()[0] for line in r.stdout.splitlines() if line.strip()]
    # The bound on the closure is the shipped (Release) build's: a sanitized build (RelWithDebInfo,
    # instrumented) pulls more objects of the static recording library into the game, netCDF's and HDF5's
    # ~45 libraries with them (the land mask's reader; measured with readelf -d).
    sanitized = any(lib.startswith(("libasan.", "libtsan.")) for lib in libs)
    c.check(r.returncode == 0 and "libpng16.so.16" in libs and not any("OpenImageIO" in lib for lib in libs)
            and (sanitized or len(libs) < 60),
            "the game links libpng, not OpenImageIO ("
            + ("sanitized build: the library count is the Release build's check" if sanitized
               else "fewer than 60 shared libraries") + ")",
            " ".join(libs))

sys.exit(c.finish(f"game {args.case}", started, tmp))
