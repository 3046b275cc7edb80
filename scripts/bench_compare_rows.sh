#!/usr/bin/env bash
# bench_compare_rows.sh - compare's time and memory against the number of rows (issue 31,
# Medium 5: a linear search per figure made it quadratic). A rows document of an accuracy run
# (4 metrics a row) is copied into documents of N rows with distinct labels; compare reads two
# of them and rows reads one; the script prints wall seconds and peak memory of each. A
# benchmark, not a test: it asserts nothing.
#
#   scripts/bench_compare_rows.sh [BRDFBENCH] [N ...]     (defaults: build/brdfbench, 2000 5000 20000)
set -euo pipefail
cd "$(dirname "$0")/.."
bin=$(realpath "${1:-build/brdfbench}")
shift || true
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(2000 5000 20000)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
"$bin" accuracy --models fq2 --n-max 10 --samples 64 --out acc --quiet
"$bin" rows acc --format json --output rows.json
printf '%8s %12s %12s %12s %12s\n' rows "compare s" "compare MB" "rows s" "rows MB"
for n in "${sizes[@]}"; do
  python3 - "$n" <<'PY'
import copy, json, sys
n = int(sys.argv[1])
d = json.load(open("rows.json"))
base = d["rows"][0]
rows = []
for i in range(n):
    r = copy.deepcopy(base)
    r["row"] = r["model"] = "m%d" % i
    r["keys"] = {"model": "m%d" % i}
    rows.append(r)
d["rows"] = rows
json.dump(d, open("big.json", "w"))
PY
  /usr/bin/time -o t_c -f "%e %M" "$bin" compare big.json big.json --out cmp --quiet >/dev/null 2>&1 || true
  /usr/bin/time -o t_r -f "%e %M" "$bin" rows big.json --output /dev/null >/dev/null 2>&1 || true
  c=$(tail -1 t_c)
  r=$(tail -1 t_r)
  printf '%8s %12s %12s %12s %12s\n' "$n" "${c% *}" "$(( ${c#* } / 1024 ))" "${r% *}" "$(( ${r#* } / 1024 ))"
done
