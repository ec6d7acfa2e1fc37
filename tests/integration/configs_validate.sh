source "$(dirname "$0")/lib.sh"
# Every config users copy must validate, the templates included (each
# also runs in some test; configs/templates/concurrent_tension.yaml in
# template_concurrent_tension).
n=0
for f in "$ROOT"/configs/*.yaml "$ROOT"/configs/templates/*.yaml; do
  "$PBMS" validate "$f" || fail "$f does not validate"
  n=$((n + 1))
done
[ "$n" -ge 2 ] || fail "expected at least quickstart.yaml and md_reference.yaml"
echo "$n passed, 0 failed"
