#!/usr/bin/env python3
"""Faults, nothing lost or half-written (docs/RELIABILITY.md, "Faults"): `pacifica replay` killed, out of disk,
given a read-only folder, no GPU or no EGL, a bad $OCIO; the game given a screenshot it cannot write.

Cases (chosen with --case, one ctest test each):
  kill         20 replays into one folder, each killed with SIGKILL: 5 at a random time during start-up, 15
               once the run has staged a random number of its image files. After every kill the folder holds
               only whole images (PNG ending in IEND, EXR with its magic) of earlier commits, at most one
               staging folder (the dead run's) and a summary.json that is absent or valid and names only files
               that exist. A last run completes the folder: it removes the dead run's staging folder, and every
               frame's EXR pixel hash, recomputed from the file, equals a run that was never killed.
  full-disk    a file-size limit (RLIMIT_FSIZE, SIGXFSZ ignored: the write fails with EFBIG as on a full disk):
               one 'pacifica: error:' line naming the frame, a non-zero exit, the folder of an earlier run
               exactly as it was and no staging or temporary file left; a folder the run had to create is gone.
  read-only    the output folder on a read-only file system (a tmpfs mounted read-only in a private mount
               namespace, `unshare -rm`): refused before a GL context is made, naming the file system.
  no-gpu       --egl-device naming a device that does not exist (the devices listed) or neither a number nor
               'auto', --egl-device auto (the first GPU of CUDA_VISIBLE_DEVICES=1,0, which is CUDA device 0; on
               llvmpipe the default device with the summary saying CUDA device 0 was asked for), EGL with no vendor
               library (__EGL_VENDOR_LIBRARY_FILENAMES to nothing), and no libEGL at all (/dev/null bound over it
               in a private mount namespace): each one 'pacifica: error:' line, a non-zero exit, no output.
  bad-ocio     $OCIO naming a missing file, and a file that is not an OCIO config: one error naming $OCIO and
               the file, a non-zero exit, no output.
  hostile      inputs built to exhaust memory or time, each refused with one clear error, its peak RSS
               (wait4) under a stated bound: a zip ACMI whose member inflates past 4 GiB (its header lies about the
               size and CRC), 10^7 object ids, a line of 1 GB (a sparse file), a '\' continuation chain of
               600 000 lines, an IGC of 10^8 B records (3.5 GB, sparse), an EXR declaring 65535 x 65535 pixels
               (--env), one of 16384 x 8192 (within the limit) without its pixels, and a height map holding
               a NaN (--height-map).
  game-shot    the game asked for a screenshot into a folder that does not exist: it says so, plays on to the
               last frame, writes the next screenshot and its summary (the failed shot with its error), and
               exits 1. PACIFICA_GAME_EXE names the game (set by ctest).

Usage: test_faults.py --case CASE PACIFICA_EXE SOURCE_DIR     (python3 standard library + OIIO's oiiotool)
"""
import json
import os
import struct
import zlib
import random
import resource
import shutil
import socket
import signal
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import test_e2e  # noqa: E402
from test_e2e import child_env, exr_xxh64  # noqa: E402

RUN_TIMEOUT_S = 240
STAGING = ".pacifica-staging-"
# This host's staging folders: ".pacifica-staging-<host>-<pid>" (tools/src/OutputTransaction.cpp's hostPrefix).
HOST_STAGING = STAGING + "".join(ch if ch.isascii() and (ch.isalnum() or ch in "._") else "_"
                                 for ch in (socket.gethostname() or "host")) + "-"


def sortie(source_dir):
    return os.path.join(source_dir, "tools", "data", "sortie.txt.acmi")


def slice_args(source_dir, out, frames=8):
    """`frames` frames of the bundled sortie around the bomb's impact at ~223.8 s, small."""
    return [sortie(source_dir), "--start", "218", "--end", str(218 + frames - 1), "--fps", "1", "--size", "160x90",
            "--no-progress", "--out", out]


