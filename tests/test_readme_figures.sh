#!/usr/bin/env bash
# test_readme_figures.sh - README's accuracy table holds what the program computes: the models
# of its table (the block between <!-- figures:accuracy --> and <!-- /figures:accuracy -->),
# swept with `brdfbench accuracy` on the grid the table states (the default: n in [2, 1000] step
# 1, 4096 samples per zone), then scripts/readme_tables.py --check compares every figure of the
# table, as printed (4 significant digits, and the n where each max delta occurs), with the
# run's. The expected values are README's own text; the figures under test are a fresh run's.
set -u
BIN=${BRDFBENCH:?BRDFBENCH must name the brdfbench binary}
HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
ROOT=$(dirname "$HERE")
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$T/pocl-cache}"
mkdir -p "$POCL_CACHE_DIR"
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }

# the table's models, by the label each row was generated from (first column: `name` or
# **label**; the names map back through readme_tables.py's table)
models=$(python3 - "$ROOT/README.md" "$ROOT/scripts/readme_tables.py" <<'PY'
import re, sys, importlib.util
spec = importlib.util.spec_from_file_location("rt", sys.argv[2]); rt = importlib.util.module_from_spec(spec)
spec.loader.exec_module(rt)
doc = open(sys.argv[1], encoding="utf-8").read()
block = re.search(r"<!-- figures:accuracy -->\n(.*?)\n<!-- /figures:accuracy -->", doc, re.S).group(1)
by_name = {v[0]: k for k, v in rt.NAMES.items()}
labels = []
for line in block.splitlines()[2:]:
    if not line.startswith("| "):
        continue
    first = line.split(" | ")[0][2:]
    m = re.match(r"\*\*(.+?)\*\*", first)
    labels.append(m.group(1) if m else by_name.get(first, first))
print(",".join(labels))
PY
)
[ -n "$models" ] && ok || bad "README has no accuracy block with rows"
# the grid the table states in its run line
grep -q "n ∈ \[2, 1000\], n step 1, 4096 samples per zone" "$ROOT/README.md" && ok \
    || bad "README's accuracy block does not state the grid this test sweeps"

"$BIN" accuracy --models "$models" --quiet --out "$T/run" >"$T/out" 2>"$T/err"
rc=$?
if [ $rc -eq 77 ]; then echo "no OpenCL device"; echo "0 passed, 0 failed"; exit 77; fi
[ $rc -eq 0 ] && ok || bad "accuracy --models $models exited $rc: $(head -c 300 "$T/err")"
python3 "$ROOT/scripts/readme_tables.py" "$T/run" --check "$ROOT/README.md" --only accuracy && ok \
    || bad "README's accuracy table differs from the run's figures (above)"

echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
