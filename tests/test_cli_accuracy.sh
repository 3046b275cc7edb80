#!/usr/bin/env bash
# test_cli_accuracy.sh - `brdfbench accuracy` end to end: the JSON contract, the CSV, and
# each error path of the foundation (message and exit code; nothing written on bad input).
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init

# A small sweep into a folder; the JSON contract is checked with python's strict parser.
"$BIN" accuracy --models cq2,fq:Q=0.64,lyon:k=3 --n-min 2 --n-max 50 --samples 256 --out "$T/run" >"$T/table" 2>"$T/err"
rc=$?
if [ $rc -eq 77 ]; then echo "no OpenCL device"; echo "0 passed, 0 failed, 1 skipped"; exit 77; fi
[ $rc -eq 0 ] && ok || bad "small sweep exit $rc: $(cat "$T/err")"
jsoncheck cli_accuracy_accuracy_contract "$T/run/accuracy.json" "${INDEP:?INDEP must name the tests/indep binary}" && ok || bad "accuracy.json contract"
# The CSV: a header and one row per model per n (49 values of n, 3 models).
rows=$(($(wc -l <"$T/run/accuracy.csv") - 1))
[ "$rows" -eq 147 ] && ok || bad "accuracy.csv has $rows rows, expected 147"
head -1 "$T/run/accuracy.csv" | grep -q '^model,n,epicentre_max_rel_fraction,epicentre_at_x_rad,attenuation_max_abs' && ok || bad "csv header"
grep -q 'G points/s' "$T/table" && grep -q 'largest difference' "$T/table" && ok || bad "table lacks speed or check line"

# A model with invalid values (negative past c = 0.5, equal to the reference elsewhere): the
# invalid values are counted and located, not folded into a maximum (which is then 0 up to
# rounding, since the model equals c^n wherever it is valid).
"$BIN" accuracy --model 'negpart=c > 0.5 ? pow(c, n) : -1.0' --models negpart --n-max 20 --samples 256 --out "$T/neg" >/dev/null 2>"$T/err" && ok || bad "negpart sweep: $(cat "$T/err")"
jsoncheck cli_accuracy_invalid_values_folded_into_maxima "$T/neg/accuracy.json" && ok || bad "invalid values folded into maxima"

# -h is --help after a command name too.
"$BIN" accuracy -h >"$T/help" 2>&1 && grep -q '^usage: brdfbench accuracy' "$T/help" && ok || bad "accuracy -h"

# Error paths: one line naming the argument and the accepted range, exit 2, nothing written.
sum_before=$(md5sum "$T/run/accuracy.json")
expect 2 "unknown model 'nosuch'" accuracy --models nosuch --out "$T/run"
expect 2 "parameter Q='1.5' must be a number in \[1e-06, 0.999999\]" accuracy --models fq:Q=1.5 --out "$T/run"
expect 2 "no parameter 'z'" accuracy --models lyon:z=2 --out "$T/run"
expect 2 "n-min \(10\) must be below --n-max \(5\)" accuracy --n-min 10 --n-max 5 --out "$T/run"
expect 2 "n-min: '0' is not a finite number in" accuracy --n-min 0 --out "$T/run"
expect 2 "n-min: '-3' is not a finite number" accuracy --n-min -3 --out "$T/run"
expect 2 "n-max: 'nan' is not a finite number" accuracy --n-max nan --out "$T/run"
expect 2 "n-step: 'inf' is not a finite number" accuracy --n-step inf --out "$T/run"
expect 2 "samples: '0' is not an integer in \[16, " accuracy --samples 0 --out "$T/run"
expect 2 "samples: '99999999999' is not an integer in" accuracy --samples 99999999999 --out "$T/run"
expect 2 "samples: 100 is not a multiple of 16" accuracy --samples 100 --out "$T/run"
expect 2 "n-step: 1e-06 gives .* values of n \(accepted: 2 to" accuracy --n-step 1e-6 --out "$T/run"
expect 2 "unknown option '--bogus'" accuracy --bogus
expect 2 "models: missing value" accuracy --models
[ "$(md5sum "$T/run/accuracy.json")" = "$sum_before" ] && ok || bad "a rejected run changed earlier results"

# An output folder that cannot be written: exit 3, earlier results untouched.
expect 3 "cannot create folder" accuracy --models cq2 --n-max 10 --samples 64 --out /proc/brdfbench-nope
# As root, permission bits do not stop a write: the command runs as user nobody (setpriv), with
# a cache folder of its own; where that is impossible the case is a visible skip (exit 77).
mkdir -p "$T/ro" && chmod a-w "$T/ro"
skipped=0
if [ "$(id -u)" -ne 0 ]; then
    expect 3 "not writable" accuracy --models cq2 --n-max 10 --samples 64 --out "$T/ro"
elif command -v setpriv >/dev/null && setpriv --reuid=65534 --regid=65534 --clear-groups true 2>/dev/null; then
    chmod 755 "$T" && mkdir -p "$T/pocl-nobody" && chmod 777 "$T/pocl-nobody"
    POCL_CACHE_DIR="$T/pocl-nobody" setpriv --reuid=65534 --regid=65534 --clear-groups \
        "$BIN" accuracy --models cq2 --n-max 10 --samples 64 --out "$T/ro" >"$T/out" 2>"$T/err"
    rc=$?
    [ $rc -eq 3 ] && grep -q "not writable" "$T/err" && ok || bad "read-only --out as nobody: exit $rc: $(head -c 300 "$T/err")"
else
    skipped=1
    echo "skipped: read-only output folder (running as root without setpriv)"
fi

# A kernel that fails to build: the build log and the options, exit 3.
mkdir -p "$T/kern" && cp "$SRC"/kernels/* "$T/kern/"
echo 'this is not OpenCL C;' >>"$T/kern/accuracy.cl"
expect 3 "building accuracy.cl failed with CL_BUILD_PROGRAM_FAILURE" accuracy --kernel-dir "$T/kern" --models cq2 --n-max 10 --samples 64 --out "$T/k"
grep -q '^build log:' "$T/err" && grep -q '^options:' "$T/err" && ok || bad "build failure lacks log or options"
[ ! -e "$T/k/accuracy.json" ] && ok || bad "failed build wrote results"

# No OpenCL platform: a one-line hint, exit 77.
mkdir -p "$T/novendors"
OCL_ICD_VENDORS="$T/novendors" expect 77 "no OpenCL platform found; install the CPU OpenCL driver: apt-get install pocl-opencl-icd" accuracy --models cq2 --out "$T/nd"

echo "$pass passed, $fail failed, $skipped skipped"
[ "$fail" -eq 0 ] || exit 1
[ "$skipped" -eq 0 ] || exit 77
