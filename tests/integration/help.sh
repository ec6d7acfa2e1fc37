source "$(dirname "$0")/lib.sh"
"$PBMS" --help | grep -q "Usage: ./pbms COMMAND" || fail "pbms --help"
for c in run validate test plot export bench report; do
  "$PBMS" "$c" --help >/dev/null || fail "pbms $c --help exited non-zero"
done
if "$PBMS" frobnicate 2>/dev/null; then fail "unknown command accepted"; fi
"$ROOT/build/bin/md_driver" --help | grep -q md_isotherm || fail "md_driver --help"
"$ROOT/build/bin/coupler" --help >/dev/null || fail "coupler --help"
echo "1 passed, 0 failed"
