"""Shared by the Python end-to-end tests (tests/e2e, tests/determinism, tests/badinput): a check counter that
prints every check and collects the failures for the closing 'N passed, N failed' summary."""


import shutil
import time


class Checks:
    def __init__(self):
        self.passed = 0
        self.failed = []

    def check(self, ok, what, detail=""):
        if ok:
            self.passed += 1
            print(f"  ok    {what}")
        else:
            self.failed.append(what + (f": {detail}" if detail else ""))
            print(f"  FAIL  {what}" + (f": {detail}" if detail else ""))
        return ok

    def finish(self, label, started, tmp):
        """Prints the closing summary; keeps `tmp` for inspection on failure, removes it on success.
        Returns the process exit status (0 = all checks passed)."""
        elapsed = time.monotonic() - started
        print(f"\nSUMMARY {label}: {self.passed} checks passed, {len(self.failed)} failed, {elapsed:.1f} s")
        if self.failed:
            for f in self.failed:
                print(f"  failed: {f}")
            print(f"  output kept in {tmp}")
            return 1
        shutil.rmtree(tmp, ignore_errors=True)
        return 0
