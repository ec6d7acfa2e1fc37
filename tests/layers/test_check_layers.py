#!/usr/bin/python3
"""check_layers.py finds each kind of violation put into a small tree on purpose,
and passes the same tree without them."""
import subprocess
import sys
import tempfile
from pathlib import Path

CHECKER = Path(__file__).with_name("check_layers.py")

CLEAN = {
    "core/include/pbms/units.hpp": "#pragma once\n",
    "core/src/units.cpp": '#include "pbms/units.hpp"\n#include <vector>\n',
    "grid/include/pbms/grid/regular_grid.hpp": '#pragma once\n#include "pbms/units.hpp"\n',
    "coupling/include/pbms/coupling/link.hpp": '#pragma once\n#include "pbms/grid/regular_grid.hpp"\n',
    "dpd_driver/engine/dpd_engine.hpp": '#pragma once\n#include "pbms/coupling/link.hpp"\n',
    "mpm_driver/materials/linear_elastic.hpp": '#pragma once\n#include "pbms/grid/regular_grid.hpp"\n',
    "md_driver/md_isotherm.cpp": '#include "pbms/units.hpp"\n',
    "coupler/daemon.cpp": '#include "pbms/coupling/link.hpp"\n',
    "dpd_driver/stage/dpd_run_params.cpp": (
        '#include "engine/dpd_engine.hpp"\n'
        "DpdRunParams DpdRunParams::from_yaml(const YAML::Node& p) {\n"
        '  r.steps = p["steps"].as<int>();\n'
        "}\n"
        "void report(StageResults& r) {\n"
        '  r.attributes["wave_speed"] = "not measured";\n'
        '  request["strain_state"] = name;\n'
        "}\n"),
}

VIOLATIONS = {
    "dpd_driver/engine/grid_step.cpp": ('#include "materials/linear_elastic.hpp"\n',
                                        "dpd_driver includes mpm_driver's"),
    "coupler/fit/judge.cpp": ('#include "engine/dpd_engine.hpp"\n', "coupler includes dpd_driver's"),
    "grid/src/step.cpp": ('#include "pbms/coupling/link.hpp"\n', "grid includes coupling's"),
    "grid/src/points.cpp": ('#include "engine/dpd_engine.hpp"\n', "grid includes dpd_driver's"),
    "core/src/workflow.cpp": ('#include "pbms/grid/regular_grid.hpp"\n', "core includes grid's"),
    "dpd_driver/stage/dpd_run.cpp": (
        'void run_stage(StageContext& ctx) {\n  const double dt = ctx.params()["time_step"].as<double>();\n}\n',
        "dpd_driver/stage/dpd_run.cpp: 1 parameter reads by string key"),
}


def write(root, files):
    for name, text in files.items():
        p = root / name
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_text(text)


def run(root):
    r = subprocess.run([sys.executable, str(CHECKER), str(root)], capture_output=True, text=True)
    return r.returncode, r.stdout


def main():
    failures = []
    with tempfile.TemporaryDirectory() as d:
        root = Path(d)
        write(root, CLEAN)
        rc, out = run(root)
        if rc != 0:
            failures.append(f"the clean tree fails:\n{out}")
        write(root, {k: v[0] for k, v in VIOLATIONS.items()})
        rc, out = run(root)
        print(out)
        if rc != 1:
            failures.append(f"exit code {rc} with violations in the tree")
        for name, (_, expected) in VIOLATIONS.items():
            if not any(name in line and expected in line for line in out.splitlines()):
                failures.append(f"not reported: {expected} ({name})")
        if len(out.strip().splitlines()) != len(VIOLATIONS) + 1:
            failures.append("reported something else as well")
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
