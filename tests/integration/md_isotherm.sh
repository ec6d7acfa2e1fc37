source "$(dirname "$0")/lib.sh"
# configs/md_isotherm.yaml as a user runs it (default ranks from the config).
"$PBMS" run "$ROOT/configs/md_isotherm.yaml" > out.txt 2>&1 || { cat out.txt; fail "md_isotherm failed"; }
run=runs/md_isotherm
grep -q "\[isotherm\] step .* steps/s | ETA" out.txt || fail "no progress lines"
grep -q "\[isotherm\] step .* steps/s | ETA" "$run/log.txt" || fail "no progress lines in the log"
"$PY" "$(dirname "$0")/check_isotherm.py" "$run"
