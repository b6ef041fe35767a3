#!/usr/bin/env python3
"""End-to-end tests of `pacifica tonemap compare` (tools/src/TonemapCompare.cpp, tools/tonemap).

Cases (chosen with --case, one ctest test each):
  hdr          the shared data directory's data/hdr/*.exr with the ACES studio config: the report (HTML self-contained, Markdown,
               JSON), a labelled contact sheet per input, NaN/Inf of BrightRingsNanInf counted and every output
               finite, the shipped clamp equal to the configs' un-tone-mapped view, 1D LUTs within 1e-4 of their
               closed forms and PBR Neutral's cube error falling with its size, non-sRGB displays listed.
  replay       a replay output folder and a flight file (rendered first) as inputs.
  replay-views `replay --view A --view B`: one render, one more tonemap pass per extra view (its PNGs and
               summary entries; scene passes and EXR hashes equal to a one-view run); an unknown view is
               refused listing the valid ones, nothing written.
  bad-input    not an image, one channel, an image over --max-pixels (its size named), a missing input, a
               missing --ocio-config: each exits non-zero with one 'pacifica: error:' line naming it and
               leaves no output folder.

Usage: test_tonemap_compare.py --case CASE PACIFICA_EXE SOURCE_DIR     (python3 standard library + oiiotool)
"""
import json
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
import test_e2e  # noqa: E402
from pngread import read_png  # noqa: E402
from test_e2e import child_env, oiio_tool  # noqa: E402

RUN_TIMEOUT_S = 240


def shared(source_dir, *parts):
    return os.path.join(os.environ.get("PACIFICA_SHARED_DIR", ""), *parts)  # set by ctest (tests/README.md)


def run(exe, args):
    cmd = [exe, *args]
    # Arguments that are not UTF-8 (surrogate escapes) are printed as \xNN.
    print("  $ " + " ".join(cmd).encode("utf-8", "surrogateescape").decode("utf-8", "backslashreplace"))
    t = time.monotonic()
    p = subprocess.run(cmd, env=child_env(), capture_output=True, text=True, errors="surrogateescape",
                       timeout=RUN_TIMEOUT_S)
    print(f"    exit {p.returncode} after {time.monotonic() - t:.1f} s")
    return p