def run(exe, args, env=None, **kw):
    cmd = [exe, *args]
    print("  $ " + " ".join(f"'{a}'" if (" " in a or not a) else a for a in cmd))
    t = time.monotonic()
    p = subprocess.run(cmd, env=child_env(env), capture_output=True, text=True, timeout=RUN_TIMEOUT_S, **kw)
    print(f"    exit {p.returncode} after {time.monotonic() - t:.1f} s")
    return p


def errors(p):
    return [line for line in p.stderr.splitlines() if line.startswith("pacifica: error: ")]


def one_clear_error(c, name, p, must):
    err = errors(p)
    c.check(p.returncode != 0, f"{name}: non-zero exit", str(p.returncode))
    c.check(len(err) == 1 and all(m in err[0] for m in must), f"{name}: one error naming {must}",
            "\n".join(p.stderr.splitlines()[-6:]))


def snapshot(folder):
    """{relative path: bytes} of every file under `folder`."""
    out = {}
    for root, _, files in os.walk(folder):
        for f in files:
            path = os.path.join(root, f)
            with open(path, "rb") as fh:
                out[os.path.relpath(path, folder)] = fh.read()
    return out


def whole_image(path):
    with open(path, "rb") as f:
        data = f.read()
    if path.endswith(".png"):
        return data.startswith(b"\x89PNG\r\n\x1a\n") and data.endswith(b"IEND\xaeB`\x82")
    if path.endswith(".exr"):
        return data.startswith(b"\x76\x2f\x31\x01") and len(data) > 1000
    return False


def folder_state(out):
    """(problems, staging folders) of a replay folder after a kill."""
    problems, staging = [], []
    if not os.path.isdir(out):
        return problems, staging
    for name in sorted(os.listdir(out)):
        path = os.path.join(out, name)
        if name.startswith(STAGING):
            if os.path.isdir(path):
                staging.append(name)
            elif not name.endswith(".lock"):
                problems.append(f"{name}: unexpected staging entry")
        elif name == "summary.json":
            try:
                with open(path) as f:
                    s = json.load(f)
                for fr in s["views"][0]["frames"]:
                    for key in ("exr", "png"):
                        if not os.path.isfile(os.path.join(out, fr[key])):
                            problems.append(f"summary.json names {fr[key]}, which is missing")
            except (ValueError, KeyError, IndexError) as e:
                problems.append(f"summary.json is not a valid summary: {e}")
        elif name.startswith("."):
            problems.append(f"{name}: a hidden file outside the staging folders (a partial write?)")
        elif not whole_image(path):
            problems.append(f"{name}: not a whole image")
    return problems, staging


def staged_files(out, pid):
    """Image files the run `pid` has finished writing into its staging folder (its temporaries are hidden)."""
    try:
        return sum(1 for f in os.listdir(os.path.join(out, HOST_STAGING + str(pid))) if not f.startswith("."))
    except OSError:
        return 0


