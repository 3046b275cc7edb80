#!/bin/bash
# same_outputs.sh - do two builds write the same results? Runs `all --quick` and a family fit
# with each binary and compares every JSON file of the two runs field by field, leaving out
# what differs from run to run by nature: dates, the revision, load averages and anything
# timed (rates, seconds, medians, normalised rates, retries, checksums of time-bounded loops,
# the hashes of the kernel sources, ratios of rates, Pareto
# flags that follow the rates). A check for changes meant to leave the figures alone.
# usage: scripts/same_outputs.sh OLD_BINARY NEW_BINARY
set -euo pipefail
[ $# -eq 2 ] || { echo "usage: $0 OLD_BINARY NEW_BINARY" >&2; exit 2; }
out=$(mktemp -d); trap 'rm -rf "$out"' EXIT
for side in old new; do
    bin=$1; [ "$side" = new ] && bin=$2
    export POCL_CACHE_DIR="$out/pocl-$side"
    "$bin" all --quick --quiet --out "$out/$side/all" >/dev/null
    "$bin" fit --quiet --power 3 --n-max 100 --samples 256 --out "$out/$side/fit" >/dev/null
done
python3 - "$out/old" "$out/new" <<'PY'
import json, os, re, sys
old, new = sys.argv[1:3]
timed = re.compile(r'date|git_revision|loadavg|seconds|timings|peak|rate|flops|per_s|_ms|mpixel|gbyte|'
                   r'fraction_of|speed|ratio|launch|wall|median|fma|time|cost|front|pareto|checksum|normalised|disturbed|'
                   r'preemption|kernel_sources|kernel sources|/context/machine|/y\[')
diffs, files = [], 0
def walk(a, b, p):
    if timed.search(p):
        return
    # a rows member's metric says itself whether it is timed (its path does not)
    if isinstance(a, dict) and isinstance(b, dict) and a.get('timed') is True and b.get('timed') is True:
        return
    if type(a) != type(b):
        diffs.append(f"{p}: {a!r:.60} | {b!r:.60}")
    elif isinstance(a, dict):
        for k in sorted(set(a) | set(b)):
            if k not in a or k not in b:
                diffs.append(f"{p}/{k}: only in {'new' if k in b else 'old'}")
            else:
                walk(a[k], b[k], f"{p}/{k}")
    elif isinstance(a, list):
        if len(a) != len(b):
            diffs.append(f"{p}: {len(a)} items | {len(b)} items")
        for i, (x, y) in enumerate(zip(a, b)):
            walk(x, y, f"{p}[{i}]")
    elif isinstance(a, str) and a.replace(old, new) == b:
        return   # the same but for the run's folder
    elif a != b:
        diffs.append(f"{p}: {a!r:.60} | {b!r:.60}")
for root, _, names in os.walk(old):
    for name in sorted(names):
        if name.endswith('.json'):
            rel = os.path.relpath(os.path.join(root, name), old)
            files += 1
            if not os.path.exists(os.path.join(new, rel)):
                diffs.append(f"{rel}: missing in the new run")
                continue
            with open(os.path.join(old, rel)) as fa, open(os.path.join(new, rel)) as fb:
                walk(json.load(fa), json.load(fb), rel + ":")
print("\n".join(diffs))
print(f"{files} JSON files compared, {len(diffs)} differences outside the timed fields")
sys.exit(1 if diffs else 0)
PY