def case_hdr(c, exe, source_dir, tmp):
    out = os.path.join(tmp, "cmp")
    hdr = [shared(source_dir, "data", "hdr", n) for n in ("BrightRings.exr", "BrightRingsNanInf.exr", "KernerEnvLatLong.exr")]
    studio = shared(source_dir, "data", "ocio", "studio-config-v1.0.0_aces-v1.3_ocio-v2.1.ocio")
    p = run(exe, ["tonemap", "compare", *hdr, "--ocio-config", studio, "--out", out])
    c.require(p.returncode == 0, "tonemap compare succeeds", p.stderr[-1500:])
    for name in ("report.html", "report.md", "metrics.json", "ocio/pacifica-tonemappers.ocio"):
        c.check(os.path.isfile(os.path.join(out, name)), f"{name} written")
    with open(os.path.join(out, "metrics.json")) as f:
        m = json.load(f)
    names = [i["name"] for i in m["inputs"]]
    c.check(names == ["test-chart", "brightrings", "brightringsnaninf", "kernerenvlatlong"], "inputs in order", names)
    labels = [t["label"] for t in m["transforms"]]
    c.check(len([l for l in labels if l.startswith("pacifica: ")]) == 6, "the six shipped tonemappers", labels)
    c.check(any(l.startswith("embedded: sRGB / ACES 1.0 - SDR Video") for l in labels), "embedded ACES view")
    studio_views = [l for l in labels if not l.startswith(("pacifica: ", "embedded: "))]
    c.check(len(studio_views) >= 2, "the studio config's sRGB views are compared", studio_views)
    # Every display of the studio config is compared, decoded through its display colour space: the PQ
    # display's un-tone-mapped view keeps Kerner's Rec.709 colours (wide gamut, no clipping below 10000 cd/m^2).
    c.check(any("Rec.2100-PQ - Display / ACES 1.1 - HDR Video (1000 nits" in l for l in labels)
            and any("P3-D65 - Display / ACES 1.0 - SDR Cinema" in l for l in labels), "HDR and P3 displays compared")
    c.check(all("Raw" in s for s in m["skipped_displays"]), "only the Raw (data) views are left out",
            m["skipped_displays"])
    by = {i["name"]: i for i in m["inputs"]}
    nan = by["brightringsnaninf"]["census"]
    c.check(nan["nan"] > 0 and nan["inf"] > 0, "NaN and Inf counted in BrightRingsNanInf", nan)
    c.check(by["brightrings"]["census"]["nan"] == 0, "BrightRings has no NaN")
    kerner = {r["transform"]: r["metrics"] for r in by["kernerenvlatlong"]["results"]}
    pq = [v for k, v in kerner.items() if k.endswith("Rec.2100-PQ - Display / Un-tone-mapped")]
    c.check(len(pq) == 1 and pq[0]["hue_shift_mean_deg"] < 0.1 and abs(pq[0]["chroma_ratio"] - 1) < 0.01,
            "PQ un-tone-mapped: Kerner's hues and chroma kept", pq)
    nonfinite = [(i["name"], r["transform"]) for i in m["inputs"] for r in i["results"]
                 if r["metrics"]["non_finite_output"] != 0]
    c.check(not nonfinite, "every output finite (NaN/Inf inputs included)", nonfinite)
    # GPU (OCIO's GLSL, LUT textures included) against the CPU processor. Measured on llvmpipe <= 1.6e-5 for
    # every shipped and embedded transform (LUT ones too: llvmpipe filters in float); the 1e-3 bound of the 3D
    # LUT leaves room for a hardware GPU's 8-bit-fraction filtering. The studio config's other displays reach
    # 1.2e-4 (P3-D60's 1/2.6 power near black, OCIO's GPU and CPU power functions): bound 5e-4 there.
    c.check(m["gl_renderer"] != "", "the GPU path ran", m["gl_renderer"])

    def gpu_bound(t):
        if t.startswith("pacifica: Khronos"):
            return 1e-3
        return 1e-4 if t.startswith(("pacifica: ", "embedded: ")) else 5e-4
    gpu_bad = [(i["name"], r["transform"], r.get("gpu_cpu_max_difference")) for i in m["inputs"] for r in i["results"]
               if r.get("gpu_cpu_max_difference", 1.0) > gpu_bound(r["transform"])]
    c.check(not gpu_bad, "GPU within 1e-4 of the CPU processor (1e-3 for the 3D LUT, 5e-4 other configs)", gpu_bad)
    c.check(any("Raw" in s and "passes scene-linear data through" in s for s in m["skipped_displays"]),
            "the studio config's Raw view is left out as a data view", m["skipped_displays"])
    chart = {r["transform"]: r for r in by["test-chart"]["results"]}
    clamp, untm = chart["pacifica: Clamp (no tonemap)"], chart["embedded: sRGB / Un-tone-mapped"]
    # Same transform, two decode paths (sRGB EOTF vs the display colour space -> XYZ -> Rec.709 matrices).
    for k, tol in (("clipped", 1e-6), ("crushed", 1e-6), ("hue_shift_mean_deg", 0.02), ("chroma_ratio", 1e-3)):
        c.check(abs(clamp["metrics"][k] - untm["metrics"][k]) < tol, f"shipped clamp == un-tone-mapped view: {k}",
                (clamp["metrics"][k], untm["metrics"][k]))
    studio_untm = [r for t, r in chart.items() if t.endswith("sRGB - Display / Un-tone-mapped")]
    c.check(len(studio_untm) == 1 and abs(studio_untm[0]["metrics"]["hue_shift_mean_deg"] -
                                           clamp["metrics"]["hue_shift_mean_deg"]) < 0.02,
            "the studio config is entered through its linear Rec.709 space (its un-tone-mapped view == clamp)",
            [r["metrics"]["hue_shift_mean_deg"] for r in studio_untm])
    for r in [r for t, r in chart.items() if "sRGB" in t]:
        c.check(0.3 < r["sweep"]["mid_grey_code"] < 0.6, f"{r['transform']}: 0.18 lands mid-range",
                r["sweep"]["mid_grey_code"])
    luts = m["luts"]
    for r in luts:
        if r["lut"].startswith("1D"):
            c.check(r["max_code_error"] < 1e-4, f"{r['tonemapper']} 1D LUT within 1e-4", r["max_code_error"])
    cube = [r["max_code_error"] for r in luts if r["tonemapper"] == "pbr-neutral"]
    c.check(len(cube) == 3 and cube[0] > cube[1] > cube[2], "PBR Neutral: error falls with cube size 17/33/65", cube)
    with open(os.path.join(out, "report.html")) as f:
        html = f.read()
    c.check(html.count("data:image/png;base64,") == 4 * 5, "report.html embeds the 4 x 5 sheets")
    for n in names:
        for suffix in ("", "-bracket", "-falsecolour", "-histograms", "-wipe"):
            c.check(os.path.isfile(os.path.join(out, "sheets", n + suffix + ".png")), f"sheets/{n}{suffix}.png")
    pair = by["brightrings"]["pair"]
    c.check(pair["a"].startswith("pacifica: AgX base") and pair["b"] == "embedded: sRGB / ACES 1.0 - SDR Video"
            and 0.01 < pair["max_code_difference"] < 1.0, "default wipe pair and its difference", pair)
    w, h, _, rows = read_png(os.path.join(out, "sheets", "brightrings-wipe.png"))
    mid = [rows[h // 4][3 * x] for x in (w // 2 - 1, w // 2)] if w == 720 else []
    c.check(mid == [255, 255], "the wipe's divider is drawn at the middle", (w, mid))
    c.check("src=\"sheets/" not in html and "<link" not in html, "report.html is self-contained")
    w, h, _, rows = read_png(os.path.join(out, "sheets", "brightrings.png"))
    c.check(w > 1000 and h > 1000, "contact sheet size", (w, h))
    # The header (first ~18 rows) is dark grey (0.12 -> code 31) except where the title text is drawn.
    lit = sum(1 for y in range(4, 20) for x in range(0, 300) if rows[y][3 * x] > 160)
    c.check(lit > 100, "the title is drawn in the header", lit)
    # HDR display output: 16-bit PQ PNG and an EXR in cd/m^2 per input; ACES 1.1 HDR puts 0.18 at ~15 cd/m^2.
    for n in names:
        png = os.path.join(out, "hdr", n + "-pq.png")
        c.check(os.path.isfile(png) and os.path.isfile(os.path.join(out, "hdr", n + "-nits.exr")), f"hdr/{n} files")
        if os.path.isfile(png):
            with open(png, "rb") as f:
                head = f.read(26)
            c.check(head[24] == 16, f"hdr/{n}-pq.png is 16-bit", head[24])
    c.check(13.5 < by["test-chart"]["hdr"]["mid_grey_nits"] < 16.5, "HDR: 0.18 -> ~15 cd/m^2",
            by["test-chart"]["hdr"]["mid_grey_nits"])
    # Measured 1011: a saturated channel can sit a little above the 1000 cd/m^2 white.
    c.check(900 < by["test-chart"]["hdr"]["peak_nits"] <= 1050, "HDR: the sun-glint patch reaches the ~1000 cd/m^2 peak",
            by["test-chart"]["hdr"]["peak_nits"])
    c.check(by["brightringsnaninf"]["hdr"]["peak_nits"] <= 1050, "HDR output finite and within the peak")
    with open(os.path.join(out, "report.md")) as f:
        md = f.read()
    c.check("least clipping" in md and "least hue shift" in md, "report.md names the least clipping / hue shift")


def case_replay(c, exe, source_dir, tmp):
    flight = os.path.join(source_dir, "tools", "data", "demo_flight.csv")
    rep = os.path.join(tmp, "rep")
    p = run(exe, ["replay", flight, "--out", rep, "--size", "160x90", "--fps", "1", "--start", "0", "--end", "3",
                  "--no-progress"])
    c.require(p.returncode == 0, "a short replay", p.stderr[-800:])
    out = os.path.join(tmp, "cmp")
    p = run(exe, ["tonemap", "compare", rep, flight, "--frames", "2", "--out", out])
    c.require(p.returncode == 0, "compare a replay folder and a flight file", p.stderr[-1500:])
    with open(os.path.join(out, "metrics.json")) as f:
        m = json.load(f)
    names = [i["name"] for i in m["inputs"]]
    c.check(len(names) == 5, "chart + 2 frames of the folder + 2 rendered frames", names)
    c.check(any(i["source"].startswith(os.path.join(out, "renders")) or "/renders/" in i["source"]
                for i in m["inputs"]), "the flight was rendered first", [i["source"] for i in m["inputs"]])
    c.check(len(os.listdir(os.path.join(out, "sheets"))) == 5 * 5, "five sheets per input")


def case_bad_input(c, exe, source_dir, tmp):
    def refuse(args, needle, what):
        out = os.path.join(tmp, "never")
        p = run(exe, ["tonemap", "compare", *args, "--out", out])
        errs = [l for l in p.stderr.splitlines() if l.startswith("pacifica: error:")]
        c.check(p.returncode != 0, f"{what}: non-zero exit")
        c.check(len(errs) == 1 and needle in errs[0], f"{what}: error names it", p.stderr[-600:])
        c.check(not os.path.exists(out), f"{what}: no output folder")
        c.check(not [n for n in os.listdir(tmp) if n.startswith(".never")], f"{what}: no staging left")

    text = os.path.join(tmp, "notes.exr")
    with open(text, "w") as f:
        f.write("not an image\n")
    refuse([text], "notes.exr: not an image", "not an image")
    grey = os.path.join(tmp, "grey.exr")
    subprocess.run([oiio_tool("oiiotool"), "--create", "8x8", "1", "-d", "half", "-o", grey], check=True)
    refuse([grey], "grey.exr: has 1 channel(s); RGB or RGBA is needed", "one channel")
    rings = shared(source_dir, "data", "hdr", "BrightRings.exr")
    refuse([rings, "--max-pixels", "1000"], "800x800 = 640000 pixels is over the limit of 1000", "huge image")
    refuse([os.path.join(tmp, "missing.exr")], "missing.exr: no such file", "missing input")
    refuse([rings, "--ocio-config", os.path.join(tmp, "nope.ocio")], "nope.ocio", "missing config")
    refuse([rings, "--pair", "hable,nosuchthing"], "--pair: 'nosuchthing' names no transform", "unknown wipe transform")
    refuse([rings, "--pair", "pacifica,clamp"], "--pair: 'pacifica' names more than one", "ambiguous transform")
    # Bounds checked while parsing: a usage error (exit 2) before anything is read.
    for args, needle, what in [(["--lut3d", "1"], "--lut3d", "a LUT edge below 2"),
                               (["--tile-width", "5000"], "--tile-width", "a tile over 4096 pixels"),
                               (["--max-pixels", "0"], "--max-pixels", "no pixels allowed"),
                               (["--pair", "hable"], "expected two transforms, A,B", "a pair without a comma")]:
        refuse([rings, *args], needle, what)
        c.check(run(exe, ["tonemap", "compare", rings, *args, "--out", os.path.join(tmp, "never")]).returncode == 2,
                f"{what}: exit status 2")
    # An input whose file name is not UTF-8 (byte 0xA1) is compared; metrics.json names it with U+FFFD (its
    # JSON threw after the work before).
    odd = os.path.join(tmp, "rings\udca1.exr")
    with open(rings, "rb") as src, open(odd, "wb") as dst:
        dst.write(src.read())
    out = os.path.join(tmp, "odd-name")
    p = run(exe, ["tonemap", "compare", odd, "--out", out, "--no-gpu"])
    c.check(p.returncode == 0, "a non-UTF-8 input name: compared",
            p.stderr[-600:].encode("utf-8", "surrogateescape").decode("utf-8", "backslashreplace"))
    if p.returncode == 0:
        with open(os.path.join(out, "metrics.json"), encoding="utf-8") as f:
            sources = [i["source"] for i in json.load(f)["inputs"]]
        c.check(any(src.endswith("rings\ufffd.exr") for src in sources), "metrics.json names it with U+FFFD",
                sources)


def case_replay_views(c, exe, source_dir, tmp):
    flight = os.path.join(source_dir, "tools", "data", "demo_flight.csv")
    common = ["replay", flight, "--size", "160x90", "--fps", "1", "--start", "0", "--end", "2", "--no-progress"]
    one, two = os.path.join(tmp, "one"), os.path.join(tmp, "two")
    p = run(exe, [*common, "--out", one])
    c.require(p.returncode == 0, "one view", p.stderr[-800:])
    p = run(exe, [*common, "--out", two, "--view", "ACES 1.0 - SDR Video", "--view", "Un-tone-mapped"])
    c.require(p.returncode == 0, "two views", p.stderr[-800:])
    with open(os.path.join(one, "summary.json")) as f:
        s1 = json.load(f)
    with open(os.path.join(two, "summary.json")) as f:
        s2 = json.load(f)
    c.check(s2["ocio"]["view"] == "ACES 1.0 - SDR Video" and s2["ocio"]["extra_views"] == ["Un-tone-mapped"],
            "summary names both views", s2["ocio"])
    f1, f2 = s1["frames"], s2["frames"]
    c.require(len(f1) == len(f2) == 3, "3 frames each", (len(f1), len(f2)))
    for a, b in zip(f1, f2):
        c.check(a["counters"]["passes"] == b["counters"]["passes"] and a["counters"]["draws"] == b["counters"]["draws"],
                f"frame {a['index']}: scene passes and draws do not grow with views",
                (a["counters"]["passes"], b["counters"]["passes"]))
        c.check(a["counters"]["tonemap_passes"] == 1 and b["counters"]["tonemap_passes"] == 2,
                f"frame {a['index']}: one tonemap pass per view")
        c.check(a["exr_pixel_hash"] == b["exr_pixel_hash"], f"frame {a['index']}: the same scene render")
        extra = b.get("extra_views", [])
        c.check(len(extra) == 1 and os.path.isfile(os.path.join(two, extra[0]["png"])),
                f"frame {a['index']}: the extra view's PNG", extra)
        if extra:
            with open(os.path.join(two, b["png"]), "rb") as fa, open(os.path.join(two, extra[0]["png"]), "rb") as fb:
                c.check(fa.read() != fb.read(), f"frame {a['index']}: the two views differ")
    bad = os.path.join(tmp, "bad")
    p = run(exe, [*common, "--out", bad, "--view", "ACES 1.0 - SDR Video", "--view", "Filmic"])
    errs = [l for l in p.stderr.splitlines() if l.startswith("pacifica: error:")]
    c.check(p.returncode != 0 and len(errs) == 1 and "unknown view 'Filmic'" in errs[0] and "Un-tone-mapped" in errs[0],
            "an unknown extra view is refused listing the valid ones", p.stderr[-600:])
    c.check(not os.path.exists(bad) or not os.listdir(bad), "nothing written for the refused run")


CASES = {"hdr": case_hdr, "replay": case_replay, "replay-views": case_replay_views, "bad-input": case_bad_input}

if __name__ == "__main__":
    sys.exit(test_e2e.main(CASES, "tonemap", __doc__))
