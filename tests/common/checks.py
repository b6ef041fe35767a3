"""Shared by the Python end-to-end tests (tests/e2e, tests/determinism, tests/badinput): a check counter that
prints every check and collects the failures for the closing 'N passed, N failed' summary."""


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
