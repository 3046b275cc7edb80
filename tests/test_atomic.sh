#!/usr/bin/env bash
# test_atomic.sh - a run that fails part-way leaves the previous run folder and
# results/latest as they were, leaves no temporary files, and exits 3:
#   - output to a full device: the gate's reports to /dev/full (ENOSPC); the accuracy
#     results with the file size limit at 2 KiB (EFBIG: the sweep runs, its files cannot be
#     written); and, where the kernel lets an unprivileged user mount one, a tmpfs that is
#     full (ENOSPC);
#   - output to a read-only folder (as root the command runs as user nobody, since root
#     writes through permission bits).
set -u
BIN=${BRDFBENCH:?BRDFBENCH must name the brdfbench binary}
SRC=${SRC_DIR:?}
T=$(mktemp -d)
chmod 755 "$T"
trap 'chmod -R u+w "$T" 2>/dev/null; rm -rf "$T"' EXIT
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
cd "$T" || exit 1
skipped=0
skip() { skipped=$((skipped + 1)); echo "skipped: $*"; }

# 39801 values of n: accuracy.json is about 2.4 KB, accuracy.csv about 3.9 MB.
ARGS=(accuracy --models cq2 --n-min 2 --n-max 400 --n-step 0.01 --samples 64 --quiet)

# The previous run: a run folder and results/latest pointing at it, with a fingerprint of
# every file in the results tree.
"$BIN" "${ARGS[@]}" 2>"$T/err"
rc=$?
if [ $rc -eq 77 ]; then echo "no OpenCL device"; echo "0 passed, 0 failed, 1 skipped"; exit 77; fi
[ $rc -eq 0 ] && ok || bad "the first run: exit $rc: $(cat "$T/err")"
previous=$(readlink results/latest)
[ -n "$previous" ] && [ -s "results/$previous/accuracy.json" ] && ok || bad "no previous run folder"
fingerprint() { (cd "$T/results/$previous" && sha256sum accuracy.json accuracy.csv); readlink "$T/results/latest"; }
before=$(fingerprint)

# intact WHAT: the previous run and results/latest are unchanged, and no temporary file is left.
intact() {
    [ "$(fingerprint)" = "$before" ] && ok || bad "$1: the previous run folder or results/latest changed"
    local tmps
    tmps=$(find "$T/results" -name '*.tmp*' 2>/dev/null)
    [ -z "$tmps" ] && ok || bad "$1: temporary files left: $tmps"
}
# fails WHAT CODE PATTERN: the last command exited CODE with a stderr line matching PATTERN.
fails() {
    [ "$rc" -eq "$2" ] && grep -qE -- "$3" "$T/err" && ok || bad "$1: exit $rc, stderr: $(head -c 300 "$T/err")"
}

# 1. A full device: a file size limit of 3 MB lets the sweep run (and the OpenCL driver write
#    its cache) and accuracy.json be written, and stops accuracy.csv part-way. SIGXFSZ is
#    ignored, so write() fails with EFBIG instead of killing the process.
(trap '' XFSZ; ulimit -f 3000; exec "$BIN" "${ARGS[@]}") 2>"$T/err"
rc=$?
fails "file size limit" 3 "^brdfbench accuracy: cannot write results/[^/]+/accuracy.csv: File too large"
intact "file size limit"

# 2. /dev/full: the gate's reports cannot be written (ENOSPC); the JUnit file written
#    before it is whole, and the results tree is untouched.
printf '{"gates":[{"model":"cq2","metric":"epicentre.max_rel","n_max":40,"samples":64,"max":1}]}' >gates.json
"$BIN" gate gates.json --junit junit.xml --json /dev/full --quiet >"$T/out" 2>"$T/err"
rc=$?
fails "gate --json /dev/full" 3 "^brdfbench gate: cannot write /dev/full: No space left on device"
[ -c /dev/full ] && ok || bad "/dev/full is no longer a device"
python3 -c 'import sys, xml.etree.ElementTree as E; assert E.parse(sys.argv[1]).getroot().get("tests") == "1"' junit.xml \
    && ok || bad "junit.xml is not whole"
"$BIN" gate gates.json --junit /dev/full --quiet >"$T/out" 2>"$T/err"
rc=$?
fails "gate --junit /dev/full" 3 "^brdfbench gate: cannot write /dev/full: No space left on device"
intact "/dev/full"

# 3. A read-only results folder.
runas=()
if [ "$(id -u)" -eq 0 ]; then
    if command -v setpriv >/dev/null; then
        runas=(setpriv --reuid=65534 --regid=65534 --clear-groups)
        mkdir -p "$T/pocl-nobody" && chmod 777 "$T/pocl-nobody"
    else
        runas=(none)
    fi
fi
if [ "${runas[0]:-}" = none ]; then
    skip "read-only folder: running as root without setpriv"
else
    chmod -R a-w "$T/results"
    cache=${POCL_CACHE_DIR:-$T/pocl}
    [ ${#runas[@]} -gt 0 ] && cache=$T/pocl-nobody
    POCL_CACHE_DIR=$cache "${runas[@]}" "$BIN" "${ARGS[@]}" 2>"$T/err"
    rc=$?
    fails "read-only results folder" 3 "^brdfbench accuracy: folder results is not writable: Permission denied"
    chmod -R u+w "$T/results"
    intact "read-only results folder"
fi

# 4. A full file system: a small tmpfs filled to the last byte, in a private mount namespace
#    (a user namespace where the kernel allows one; as root, a plain mount namespace).
userns=()
if unshare -rm true 2>/dev/null; then
    userns=(unshare -rm)
elif [ "$(id -u)" -eq 0 ] && unshare -m true 2>/dev/null; then
    userns=(unshare -m)
fi
if [ ${#userns[@]} -gt 0 ]; then
    mkdir -p "$T/small"
    "${userns[@]}" bash -c '
        T=$1 BIN=$2 previous=$3
        mount -t tmpfs -o size=16m tmpfs "$1/small" || exit 90
        cp -a "$T/results" "$T/small/results"
        dd if=/dev/zero of="$T/small/filler" bs=4k 2>/dev/null
        shift 3
        cd "$T/small" && "$BIN" "$@" 2>"$T/err"
        rc=$?
        rm -f "$T/small/filler"
        (cd "$T/small/results/$previous" && sha256sum accuracy.json accuracy.csv; readlink "$T/small/results/latest") >"$T/after"
        find "$T/small/results" -name "*.tmp*" >"$T/tmps"
        exit $rc' _ "$T" "$BIN" "$previous" "${ARGS[@]}"
    rc=$?
    if [ $rc -eq 90 ]; then
        skip "full tmpfs: mounting a tmpfs failed"
    else
        fails "full tmpfs" 3 "^brdfbench accuracy: cannot (write results/[^/]+/accuracy.(json|csv)|create run folder results/[^ ]+): No space left on device"
        [ "$(cat "$T/after")" = "$before" ] && ok || bad "full tmpfs: the previous run or latest changed"
        [ ! -s "$T/tmps" ] && ok || bad "full tmpfs: temporary files left: $(cat "$T/tmps")"
    fi
else
    skip "full tmpfs: no mount namespace can be made here"
fi

# A skipped case is not a pass: ctest shows the test as skipped (77) unless a case failed.
echo "$pass passed, $fail failed, $skipped skipped"
[ "$fail" -eq 0 ] || exit 1
[ "$skipped" -eq 0 ] || exit 77
