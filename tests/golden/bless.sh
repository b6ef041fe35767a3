#!/bin/sh
# Re-bless the golden images deliberately: renders every case of cases.json with the current build and
# copies the PNGs over tests/golden/<name>.png. Review the new images (and git diff) before committing.
set -eu
ROOT=$(CDPATH= cd -- "$(dirname -- "$0")/../.." && pwd)
"$ROOT/pacifica" build
CLI="${PACIFICA_BUILD_DIR:-$ROOT/build}/tools/pacifica"
python3 - "$CLI" "$ROOT" <<'PY'
import json, os, shutil, subprocess, sys, tempfile
cli, root = sys.argv[1:3]
gd = os.path.join(root, "tests", "golden")
for case in json.load(open(os.path.join(gd, "cases.json")))["cases"]:
    out = tempfile.mkdtemp()
    t = str(case["time"])
    subprocess.run([cli, "replay", os.path.join(gd, case["flight"]), "--out", out, "--start", t, "--end", t,
                    "--size", case["size"], "--no-progress", *case.get("args", [])], check=True)
    shutil.copy(os.path.join(out, "frame_00000.png"), os.path.join(gd, case["name"] + ".png"))
    shutil.rmtree(out)
    print("blessed", case["name"])
PY