def case_kill(c, exe, source_dir, tmp):
    # Mesa's shader cache in a folder of the test's own (crash-safe: Mesa writes each entry to a temporary and
    # renames it), so that 20 start-ups take ~2 s each instead of ~6 s of shader compilation.
    env = {"MESA_SHADER_CACHE_DISABLE": "false", "MESA_SHADER_CACHE_DIR": os.path.join(tmp, "mesa-cache")}
    frames = 8
    ref_dir, out = os.path.join(tmp, "reference"), os.path.join(tmp, "killed")
    p = run(exe, ["replay", *slice_args(source_dir, ref_dir, frames)], env)
    c.require(p.returncode == 0, "the reference run succeeds", p.stderr[-500:])
    with open(os.path.join(ref_dir, "summary.json")) as f:
        reference = {fr["exr"]: fr["exr_pixel_hash"] for fr in json.load(f)["views"][0]["frames"]}
    c.require(len(reference) == frames, f"the reference run wrote {frames} frames", str(len(reference)))

    rng = random.Random(26)
    plan = [("start-up", rng.uniform(0.2, 1.5)) for _ in range(5)]
    plan += [("staged", rng.randint(1, 2 * frames)) for _ in range(15)]
    rng.shuffle(plan)
    mid_run, bad = 0, []
    for i, (kind, when) in enumerate(plan):
        cmd = [exe, "replay", *slice_args(source_dir, out, frames)]
        proc = subprocess.Popen(cmd, env=child_env(env), stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        t0 = time.monotonic()
        while proc.poll() is None and time.monotonic() - t0 < RUN_TIMEOUT_S:
            if kind == "start-up" and time.monotonic() - t0 >= when:
                break
            if kind == "staged" and staged_files(out, proc.pid) >= when:
                break
            time.sleep(0.01)
        finished = proc.poll() is not None
        proc.send_signal(signal.SIGKILL)
        proc.wait()
        problems, staging = folder_state(out)
        mid_run += 0 if finished else 1
        print(f"    kill {i + 1:2d} ({kind} {when:.2f}) after {time.monotonic() - t0:.2f} s: "
              f"{'finished first' if finished else 'killed'}, staging folders {len(staging)}, "
              f"{len(problems)} problems")
        if problems or len(staging) > 1:
            bad.append(f"kill {i + 1}: {problems} staging {staging}")
    c.check(not bad, "after every kill: only whole images, at most the dead run's staging folder, and a "
            "summary that is absent or valid", "; ".join(bad[:3]))
    c.check(mid_run >= 15, "at least 15 of the 20 runs were killed before they finished", str(mid_run))

    p = run(exe, ["replay", *slice_args(source_dir, out, frames)], env)
    c.require(p.returncode == 0, "a rerun into the same folder completes it", p.stderr[-500:])
    problems, staging = folder_state(out)
    c.check(not problems and not staging and not any(n.startswith(".") for n in os.listdir(out)),
            "nothing of the killed runs is left (staging folders and their locks removed)", str(os.listdir(out)))
    c.check("staging folder(s) of earlier runs" in p.stderr, "the rerun says it removed a dead run's staging",
            p.stderr[-400:])
    names = sorted(reference)
    c.check(exr_xxh64(out, names) == {n: reference[n] for n in names},
            "every frame's EXR pixel hash (recomputed from the file) equals the run that was never killed", "")


def case_full_disk(c, exe, source_dir, tmp):
    def limited():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # the write fails with EFBIG instead of killing
        resource.setrlimit(resource.RLIMIT_FSIZE, (20000, 20000))

    earlier = os.path.join(tmp, "earlier")
    p = run(exe, ["replay", *slice_args(source_dir, earlier, 2)])
    c.require(p.returncode == 0, "an earlier run fills the folder", p.stderr[-400:])
    before = snapshot(earlier)
    p = run(exe, ["replay", *slice_args(source_dir, earlier, 3)], preexec_fn=limited)
    one_clear_error(c, "full disk", p, ["frame_00000.exr", "write"])
    c.check(snapshot(earlier) == before, "the earlier run's folder is exactly as it was (no partial, staging or "
            "temporary file)", str(sorted(set(snapshot(earlier)) - set(before))))
    fresh = os.path.join(tmp, "fresh", "deeper")
    p = run(exe, ["replay", *slice_args(source_dir, fresh, 2)], preexec_fn=limited)
    one_clear_error(c, "full disk, new folder", p, ["frame_00000.exr"])
    c.check(not os.path.exists(os.path.join(tmp, "fresh")), "the folders the run created are removed again", "")


def in_private_mounts(script, exe_args):
    """`unshare -rm sh -c SCRIPT` with the replay's arguments as "$@": mounts seen by that process only."""
    return ["unshare", "-rm", "sh", "-c", script + ' && exec "$@"', "sh", *exe_args]


def case_read_only(c, exe, source_dir, tmp):
    mount = os.path.join(tmp, "ro")
    os.makedirs(mount)
    cmd = in_private_mounts(f"mount -t tmpfs -o ro,size=1m tmpfs '{mount}'",
                            [exe, "replay", *slice_args(source_dir, os.path.join(mount, "frames"), 2)])
    p = subprocess.run(cmd, env=child_env(), capture_output=True, text=True, timeout=RUN_TIMEOUT_S)
    print(f"  $ {' '.join(cmd)}\n    exit {p.returncode}")
    one_clear_error(c, "read-only output folder", p, ["--out", "read-only file system", mount])
    c.check("GL context" not in p.stderr, "refused before a GL context was made (nothing rendered)", p.stderr[-300:])


def lib_egl():
    p = subprocess.run(["ldconfig", "-p"], capture_output=True, text=True)
    for line in p.stdout.splitlines():
        if line.strip().startswith("libEGL.so.1 ") and "x86-64" in line:
            return os.path.realpath(line.split("=>", 1)[1].strip())
    return ""


def case_no_gpu(c, exe, source_dir, tmp):
    out = os.path.join(tmp, "a")
    p = run(exe, ["replay", *slice_args(source_dir, out, 1), "--egl-device", "15"])
    one_clear_error(c, "--egl-device 15", p, ["EGL device 15 does not exist", "this machine has"])
    c.check(not os.path.exists(out), "--egl-device 15: no output folder", "")

    out = os.path.join(tmp, "b")
    p = run(exe, ["replay", *slice_args(source_dir, out, 1)],
            {"__EGL_VENDOR_LIBRARY_FILENAMES": os.path.join(tmp, "no-such-vendor.json")})
    one_clear_error(c, "EGL without a vendor library", p, ["EGL found no driver", "libegl-mesa0"])
    c.check(not os.path.exists(out), "no vendor library: no output folder", "")

    # --egl-device auto: the first GPU of CUDA_VISIBLE_DEVICES, found as --cuda-device finds it; where no EGL
    # device is a CUDA device (llvmpipe) the default device, with a warning and the summary saying so.
    out = os.path.join(tmp, "auto")
    p = run(exe, ["replay", *slice_args(source_dir, out, 1), "--egl-device", "auto"], {"CUDA_VISIBLE_DEVICES": "1,0"})
    c.check(p.returncode == 0, "--egl-device auto with CUDA_VISIBLE_DEVICES=1,0: renders", p.stderr[-400:])
    if p.returncode == 0:
        with open(os.path.join(out, "summary.json")) as f:
            device = json.load(f)["gl"]["device"]
        c.check("CUDA device 0 " in device or device.endswith("CUDA device 0"),
                "--egl-device auto: the summary's device is CUDA device 0 (the first visible GPU: CUDA renumbers them "
                "from 0), or says it was asked for",
                device)
    # A GPU-UUID there is passed on as it is (UUIDs do not depend on CUDA_VISIBLE_DEVICES).
    uuid = "GPU-00000000-1111-2222-3333-444444444444"
    out = os.path.join(tmp, "auto-uuid")
    p = run(exe, ["replay", *slice_args(source_dir, out, 1), "--egl-device", "auto"], {"CUDA_VISIBLE_DEVICES": uuid})
    if p.returncode == 0:
        with open(os.path.join(out, "summary.json")) as f:
            device = json.load(f)["gl"]["device"]
        c.check(f"CUDA device {uuid} asked for" in device, "--egl-device auto with a UUID: asked for by that UUID",
                device)
    else:  # a machine with NVIDIA's EGL: no GPU has that UUID, which is an error naming it
        one_clear_error(c, "--egl-device auto with an unknown UUID", p, [uuid])
    p = run(exe, ["replay", *slice_args(source_dir, os.path.join(tmp, "e"), 1), "--egl-device", "gpu"])
    one_clear_error(c, "--egl-device gpu", p, ["--egl-device", "gpu"])
    # Decimal only: "017" passed CLI11's range check as octal 15 and then named device 17.
    p = run(exe, ["replay", *slice_args(source_dir, os.path.join(tmp, "e8"), 1), "--egl-device", "017"])
    one_clear_error(c, "--egl-device 017", p, ["--egl-device", "'017'"])
    p = run(exe, ["replay", *slice_args(source_dir, os.path.join(tmp, "f"), 1), "--egl-device", "auto",
                  "--cuda-device", "0"])
    one_clear_error(c, "--egl-device auto --cuda-device 0", p, ["name the device twice"])

    lib = lib_egl()
    c.require(bool(lib), "ldconfig knows libEGL.so.1", "")
    out = os.path.join(tmp, "c")
    cmd = in_private_mounts(f"mount --bind /dev/null '{lib}'", [exe, "replay", *slice_args(source_dir, out, 1)])
    p = subprocess.run(cmd, env=child_env(), capture_output=True, text=True, timeout=RUN_TIMEOUT_S)
    print(f"  $ {' '.join(cmd)}\n    exit {p.returncode}")
    one_clear_error(c, "no libEGL at all", p, ["no EGL library", "libEGL.so.1", "install libegl1"])
    c.check(p.returncode == 1 and not os.path.exists(out), "no libEGL: exit 1 (not an abort), no output folder",
            str(p.returncode))


def case_bad_ocio(c, exe, source_dir, tmp):
    garbage = os.path.join(tmp, "garbage.ocio")
    with open(garbage, "w") as f:
        f.write("this is not an OCIO config\n")
    for name, path in [("missing", os.path.join(tmp, "missing.ocio")), ("garbage", garbage)]:
        out = os.path.join(tmp, name)
        p = run(exe, ["replay", *slice_args(source_dir, out, 1)], {"OCIO": path})
        one_clear_error(c, f"$OCIO {name}", p, ["$OCIO", path])
        c.check(not os.path.exists(out), f"$OCIO {name}: no output folder", "")


def case_game_shot(c, exe, source_dir, tmp):
    game = os.environ.get("PACIFICA_GAME_EXE", "")
    c.require(os.path.isfile(game), "PACIFICA_GAME_EXE names the game", game)
    good, summary = os.path.join(tmp, "later.png"), os.path.join(tmp, "summary.json")
    bad = os.path.join(tmp, "no-such-folder", "early.png")
    p = run(game, ["--headless", "--autopilot", "--frames", "16", "--fps", "4", "--size", "160x90",
                   "--screenshot", f"1:{bad}", "--screenshot", f"3:{good}", "--summary", summary])
    c.check(p.returncode == 1, "the game exits 1: a screenshot was not written", str(p.returncode))
    c.check("screenshot not written, the game goes on" in p.stderr and bad in p.stderr,
            "it says which screenshot failed and that it goes on", p.stderr[-400:])
    c.check(os.path.isfile(good) and whole_image(good), "the later screenshot is written", "")
    c.require(os.path.isfile(summary), "the summary is written", "")
    with open(summary) as f:
        s = json.load(f)
    shots = s.get("screenshots", [])
    c.check(len(shots) == 2 and "error" in shots[0] and bad in shots[0]["error"] and "error" not in shots[1],
            "the summary lists both shots, the failed one with its error", json.dumps(shots)[:400])
    c.check("16 frames" in p.stdout, "the game played all 16 frames", p.stdout[-300:])


ACMI_HEADER = b"FileType=text/acmi/tacview\nFileVersion=2.2\n0,ReferenceTime=2026-11-27T10:00:00Z\n#0\n"


def write_zip_bomb(path):
    """A zip whose one member inflates to 4.1 GiB of ACMI comment lines from 25 MB: the same 1 MiB block,
    compressed once after a full flush (which empties the compressor's window, so every copy is the same
    bytes), repeated. The header declares 1 kB and a CRC of 0: the reader must count what it inflates."""
    chunk = b"// " + b"x" * 1020 + b"\n"
    chunk *= 1024
    c = zlib.compressobj(1, zlib.DEFLATED, -15)
    head = c.compress(ACMI_HEADER) + c.flush(zlib.Z_FULL_FLUSH)
    block = c.compress(chunk) + c.flush(zlib.Z_FULL_FLUSH)
    again = c.compress(chunk) + c.flush(zlib.Z_FULL_FLUSH)
    assert block == again, "a full flush should make each copy the same bytes"
    copies = 4100
    tail = c.flush(zlib.Z_FINISH)
    size = len(head) + len(block) * (copies + 1) + len(tail)
    name = b"bomb.txt.acmi"
    local = struct.pack("<IHHHHHIIIHH", 0x04034B50, 20, 0, 8, 0, 0x5B7B, 0, size, 1000, len(name), 0) + name
    with open(path, "wb") as f:
        f.write(local + head + block)
        for _ in range(copies):
            f.write(again)
        f.write(tail)
        central = struct.pack("<IHHHHHHIIIHHHHHII", 0x02014B50, 20, 20, 0, 8, 0, 0x5B7B, 0, size, 1000, len(name),
                              0, 0, 0, 0, 0, 0) + name
        offset = f.tell()
        f.write(central + struct.pack("<IHHHHIIH", 0x06054B50, 0, 0, 1, 1, len(central), offset, 0))


def write_sparse(path, head, size):
    """`head`, then zeros up to `size` bytes without using the disk (a hole)."""
    with open(path, "wb") as f:
        f.write(head)
        f.truncate(size)


def write_exr_header(path, width, height):
    """An OpenEXR file (scanline, uncompressed, RGB half) whose header declares width x height, with a
    line-offset table of zeros and no pixels: only a reader that believes the header allocates the pixels."""
    def attr(name, kind, value):
        return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(value)) + value
    chans = b"".join(ch + b"\0" + struct.pack("<iBxxxii", 1, 0, 1, 1) for ch in (b"B", b"G", b"R")) + b"\0"
    box = struct.pack("<iiii", 0, 0, width - 1, height - 1)
    header = (attr("channels", "chlist", chans) + attr("compression", "compression", b"\0") +
              attr("dataWindow", "box2i", box) + attr("displayWindow", "box2i", box) +
              attr("lineOrder", "lineOrder", b"\0") + attr("pixelAspectRatio", "float", struct.pack("<f", 1)) +
              attr("screenWindowCenter", "v2f", struct.pack("<ff", 0, 0)) +
              attr("screenWindowWidth", "float", struct.pack("<f", 1)) + b"\0")
    with open(path, "wb") as f:
        f.write(struct.pack("<Ii", 20000630, 2) + header + bytes(8 * height))


