#!/usr/bin/env bash
# test_sweep_chunks.sh - the accuracy sweep split into chunks of samples per n (a GPU's launch:
# accuracy.c sweep_chunks) gives the figures of the unsplit sweep (a CPU device's launch): the
# same samples are evaluated, and the largest of each n's chunk maxima is the maximum over all
# of them. The expectation is the program's own unsplit run (BRDFBENCH_SWEEP_CHUNKS=1), a
# second path through the kernel and the host: every figure, its position and status, the
# invalid-value count and its first position must be equal, for built-in lobes, a model that
# sees only c (phongpow), a user model with invalid values (negative past c = 0.5), and the
# smallest chunk (16 samples).
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$T/pocl-cache}"
run() {   # run CHUNKS NAME ARGS...
    local k=$1 name=$2
    shift 2
    BRDFBENCH_SWEEP_CHUNKS=$k "$BIN" accuracy "$@" --json "$T/$name-$k.json" >"$T/out" 2>"$T/err"
}
same() {   # same NAME K: the figures of the unsplit run and of K chunks
    python3 - "$T/$1-1.json" "$T/$1-$2.json" <<'EOF2'
import json, sys
def figures(path):
    rows = json.load(open(path))["results"]
    keep = ("label", "status", "epicentre", "attenuation", "whole", "invalid")
    return [{k: r.get(k) for k in keep} for r in rows]
a, b = figures(sys.argv[1]), figures(sys.argv[2])
assert len(a) > 0 and a == b, [(x, y) for x, y in zip(a, b) if x != y][:2]
EOF2
}
ARGS=(--models fvol,cq2,phongpow,ggx,schlick --samples 1024 --n-step 7)
run 1 lobes "${ARGS[@]}"
rc=$?
if [ $rc -eq 77 ]; then echo "no OpenCL device"; echo "0 passed, 0 failed"; exit 77; fi
[ $rc -eq 0 ] && ok || bad "unsplit sweep: exit $rc: $(head -c 300 "$T/err")"
for k in 4 64; do
    run $k lobes "${ARGS[@]}" && ok || bad "$k chunks: $(head -c 300 "$T/err")"
    same lobes $k && ok || bad "$k chunks: figures differ from the unsplit sweep"
done
# invalid values: 1 - 4 s^2... written so that it is negative for s > 0.5 (c < 0.5)
UM=(--model 'neg=(1.0f - 2.0f * (1.0f - c)) * pow(c, n)' --samples 256 --n-step 50)
run 1 neg "${UM[@]}" && ok || bad "user model, unsplit: $(head -c 300 "$T/err")"
run 16 neg "${UM[@]}" && ok || bad "user model, 16 chunks: $(head -c 300 "$T/err")"
same neg 16 && ok || bad "user model: figures or invalid counts differ"
python3 -c "
import json, sys
r = json.load(open(sys.argv[1]))['results'][0]
assert r['invalid']['count'] > 0, r['invalid']
" "$T/neg-16.json" && ok || bad "the user model's negative values are counted"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
