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


def law_gauge_modulus(youngs_modulus, run, stage, value):
    """What a hypoelastic rod's gauge should read: the slope of E ln(1 + e)
    (the Cauchy stress of the Jaumann update under uniaxial stress) at the
    gauge's strains, fitted as the gauge modulus is, from the first sample
    to the one where the stress first reaches half its largest. Returns the
    slope (GPa) and the strains fitted."""
    import h5py
    import numpy as np

    with h5py.File(f"runs/{run}/results.h5", "r") as f:
        curve = f[stage]["gauge_curve"]
        strain, stress = curve["strain"][:], curve["stress"][:]
    fitted = int(np.argmax(stress >= 0.5 * value(stage, "gauge_max_stress"))) + 1
    e = strain[:fitted]
    return np.polyfit(e, youngs_modulus * np.log1p(e), 1)[0], e
