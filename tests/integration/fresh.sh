#!/usr/bin/env bash
# fresh.sh WORKDIR INTERPRETER SCRIPT ARGS...: empties WORKDIR (a test's own
# directory under build/test-work/, as ctest names it), then runs SCRIPT
# there with INTERPRETER (bash, or /usr/bin/python3). Each
# ctest run of a test starts from nothing, so no run finds the run directory
# an earlier ctest left behind.
set -euo pipefail
work="$1"
shift
case "$work" in
  */test-work/*) ;;
  *) echo "fresh.sh: refusing to empty '$work': not a directory under test-work/" >&2; exit 2 ;;
esac
mkdir -p "$work"
cd "$work"
find . -mindepth 1 -delete
exec "$@"
