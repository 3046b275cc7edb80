#!/usr/bin/env bash
# test_nodevice.sh - with no OpenCL device (the ICD loader pointed at an empty vendors
# folder through OCL_ICD_VENDORS), every command that needs a device prints a one-line hint
# and exits 77, writing nothing; list still lists the models and says no device was found.
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init
mkdir -p "$T/vendors"
export OCL_ICD_VENDORS=$T/vendors
HINT='no OpenCL platform found; install the CPU OpenCL driver: apt-get install pocl-opencl-icd'

printf '{"gates":[{"model":"fq2","metric":"epicentre.max_rel","max":0.0126}]}' >"$T/gates.json"
# nodevice NAME ARGS...: exit 77, exactly one line on stderr with the hint, no output folder.
nodevice() {
    local name=$1
    shift
    (cd "$T" && "$BIN" "$@" >"$T/out" 2>"$T/err")
    local rc=$?
    [ "$rc" -eq 77 ] || { bad "$name: exit $rc, expected 77: $(head -c 300 "$T/err")"; return; }
    [ "$(wc -l <"$T/err")" -eq 1 ] || { bad "$name: $(wc -l <"$T/err") lines on stderr, expected one"; return; }
    grep -qF "brdfbench $name: $HINT" "$T/err" || { bad "$name: message '$(cat "$T/err")'"; return; }
    [ ! -e "$T/run" ] && [ ! -e "$T/results" ] || { bad "$name wrote results without a device"; rm -rf "$T/run" "$T/results"; return; }
    ok
}
nodevice accuracy accuracy --n-max 4 --samples 16 --out run
nodevice accuracy accuracy --n-max 4 --samples 16
nodevice gate gate gates.json --json run.json
nodevice render render --out run
nodevice all all --quick --out run
[ ! -e "$T/run.json" ] && ok || bad "gate wrote its JSON without a device"
nodevice fit fit --out run
nodevice throughput throughput --out run
nodevice reproduce reproduce --out run
nodevice fit fit
nodevice throughput throughput
nodevice reproduce reproduce

"$BIN" list >"$T/out" 2>"$T/err"
rc=$?
[ $rc -eq 0 ] && grep -q "none found" "$T/out" && grep -q "fq2" "$T/out" && ok \
    || bad "list without a device: exit $rc: $(tail -2 "$T/out")"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
