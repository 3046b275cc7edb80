#!/bin/bash
# bench_rows_member.sh - what carrying the rows costs: the size of each result file with and
# without its "rows" member, and the time `brdfbench rows FILE --format json` takes to read it
# through the member and through the previous version's layout (the upgrade function); medians
# of N runs (default 20) and their ratio, in one run. The files are one small run of each kind.
# usage: scripts/bench_rows_member.sh [BINARY] [N]
set -euo pipefail
bin=${1:-build/brdfbench}; n=${2:-20}
bin=$(readlink -f "$bin")
out=$(mktemp -d); trap 'rm -rf "$out"' EXIT
cd "$out"
"$bin" throughput --models fq2,cq2,phong --variants default --n-modes uniform,varying --no-sweep --no-host-c \
    --reps 10 --min-time 0.001 --json throughput.json >/dev/null 2>&1
"$bin" render --scene spheres --models phong,fq2,cq2 --size 64x32 --time-sizes 64x32 --reps 10 --warmup 0 \
    --json render.json >/dev/null 2>&1
"$bin" fit --n-min 2 --n-max 100 --samples 64 --json fit.json --quiet >/dev/null 2>&1
"$bin" frontier --models phong,fq2,cq2 --samples 64 --reps 1 --rounds 1 --no-image --json frontier.json >/dev/null 2>&1
python3 - "$bin" "$n" <<'PY'
import json, statistics, subprocess, sys, time
bin, n = sys.argv[1], int(sys.argv[2])
prev = {"throughput": "brdfbench.throughput/3", "render": "brdfbench.render/1", "fit": "brdfbench.fit/1",
        "frontier": "brdfbench.frontier/1"}
print("bytes: the file, and without its rows (as indented JSON); read: median of %d runs of `rows FILE --format json`" % n)
print("%-10s %9s %9s %12s %12s %7s" % ("kind", "bytes", "no rows", "read rows", "read layout", "ratio"))
for k, s in prev.items():
    d = json.load(open(k + ".json"))
    size = len(json.dumps(d, indent=2))   # both sizes in one formatting
    d.pop("rows")
    d["schema"] = s
    json.dump(d, open("prev_" + k + ".json", "w"), indent=2)
    def med(path):
        t = []
        for _ in range(n):
            t0 = time.perf_counter()
            subprocess.run([bin, "rows", path, "--format", "json"], stdout=subprocess.DEVNULL, check=True)
            t.append(time.perf_counter() - t0)
        return statistics.median(t)
    a, b = med(k + ".json"), med("prev_" + k + ".json")
    print("%-10s %9d %9d %10.1fms %10.1fms %6.2fx" % (k, size, len(open("prev_" + k + ".json").read()),
                                                      a * 1e3, b * 1e3, a / b))
PY
