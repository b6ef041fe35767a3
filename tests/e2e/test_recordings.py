#!/usr/bin/env python3
"""End-to-end tests of `pacifica replay` on recorded flights (engine/recording): the real DCS recording of an
F-14B over the Black Sea (data/flights in the shared data directory, $PACIFICA_SHARED_DIR; Tacview ACMI 2.2 text) and files this script makes from it
(a zip of it) or writes itself (an IGC glider flight, malformed recordings).

Cases (chosen with --case, one ctest test each):
  acmi-rigs    chase and cockpit rigs on the F-14B: frame count, recording summary (objects per type, the 6
               ships, the navaids left out and why), chase pitch atan(8/40), cockpit pose against the recorded
               altitude; the followed aircraft drawn by the chase, not by the cockpit, none with --no-objects;
               --list-objects lists the F-14B with its pilot.
  acmi-ships   an orbit of the carrier group: every ship's wake is active and in the effects field, and the
               wakes change and brighten the frame against --no-events.
  acmi-views   two views in one run (chase + a named orbit with its own size and fov): each its own image
               sequence and summary entry; the effects were simulated once per frame (same counters).
  acmi-video   --video .mp4 (H.264) and .mov (ProRes): ffprobe reads back the codec and the frame count.
  formats      the same slice from a zip of the recording (same pixel hashes as the text: the zip is streamed
               through the same parser), the text twice (deterministic), and a generated IGC flight with a
               chase rig (derived attitude: the camera follows the glider's turn).
  fleet        a generated recording of a fleet and a battle (64 ships on crossing courses, 500 weapons ending on
               the sea, two aircraft), replayed from a chase rig and from 8 km up: every ship's wake and every
               impact simulated and in the effects field (none dropped, per frame and in total), the effects
               brighten the view from 8 km against --no-events, and a second run gives the same pixel hashes.
  bad-input    malformed ACMI (file:line and field named), unknown and ambiguous objects (candidates
               listed), a bad rig kind, too many frames (the count named), a bad --video name, ffmpeg
               missing: each exits non-zero with one 'pacifica: error:' line and leaves no output behind.

Usage: test_recordings.py --case CASE PACIFICA_EXE SOURCE_DIR     (python3 standard library + ffprobe)
"""
import json
import math
import os
import subprocess
import sys
import time
import zipfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import test_e2e  # noqa: E402
from test_e2e import child_env, exr_pixels  # noqa: E402

RUN_TIMEOUT_S = 240
SMALL = ["--size", "160x90", "--no-progress"]


def shared_dir(source_dir):
    return os.environ.get("PACIFICA_SHARED_DIR", "")  # set by ctest (tests/README.md)


def recording(source_dir):
    return os.path.join(shared_dir(source_dir), "data", "flights", "dcs-blacksea-f14b.txt.acmi")


def run(exe, args, env=None):
    cmd = [exe, "replay", *args]
    print("  $ " + " ".join(f"'{a}'" if (" " in a or not a) else a for a in cmd))
    t = time.monotonic()
    p = subprocess.run(cmd, env=child_env(env), capture_output=True, text=True, timeout=RUN_TIMEOUT_S)
    print(f"    exit {p.returncode} after {time.monotonic() - t:.1f} s")
    return p


def replay(c, exe, args, out, env=None):
    p = run(exe, [*args, "--out", out], env)
    c.require(p.returncode == 0, f"replay {' '.join(args[1:4])}... succeeds", p.stderr[-800:])
    with open(os.path.join(out, "summary.json"), encoding="utf-8") as f:
        return json.load(f)


def acmi_track(path, object_id):
    """(time, alt) of every T= line of one object in an ACMI text file (altitude carried over when empty)."""
    out, t, alt = [], 0.0, None
    with open(path, encoding="utf-8-sig") as f:
        for line in f:
            line = line.rstrip("\r\n")
            if line.startswith("#"):
                t = float(line[1:])
            elif line.startswith(object_id + ",T="):
                fields = line.split(",")[1][2:].split("|")
                if fields[2]:
                    alt = float(fields[2])
                out.append((t, alt))
    return out


