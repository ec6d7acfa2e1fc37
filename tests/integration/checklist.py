"""Shared by the Python integration tests: one line per check, and the
closing "N passed, N failed" line that ctest output is read for."""


class Checklist:
    def __init__(self):
        self.passed = []
        self.failed = []

    def __call__(self, ok, what):
        print(("ok   " if ok else "FAIL ") + what, flush=True)
        (self.passed if ok else self.failed).append(what)
        return ok

    def finish(self):
        """Prints the closing line; the exit status for sys.exit."""
        print(f"{len(self.passed)} passed, {len(self.failed)} failed")
        return 1 if self.failed else 0
