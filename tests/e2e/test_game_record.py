#!/usr/bin/env python3
"""game_record_replay: the record -> replay loop. The game flies its scripted session under Xvfb with
--record (Tacview ACMI 2.2), then `pacifica replay` reads that recording: the bomb's impact becomes an
explosion at the same time (to the 1 ms the ACMI frame line keeps) and place (to the 7 decimals of a degree,
~1 cm), the ship sails on the recorded track with its wake, and the recording ends where the game's ship ended.
Usage: test_game_record.py XVFB_RUN GAME_EXE PACIFICA_EXE"""
import json
import os
import re
import subprocess
import sys
import tempfile

xvfb, game, pacifica = sys.argv[1:4]
tmp = tempfile.mkdtemp(prefix="pacifica-game-record-")
acmi = os.path.join(tmp, "session.txt.acmi")
passed, failed = [], []


def check(ok, what, detail=""):
    print(("  ok    " if ok else "  FAIL  ") + what + ("" if ok else f": {detail}"))
    (passed if ok else failed).append(what)


g = subprocess.run([xvfb, "-a", "-s", "-screen 0 640x360x24", game, "--frames", "8", "--record", acmi],
                   capture_output=True, text=True, timeout=240)
print(g.stdout)
check(g.returncode == 0 and os.path.exists(acmi), "the game's scripted session runs and writes its recording",
      g.stderr[-500:])
impact = re.search(r"impact t=([\d.]+) lat=([-\d.]+) lon=([-\d.]+)", g.stdout)
ship = re.search(r"ship t=([\d.]+) lat=([-\d.]+) lon=([-\d.]+)", g.stdout)
check(bool(impact and ship), "the game reports its impact and its ship", g.stdout)
if impact and ship:
    t0, lat0, lon0 = map(float, impact.groups())
    out = os.path.join(tmp, "replay")
    r = subprocess.run([pacifica, "replay", acmi, "--rig", "chase:Player", "--out", out, "--size", "160x90",
                        "--fps", "30", "--no-progress"], capture_output=True, text=True, timeout=240)
    check(r.returncode == 0, "pacifica replay reads the game's recording", r.stderr[-500:])
    if r.returncode == 0:
        s = json.load(open(os.path.join(out, "summary.json")))
        x = s["recording"]["explosions"]
        check(len(x) == 1 and x[0]["type"] == "Weapon+Bomb", "one explosion, from the recorded bomb", str(x))
        if x:
            check(abs(x[0]["time_s"] - t0) <= 1e-3, "at the game's time (1 ms)", f"{x[0]['time_s']} vs {t0}")
            check(abs(x[0]["latitude_deg"] - lat0) < 1e-7 and abs(x[0]["longitude_deg"] - lon0) < 1e-7,
                  "at the game's place (1e-7 deg, ~1 cm)", f"{x[0]} vs {lat0}, {lon0}")
        check(len(s["recording"]["ships"]) == 1, "one ship", str(s["recording"]["ships"]))
        last = s["frames"][-1]["counters"]
        check(last["explosions"]["active"] == 1 and last["wakes"]["active"] == 1,
              "the explosion and the ship's wake are alive in the replay's last frame", str(last))
    # The recording's last ship position is where the game's ship ended.
    t1, lat1, lon1 = map(float, ship.groups())
    ref_lat = ref_lon = 0.0
    lat = lon = None
    with open(acmi, encoding="utf-8") as f:
        for line in f:
            line = line.rstrip("\n")
            if line.startswith("0,ReferenceLatitude="):
                ref_lat = float(line.split("=")[1])
            elif line.startswith("0,ReferenceLongitude="):
                ref_lon = float(line.split("=")[1])
            elif line.startswith("200,T="):
                fields = line.split(",")[1][2:].split("|")
                lon = float(fields[0]) + ref_lon if fields[0] else lon
                lat = float(fields[1]) + ref_lat if fields[1] else lat
    check(lat is not None and abs(lat - lat1) < 1e-7 and abs(lon - lon1) < 1e-7,
          "the recorded ship ends where the game's ship did", f"{lat}, {lon} vs {lat1}, {lon1}")
print(f"{len(passed)} passed, {len(failed)} failed")
if not failed:
    import shutil
    shutil.rmtree(tmp, ignore_errors=True)
else:
    print(f"output kept in {tmp}")
sys.exit(1 if failed else 0)