def case_acmi_rigs(c, exe, source_dir, tmp):
    acmi = recording(source_dir)
    p = run(exe, [acmi, "--list-objects"])
    c.require(p.returncode == 0, "--list-objects succeeds", p.stderr[-500:])
    f14 = [line for line in p.stdout.splitlines() if line.startswith("d01 ")]
    c.check(len(f14) == 1 and "F-14B" in f14[0] and "Nuevo apodo" in f14[0], "--list-objects lists the F-14B",
            p.stdout[:400])
    rows = [line for line in p.stdout.splitlines()[1:] if not line.startswith("(")]
    c.check(len(rows) == 14, "--list-objects: 14 objects", str(len(rows)))
    c.check("over_sea" in p.stdout.splitlines()[0] and "binned_GSHHS" in p.stdout,
            "--list-objects: the share over the sea by the GSHHG shorelines", p.stdout[-300:])
    share = float(f14[0].split()[-1].rstrip("%")) if f14 else -1.0
    c.check(50.0 <= share <= 75.0, "the F-14B flies over the sea part of the time (coast near Anapa)", str(share))

    s = replay(c, exe, [acmi, "--rig", "chase:F-14B", "--start", "100", "--end", "102", "--fps", "1", *SMALL],
               os.path.join(tmp, "chase"))
    c.check(s["format"] == "acmi-text" and len(s["frames"]) == 3, "chase: 3 frames of an acmi-text flight",
            f"{s['format']} {len(s['frames'])}")
    rec = s["recording"]
    by = rec["by_type"]
    c.check(by["Sea+Watercraft+Warship"]["ships"] == 5 and by["Sea+Watercraft+AircraftCarrier"]["ships"] == 1,
            "summary: 5 warships and 1 carrier became ships", json.dumps(by)[:300])
    c.check(by["Navaid+Static+Bullseye"]["left_out"] == {"not a ship, weapon or aircraft": 3},
            "summary: the 3 bullseyes are left out, with the reason", str(by["Navaid+Static+Bullseye"]))
    c.check(by["Air+FixedWing"]["read"] == 4 and by["Air+FixedWing"]["explosions"] == 0,
            "summary: 4 aircraft read, none exploded (nothing ends at the sea)", str(by["Air+FixedWing"]))
    c.check(str(rec.get("land_mask")).endswith(".nc") and "binned_GSHHS" in str(rec.get("land_mask")),
            "summary names the GSHHG land mask used", str(rec.get("land_mask")))
    c.check(rec["rigs"][0]["object"].startswith("d01 Air+FixedWing 'F-14B'"), "the rig follows d01",
            str(rec["rigs"]))
    # Chase: 40 m behind, 8 m above, looking at the aircraft: pitch -atan(8/40) = -11.3 deg.
    pitches = [f["pose"]["pitch_deg"] for f in s["frames"]]
    c.check(all(-11.6 < p < -11.0 for p in pitches), "chase camera looks down atan(8/40) at the F-14B",
            str(pitches))
    c.check(all(f["counters"]["wakes"]["active"] == 6 for f in s["frames"]), "every frame has 6 active wakes",
            str([f["counters"]["wakes"] for f in s["frames"]]))

    c.check(all(f["counters"]["objects_drawn"] >= 1 for f in s["frames"]), "chase: the F-14B itself is drawn",
            str([f["counters"]["objects_drawn"] for f in s["frames"]]))
    bare = replay(c, exe, [acmi, "--rig", "chase:F-14B", "--start", "100", "--end", "100", "--no-objects", *SMALL],
                  os.path.join(tmp, "bare"))
    c.check(bare["frames"][0]["counters"]["objects_drawn"] == 0 and
            bare["frames"][0]["exr_pixel_hash"] != s["frames"][0]["exr_pixel_hash"],
            "--no-objects: nothing drawn, and the frame differs", "")

    chase50 = replay(c, exe, [acmi, "--rig", "chase:d01", "--start", "50", "--end", "50", *SMALL],
                     os.path.join(tmp, "chase50"))
    s = replay(c, exe, [acmi, "--rig", "cockpit:d01", "--start", "50", "--end", "50", *SMALL],
               os.path.join(tmp, "cockpit"))
    c.check(s["frames"][0]["counters"]["objects_drawn"] == chase50["frames"][0]["counters"]["objects_drawn"] - 1,
            "cockpit: the aircraft the eye sits in is not drawn",
            f"{s['frames'][0]['counters']['objects_drawn']} vs chase {chase50['frames'][0]['counters']['objects_drawn']}")
    track = acmi_track(acmi, "d01")
    before = [a for (t, a) in track if t <= 50.0 and a is not None][-1]
    after = [a for (t, a) in track if t >= 50.0 and a is not None][0]
    z = s["frames"][0]["pose"]["z_m"]
    # The eye is 1 m above the aircraft's origin (body up axis); the recorded altitude brackets it.
    c.check(min(before, after) - 2.0 <= z <= max(before, after) + 2.0,
            "cockpit eye at the recorded altitude (within 2 m)", f"z {z}, recorded {before}..{after}")


