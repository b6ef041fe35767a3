"""bench_no_gl_context: every GL bench ends the same way when no GL context can be made (EGL without a
vendor library: __EGL_VENDOR_LIBRARY_FILENAMES names a file that does not exist): exit 2, one line
"NAME: no GL context: ..." naming EGL's reason, and no report in the output folder (it may exist, empty).

Usage: test_no_gl_context.py OUT_DIR NAME=EXE [NAME=EXE ...]"""
import os
import shutil
import subprocess
import sys


def main():
    out_root = sys.argv[1]
    shutil.rmtree(out_root, ignore_errors=True)
    failures = []
    for pair in sys.argv[2:]:
        name, exe = pair.split("=", 1)
        out = os.path.join(out_root, name)
        env = dict(os.environ)
        env["__EGL_VENDOR_LIBRARY_FILENAMES"] = os.path.join(out_root, "no-such-vendor.json")
        p = subprocess.run([exe, "--out", out], env=env, capture_output=True, text=True, timeout=120)
        lines = [ln for ln in p.stderr.splitlines() if ln.startswith(name + ": no GL context: ")]
        reports = os.listdir(out) if os.path.isdir(out) else []
        ok = p.returncode == 2 and len(lines) == 1 and "EGL found no driver" in lines[0] and not reports
        print(f"{'ok' if ok else 'FAILED'} {name}: exit {p.returncode}, {lines[0] if lines else 'no such line'}"
              f"{', files ' + str(reports) if reports else ''}")
        if not ok:
            failures.append(name)
            print(p.stderr[-800:])
    if failures:
        print("failed: " + ", ".join(failures))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
