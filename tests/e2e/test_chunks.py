#!/usr/bin/env python3
"""Chunks of a sharded replay (`pacifica replay ... --frames I-J`, docs/SCALE.md): bit-identical to one process,
resumable, whole after a kill.

Cases (chosen with --case, one ctest test each):
  chunks   the bundled sortie's bomb run (8 frames, two views: a chase of the jet and an orbit of the carrier,
           160x90) rendered once in one process and once as three chunks (0-2, 3-6, 7-7) into one folder. Every
           view frame's EXR pixel hash, recomputed from the file, and every PNG's bytes equal the one-process
           run's; the last chunk's explosion started in the chunk before it (its pre-roll). Then: a chunk run
           again keeps all its frames (nothing rewritten), a chunk with one PNG damaged renders that frame
           only and restores it, a chunk with other options (--fov) renders all its frames again, so does a
           chunk whose recording (a copy) was edited in place since its frames were rendered or that another
           build of the program runs, and bad
           ranges (J < I, past the run's end, text, with --video) are refused naming --frames.
  kill     a chunk of 8 frames killed with SIGKILL once its third frame has landed, then run again: the folder
           holds only whole frames with their sidecars in between, the second run keeps what landed, renders
           the rest, removes the dead run's staging folder, and its frames equal the one-process run's.

Usage: test_chunks.py --case CASE PACIFICA_EXE SOURCE_DIR     (python3 standard library + OIIO's oiiotool)
"""
import json
import os
import shutil
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import test_e2e  # noqa: E402
import test_faults  # noqa: E402
from test_e2e import child_env, exr_xxh64  # noqa: E402
from test_faults import run  # noqa: E402

RUN_TIMEOUT_S = test_faults.RUN_TIMEOUT_S
STAGING = ".pacifica-staging-"
VIEWS = ("chase", "orbit")


def run_args(source_dir, out, extra=()):
    """The bundled sortie around the bomb's impact at ~223.8 s: 8 frames at 1 frame/s, two views, small."""
    acmi = os.path.join(source_dir, "tools", "data", "sortie.txt.acmi")
    return ["replay", acmi, "--rig", "chase:Pacifica Jet,name=chase", "--rig",
            "orbit:Carrier,name=orbit,distance=900,elevation=35,rate=0,azimuth=315", "--start", "218", "--end", "225",
            "--fps", "1", "--size", "160x90", "--no-progress", "--out", out, *extra]


def load(c, path):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        c.require(False, f"{path} is valid JSON", str(e))


def names(k):
    return {v: f"{v}_frame_{k:05d}" for v in VIEWS}


def file_bytes(folder, name):
    with open(os.path.join(folder, name), "rb") as f:
        return f.read()


def frames_equal(c, out, ref, ks, what):
    """Every view frame k in ks: EXR pixel hash (from the file) and PNG bytes equal the reference folder's."""
    bad, exrs = [], []
    for k in ks:
        for base in names(k).values():
            exr, png = base + ".exr", base + ".png"
            if not (os.path.isfile(os.path.join(out, exr)) and os.path.isfile(os.path.join(out, png))):
                bad.append(f"{base}: missing")
                continue
            exrs.append(exr)
            if file_bytes(out, png) != file_bytes(ref, png):
                bad.append(f"{png}: bytes differ")
    if exrs:
        got, want = exr_xxh64(out, exrs), exr_xxh64(ref, exrs)
        bad += [f"{n}: pixels differ" for n in exrs if got.get(n) != want.get(n)]
    c.check(not bad and len(exrs) == 2 * len(ks), what, "; ".join(bad[:6]))


def chunk_summary(c, out, first, last):
    return load(c, os.path.join(out, f"chunk-{first:05d}-{last:05d}.json"))


