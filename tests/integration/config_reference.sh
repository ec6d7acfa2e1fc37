source "$(dirname "$0")/lib.sh"
# docs/config-reference.md is generated from the schema; it must be current.
"$ROOT/build/bin/coupler" reference > generated.md
if ! diff -u "$ROOT/docs/config-reference.md" generated.md; then
  fail "docs/config-reference.md is stale: run ./pbms reference > docs/config-reference.md"
fi
echo "1 passed, 0 failed"
