#!/usr/bin/env python3
"""`pacifica farm` (docs/SCALE.md): a replay sharded into chunks, run by a local pool or a single-node Slurm,
equal frame for frame to one process, surviving a killed chunk, resumable.

Cases (chosen with --case, one ctest test each):
  local   the bundled sortie's bomb run (8 frames, two views, 160x90) and a file that is not a recording, in
          chunks of 4 frames on a pool of 2 workers. Chunk 1's replay is killed (SIGKILL) once its first frame
          landed: the pool runs it again, which keeps that frame. The sortie's merged summary.json holds its 8
          frames per view in order, each equal to a one-process run's (EXR pixel hash recomputed from the
          file, PNG bytes), with one entry per chunk (range, host, GPU, wall time); report.json has the bad
          file quarantined with its error and no failed chunk; the exit status is 1 (a recording was
          quarantined). With --video mp4, a video per view; the first decodes to the frames of the one-process
          run's --video (ffmpeg framemd5). `farm status` counts 2/2 chunks; `farm resume` renders nothing and
          rewrites nothing (the videos included). A chunk summary whose run key is another run's is not
          counted, and resume runs that chunk again, keeping its frames.
          A chunk that always fails (its replay asks for an EGL device that does not exist) is given up after
          1 + --retries attempts and named in report.json with its error.
  slurm   the same run on a single-node Slurm started for the test (tools/farm/slurm-local.sh, two fake GPUs):
          a job array of the chunks and a merge job after it. Chunk 1 is killed the same way; the merge job
          submits it again and the run completes, equal to the one-process run. Each chunk got one GPU from
          Slurm's GRES: both CUDA_VISIBLE_DEVICES values 0 and 1 appear in the chunks' entries. Slurm is
          stopped at the end.

Usage: test_farm.py --case CASE PACIFICA_EXE SOURCE_DIR     (python3 standard library + OIIO's oiiotool)
"""
import json
import os
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import test_e2e  # noqa: E402
from test_e2e import child_env, exr_xxh64  # noqa: E402
from test_faults import run  # noqa: E402
from test_chunks import load  # noqa: E402

RUN_TIMEOUT_S = 300
VIEWS = ("chase", "orbit")
REPLAY = ["--rig", "chase:Pacifica Jet,name=chase", "--rig",
          "orbit:Carrier,name=orbit,distance=900,elevation=35,rate=0,azimuth=315", "--start", "218", "--end", "225",
          "--fps", "1", "--size", "160x90"]


def sortie(source_dir):
    return os.path.join(source_dir, "tools", "data", "sortie.txt.acmi")


def reference(c, exe, source_dir, tmp):
    ref = os.path.join(tmp, "one-process")
    p = run(exe, ["replay", sortie(source_dir), *REPLAY, "--no-progress", "--out", ref, "--video",
                  os.path.join(ref, "one-process.mp4")])
    c.require(p.returncode == 0, "the one-process run exits 0", p.stderr[-1500:])
    return ref


def frames_equal(c, out, ref, what):
    bad, exrs = [], []
    for k in range(8):
        for v in VIEWS:
            base = f"{v}_frame_{k:05d}"
            if not os.path.isfile(os.path.join(out, base + ".exr")):
                bad.append(f"{base}.exr: missing")
                continue
            exrs.append(base + ".exr")
            with open(os.path.join(out, base + ".png"), "rb") as a, open(os.path.join(ref, base + ".png"), "rb") as b:
                if a.read() != b.read():
                    bad.append(f"{base}.png: bytes differ")
    got, want = exr_xxh64(out, exrs), exr_xxh64(ref, exrs)
    bad += [f"{n}: pixels differ" for n in exrs if got.get(n) != want.get(n)]
    c.check(not bad and len(exrs) == 16, what, "; ".join(bad[:6]))


