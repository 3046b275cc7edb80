#!/usr/bin/env bash
# test_render_cli.sh - `brdfbench render` end to end: exit codes and messages of bad sizes and
# scene files (nothing written), and a small run whose render.json carries the metrics, the
# double-reference check and the timings against the copy kernel.
set -u
BIN=${BRDFBENCH:?BRDFBENCH must name the brdfbench binary}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$T}/test_render_cli"
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
check_json "$T/run/render.json" "render.json contract" "$T/run" <<'PY'
import os
has_context(d, "brdfbench.render/1", ("date", "device", "platform_version", "build_options", "git_revision"))
scenes = {s["scene"]: s for s in d["scenes"]}
assert sorted(scenes) == ["spheres", "teapot"], sorted(scenes)
for s in scenes.values():
    assert [m["model"] for m in s["models"]] == ["phong", "blinn", "cq2", "fq2"]
    for m in s["models"]:
        assert m["double_reference_check"]["within_bound"] is True, m
        for f in m["files"].values():
            assert os.path.getsize(os.path.join(sys.argv[2], f)) > 0, f
        # the signed error image beside the absolute one, named after it
        fs = m["files"]
        assert set(fs) == {"image", "error_image", "signed_error_image", "contact_sheet"}, fs
        assert fs["signed_error_image"] == fs["error_image"][:-len("_error.png")] + "_signed_error.png", fs
        # a model that is its own reference has no error at all
        if m["model"] == m["reference"]:
            assert m["metrics"]["max_abs"] == 0 and m["metrics"]["psnr_db"] is None
    (t,) = s["timings"]
    assert (t["width"], t["height"]) == (128, 64)
    cp = t["copy"]
    assert abs(cp["mpixel_per_s"] - 128 * 64 / (cp["median_ms"] * 1e3)) <= 1e-9 * cp["mpixel_per_s"], cp
    names = {e["name"]: e for e in t["entries"]}
    assert set(names) == {"phong", "blinn", "cq2", "fq2"}, names
    for e in names.values():
        assert 0 < e["min_ms"] <= e["median_ms"] <= e["max_ms"], e
        # Mpixel/s is the image's pixels over the median time (128 x 64 here)
        assert abs(e["mpixel_per_s"] - 128 * 64 / (e["median_ms"] * 1e3)) <= 1e-9 * e["mpixel_per_s"], e
        # each of the --reps 3 timed launches' rate: the slowest is the longest time, the
        # middle one is the median's
        reps = sorted(e["mpixel_per_s_reps"])
        assert len(reps) == 3, e
        assert abs(reps[0] - 128 * 64 / (e["max_ms"] * 1e3)) <= 1e-9 * reps[0], e
        assert abs(reps[1] - e["mpixel_per_s"]) <= 1e-9 * reps[1], e
        assert abs(reps[2] - 128 * 64 / (e["min_ms"] * 1e3)) <= 1e-9 * reps[2], e
        # the ratio is the interleaved copy's median over this entry's median
        assert abs(e["fraction_of_copy"] - e["copy_median_ms_interleaved"] / e["median_ms"]) < 1e-9
        # the speed-up is the reference's median time over this entry's (docs/definitions.md: cq2 and fq2 against
        # phong; a reference entry has none other than itself)
        r = names[e["reference"]]
        assert abs(e["speedup_vs_reference"] - r["median_ms"] / e["median_ms"]) <= 1e-9 * e["speedup_vs_reference"], e
    assert names["cq2"]["reference"] == "phong" and names["fq2"]["reference"] == "phong"
    assert names["blinn"]["reference"] == "blinn"
PY
[ -d "$T/run/render" ] && [ -z "$(ls -A "$T/run" | grep 'render-')" ] && ok || bad "staging folders left in $T/run"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
