#!/usr/bin/env bash
# bench_reproduce_stability.sh - do `brdfbench reproduce` runs agree? RUNS runs one after the
# other (the same binary, the same flags), a table of every row's verdict per run, and whether
# every row has one verdict in all of them.
#
#   bash scripts/bench_reproduce_stability.sh [RUNS]      (default 5)
#
# Environment: BRDFBENCH (default build/brdfbench), REPRO_FLAGS (extra flags for reproduce),
# KEEP=1 to keep the runs (their folder is printed). A benchmark, not a test: its result goes
# into notes, never into assertions. Exit status 0 whatever the verdicts.
set -euo pipefail
cd "$(dirname "$0")/.."
B=${BRDFBENCH:-build/brdfbench}
RUNS=${1:-5}
W=$(mktemp -d)
[ -n "${KEEP:-}" ] && echo "runs kept in $W" || trap 'rm -rf "$W"' EXIT

for r in $(seq 1 "$RUNS"); do
    start=$(date +%s)
    "$B" reproduce --quiet ${REPRO_FLAGS:-} --out "$W/run$r" >/dev/null
    echo "run $r: $(( $(date +%s) - start )) s, load $(cut -d' ' -f1-3 /proc/loadavg)" >&2
done

python3 - "$W" "$RUNS" <<'PY'
import json, sys
w, runs = sys.argv[1], int(sys.argv[2])
docs = [json.load(open(f"{w}/run{r}/claims.json")) for r in range(1, runs + 1)]
ids = [c["id"] for c in docs[0]["claims"]]
short = {"reproduced": "yes", "not reproduced": "no", "within noise": "noise"}
verdicts = {i: [] for i in ids}
for d in docs:
    got = {c["id"]: c["verdict"] for c in d["claims"]}
    for i in ids:
        verdicts[i].append(short.get(got.get(i, "missing"), got.get(i, "missing")))
print(f"{'id':24} " + " ".join(f"run{r:<3}" for r in range(1, runs + 1)) + "  agree")
flipping = []
for i in ids:
    v = verdicts[i]
    same = len(set(v)) == 1
    if not same:
        flipping.append(i)
    print(f"{i:24} " + " ".join(f"{x:6}" for x in v) + ("  yes" if same else "  NO"))
for r, d in enumerate(docs, 1):
    s = d["summary"]
    print(f"run {r}: " + ", ".join(f"{k} {v}" for k, v in s.items() if isinstance(v, int)))
# the cost rows' ratios run by run (physical.json): how far identical runs move them
phys = []
for r in range(1, runs + 1):
    try:
        phys.append({x["model"]: x for x in json.load(open(f"{w}/run{r}/physical.json"))["cost"]["rows"]})
    except OSError:
        phys = []
        break
if phys:
    print("\nphysically based rows, evaluations/s over Phong's per run (min-max spread: max/min):")
    for name, row in phys[0].items():
        if not row.get("physically_based"):
            continue
        v = [p[name]["ratio_to_phong"] for p in phys if name in p]
        verd = [p[name].get("vs_phong", {}).get("verdict", "") for p in phys if name in p]
        print(f"  {name:20} " + " ".join(f"{x:7.3f}" for x in v) + f"   spread {max(v) / min(v):.3f}"
              + (f"   verdicts {','.join(sorted(set(verd)))}" if any(verd) else ""))
print(f"{len(ids)} rows, {len(ids) - len(flipping)} agree in all {runs} runs"
      + (f"; differing: {', '.join(flipping)}" if flipping else "; every row agrees"))
PY
