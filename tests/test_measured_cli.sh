#!/bin/bash
# test_measured_cli.sh - `brdfbench measured` on MERL files written by tests/merl_synth (the
# test's own writer): a Blinn-Phong material (n = 64, ks = 2.5, kd = 0.08) whose fit the
# command must give back, its outputs (measured.json with its schema and context, the table,
# both pictures), and the malformed files and bad arguments, each refused with exit 2, its own
# message, and no measured.json written.
. "$(dirname "$0")/testlib.sh"
brdf_test_init
SYN=${MERL_SYNTH:?MERL_SYNTH must name the merl_synth writer}
mkdir -p "$T/mats"
"$SYN" "$T/mats/blinn64.binary" blinn 64 2.5 0.08 neg 70 72 || { echo "cannot write the material"; exit 3; }

"$BIN" measured "$T/mats" --out "$T/run" --fit-cells 5000 >"$T/table" 2>"$T/err"
rc=$?
if [ "$rc" -eq 77 ]; then echo "no OpenCL device: skipped"; exit 77; fi
[ "$rc" -eq 0 ] && ok || bad "measured exit $rc: $(head -c 400 "$T/err")"
grep -qE '^  blinn-phong  n 64 ' "$T/table" && ok || bad "table lacks the fitted n: $(head -3 "$T/table")"
grep -qE '^  fq2 ' "$T/table" && ok || bad "table lacks the lobe fq2"
for f in measured_errors_blinn64.png measured_slice_blinn64.png; do
    [ -s "$T/run/$f" ] && ok || bad "$f not written"
done
# 2 theta_h cells x 90 x 180 = 32400 cells marked negative in green
jsoncheck measured_cli_measured "$T/run/measured.json" && ok || bad "measured.json"

# malformed files: each its own message, exit 2, nothing written
"$SYN" "$T/short.binary" pattern short
"$SYN" "$T/dims.binary" pattern dims360
"$SYN" "$T/nan.binary" pattern nan
expect 2 'short\.binary: size 34992011 bytes, 1 short of the 34992012' measured "$T/short.binary" --out "$T/bad1"
expect 2 'dims\.binary: dimensions 90 90 360 \(expected 90 90 180, product 1458000\)' measured "$T/dims.binary" --out "$T/bad2"
expect 2 "nan\\.binary: the blue block's cell 1000 \\(theta_h 0, theta_d 5, phi_d 100\\) is NaN" measured "$T/nan.binary" --out "$T/bad3"
# a good file before a bad one: still nothing written
expect 2 'nan\.binary: .* is NaN' measured "$T/mats/blinn64.binary" "$T/nan.binary" --out "$T/bad4"
for d in bad1 bad2 bad3 bad4; do
    [ ! -e "$T/$d/measured.json" ] && ok || bad "$d/measured.json written after a refusal"
done
expect 2 'expected a MERL \.binary file or a folder' measured
expect 2 'absent\.binary: No such file' measured "$T/absent.binary"
mkdir -p "$T/empty"
expect 2 'empty: no \.binary files in the folder' measured "$T/empty"
expect 2 '--fit-cells' measured "$T/mats" --fit-cells 5
expect 2 "unknown model 'nope'" measured "$T/mats" --models nope

# gates: a lobe's error against a measured material (docs/gates.md). The Blinn-Phong material is
# the lobe blinn exactly (error 0 up to rounding); fq2 differs from c^64 (its max Delta is 0.128),
# so its error against the material is not 0.
cat >"$T/gates.json" <<JSON
{"gates": [
  {"model": "blinn", "metric": "measured.rms", "measured": "mats/blinn64.binary", "max": 1e-9},
  {"model": "fq2", "metric": "measured.rms", "measured": "mats/blinn64.binary", "max": 1e-9}
]}
JSON
"$BIN" gate "$T/gates.json" --json "$T/gate.json" >"$T/gate.out" 2>"$T/gate.err"
rc=$?
[ "$rc" -eq 1 ] && ok || bad "gate exit $rc, expected 1 (fq2 fails): $(head -c 400 "$T/gate.err")"
grep -qE '^PASS .*blinn measured\.rms' "$T/gate.out" && ok || bad "blinn's gate did not pass: $(cat "$T/gate.out")"
grep -qE '^FAIL .*fq2 measured\.rms' "$T/gate.out" && ok || bad "fq2's gate did not fail: $(cat "$T/gate.out")"
printf '{"gates": [{"model": "fq2", "metric": "measured.rms", "max": 1}]}' >"$T/g_nofile.json"
expect 2 'g_nofile\.json:1:[0-9]+: gate 1: measured\.rms needs "measured"' gate "$T/g_nofile.json"
printf '{"gates": [{"model": "fq2", "metric": "whole.max_abs", "measured": "x.binary", "max": 1}]}' >"$T/g_other.json"
expect 2 'gate 1: "measured" is read only by the metric measured\.rms' gate "$T/g_other.json"
printf '{"gates": [{"model": "fq2", "metric": "measured.rms", "measured": "dims.binary", "max": 1}]}' >"$T/g_bad.json"
expect 2 'dims\.binary: dimensions 90 90 360' gate "$T/g_bad.json"

# issue 31, Medium 2: two materials whose names give one picture name (a/gold and b/gold) get
# distinct pictures, the later one gold-2, and report.md's section names each one's own
mkdir -p "$T/m2a" "$T/m2b"
cp "$T/mats/blinn64.binary" "$T/m2a/gold.binary"
"$SYN" "$T/m2b/gold.binary" blinn 16 1.5 0.05 >/dev/null
"$BIN" measured "$T/m2a/gold.binary" "$T/m2b/gold.binary" --out "$T/run2" --fit-cells 2000 --quiet >/dev/null 2>"$T/err"
rc=$?
[ "$rc" -eq 0 ] && ok || bad "measured a/gold b/gold: exit $rc: $(head -c 300 "$T/err")"
for f in measured_errors_gold.png measured_slice_gold.png measured_errors_gold-2.png measured_slice_gold-2.png; do
    [ -s "$T/run2/$f" ] && ok || bad "$f not written (two materials named gold)"
done

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
