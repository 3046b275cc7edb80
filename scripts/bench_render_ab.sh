#!/bin/bash
# bench_render_ab.sh - two builds' shading rates side by side: `render` of the sphere grid with
# each binary in alternation (old, new, old, new, ...), so that the machine's load falls on both
# alike, then per model the median Mpixel/s of each side over the rounds and their ratio
# new/old, and the median of the ratios. For a change meant to leave kernels/shade.cl's speed alone.
# usage: scripts/bench_render_ab.sh OLD_BINARY NEW_BINARY [ROUNDS (default 5)] [MODELS (default phong,fq2,blinn)]
set -euo pipefail
[ $# -ge 2 ] || { echo "usage: $0 OLD_BINARY NEW_BINARY [ROUNDS] [MODELS]" >&2; exit 2; }
old=$1 new=$2 rounds=${3:-5} models=${4:-phong,fq2,blinn}
out=$(mktemp -d); trap 'rm -rf "$out"' EXIT
for r in $(seq "$rounds"); do
    for side in old new; do
        bin=$old; [ "$side" = new ] && bin=$new
        "$bin" render --scene spheres --models "$models" --size 640x360 --time-sizes 1920x1080 --reps 7 \
            --no-images --quiet --json "$out/$side-$r.json" >/dev/null
    done
done
python3 - "$out" "$rounds" <<'PY'
import json, statistics, sys
out, rounds = sys.argv[1], int(sys.argv[2])
def rates(path):
    rows = json.load(open(path))['rows']['rows']
    return {(r['row'], m['name']): m['value'] for r in rows for m in r['metrics'] if m.get('timed')}
old = [rates(f'{out}/old-{i}.json') for i in range(1, rounds + 1)]
new = [rates(f'{out}/new-{i}.json') for i in range(1, rounds + 1)]
ratios = []
for k in old[0]:
    mo, mn = statistics.median(x[k] for x in old), statistics.median(x[k] for x in new)
    ratios.append(mn / mo)
    print(f'{k[0]:28s} {k[1]:26s} old {mo:9.1f}  new {mn:9.1f}  new/old {mn / mo:.3f}')
print(f'median of the ratios new/old: {statistics.median(ratios):.3f} ({rounds} rounds each, alternating)')
PY
