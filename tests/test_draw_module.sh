#!/usr/bin/env bash
# test_draw_module.sh - the pictures live in the module libbrdfbench-draw.so, opened when a command
# first draws (host/output/draw_load.c): the main binary does not link OpenCV; a command that draws
# nothing does not load it; a drawing command (plot) works through the module; without the module
# (the binary copied alone into a folder) the drawing commands stop with one line and exit 3 and
# leave the pictures as they were, while the others work as before; a file that is not the module,
# or a module of another interface version, is refused with one line.
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init
cd "$T" || exit 1
MOD=libbrdfbench-draw.so

# 1. Linking: no OpenCV in the binary; the module beside it holds it (so the check means something).
ldd "$BIN" >ldd.bin 2>&1 && ok || bad "ldd $BIN failed: $(head -3 ldd.bin)"
grep -qi opencv ldd.bin && bad "the main binary links OpenCV: $(grep -i opencv ldd.bin | head -3)" || ok
[ -f "$(dirname "$BIN")/$MOD" ] && ok || bad "no $MOD beside $BIN"
ldd "$(dirname "$BIN")/$MOD" 2>&1 | grep -q libopencv_imgcodecs && ok || bad "$MOD does not link OpenCV's imgcodecs"

# 2. Loading: version and rows do not load OpenCV; plot does (LD_DEBUG lists every library loaded).
loads_opencv() { LD_DEBUG=files "$BIN" "$@" 2>&1 >/dev/null | grep -q 'file=libopencv_core'; }

# The run folder of `all --quick --models fq2` that test_cli_errors and test_hostile read (the
# fixture brdf_runs), or one made here when run by hand.
if [ -n "${BRDF_RUNS:-}" ] && [ -f "$BRDF_RUNS/done" ]; then
    cp -r "$BRDF_RUNS/R0" R0 && rc=0 || rc=1
else
    timeout -s KILL 420 bash "$SRC/tests/fixture_runs.sh" "$T/runs" >out 2>err
    rc=$?
    [ $rc -eq 0 ] && cp -r runs/R0 R0
fi
if [ $rc -eq 77 ]; then echo "no OpenCL device"; echo "0 passed, 0 failed, 1 skipped"; exit 77; fi
[ $rc -eq 0 ] && [ -s R0/plots.json ] && ok || { bad "the fixture run R0: exit $rc"; echo "$pass passed, $fail failed"; exit 1; }

loads_opencv version && bad "version loads OpenCV" || ok
loads_opencv rows R0 && bad "rows loads OpenCV" || ok
loads_opencv compare R0 R0 --json - && bad "compare --json - loads OpenCV" || ok
cp -r R0 P0
loads_opencv plot P0 && ok || bad "plot does not load OpenCV (is the module used at all?)"

# 3. plot redraws every picture of the run from its JSON, through the module: exit 0, each picture
# it names a PNG, byte for byte the one `all` drew into the run (the same drawing, the same input).
cp -r R0 P1
"$BIN" plot P1 >plot.out 2>plot.err
rc=$?
[ $rc -eq 0 ] && ok || bad "plot: exit $rc: $(head -3 plot.err)"
npng=$(grep -c '\.png$' plot.out)
[ "$npng" -ge 5 ] && ok || bad "plot named $npng pictures (expected every plot and heatmap of the run)"
while read -r png; do
    [ "$(head -c 4 "$png" | od -An -c | tr -d ' ')" = "211PNG" ] || { bad "$png is not a PNG"; continue; }
    cmp -s "$png" "R0/${png#P1/}" && ok || bad "$png differs from the picture all drew"
done < <(grep '\.png$' plot.out)

# 4. Without the module: the binary alone in a folder.
mkdir alone && cp "$BIN" alone/brdfbench
A=alone/brdfbench
sums() { (cd "$1" && md5sum ./*.png); }
cp -r R0 M0
sums M0 >before.md5
for cmd in plot heatmap; do
    "$A" "$cmd" M0 >out 2>err
    rc=$?
    [ $rc -eq 3 ] && ok || bad "$cmd without the module: exit $rc, expected 3"
    [ "$(wc -l <err)" -eq 1 ] && ok || bad "$cmd without the module: $(wc -l <err) lines on stderr, expected one: $(head -c 600 err)"
    grep -qE "^brdfbench $cmd: the drawing module $MOD \(pictures, OpenCV\) is not installed: not found in .*/alone nor in .*/alone/\.\./lib/brdfbench" err &&
        ok || bad "$cmd without the module: message: $(head -c 400 err)"
done
sums M0 | cmp -s - before.md5 && ok || bad "the pictures changed although nothing could be drawn"
"$A" all --quick --models fq2 --out M1 >out 2>err
rc=$?
[ $rc -eq 3 ] && [ "$(wc -l <err)" -eq 1 ] && grep -q "^brdfbench all: the drawing module" err && ok ||
    bad "all without the module: exit $rc, expected 3 with one line before any work: $(head -c 400 err)"
[ ! -e M1 ] && ok || bad "all without the module made its folder M1"
# the commands that draw nothing work as with the module, with the same output
"$A" version >out 2>err && grep -q '^brdfbench ' out && ok || bad "version without the module: $(head -c 300 err)"
"$A" help >out 2>err && ok || bad "help without the module: $(head -c 300 err)"
"$A" rows R0 >rows.alone 2>err && "$BIN" rows R0 >rows.full 2>&1 && cmp -s rows.alone rows.full && ok ||
    bad "rows without the module differs or failed: $(head -c 300 err)"
"$A" compare R0 R0 --json - 2>err | grep -v '"date"' >cmp.alone && "$BIN" compare R0 R0 --json - 2>/dev/null |
    grep -v '"date"' >cmp.full && [ -s cmp.alone ] && cmp -s cmp.alone cmp.full && ok ||
    bad "compare --json - without the module differs or failed: $(head -c 300 err)"
cp -r R0 Q0 && cp -r R0 Q1
"$A" report Q0 >/dev/null 2>err && "$BIN" report Q1 >/dev/null 2>&1 && cmp -s Q0/report.md Q1/report.md && ok ||
    bad "report without the module differs or failed: $(head -c 300 err)"

# 5. Something else under the module's name: a text file, then a library of another interface
# version; each refused with one line naming it, exit 3.
echo "not a library" >alone/$MOD
"$A" plot M0 >out 2>err
rc=$?
[ $rc -eq 3 ] && [ "$(wc -l <err)" -eq 1 ] && grep -qE "^brdfbench plot: the drawing module .*/alone/$MOD does not load: " err &&
    ok || bad "a text file as the module: exit $rc: $(head -c 400 err)"
CC=${CC:-cc}
if command -v "$CC" >/dev/null 2>&1; then
    # the entry's name and the table's first member (abi) as draw_module.h declares them
    printf 'static const int table[64] = {9999};\nconst void *brdfbench_draw_module(const void *host) { (void)host; return table; }\n' >old.c
    "$CC" -shared -fPIC -o alone/$MOD old.c 2>cc.err && ok || bad "cc: $(head -3 cc.err)"
    "$A" plot M0 >out 2>err
    rc=$?
    [ $rc -eq 3 ] && [ "$(wc -l <err)" -eq 1 ] && grep -qE "^brdfbench plot: .*/alone/$MOD is not a drawing module of this brdfbench \(interface [0-9]+ expected\)" err &&
        ok || bad "a module of another version: exit $rc: $(head -c 400 err)"
    sums M0 | cmp -s - before.md5 && ok || bad "the pictures changed although nothing could be drawn"
fi

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
