# Shared helpers for integration tests. Each test runs in its own working
# directory (set by ctest) and gets the repository root as $1.
set -euo pipefail
ROOT="$1"
shift
PBMS="$ROOT/pbms"
PY=/usr/bin/python3
# The Python checks import tests/integration/summary_checks.py.
export PYTHONPATH="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)${PYTHONPATH:+:$PYTHONPATH}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# As ./pbms runs its jobs (mpi_env there), for the tests' own plain `mpirun lmp`.
export OMPI_MCA_rmaps_base_oversubscribe=1 OMPI_MCA_mpi_yield_when_idle=1
export OMPI_MCA_btl_vader_single_copy_mechanism=none PMIX_MCA_gds=hash

fail() { echo "FAIL: $*" >&2; exit 1; }

# Reads a value from a YAML file: yget FILE key.path.with.dots
yget() {
  "$PY" - "$1" "$2" <<'PYEOF'
import sys, yaml
node = yaml.safe_load(open(sys.argv[1]))
for k in sys.argv[2].split('.'):
    node = node[int(k)] if isinstance(node, list) else node[k]
print(node)
PYEOF
}
