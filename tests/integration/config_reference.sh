source "$(dirname "$0")/lib.sh"
# docs/config-reference.md is generated from the schema; it must be current,
# and it must show every nested key: each key whose value is a map, or a
# list or named map of maps, has a table of its own (`#### kind.key`, per
# variant where a discriminator picks the keys), except regions, which the
# Regions section describes once.
"$ROOT/build/bin/coupler" reference > generated.md
if ! diff -u "$ROOT/docs/config-reference.md" generated.md; then
  fail "docs/config-reference.md is stale: run ./pbms reference > docs/config-reference.md"
fi
"$PY" - generated.md <<'PYEOF'
import re, sys
text = open(sys.argv[1]).read()
headings = [h.split(" with ")[0].strip("`") for h in re.findall(r"^#### (.+)$", text, re.M)]
missing, prefix, checked = [], None, 0
for line in text.splitlines():
    m = re.match(r"^### (?:stage|material) kind `([^`]+)`", line)
    if m:
        prefix = m.group(1)
        continue
    m = re.match(r"^## `([^`]+)`", line)
    if m:
        prefix = m.group(1)
        continue
    if line.startswith("## ") or line.startswith("### ") or line.startswith("Outputs"):
        prefix = None
        continue
    m = re.match(r"^#### `([^`]+)`", line)
    if m:
        prefix = m.group(1)
        continue
    m = re.match(r"^\| `([^`]+)` \| (map|list of map|map of map) \|[^|]*\|(.*)\|$", line)
    if not m or prefix is None or "A region" in m.group(3):
        continue
    checked += 1
    key = f"{prefix}.{m.group(1)}"
    if not any(h in (key, key + "[]", key + ".<name>") for h in headings):
        missing.append(key)
print(f"{checked} nested maps, {len(missing)} without a table of their keys")
for k in missing:
    print("FAIL no table for", k)
if "## Regions" not in text or text.count("### region style") < 3:
    print("FAIL no Regions section with the styles")
    sys.exit(1)
sys.exit(1 if missing else 0)
PYEOF
echo "1 passed, 0 failed"