def case_chunks(c, exe, source_dir, tmp):
    ref, out = os.path.join(tmp, "one-process"), os.path.join(tmp, "sharded")
    p = run(exe, run_args(source_dir, ref))
    c.require(p.returncode == 0, "the one-process run exits 0", p.stderr[-1500:])
    one = load(c, os.path.join(ref, "summary.json"))
    one_hashes = {v["name"]: [f["exr_pixel_hash"] for f in v["frames"]] for v in one["views"]}
    c.require(sorted(one_hashes) == sorted(VIEWS) and all(len(h) == 8 for h in one_hashes.values()),
              "the one-process run has two views of 8 frames", str(one_hashes))
    active = [f["counters"]["explosions"]["active"] for f in one["frames"]]
    c.require(active[5] == 0 and active[6] == 1 and active[7] == 1,
              "the bomb's explosion starts at frame 6 (~223.8 s), so the chunk 7-7 inherits it", str(active))

    print("[sharded] chunks 0-2, 3-6 and 7-7 into one folder")
    chunks = [(0, 2), (3, 6), (7, 7)]
    for first, last in chunks:
        p = run(exe, run_args(source_dir, out, ["--frames", f"{first}-{last}"]))
        c.require(p.returncode == 0, f"chunk {first}-{last} exits 0", p.stderr[-1500:])
    c.check(not os.path.exists(os.path.join(out, "summary.json")), "no chunk writes summary.json")
    leftovers = [n for n in os.listdir(out) if n.startswith(".")]
    c.check(not leftovers, "no staging folder or temporary file is left", str(leftovers))
    frames_equal(c, out, ref, range(8), "every view frame of the chunks equals the one-process run's (EXR pixel "
                 "hash recomputed from the file, PNG bytes)")
    for first, last in chunks:
        s = chunk_summary(c, out, first, last)
        ch = s.get("chunk", {})
        c.check(ch.get("first") == first and ch.get("last") == last and ch.get("preroll_frames") == first and
                ch.get("rendered") == last - first + 1 and ch.get("kept") == 0 and ch.get("run_frames") == 8 and
                ch.get("host") and ch.get("gl_renderer"),
                f"chunk-{first:05d}-{last:05d}.json: its range, pre-roll, rendered count, host and GL renderer",
                str(ch))
        got = {v["name"]: [f["exr_pixel_hash"] for f in v["frames"]] for v in s.get("views", [])}
        want = {v: h[first:last + 1] for v, h in one_hashes.items()}
        c.check(got == want, f"chunk {first}-{last}: its summary's hashes are the one-process run's frames "
                f"{first}..{last}", f"{got} vs {want}")
        c.check([f["index"] for f in s["frames"]] == list(range(first, last + 1)),
                f"chunk {first}-{last}: frame indices are the run's", str([f["index"] for f in s["frames"]]))
    last_chunk = chunk_summary(c, out, 7, 7)
    c.check(last_chunk["frames"][0]["counters"]["explosions"]["active"] == 1,
            "chunk 7-7 draws the explosion that started in frame 6 (its pre-roll)",
            str(last_chunk["frames"][0]["counters"]["explosions"]))

    print("[resume] chunk 3-6 again: every frame is kept")
    stamps = {n: os.stat(os.path.join(out, n)).st_mtime_ns for n in os.listdir(out) if not n.startswith("chunk-")}
    p = run(exe, run_args(source_dir, out, ["--frames", "3-6"]))
    ch = chunk_summary(c, out, 3, 6).get("chunk", {})
    c.check(p.returncode == 0 and ch.get("kept") == 4 and ch.get("rendered") == 0,
            "a second run of a finished chunk keeps its 4 frames and renders none", str(ch) + p.stderr[-500:])
    changed = [n for n, t in stamps.items() if os.stat(os.path.join(out, n)).st_mtime_ns != t]
    c.check(not changed, "nothing in the folder was rewritten", str(changed))
    resumed = chunk_summary(c, out, 3, 6)
    c.check([f["exr_pixel_hash"] for f in resumed["frames"]] == one_hashes["chase"][3:7],
            "the kept frames' summary entries (from their sidecars) carry the one-process hashes")

    print("[damaged] frame 5's orbit PNG cut short: that frame is rendered again")
    png = names(5)["orbit"] + ".png"
    with open(os.path.join(out, png), "r+b") as f:
        f.truncate(100)
    p = run(exe, run_args(source_dir, out, ["--frames", "3-6"]))
    ch = chunk_summary(c, out, 3, 6).get("chunk", {})
    c.check(p.returncode == 0 and ch.get("kept") == 3 and ch.get("rendered") == 1,
            "the chunk renders the damaged frame only", str(ch) + p.stderr[-500:])
    frames_equal(c, out, ref, [5], "the damaged frame is restored, equal to the one-process run's")

    print("[other options] chunk 7-7 with --fov 50: its sidecar names another run, so it is rendered again")
    p = run(exe, run_args(source_dir, out, ["--frames", "7-7", "--fov", "50"]))
    ch = chunk_summary(c, out, 7, 7).get("chunk", {})
    c.check(p.returncode == 0 and ch.get("kept") == 0 and ch.get("rendered") == 1,
            "a chunk with other options keeps nothing", str(ch) + p.stderr[-500:])
    c.check(exr_xxh64(out, [names(7)["chase"] + ".exr"]) != exr_xxh64(ref, [names(7)["chase"] + ".exr"]),
            "and its frame is the new run's (another field of view)")

    print("[edited input] a copy of the recording, changed in place after a chunk: the chunk keeps nothing")
    copy = os.path.join(tmp, "copy.txt.acmi")
    shutil.copyfile(os.path.join(source_dir, "tools", "data", "sortie.txt.acmi"), copy)
    edited = os.path.join(tmp, "edited")
    args = run_args(source_dir, edited, ["--frames", "7-7"])
    args[1] = copy
    p = run(exe, args)
    c.require(p.returncode == 0, "the chunk on the copy exits 0", p.stderr[-500:])
    with open(copy, "a") as f:
        f.write("// edited after the first run\n")
    p = run(exe, args)
    ch = chunk_summary(c, edited, 7, 7).get("chunk", {})
    c.check(p.returncode == 0 and ch.get("kept") == 0 and ch.get("rendered") == 1,
            "a chunk whose recording changed keeps nothing (the key holds the input's XXH64)",
            str(ch) + p.stderr[-500:])
    rebuilt = os.path.join(tmp, "pacifica-rebuilt")  # another build: the same program with one byte more
    shutil.copy2(exe, rebuilt)
    with open(rebuilt, "ab") as f:
        f.write(b"\0")
    p = run(rebuilt, args)
    ch = chunk_summary(c, edited, 7, 7).get("chunk", {})
    c.check(p.returncode == 0 and ch.get("kept") == 0 and ch.get("rendered") == 1,
            "a chunk run by another build keeps nothing (the key holds the program's XXH64)",
            str(ch) + p.stderr[-500:])

    print("[bad ranges] refused before anything is written")
    bad_out = os.path.join(tmp, "bad")
    for extra, must in ((["--frames", "5-3"], "--frames"), (["--frames", "0-8"], "the run has 8 frames (0-7)"),
                        (["--frames", "two"], "--frames"),
                        (["--frames", "0-3", "--video", os.path.join(tmp, "x.mp4")], "--frames")):
        p = run(exe, run_args(source_dir, bad_out, extra))
        errors = [ln for ln in p.stderr.splitlines() if ln.startswith("pacifica: error:")]
        c.check(p.returncode == 2 and len(errors) == 1 and must in errors[0],
                f"{' '.join(extra[:2])}: exit 2 with one error naming '{must}'", p.stderr[-600:])
    c.check(not os.path.exists(bad_out), "no output folder was made by a refused run")