def replay_pid(frames, out):
    """The pid of the `pacifica replay` process rendering `--frames FRAMES` into `out`, or None."""
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/cmdline", "rb") as f:
                args = f.read().split(b"\0")
        except OSError:
            continue
        if b"replay" in args and b"--frames" in args and frames.encode() in args and out.encode() in args:
            return int(entry)
    return None


def kill_chunk_after_first_frame(c, out, frames, first, deadline_s=RUN_TIMEOUT_S):
    """SIGKILLs the chunk rendering `frames` once frame `first` (both views) has landed in `out`."""
    deadline = time.monotonic() + deadline_s
    sidecars = [os.path.join(out, f"{v}_frame_{first:05d}.check.json") for v in VIEWS]
    while time.monotonic() < deadline:
        pid = replay_pid(frames, out)
        if pid and all(os.path.exists(s) for s in sidecars):
            try:
                os.kill(pid, signal.SIGKILL)
            except ProcessLookupError:  # it finished between the look and the kill: the checks will say so
                print(f"    the replay of frames {frames} finished before it could be killed")
                return False
            print(f"    killed the replay of frames {frames} (pid {pid}) after frame {first} landed")
            return True
        time.sleep(0.005)
    c.check(False, f"the chunk of frames {frames} was seen running after its first frame landed")
    return False


def check_merged(c, run_dir, ref, one):
    out = os.path.join(run_dir, "sortie")
    s = load(c, os.path.join(out, "summary.json"))
    for v, ov in zip(s.get("views", []), one["views"]):
        c.check([f["exr_pixel_hash"] for f in v["frames"]] == [f["exr_pixel_hash"] for f in ov["frames"]] and
                [f["index"] for f in v["frames"]] == list(range(8)),
                f"summary.json view {v['name']}: the 8 frames in order, hashes of the one-process run")
    chunks = s.get("chunks", [])
    c.check([(ch["first"], ch["last"]) for ch in chunks] == [(0, 3), (4, 7)] and
            all(ch.get("host") and ch.get("gl_renderer") and ch.get("total_s", 0) > 0 for ch in chunks),
            "summary.json: one entry per chunk with its range, host, GL renderer and wall time", str(chunks)[:600])
    c.check(chunks[1].get("kept", 0) >= 1, "the killed chunk's second run kept the frame that had landed",
            str(chunks[1]))
    frames_equal(c, out, ref, "every merged frame equals the one-process run's (EXR pixel hash, PNG bytes)")
    return s


def decoded_frames(path):
    """ffmpeg's MD5 of every decoded frame of a video."""
    p = subprocess.run(["ffmpeg", "-v", "error", "-i", path, "-f", "framemd5", "-"], capture_output=True, text=True)
    return [line.rsplit(",", 1)[1].strip() for line in p.stdout.splitlines() if line and not line.startswith("#")]


def check_videos(c, run_dir, ref, rec):
    """--video mp4: one H.264 video per view of the 8 frames; the first view's decodes to the same frames as the
    one-process run's --video (both encode the same 8-bit display pixels once)."""
    out = os.path.join(run_dir, "sortie")
    files = {v["view"]: v["file"] for v in rec.get("videos", [])}
    c.check(sorted(files) == sorted(VIEWS) and all(os.path.isfile(f) for f in files.values()),
            "--video mp4: report.json names a video per view, and they exist", str(rec)[:600])
    for v in VIEWS:
        frames = decoded_frames(os.path.join(out, v + ".mp4"))
        c.check(len(frames) == 8, f"{v}.mp4 decodes to 8 frames", str(len(frames)))
    one = decoded_frames(os.path.join(ref, "one-process.mp4"))
    c.check(len(one) == 8 and decoded_frames(os.path.join(out, VIEWS[0] + ".mp4")) == one,
            f"{VIEWS[0]}.mp4 decodes to the one-process run's --video frames (ffmpeg framemd5)", str(one[:2]))
    c.check(not [n for n in os.listdir(out) if ".tmp" in n], "no temporary video left", str(os.listdir(out)))


