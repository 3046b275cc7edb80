#!/usr/bin/env bash
# test_deadline.sh - every kernel launch has a deadline (docs/architecture.md, habit 12): a user model
# whose loop never ends stops `accuracy`, `gate` and `all` with exit 3 and one line naming
# the kernel and the model (a program build past it: the program), well within the deadline plus a margin, leaving no folder it
# made and no file half-written; a folder or file that existed before stays as it was.
# The deadline comes from --timeout or the gates file's "timeout" (the flag wins).
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init
cd "$T" || exit 1
cp "$SRC/tests/test_usermodel_files/spin.cl" .

# runaway LABEL DEADLINE ARGS...: runs brdfbench ARGS in a fresh folder (which must stay
# empty apart from what the test put there); asserts exit 3, one stderr line naming the
# sweep kernel, model spin and the deadline, and an end within DEADLINE + 15 s (a bound on
# a hang, generous for a loaded machine; the kill at DEADLINE + 20 s only keeps a broken build from
# hanging the suite).
runaway() {
    local label=$1 deadline=$2
    shift 2
    local t0 t1 rc
    t0=$(date +%s)
    timeout -s KILL $((deadline + 20)) "$BIN" "$@" >"$T/out" 2>"$T/err"
    rc=$?
    t1=$(date +%s)
    if [ "$rc" -eq 77 ]; then echo "no OpenCL device"; echo "0 passed, 0 failed, 1 skipped"; exit 77; fi
    [ "$rc" -eq 3 ] && ok || bad "$label: exit $rc, expected 3: $(head -c 600 "$T/err")"
    local n
    n=$(grep -c "ran past its deadline" "$T/err")
    [ "$n" -eq 1 ] && ok || bad "$label: $n deadline lines on stderr: $(head -c 600 "$T/err")"
    grep -qE "^brdfbench: kernel ${KERNEL:-accuracy_sweep} of model 'spin' ran past its deadline of $deadline s \(accepted: --timeout SECONDS" "$T/err" \
        && ok || bad "$label: message does not name kernel, model and deadline: $(head -c 600 "$T/err")"
    [ $((t1 - t0)) -lt $((deadline + 15)) ] && ok || bad "$label: ended after $((t1 - t0)) s (deadline $deadline s)"
}

# accuracy: --out names a folder that does not exist yet, nor does its parent.
runaway "accuracy --out" 4 accuracy --model-file spin.cl --n-max 20 --out new/run --timeout 4
[ ! -e new ] && ok || bad "accuracy left $(find new | head -5 | tr '\n' ' ')"
# accuracy without --out: results/ and its run folder are made by the run, and removed.
runaway "accuracy (results/)" 4 accuracy --model-file spin.cl --n-max 20 --timeout 4
[ ! -e results ] && ok || bad "accuracy left $(find results | head -5 | tr '\n' ' ')"
# A folder that existed before stays, with what it held and nothing more.
mkdir kept && echo before >kept/note.txt
runaway "accuracy --out existing" 4 accuracy --model-file spin.cl --n-max 20 --out kept --timeout 4
[ "$(ls -A kept)" = note.txt ] && [ "$(cat kept/note.txt)" = before ] && ok \
    || bad "the existing folder changed: $(ls -A kept | tr '\n' ' ')"

# gate: the deadline from the gates file; the reports that existed stay as they were.
printf '{"timeout": 2, "gates": [{"model": "spin", "model_file": "spin.cl", "metric": "whole.max_abs", "n_max": 20, "max": 1}]}\n' >g.json
echo old-json >gates.json
echo old-xml >gates.xml
runaway "gate (file timeout)" 2 gate g.json --json gates.json --junit gates.xml
[ "$(cat gates.json)" = old-json ] && [ "$(cat gates.xml)" = old-xml ] && ok || bad "gate replaced its earlier reports"
# --timeout wins over the file's.
printf '{"timeout": 600, "gates": [{"model": "spin", "model_file": "spin.cl", "metric": "whole.max_abs", "n_max": 20, "max": 1}]}\n' >g600.json
runaway "gate --timeout over the file" 3 gate g600.json --timeout 3

# render: the shading kernel, named with the model it shades.
KERNEL=shade runaway "render --out" 4 render --scene spheres --model-file spin.cl --models spin --size 320x200 \
    --time-sizes none --out rrun --timeout 4
[ ! -e rrun ] && ok || bad "render left $(find rrun | head -5 | tr '\n' ' ')"

# all: its run folder is removed.
runaway "all --out" 3 all --quick --model-file spin.cl --out allrun --timeout 3
[ ! -e allrun ] && ok || bad "all left $(find allrun | head -5 | tr '\n' ' ')"

# Nothing else appeared in the test's folder (no temporary files beside the reports).
left=$(ls -A | grep -v -x -e spin.cl -e kept -e g.json -e g600.json -e gates.json -e gates.xml -e out -e err)
[ -z "$left" ] && ok || bad "left behind: $left"

# A program build is under the deadline too: with a cache of its own (a cold build) and a
# deadline of 10 ms, the build of the accuracy program cannot finish in time; one line names
# the program and its options, exit 3, no folder left.
POCL_CACHE_DIR="$T/coldcache" "$BIN" accuracy --models fq2 --n-max 8 --samples 16 --out coldrun --timeout 0.01 \
    >"$T/out" 2>"$T/err"
rc=$?
[ "$rc" -eq 3 ] && ok || bad "a build past its deadline: exit $rc, expected 3: $(head -c 400 "$T/err")"
grep -qE "^brdfbench: building kernels/accuracy.cl.* ran past its deadline of 0.01 s" "$T/err" && ok ||
    bad "a build past its deadline: message $(head -c 400 "$T/err")"
[ ! -e coldrun ] && ok || bad "a build past its deadline left its folder"
rm -rf "$T/coldcache"

# The flag and the key are checked like any other value.
expect 2 "^brdfbench accuracy: --timeout: '0' is not a finite number in \[0.01, 604800\]" accuracy --timeout 0
printf '{"timeout": -1, "gates": [{"model": "fq2", "metric": "whole.max_abs", "max": 1}]}\n' >gneg.json
expect 2 "^brdfbench gate: gneg.json:1:[0-9]+: \"timeout\" -1 is out of range \(accepted: seconds in \[0.01, 604800\]\)" gate gneg.json
rm -f gneg.json

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
