#!/usr/bin/env bash
# test_render_cli.sh - `brdfbench render` end to end: exit codes and messages of bad sizes and
# scene files (nothing written), and a small run whose render.json carries the metrics, the
# double-reference check and the timings against the copy kernel.
set -u
BIN=${BRDFBENCH:?BRDFBENCH must name the brdfbench binary}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
# the kernel cache the other tests share (POCL_CACHE_DIR of tests/CMakeLists.txt), whose builds of
# the built-in kernels this test reuses; one of its own under T when run without it
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$T/pocl-cache}"
mkdir -p "$POCL_CACHE_DIR"
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"

# expect CODE PATTERN ARGS... : as testlib.sh's, and the whole test is skipped (77) without a device
expect() {
    local code=$1 pattern=$2
    shift 2
    "$BIN" "$@" >"$T/out" 2>"$T/err"
    local rc=$?
    if [ "$rc" -eq 77 ]; then echo "no OpenCL device"; echo "0 passed, 0 failed"; exit 77; fi
    if [ "$rc" -ne "$code" ]; then bad "$* -> exit $rc, expected $code: $(head -c 300 "$T/err")"; return; fi
    if ! grep -qE -- "$pattern" "$T/err"; then bad "$* -> message '$(head -c 300 "$T/err")' lacks /$pattern/"; return; fi
    ok
}

# sizes: zero, negative, not WxH, absurd (checked against the device's memory), too low for
# the sphere grid; each exits 2 with the accepted range and writes nothing
expect 2 "--size: '0x100' is not WxH with W and H integers in \[16, 16384\]" render --size 0x100 --out "$T/a"
expect 2 "--size: '-640x480' is not WxH" render --size -640x480 --out "$T/a"
expect 2 "--size: '640' is not WxH" render --size 640 --out "$T/a"
expect 2 "--size: '640x480x3' is not WxH" render --size 640x480x3 --out "$T/a"
expect 2 "--time-sizes: '99999x99999' is not WxH" render --time-sizes 99999x99999 --out "$T/a"
expect 2 "--size: 16384x16384 is outside the accepted range.*MiB" render --size 16384x16384 --out "$T/a"
expect 2 "8 pixel rows per model" render --scene spheres --models phong,cq2,fq2 --size 64x20 --out "$T/a"
[ -e "$T/a" ] && bad "a refused size wrote $T/a" || ok

# other options
expect 2 "--scene: 'cube' is not a list" render --scene cube --out "$T/a"
expect 2 "unknown model 'nosuch'" render --models nosuch --out "$T/a"
expect 2 "--light: 'spot'" render --light spot --out "$T/a"
expect 2 "--reps" render --reps 0 --out "$T/a"

# scene files: malformed (file:line: problem), missing (named)
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n' >"$T/bad.obj"
expect 2 "$T/bad.obj:4: face corner '7'" render --scene bunny --bunny-file "$T/bad.obj" --size 64x48 --time-sizes none --out "$T/b"
printf 'bicubic_patch {\n <0,0,0> <1,0,0>\n}\n' >"$T/bad.inc"
expect 2 "$T/bad.inc:3: bicubic_patch starting at line 1 has 2 control points, 16 needed" render --scene teapot --teapot-file "$T/bad.inc" --size 64x48 --time-sizes none --out "$T/b"
expect 2 "cannot read /nonexistent/t.inc" render --scene teapot --teapot-file /nonexistent/t.inc --out "$T/b"
[ -e "$T/b/render.json" ] && bad "a failed run wrote render.json" || ok

# a small run with timings
"$BIN" render --scene spheres,teapot --models phong,blinn,cq2,fq2 --size 160x64 \
    --time-sizes 128x64 --reps 3 --warmup 1 --tess 4 --out "$T/run" >"$T/out" 2>"$T/err"
rc=$?
[ $rc -eq 0 ] && ok || bad "small run exit $rc: $(cat "$T/err")"
jsoncheck render_cli_render_contract "$T/run/render.json" "$T/run" && ok || bad "render.json contract"
[ -d "$T/run/render" ] && [ -z "$(ls -A "$T/run" | grep 'render-')" ] && ok || bad "staging folders left in $T/run"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