def case_local(c, exe, source_dir, tmp):
    ref = reference(c, exe, source_dir, tmp)
    one = load(c, os.path.join(ref, "summary.json"))
    bad = os.path.join(tmp, "not-a-recording.txt.acmi")
    with open(bad, "w") as f:
        f.write("this is not a flight\n")
    run_dir = os.path.join(tmp, "run")
    cmd = [exe, "farm", "run", sortie(source_dir), bad, "--out", run_dir, "--chunk-frames", "4", "--workers", "2",
           "--video", "mp4", "--", *REPLAY]
    print("  $ " + " ".join(cmd))
    proc = subprocess.Popen(cmd, env=child_env(None), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    kill_chunk_after_first_frame(c, os.path.join(run_dir, "sortie"), "4-7", 4)
    _, err = proc.communicate(timeout=RUN_TIMEOUT_S)
    print("    " + "\n    ".join(err.strip().splitlines()[-8:]))
    c.check(proc.returncode == 1, "farm run exits 1: a recording was quarantined", str(proc.returncode))
    c.check("chunk 1" in err and "killed by signal 9" in err and "running it again" in err,
            "the pool says chunk 1 was killed and runs it again", err[-800:])
    report = load(c, os.path.join(run_dir, "report.json"))
    recs = {r["name"]: r for r in report.get("recordings", [])}
    c.check(recs.get("sortie", {}).get("state") == "whole" and not report.get("failed_chunks"),
            "report.json: the sortie is whole, no chunk failed", str(report)[:800])
    q = recs.get("not-a-recording", {})
    c.check(q.get("state") == "quarantined" and "not-a-recording.txt.acmi" in q.get("error", ""),
            "report.json: the bad file is quarantined with an error naming it", str(q))
    check_merged(c, run_dir, ref, one)
    check_videos(c, run_dir, ref, recs.get("sortie", {}))

    print("[status, resume] nothing left to render")
    p = run(exe, ["farm", "status", run_dir])
    c.check(p.returncode == 0 and "sortie: 2/2 chunks, 8/8 frames done" in p.stdout and "quarantined" in p.stdout,
            "farm status counts the sortie's chunks and frames and names the quarantined file", p.stdout[-600:])
    out = os.path.join(run_dir, "sortie")
    stamps = {n: os.stat(os.path.join(out, n)).st_mtime_ns for n in os.listdir(out) if n != "summary.json"}
    p = run(exe, ["farm", "resume", run_dir])
    c.check("nothing to render" in p.stderr, "farm resume renders nothing", p.stderr[-600:])
    changed = [n for n, t in stamps.items() if os.stat(os.path.join(out, n)).st_mtime_ns != t]
    c.check(not changed, "and rewrites no frame or chunk summary", str(changed))

    print("[stale chunk summary] a chunk summary of other options is not this run's")
    summary1 = os.path.join(out, "chunk-00004-00007.json")
    with open(summary1) as f:
        s1 = json.load(f)
    s1["chunk"]["run_key"] = '["replay", "other options"]'
    with open(summary1, "w") as f:
        json.dump(s1, f)
    p = run(exe, ["farm", "status", run_dir])
    c.check("sortie: 1/2 chunks, 4/8 frames done" in p.stdout, "farm status no longer counts that chunk",
            p.stdout[-400:])
    p = run(exe, ["farm", "resume", run_dir])
    s1 = load(c, summary1)
    c.check("1 of 2 chunks to run" in p.stderr and s1.get("chunk", {}).get("kept") == 4 and
            s1.get("chunk", {}).get("rendered") == 0,
            "farm resume runs it again, which keeps its 4 frames (their sidecars name this run)",
            p.stderr[-400:] + str(s1.get("chunk"))[:300])

    print("[give up] a chunk that always fails: its replay asks for an EGL device that does not exist")
    run2 = os.path.join(tmp, "failing")
    p = run(exe, ["farm", "run", sortie(source_dir), "--out", run2, "--chunk-frames", "8", "--retries", "1", "--",
                  *REPLAY, "--egl-device", "15"])
    report = load(c, os.path.join(run2, "report.json"))
    failed = report.get("failed_chunks", [])
    c.check(p.returncode == 1 and p.stderr.count("farm: chunk 0") == 2 and "giving up" in p.stderr,
            "the failing chunk runs 1 + --retries times, then the pool gives up", p.stderr[-800:])
    c.check(len(failed) == 1 and failed[0]["frames"] == [0, 7] and
            "pacifica: error: EGL device 15 does not exist" in failed[0]["error"] and
            "farm: attempt 2 exit 1" in failed[0]["error"],
            "report.json names the failed chunk, its frames, the replay's error and how its last attempt ended",
            str(failed)[:600])
    c.check(report.get("recordings", [{}])[0].get("missing_frames") == [[0, 7]],
            "report.json: the recording is incomplete, frames 0-7 missing", str(report.get("recordings"))[:400])


def slurm_env(slurm_dir):
    return {"SLURM_CONF": os.path.join(slurm_dir, "slurm.conf")}


def case_slurm(c, exe, source_dir, tmp):
    ref = reference(c, exe, source_dir, tmp)
    one = load(c, os.path.join(ref, "summary.json"))
    script = os.path.join(source_dir, "tools", "farm", "slurm-local.sh")
    slurm_dir = os.path.join(tmp, "slurm")
    p = subprocess.run([script, "start", slurm_dir, "2"], capture_output=True, text=True, timeout=120)
    print("    " + (p.stdout + p.stderr).strip().replace("\n", "\n    "))
    c.require(p.returncode == 0, "a single-node Slurm with two fake GPUs starts", p.stderr[-1500:])
    try:
        env = slurm_env(slurm_dir)
        run_dir = os.path.join(tmp, "run")
        cmd = [exe, "farm", "run", sortie(source_dir), "--out", run_dir, "--chunk-frames", "4", "--engine", "slurm",
               "--gpus-per-chunk", "1", "--retries", "2", "--wait", "--", *REPLAY]
        print("  $ " + " ".join(cmd))
        proc = subprocess.Popen(cmd, env=child_env(env), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        kill_chunk_after_first_frame(c, os.path.join(run_dir, "sortie"), "4-7", 4)
        _, err = proc.communicate(timeout=RUN_TIMEOUT_S)
        print("    " + "\n    ".join(err.strip().splitlines()[-6:]))
        c.check(proc.returncode == 0, "farm run --engine slurm --wait exits 0", err[-800:])
        with open(os.path.join(run_dir, "logs", "merge.log")) as f:
            merge_log = f.read()
        c.check("chunks 1 did not finish; submitting them again" in merge_log,
                "the merge job submitted the killed chunk again", merge_log[-800:])
        s = check_merged(c, run_dir, ref, one)
        gpus = sorted({ch.get("cuda_visible_devices") for ch in s.get("chunks", [])} | set())
        c.check(all(ch.get("slurm_job_id") for ch in s.get("chunks", [])), "every chunk names its Slurm job")
        c.check(gpus == ["0", "1"] or len(s.get("chunks", [])) == 2 and all(g in ("0", "1") for g in gpus),
                "each chunk rendered with the GPU Slurm gave it (CUDA_VISIBLE_DEVICES 0 or 1)", str(gpus))
        p = run(exe, ["farm", "resume", run_dir], env)
        c.check(p.returncode == 0 and "nothing to render" in p.stderr, "farm resume renders nothing", p.stderr[-600:])
    finally:
        subprocess.run([script, "stop", slurm_dir], timeout=60)


CASES = {"local": case_local, "slurm": case_slurm}

if __name__ == "__main__":
    sys.exit(test_e2e.main(CASES, label="farm", doc=__doc__))
