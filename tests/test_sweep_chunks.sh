#!/usr/bin/env bash
# test_sweep_chunks.sh - the accuracy sweep split into chunks of samples per n (a GPU's launch:
# accuracy.c sweep_chunks) gives the figures of the unsplit sweep (a CPU device's launch): the
# same samples are evaluated, and the largest of each n's chunk maxima is the maximum over all
# of them. The expectation is the program's own unsplit run (BRDFBENCH_SWEEP_CHUNKS=1), a
# second path through the kernel and the host: every figure, its position and status, the
# invalid-value count and its first position must be equal, for built-in lobes, a model that
# sees only c (phongpow), a user model with invalid values (negative past c = 0.5), a user model as
# the reference (its values a table from the host), and the
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
same() {   # same NAME K [values]: the figures of the unsplit run and of K chunks ("values": the
           # values alone, for a model whose maximum is tied at many samples, where any of them
           # is its position)
    python3 - "$T/$1-1.json" "$T/$1-$2.json" "${3:-}" <<'EOF2'
import json, sys
def figures(path):
    rows = json.load(open(path))["results"]
    keep = ("label", "status", "epicentre", "attenuation", "whole", "invalid")
    out = [{k: r.get(k) for k in keep} for r in rows]
    if sys.argv[3] == "values":
        for r in out:
            for z in ("epicentre", "attenuation", "whole"):
                r[z] = {k: v for k, v in r[z].items() if k not in ("at_n", "at_x")}
    return out
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
# a user model as the reference: the host's values in a table the chunks index by their own samples
UR=(--model 'r=pow(c,n)' --model 'q=1.25f*pow(c,n)' --reference user:r --samples 512 --n-step 25)
run 1 table "${UR[@]}" && ok || bad "user reference, unsplit: $(head -c 300 "$T/err")"
run 8 table "${UR[@]}" && ok || bad "user reference, 8 chunks: $(head -c 300 "$T/err")"
# (1.25 c^n against c^n: delta is 0.25 at every sample, a tie anywhere)
same table 8 values && ok || bad "user reference: figures differ from the unsplit sweep"
# and the figure itself: 1.25 c^n against c^n has delta = 0.25 wherever c^n > 0
python3 -c "
import json, sys
r = [x for x in json.load(open(sys.argv[1]))['results'] if x['label'] == 'q'][0]
assert abs(r['epicentre']['max_rel'] - 0.25) < 1e-6, r['epicentre']
" "$T/table-8.json" && ok || bad "user reference, 8 chunks: delta of 1.25 c^n is 0.25"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
