"""What the integration scripts' Python checks share: a run's summary
values by stage and key, and ok/FAIL lines counted for the exit code."""
import math
import sys

import yaml


class Checks:
    def __init__(self):
        self.bad = 0

    def check(self, ok, text):
        self.bad += not ok
        print(f"{'ok  ' if ok else 'FAIL'} {text}")

    def exit(self):
        sys.exit(1 if self.bad else 0)


def summary_values(run):
    """value(stage, key) for runs/RUN/summary.yaml; NaN where it is missing."""
    stages = yaml.safe_load(open(f"runs/{run}/summary.yaml"))["stages"]

    def value(stage, key):
        r = stages[stage]["results"].get(key)
        return r["value"] if r else math.nan

    return value