def case_acmi_ships(c, exe, source_dir, tmp):
    acmi = recording(source_dir)
    args = [acmi, "--rig", "orbit:Stennis,distance=1800,elevation=35,rate=0,azimuth=315", "--start", "120",
            "--end", "120", "--size", "320x180", "--no-progress"]
    s = replay(c, exe, args, os.path.join(tmp, "fx"))
    w = s["frames"][0]["counters"]["wakes"]
    c.check(w["active"] == 6, "all 6 ships have an active wake", str(w))
    field = s["frames"][0]["counters"]["effect_field"]
    c.check(field["passes"] == 1 and field["tiles"] > 0 and w["drawn"] <= 2,
            "the wakes are in the effects field (secondary grids: at most the default 2)", f"{w} {field}")
    plain = replay(c, exe, args + ["--no-events"], os.path.join(tmp, "plain"))
    c.check(plain["frames"][0]["counters"]["wakes"]["active"] == 0, "--no-events: no wake", "")
    c.check(plain["frames"][0]["exr_pixel_hash"] != s["frames"][0]["exr_pixel_hash"],
            "the wakes change the pixels", "")
    lum = lambda rgb: 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]  # noqa: E731
    fx = [lum(p) for p in exr_pixels(os.path.join(tmp, "fx"), "frame_00000.exr")]
    base = [lum(p) for p in exr_pixels(os.path.join(tmp, "plain"), "frame_00000.exr")]
    # Against the median pixel of the plain frame (the sea), not its mean, which the sun's glitter sets.
    gain = (sum(fx) - sum(base)) / max(len(base), 1)
    typical = sorted(base)[len(base) // 2]
    c.check(gain > 0.01 * typical, "the wakes' foam brightens the frame by > 1% of its median pixel",
            f"mean gain {gain:.5f}, median {typical:.5f}")


def case_acmi_views(c, exe, source_dir, tmp):
    acmi = recording(source_dir)
    out = os.path.join(tmp, "views")
    s = replay(c, exe, [acmi, "--rig", "chase:F-14B,size=192x108", "--rig",
                        "orbit:Stennis,size=160x120,fov=40,name=carrier", "--start", "10", "--end", "11",
                        "--fps", "1", "--no-progress"], out)
    names = sorted(os.listdir(out))
    want = ["carrier_frame_00000.exr", "carrier_frame_00000.png", "carrier_frame_00001.exr",
            "carrier_frame_00001.png", "summary.json", "view0-chase_frame_00000.exr", "view0-chase_frame_00000.png",
            "view0-chase_frame_00001.exr", "view0-chase_frame_00001.png"]
    c.check(names == want, "one image sequence per view, named by the view", str(names))
    v = s["views"]
    c.check(len(v) == 2 and v[0]["size"] == [192, 108] and v[1]["size"] == [160, 120] and v[1]["fov_deg"] == 40,
            "summary: two views with their own size and fov", json.dumps([{k: x[k] for k in ("name", "size",
                                                                                              "fov_deg")} for x in v]))
    c.check(all(len(x["frames"]) == 2 for x in v), "each view has 2 frames", "")
    for k in range(2):
        a, b = v[0]["frames"][k]["counters"], v[1]["frames"][k]["counters"]
        c.check(a["explosions_spawned"] == b["explosions_spawned"] and a["wakes"]["active"] == b["wakes"]["active"],
                f"frame {k}: both views see the same simulated effects", f"{a['wakes']} / {b['wakes']}")
    c.check(v[0]["frames"][0]["pose"] != v[1]["frames"][0]["pose"], "the views have their own cameras", "")


def ffprobe(path):
    p = subprocess.run(["ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
                        "stream=codec_name,nb_read_frames,width,height", "-of", "json", path],
                       capture_output=True, text=True, timeout=120)
    if p.returncode != 0:
        return {}
    return json.loads(p.stdout)["streams"][0]


def case_acmi_video(c, exe, source_dir, tmp):
    acmi = recording(source_dir)
    for ext, codec in ((".mp4", "h264"), (".mov", "prores")):
        video = os.path.join(tmp, "flight" + ext)
        out = os.path.join(tmp, "frames" + ext)
        s = replay(c, exe, [acmi, "--rig", "chase:F-14B", "--start", "30", "--end", "32", "--fps", "5",
                            "--size", "160x90", "--video", video, "--no-images", "--no-progress"], out)
        info = ffprobe(video)
        c.check(info.get("codec_name") == codec, f"{ext}: ffprobe reads a {codec} stream", str(info))
        c.check(info.get("nb_read_frames") == "11" and s["video"]["frames"] == 11,
                f"{ext}: 11 frames (2 s at 5 fps)", str(info))
        c.check(info.get("width") == 160 and info.get("height") == 90, f"{ext}: 160x90", str(info))
        leftovers = [n for n in os.listdir(tmp) if n.startswith(".flight")]
        c.check(not leftovers, f"{ext}: no temporary video left beside it", str(leftovers))
    # --speed 10: 20 recording seconds in 2 video seconds at 5 fps.
    s = replay(c, exe, [acmi, "--rig", "chase:F-14B", "--start", "30", "--end", "50", "--fps", "5", "--speed",
                        "10", *SMALL, "--no-images"], os.path.join(tmp, "lapse"))
    times = [f["time_s"] for f in s["frames"]]
    c.check(len(times) == 11 and abs(times[1] - times[0] - 2.0) < 1e-9, "--speed 10: 11 frames 2 s apart",
            str(times[:3]))


def write_igc(path):
    """A glider over the Black Sea: 60 s straight east at 30 m/s, then a steady right turn (6 deg/s)."""
    lat0, lon0 = 44.5, 37.0
    lines = ["AXXXPACIFICA", "HFDTEDATE:010820,01", "HFPLTPILOTINCHARGE:Test Pilot", "HFGTYGLIDERTYPE:Duo Discus"]
    x = y = 0.0
    heading = 90.0
    for k in range(181):
        if k > 0:
            if k > 60:
                heading += 6.0
            x += 30.0 * math.sin(math.radians(heading))
            y += 30.0 * math.cos(math.radians(heading))
        lat = lat0 + y / 111195.0
        lon = lon0 + x / (111195.0 * math.cos(math.radians(lat0)))
        secs = 12 * 3600 + k
        lat_m = round((lat - int(lat)) * 60000)
        lon_m = round((lon - int(lon)) * 60000)
        lines.append(f"B{secs // 3600:02d}{secs // 60 % 60:02d}{secs % 60:02d}{int(lat):02d}{lat_m:05d}N"
                     f"{int(lon):03d}{lon_m:05d}EA{800:05d}{810:05d}")
    with open(path, "w", encoding="ascii") as f:
        f.write("\r\n".join(lines) + "\r\n")


def case_formats(c, exe, source_dir, tmp):
    acmi = recording(source_dir)
    zipped = os.path.join(tmp, "blacksea.zip.acmi")
    with zipfile.ZipFile(zipped, "w", zipfile.ZIP_DEFLATED) as z:
        z.write(acmi, "dcs-blacksea-f14b.txt.acmi")
    args = ["--rig", "chase:F-14B", "--start", "60", "--end", "61", "--fps", "1", *SMALL]
    a = replay(c, exe, [acmi, *args], os.path.join(tmp, "text1"))
    b = replay(c, exe, [acmi, *args], os.path.join(tmp, "text2"))
    z = replay(c, exe, [zipped, *args], os.path.join(tmp, "zip"))
    ha = [f["exr_pixel_hash"] for f in a["frames"]]
    c.check(ha == [f["exr_pixel_hash"] for f in b["frames"]], "the same recording twice: identical hashes", "")
    c.check(z["format"] == "acmi-zip" and ha == [f["exr_pixel_hash"] for f in z["frames"]],
            "the zip replays to the same pixels as the text", f"{z['format']}")

    igc = os.path.join(tmp, "glider.igc")
    write_igc(igc)
    s = replay(c, exe, [igc, "--rig", "chase:Test Pilot,smoothing=0", "--start", "30", "--end", "150", "--fps",
                        "0.05", *SMALL], os.path.join(tmp, "igc"))
    c.check(s["format"] == "igc" and len(s["frames"]) == 7, "IGC: 7 frames 20 s apart", f"{s['format']}")
    # `pacifica convert` writes the IGC flight as ACMI: it lists and replays to the same frames.
    converted = os.path.join(tmp, "glider.txt.acmi")
    p = subprocess.run([exe, "convert", igc, converted], env=child_env(), capture_output=True, text=True,
                       timeout=RUN_TIMEOUT_S)
    c.check(p.returncode == 0 and os.path.exists(converted), "convert IGC -> ACMI succeeds", p.stderr[-300:])
    s2 = replay(c, exe, [converted, "--rig", "chase:Test Pilot,smoothing=0", "--start", "30", "--end", "150",
                         "--fps", "0.05", *SMALL], os.path.join(tmp, "igc2"))
    h0 = [f["pose"]["heading_deg"] for f in s["frames"]]
    h1 = [f["pose"]["heading_deg"] for f in s2["frames"]]
    c.check(s2["format"] == "acmi-text" and len(h1) == len(h0) and all(abs(a - b) < 0.2 for a, b in zip(h0, h1)),
            "the converted flight replays with the same camera (within 0.2 deg)", f"{h0} vs {h1}")
    heads = [f["pose"]["heading_deg"] for f in s["frames"]]
    c.check(abs(heads[0] - 90.0) < 1.5, "IGC chase: heading east on the straight leg", str(heads))
    # In the turn the heading grows 6 deg/s: 20 s between frames = 120 deg (mod 360).
    d = (heads[4] - heads[3]) % 360.0
    c.check(abs(d - 120.0) < 5.0, "IGC chase: the camera follows the turn (120 deg per 20 s)", str(heads))


def case_bad_input(c, exe, source_dir, tmp):
    acmi = recording(source_dir)
    bad = os.path.join(tmp, "bad.acmi")
    with open(bad, "w", encoding="utf-8") as f:
        f.write("FileType=text/acmi/tacview\nFileVersion=2.2\n#0\n1,T=1|2|3,Type=Air\n#1\n1,T=1|zz|3\n")
    ffmpeg_missing = {"PACIFICA_FFMPEG": os.path.join(tmp, "no-ffmpeg")}
    cases = [
        ("malformed ACMI", [bad], {}, [f"{bad}:6:", "T latitude", "'zz'"]),
        ("unknown object", [acmi, "--rig", "chase:Tomcat"], {}, ["no object 'Tomcat'", "F-14B"]),
        ("ambiguous object", [acmi, "--rig", "chase:ALBATROS"], {}, ["ambiguous", "101 ", "201 "]),
        ("bad rig kind", [acmi, "--rig", "dolly:F-14B"], {}, ["unknown rig kind 'dolly'", "chase"]),
        ("too many frames", [acmi, "--fps", "1000"], {}, ["220921 frames (220.92 s at --fps 1000", "--max-frames 100000"]),
        ("bad video name", [acmi, "--video", os.path.join(tmp, "v.avi")], {}, ["--video", ".mp4"]),
        ("ffmpeg missing", [acmi, "--video", os.path.join(tmp, "v.mp4")], ffmpeg_missing, ["PACIFICA_FFMPEG"]),
        ("UTC start before the flight", [acmi, "--start", "1990-05-01T05:00:00Z"], {}, ["--start", "outside"]),
    ]
    for name, args, env, must in cases:
        out = os.path.join(tmp, "out-" + name.replace(" ", "-"))
        p = run(exe, [*args, "--out", out, "--size", "160x90", "--no-progress"], env)
        err = [line for line in p.stderr.splitlines() if line.startswith("pacifica: error: ")]
        text = "\n".join(p.stderr.splitlines()[-12:])
        c.check(p.returncode != 0, f"{name}: non-zero exit", str(p.returncode))
        c.check(bool(err) and all(m in p.stderr for m in must), f"{name}: error names {must}", text)
        c.check(not os.path.exists(out), f"{name}: no output folder", "")
    c.check(not os.path.exists(os.path.join(tmp, "v.mp4")), "no video file was written", "")


def at_sea_shares(listing, names):
    """The at_sea column (percent) of the --list-objects rows naming each of `names`, -1 where none does."""
    header = listing.splitlines()[0].split() if listing else []
    col = header.index("at_sea") - len(header) if "at_sea" in header else None
    out = []
    for n in names:
        rows = [line for line in listing.splitlines() if f" {n} " in line]
        out.append(int(rows[0].split()[col].rstrip("%")) if rows and col is not None else -1)
    return out


def case_bundled_sample(c, exe, source_dir, tmp):
    """The README's replay example on what a clone has: tools/data/sortie.txt.acmi, the game's autopilot
    sortie recorded with --record (a carrier group, the jet's launch, a bomb that sinks a frigate)."""
    acmi = os.path.join(source_dir, "tools", "data", "sortie.txt.acmi")
    p = subprocess.run([exe, "replay", acmi, "--list-objects"], env=child_env(None), capture_output=True,
                       text=True, timeout=RUN_TIMEOUT_S)
    names = ["Carrier", "Frigate Alpha", "Frigate Bravo", "Tanker Charlie", "Pacifica Jet", "Mk-82"]
    c.check(p.returncode == 0 and all(n in p.stdout for n in names), "--list-objects lists its six objects",
            p.stdout[-600:] + p.stderr[-300:])
    c.check(at_sea_shares(p.stdout, names[:5]) == [100, 100, 100, 100, 0],
            "--list-objects: the ships are at the default sea's surface, the jet on the deck and in the air",
            p.stdout[-900:])
    bomb = at_sea_shares(p.stdout, names[5:])[0]
    c.check(1 <= bomb <= 20, "--list-objects: the bomb's last samples are at the sea surface", str(bomb))
    p = subprocess.run([exe, "replay", acmi, "--list-objects", "--model", "gerstner", "--sea-state", "30"],
                       env=child_env(None), capture_output=True, text=True, timeout=RUN_TIMEOUT_S)
    ships = at_sea_shares(p.stdout, names[:4])
    c.check(p.returncode == 0 and all(80 <= s < 100 for s in ships),
            "--list-objects at sea state 30: the crests pass 5 m above the recorded ships at times", str(ships))
    s = replay(c, exe, [acmi, "--rig", "chase:Pacifica Jet", "--start", "216", "--end", "226", "--fps", "1",
                        "--size", "160x90", "--no-progress"], os.path.join(tmp, "sortie"))
    c.check(s["events"]["ships"] == 4 and s["events"]["explosions"] == 1,
            "its four ships sail and its bomb's impact is an explosion", str(s["events"]))
    active = [f["counters"]["explosions"]["active"] for f in s["frames"]]
    c.check(active[0] == 0 and active[-1] == 1, "the explosion starts during the run (the impact at ~223.8 s)",
            str(active))
    c.check(all(f["counters"]["wakes"]["active"] >= 1 for f in s["frames"]), "the ships have wakes", "")

FLEET_REF = (37.0, 44.5)  # lon, lat: the Black Sea off Batumi's latitude, open water


def write_fleet(path, ships=64, impacts=500):
    """A Tacview ACMI 2.2 text recording of a fleet and a battle, deterministic: `ships` ships in four groups on
    crossing courses (north, east, north-east, south-east) at 8-14 m/s from t = 0 to 140 s, `impacts` weapons
    (bombs, missiles, rockets) falling onto the sea around the fleet between t = 70 and 128 s, and two aircraft
    (one at 300 m, one at 8 km). Returns the impact times."""
    lon0, lat0 = FLEET_REF
    m_lat = 111320.0
    m_lon = 111320.0 * math.cos(math.radians(lat0))

    def t_field(east, north, alt, yaw=None):
        ang = "" if yaw is None else f"|0|0|{yaw:.1f}"
        return f"T={east / m_lon:.7f}|{north / m_lat:.7f}|{alt:.1f}{ang}"

    headings = [0.0, 90.0, 45.0, 135.0]
    fleet = []
    for k in range(ships):
        g, i = k % 4, k // 4
        h = math.radians(headings[g])
        d = (math.sin(h), math.cos(h))  # east, north
        side = (d[1], -d[0])
        speed = 8.0 + (k * 7 % 13) * 0.5
        # Each group's lane starts 1.2 km back along its course, lanes 180 m apart across it.
        start = (-1200.0 * d[0] + (i - 7.5) * 180.0 * side[0], -1200.0 * d[1] + (i - 7.5) * 180.0 * side[1])
        fleet.append((start, d, speed, headings[g]))
    rng = 12345

    def rand():
        nonlocal rng
        rng = (1103515245 * rng + 12345) % 2147483648
        return rng / 2147483648.0

    kinds = [("Weapon+Bomb", "Mk-82")] * 1 + [("Weapon+Missile", "Harpoon")] * 3 + [("Weapon+Rocket", "Zuni")] * 6
    weapons = []
    for n in range(impacts):
        t = round(70.0 + 58.0 * n / impacts, 1)
        weapons.append((t, (rand() - 0.5) * 5000.0, (rand() - 0.5) * 5000.0, kinds[n % len(kinds)]))
    lines = ["FileType=text/acmi/tacview", "FileVersion=2.2", "0,ReferenceTime=2024-06-01T10:00:00Z",
             f"0,ReferenceLongitude={lon0}", f"0,ReferenceLatitude={lat0}", "0,Title=Pacifica fleet test"]
    events = {}

    def at(t, text):
        events.setdefault(round(t, 1), []).append(text)

    for step in range(0, 71):
        t = 2.0 * step
        for k, (s0, d, v, yaw) in enumerate(fleet):
            oid = f"{0x200 + k:x}"
            pos = t_field(s0[0] + d[0] * v * t, s0[1] + d[1] * v * t, 0.0, yaw)
            if step == 0:
                at(t, f"{oid},Type=Sea+Watercraft+Warship,Name=Ship {k:02d},Length={100 + (k % 5) * 40},Coalition=Allies")
            at(t, f"{oid},{pos}")
        at(t, f"100,{t_field(-3000.0 + 150.0 * t, -500.0, 300.0, 90.0)}")
        at(t, f"101,{t_field(-3000.0 + 150.0 * t, 500.0, 8000.0, 90.0)}")
        if step == 0:
            at(t, "100,Type=Air+FixedWing,Name=Jet 1,Pilot=One")
            at(t, "101,Type=Air+FixedWing,Name=Jet 2,Pilot=Two")
    for n, (t, e, north, (kind, name)) in enumerate(weapons):
        oid = f"{0x3000 + n:x}"
        at(t - 4.0, f"{oid},Type={kind},Name={name}")
        at(t - 4.0, f"{oid},{t_field(e - 400.0, north, 600.0)}")
        at(t - 2.0, f"{oid},{t_field(e - 200.0, north, 300.0)}")
        at(t, f"{oid},{t_field(e, north, 0.0)}")
        at(t, f"-{oid}")
    for t in sorted(events):
        lines.append(f"#{t:g}")
        lines.extend(events[t])
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")
    return [w[0] for w in weapons]


def case_fleet(c, exe, source_dir, tmp):
    acmi = os.path.join(tmp, "fleet.txt.acmi")
    impact_times = write_fleet(acmi)
    args = [acmi, "--rig", "chase:Jet 1,size=160x90,name=chase", "--rig",
            "orbit:Ship 00,distance=8500,elevation=70,rate=0,size=160x90,name=high", "--start", "120", "--end",
            "128", "--fps", "0.5", "--no-progress"]
    s = replay(c, exe, args, os.path.join(tmp, "fleet"))
    ev = s["events"]
    c.check(ev.get("ships") == 64 and ev.get("explosions") == 500,
            "the recording drives 64 ships and 500 impacts", str(ev))
    c.check(ev.get("explosions_dropped_total") == 0, "no impact dropped in the whole run", str(ev))
    views = s["views"]
    c.require(len(views) == 2 and all(len(v["frames"]) == 5 for v in views), "two views of 5 frames", "")
    for v in views:
        for f in v["frames"]:
            k = f["counters"]
            t = f["time_s"]
            due = sum(1 for x in impact_times if x < t)
            c.check(k["wakes"]["active"] == 64 and k["wakes_dropped"] == 0,
                    f"{v['name']} t={t}: all 64 wakes active, none dropped", str(k["wakes"]))
            c.check(k["explosions_dropped"] == 0 and due - 5 <= k["explosions"]["active"] <= due,
                    f"{v['name']} t={t}: every impact so far active ({due} due), none dropped",
                    str(k["explosions"]))
            # From 8 km up the fleet fills the view: its field is evaluated. The chase jet flies east, away
            # from the fleet behind it: out of its view sector no tile is evaluated (EffectFieldDesc::viewCull);
            # the tiles the high view wrote are only cleared.
            field = k["effect_field"]
            if v["name"] == "high":
                c.check(field["passes"] == 1 and field["tiles"] > field["cleared"],
                        f"high t={t}: the effects field is evaluated", str(field))
            else:
                c.check(field["tiles"] == field["cleared"] and field["passes"] == (1 if field["tiles"] else 0),
                        f"chase t={t}: no tile of the fleet behind it evaluated, only cleared", str(field))
    # From 8 km up the fleet's wakes and the impacts' foam brighten the sea.
    plain = replay(c, exe, args + ["--no-events"], os.path.join(tmp, "plain"))
    lum = lambda rgb: 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]  # noqa: E731
    fx = [lum(p) for p in exr_pixels(os.path.join(tmp, "fleet"), "high_frame_00004.exr")]
    base = [lum(p) for p in exr_pixels(os.path.join(tmp, "plain"), "high_frame_00004.exr")]
    typical = sorted(base)[len(base) // 2]
    brighter = sum(1 for a, b in zip(fx, base) if a > b + 0.05 * typical) / len(base)
    c.check(brighter > 0.02, "from 8 km, > 2% of the pixels are brighter by > 5% of the median (foam)",
            f"{100 * brighter:.1f}% brighter")
    # Deterministic: the same run again gives the same pixels.
    again = replay(c, exe, args, os.path.join(tmp, "again"))
    same = all(a["exr_pixel_hash"] == b["exr_pixel_hash"] for va, vb in zip(views, again["views"])
               for a, b in zip(va["frames"], vb["frames"]))
    c.check(same, "a second run gives the same EXR pixel hashes", "")


CASES = {"acmi-rigs": case_acmi_rigs, "fleet": case_fleet, "bundled-sample": case_bundled_sample, "acmi-ships": case_acmi_ships, "acmi-views": case_acmi_views,
         "acmi-video": case_acmi_video, "formats": case_formats, "bad-input": case_bad_input}


if __name__ == "__main__":
    sys.exit(test_e2e.main(CASES, "recordings", __doc__))