def run_measured(cmd, env=None):
    """(CompletedProcess-like, peak RSS in MiB, seconds) of one process, from its own rusage (wait4): its
    output goes to files, so nothing but wait4 reaps it."""
    print("  $ " + " ".join(cmd))
    t = time.monotonic()
    with tempfile.TemporaryFile("w+") as out, tempfile.TemporaryFile("w+") as err:
        p = subprocess.Popen(cmd, env=child_env(env), stdout=out, stderr=err, text=True)
        _, status, usage = os.wait4(p.pid, 0)
        p.returncode = os.waitstatus_to_exitcode(status)
        out.seek(0)
        err.seek(0)
        done = subprocess.CompletedProcess(cmd, p.returncode, out.read(), err.read())
    seconds = time.monotonic() - t
    rss = usage.ru_maxrss / 1024
    print(f"    exit {done.returncode} after {seconds:.1f} s, peak RSS {rss:.0f} MiB")
    return done, rss, seconds


def case_hostile(c, exe, source_dir, tmp):
    bomb, ids, long_line, chain = (os.path.join(tmp, n) for n in
                                   ("bomb.zip.acmi", "ids.txt.acmi", "line.txt.acmi", "chain.txt.acmi"))
    write_zip_bomb(bomb)
    with open(ids, "wb") as f:
        f.write(ACMI_HEADER)
        for start in range(1, 10**7 + 1, 10**6):
            f.write(b"".join(b"%x,T=30|40|100\n" % i for i in range(start, start + 10**6)))
    write_sparse(long_line, ACMI_HEADER + b"1,T=30|40|100,Name=", 2**30)
    with open(chain, "wb") as f:
        f.write(ACMI_HEADER + b"1,T=30|40|100,Name=" + b"a\\\n" * 600000 + b"a\n")
    igc = os.path.join(tmp, "huge.igc")
    write_sparse(igc, b"AXXXABC\r\nHFDTE271126\r\nB1000004500000N00700000EA0010000100\r\n", 10**8 * 37)
    exr = os.path.join(tmp, "huge.exr")
    write_exr_header(exr, 65535, 65535)
    # Within the size limit (16384 x 8192 RGB, 1.5 GiB as floats) but without its pixels: the reader decodes
    # a band of rows at a time, so the missing data is found before the declared size is allocated.
    truncated = os.path.join(tmp, "truncated.exr")
    write_exr_header(truncated, 16384, 8192)
    nan_map = os.path.join(tmp, "nan.exr")
    p = subprocess.run([test_e2e.oiio_tool("oiiotool"), "--pattern", "constant:color=nan", "1x1", "1", "--pattern",
                        "constant:color=0.5", "64x64", "1", "--paste", "+10+10", "-d", "float", "-o", nan_map],
                       capture_output=True, text=True)  # a 64 x 64 float map, one NaN at (10, 10)
    c.require(p.returncode == 0, "oiiotool writes a height map with a NaN", p.stderr[-300:])

    limit_mib = 1024
    cases = [("zip bomb", [bomb, "--list-objects"], [bomb, "inflates to more than 4 GiB"]),
             ("10^7 object ids", [ids, "--list-objects"], [ids, "more than 1000000 objects"]),
             ("a 1 GB line", [long_line, "--list-objects"], [long_line + ":5:", "line longer than 1 MiB"]),
             ("a continuation chain", [chain, "--list-objects"], [chain + ":5:", "continued with"]),
             ("an IGC of 10^8 B records", [igc, "--list-objects"], [igc, "larger than 256 MiB", "before reading"]),
             ("an EXR of 65535 x 65535", [*slice_args(source_dir, os.path.join(tmp, "o1"), 1), "--env", exr],
              [exr, "65535 x 65535", "refused"]),
             ("an EXR of 16384 x 8192 without pixels", [*slice_args(source_dir, os.path.join(tmp, "o3"), 1), "--env",
                                                       truncated], [truncated, "cannot read pixels"]),
             ("a height map with a NaN", [*slice_args(source_dir, os.path.join(tmp, "o2"), 1), "--height-map",
                                          nan_map], [nan_map, "NaN"])]
    for name, args, must in cases:
        p, rss, seconds = run_measured([exe, "replay", *args])
        one_clear_error(c, name, p, must)
        c.check(rss < limit_mib, f"{name}: peak RSS {rss:.0f} MiB < {limit_mib} MiB", "")
    c.check(not any(os.path.exists(os.path.join(tmp, o)) for o in ("o1", "o2", "o3")),
            "no output folder from the refused replays", "")


CASES = {"kill": case_kill, "full-disk": case_full_disk, "read-only": case_read_only, "no-gpu": case_no_gpu,
         "bad-ocio": case_bad_ocio, "game-shot": case_game_shot, "hostile": case_hostile}

if __name__ == "__main__":
    sys.exit(test_e2e.main(CASES, "faults", __doc__))
