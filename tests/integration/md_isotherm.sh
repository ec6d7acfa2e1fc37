source "$(dirname "$0")/lib.sh"
# configs/md_isotherm.yaml as a user runs it (default ranks from the config),
# checked against copper's references (check_isotherm.py). The default suite
# runs it on 6x6x6 cells (864 atoms, the quickstart's crystal) instead of
# 8x8x8 (2,048): the same stage, pressures and times at 42 % of the cost;
# with the argument `full` (validation) the config as it is.
config="$ROOT/configs/md_isotherm.yaml"
if [ "${1:-}" != full ]; then
  sed 's/^    cells: \[8, 8, 8\] .*$/    cells: [6, 6, 6]/' "$config" > md_isotherm.yaml
  grep -q '^    cells: \[6, 6, 6\]$' md_isotherm.yaml || fail "the config's cells line has changed"
  config=md_isotherm.yaml
fi
"$PBMS" run "$config" > out.txt 2>&1 || { cat out.txt; fail "md_isotherm failed"; }
run=runs/md_isotherm
grep -q "\[isotherm\] step .* steps/s | ETA" out.txt || fail "no progress lines"
grep -q "\[isotherm\] step .* steps/s | ETA" "$run/log.txt" || fail "no progress lines in the log"
"$PY" "$(dirname "$0")/check_isotherm.py" "$run"