def landed(out):
    return sorted(n for n in os.listdir(out) if n.endswith(".check.json")) if os.path.isdir(out) else []


def case_kill(c, exe, source_dir, tmp):
    ref, out = os.path.join(tmp, "one-process"), os.path.join(tmp, "killed")
    p = run(exe, run_args(source_dir, ref))
    c.require(p.returncode == 0, "the one-process run exits 0", p.stderr[-1500:])

    print("[kill] chunk 0-7, SIGKILL once frame 2 has landed")
    cmd = [exe, *run_args(source_dir, out, ["--frames", "0-7"])]
    proc = subprocess.Popen(cmd, env=child_env(None), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    deadline = time.monotonic() + RUN_TIMEOUT_S
    while time.monotonic() < deadline and proc.poll() is None and len(landed(out)) < 2 * 3:
        time.sleep(0.005)
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    done = landed(out)
    print(f"    killed with {len(done)} sidecars landed")
    c.require(proc.returncode == -signal.SIGKILL and 6 <= len(done) < 16,
              "the chunk was killed part-way, after its third frame landed", f"rc {proc.returncode}, {done}")
    bad = []
    for n in sorted(os.listdir(out)):
        if n.startswith(STAGING) or n.endswith(".check.json"):
            continue
        if n.startswith("."):
            bad.append(f"{n}: a temporary file outside the staging folder")
        elif n.startswith("chunk-"):
            bad.append(f"{n}: a chunk summary from a killed chunk")
        elif not test_faults.whole_image(os.path.join(out, n)):
            bad.append(f"{n}: not a whole image")
    c.check(not bad, "after the kill: only whole images, sidecars and the dead run's staging folder",
            "; ".join(bad[:6]))
    # A frame is kept when both views' sidecars landed (a kill between the views' renames leaves one).
    kept = sum(all(f"{b}.check.json" in done for b in names(k).values()) for k in range(8))

    print("[resume] the same chunk again")
    p = run(exe, run_args(source_dir, out, ["--frames", "0-7"]))
    ch = chunk_summary(c, out, 0, 7).get("chunk", {})
    c.check(p.returncode == 0 and ch.get("kept") == kept and ch.get("rendered") == 8 - kept,
            f"the rerun keeps the {kept} frames that landed and renders the other {8 - kept}",
            str(ch) + p.stderr[-500:])
    c.check(not [n for n in os.listdir(out) if n.startswith(".")],
            "the dead run's staging folder and lock are removed", str(os.listdir(out)))
    frames_equal(c, out, ref, range(8), "every frame equals the one-process run's")


CASES = {"chunks": case_chunks, "kill": case_kill}

if __name__ == "__main__":
    sys.exit(test_e2e.main(CASES, label="chunks", doc=__doc__))
