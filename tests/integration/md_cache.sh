source "$(dirname "$0")/lib.sh"
export PBMS_NO_PLOTS=1  # the runs here are checked by their numbers, not their plots
# MD results are kept in <output>/.cache/ and reused: a second run under a new
# name whose MD stage is unchanged, but whose later stage is, runs no LAMMPS
# and gets the same numbers and files; a changed MD parameter misses the
# cache and runs MD again, and so does a potential file edited in place
# (the cache holds its contents' digest, not its name).
write() {  # write NAME STRAIN CELLS [POTENTIAL]
  cat > "$1.yaml" <<YAML
run: {name: $1, seed: 5}
launch: {md: 1, dpd: 1}
materials:
  cu:
    kind: eam_alloy
    potential: ${4:-/usr/share/lammps/potentials/Cu_mishin1.eam.alloy}
    mass: 63.546
    lattice_constant: 3.615
  cu_cg:
    kind: dpd_mesoparticle
    mass: 508.37
    lattice_constant: 7.23
    potential_file: $ROOT/configs/potentials/cu_cg_morse.yaml
stages:
  - {name: elastic, kind: md_elastic, material: cu, cells: [3, 3, 3], strain: $2}
  - {name: dpd, kind: dpd_elastic, material: cu_cg, temperature: 0, cells: $3}
YAML
}
write first 1.0e-3 3
write second 1.0e-3 4
write third 2.0e-3 3
for n in first second third; do
  "$PBMS" run $n.yaml > out_$n.txt 2>&1 || { cat out_$n.txt; fail "run $n"; }
done
grep -q "reused from the cache" runs/first/log.txt && fail "the first run found a cache entry"
grep -q "reused from the cache" runs/second/log.txt || fail "the second run ran MD again"
grep -q "reused from the cache" runs/third/log.txt && fail "a changed strain reused the cache"
ls runs/.cache/*/identity.txt > /dev/null || fail "no cache entry"
"$PY" - <<'PYEOF'
import sys, yaml, filecmp, os
def res(n):
    return yaml.safe_load(open(f"runs/{n}/summary.yaml"))["stages"]["elastic"]["results"]
a, b, c = res("first"), res("second"), res("third")
bad = 0
for k in ("c11", "c12", "c44"):
    same = a[k]["value"] == b[k]["value"]
    bad += not same
    print(f"{'ok  ' if same else 'FAIL'} {k}: {a[k]['value']} (run) and {b[k]['value']} (cache) are equal")
# The cached run has the LAMMPS inputs of the run that computed it.
files = sorted(os.listdir("runs/first/elastic"))
same = files and files == sorted(os.listdir("runs/second/elastic")) and all(
    filecmp.cmp(f"runs/first/elastic/{f}", f"runs/second/elastic/{f}", shallow=False) for f in files)
bad += not same
print(f"{'ok  ' if same else 'FAIL'} the stage's {len(files)} files are restored from the cache")
differs = a["c11"]["value"] != c["c11"]["value"]
print(f"{'ok  ' if differs else 'FAIL'} strain 2e-3 computed anew: c11 {c['c11']['value']}")
bad += not differs
sys.exit(1 if bad else 0)
PYEOF

# The same potential file, edited in place between two runs. Only its first
# comment line changes (LAMMPS skips it, so MD would give the same numbers):
# the smallest change of contents must still miss the cache.
cp /usr/share/lammps/potentials/Cu_mishin1.eam.alloy mine.eam.alloy
write own_a 1.0e-3 3 "$PWD/mine.eam.alloy"
write own_b 1.0e-3 4 "$PWD/mine.eam.alloy"
"$PBMS" run own_a.yaml > out_own_a.txt 2>&1 || { cat out_own_a.txt; fail "run own_a"; }
sed -i '1s/.*/edited by the test/' mine.eam.alloy
"$PBMS" run own_b.yaml > out_own_b.txt 2>&1 || { cat out_own_b.txt; fail "run own_b"; }
grep -q "reused from the cache" runs/own_b/log.txt &&
  fail "a potential file edited in place reused the cache entry of its old contents"
echo "ok   a potential file edited in place (same path) misses the cache"
echo "1 passed, 0 failed"
