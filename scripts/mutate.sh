#!/usr/bin/env bash
# scripts/mutate.sh - the test suite's mutation score: applies each small deliberate bug of the
# list below, one at a time, rebuilds, runs the tests that matter for that file, restores the
# file (always: on success, on failure, on Ctrl-C) and prints which bugs survived and the
# score. Not part of CI (a full run takes about half an hour on a 2-core machine).
#
#   bash scripts/mutate.sh               # every mutant
#   bash scripts/mutate.sh fvol-0.464    # only the mutants whose name contains the word given
#   bash scripts/mutate.sh --list        # where each mutant's text is (or stale), nothing built
#
# A mutant is an exact text substitution in the files a glob names (so it follows a function
# that moves from throughput.c to throughput_report.c): the text must occur exactly once among
# them. Text found nowhere makes the mutant "stale", text found more than once "ambiguous":
# neither counts as caught, and the list must then be brought up to date. A mutant that does
# not compile is "no build", and one whose tests ended without a result (ctest killed twice) is
# "no result": neither counts. The build is a separate folder
# (build-mutate/, or $MUTATE_BUILD); the working tree is left as it was found.
set -u
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BUILD=${MUTATE_BUILD:-$ROOT/build-mutate}
FILTER=${1:-}
JOBS=${MUTATE_JOBS:-2}
cd "$ROOT" || exit 2

names=() globs=() olds=() news=() tests=()
# in_files GLOB CTEST_REGEX: the files (a glob) and the tests of the mutants listed after it
in_files() { glob=$1 regex=$2; }
# mutant NAME OLD NEW: a mutant of the files and tests the last in_files named
mutant() { names+=("$1"); globs+=("$glob"); olds+=("$2"); news+=("$3"); tests+=("$regex"); }

T_MODEL='^(test_model_table|test_models)$'
T_ACC='^(test_model_table|test_accuracy|test_cli_accuracy)$'
T_REP='^(test_reproduce|test_reproduce_cli)$'
T_TP='^(test_throughput|test_throughput_cli)$'
T_GATE='^(test_gate|test_gate_papers)$'
# the zone end x_e = acos(exp(-0.511 / n)), in double on the host and in float on the device
ZONE_HOST='return acos(exp(-0.511 / n));' ZONE_HOST_BUG='return acos(exp(-0.512 / n));'
ZONE_DEV='const float s_e = -expm1(-0.511f / n);' ZONE_DEV_BUG='const float s_e = -expm1(-0.512f / n);'
CLAIM_TOL='c->reproduced = isfinite(measured) && fabs(measured - claimed) <= tol * (1 + 1e-9) + 1e-15;'

# ---- model constants and clamps (the header: device and host reference alike)
in_files kernels/brdf_models.h "$T_MODEL"
mutant fvol-0.464        'n * RC(0.463));' 'n * RC(0.464));'
mutant fq2-intercept     'case BRDF_FQ2:      return brdf_quadratic_s(s, n * RC(0.448) + RC(0.099));' \
                         'case BRDF_FQ2:      return brdf_quadratic_s(s, n * RC(0.448) + RC(0.0991));'
mutant fq2n-offset       'RC(0.214) * (RC(0.807) + n)' 'RC(0.214) * (RC(0.808) + n)'
mutant fvol64-xi         'n * RC(29.0 / 64.0)' 'n * RC(30.0 / 64.0)'
mutant cq2-half          'brdf_quadratic_s(s, n * RC(0.5))' 'brdf_quadratic_s(s, n * RC(0.5) + RC(0.001))'
mutant quad-clamp        'REAL base = fmax(RC(1.0) - k * s, RC(0.0));' 'REAL base = RC(1.0) - k * s;'
mutant lyon-clamp        'REAL base = fmax(RC(1.0) - n * s * RC(exp2(-(RSCALAR)k)), RC(0.0));' \
                         'REAL base = RC(1.0) - n * s * RC(exp2(-(RSCALAR)k));'
mutant alpha-of-n        'sqrt(RC(2.0) / (n + RC(2.0)))' 'sqrt(RC(2.0) / (n + RC(1.0)))'
mutant blinnn-norm       '(exp2(-n * RC(0.5)) + n)' '(exp2(-n * RC(0.25)) + n)'
mutant schlick-denom     'case BRDF_SCHLICK:  return c / (n * s + c);' 'case BRDF_SCHLICK:  return c / (n * s + RC(1.0));'
mutant k_q-exponent      'expm1(RSPLAT(log(q)) / n)' 'expm1(RSPLAT(log(q)) / (n + RC(0.01)))'
mutant negative-cos      '    c = fmax(c, RC(0.0));
    return brdf_eval_cs(' '    return brdf_eval_cs('

# ---- zone ends, on the host and on the device; sample placement
in_files 'host/measure/accuracy/accuracy*.c' "$T_ACC"
mutant zone-end-host       "$ZONE_HOST" "$ZONE_HOST_BUG"
in_files kernels/accuracy.cl "$T_ACC"
mutant zone-end-device     "$ZONE_DEV" "$ZONE_DEV_BUG"
in_files kernels/field.cl '^test_report$'
mutant zone-end-field      "$ZONE_DEV" "$ZONE_DEV_BUG"
in_files 'host/measure/accuracy/field*.c' '^test_report$'
mutant zone-end-field-host "$ZONE_HOST" "$ZONE_HOST_BUG"
in_files kernels/accuracy.cl "$T_ACC"
mutant samples-att-ratio 'const float log2_r = -log2(s_e) / (float)samples;' \
                         'const float log2_r = -log2(s_e) / (float)(2 * samples);'
mutant samples-epi-short 'const float epi_step = s_e / (float)(samples - 1);' \
                         'const float epi_step = 0.9f * s_e / (float)(samples - 1);'

# ---- comparison directions: the range maxima and the gates
in_files 'host/measure/accuracy/accuracy*.c' "$T_ACC"
mutant range-max-dir     'if (e->value > out->value || (isnan(out->value) && isfinite(e->value)))' \
                         'if (e->value < out->value || (isnan(out->value) && isfinite(e->value)))'
in_files 'host/results/gate*.c' "$T_GATE"
mutant gate-margin-dir   'if (g->margin < 0) {' 'if (g->margin > 0) {'
mutant gate-max-side     'double m_hi = g->has_max ? g->max - g->measured : INFINITY;' \
                         'double m_hi = g->has_max ? g->measured - g->max : INFINITY;'

# ---- tolerances and verdicts
in_files 'host/measure/reproduce/reproduce*.c' "$T_REP"
mutant claims-tol-x2     "$CLAIM_TOL" "${CLAIM_TOL/<= tol/<= 2 * tol}"
mutant claims-tol-strict "$CLAIM_TOL" 'c->reproduced = isfinite(measured) && fabs(measured - claimed) < 0.7 * tol;'
mutant coef-tol-4        'coef_tol[4] = { 0.001, 0.001, 0.01, 0.001 };' 'coef_tol[4] = { 0.001, 0.001, 0.001, 0.001 };'
mutant zone-k-reproduce  '#define ZONE_K 0.511 ' '#define ZONE_K 0.5111 '
mutant fig4-fit          'double e = fabs((0.448 * n + 0.099) / brdf_k_q(n, 0.64) - 1.0);' \
                         'double e = fabs((0.448 * n + 0.0995) / brdf_k_q(n, 0.64) - 1.0);'

# ---- fit.json
in_files 'host/measure/fit/fit*.c' '^test_reproduce_cli$'
mutant fit-a-0.45        'jw_kv_num(w, "a", m->fit.feasible ? m->spec.params[0] : NAN);' \
                         'jw_kv_num(w, "a", m->fit.feasible ? 0.45 : NAN);'
mutant fit-spec-digits   '"quad:a=%.10g,b=%.10g"' '"quad:a=%.4g,b=%.4g"'

# ---- JSON precision
in_files host/output/jsonw.c '^(test_cli_accuracy|test_gate_papers)$'
mutant json-digits       'void jw_num(struct jw *w, double v) { jw_numf(w, v, 17); }' \
                         'void jw_num(struct jw *w, double v) { jw_numf(w, v, 6); }'

# ---- ratio formulas
in_files 'host/measure/throughput/throughput*.c' "$T_TP"
mutant host-c-inverted   'q.to_host_c = ratio(f->rate.median, e->hostc[m].rate.median);' \
                         'q.to_host_c = ratio(e->hostc[m].rate.median, f->rate.median);'
mutant peak-flops        'q.of_peak = ratio(f->rate.median, peak_fma_per_s(r));' \
                         'q.of_peak = ratio(f->rate.median, r->peak.rate.median);'
mutant sweep-speedup     'jw_ratio(&w, "speedup_vs_host_c", ratio(hsum, dsum), ' \
                         'jw_ratio(&w, "speedup_vs_host_c", ratio(dsum, hsum), '
in_files 'host/measure/render/render*.c' '^test_render_cli$'
mutant render-speedup    'jw_kv_num(&w, "speedup_vs_reference", re->med / te->med);' \
                         'jw_kv_num(&w, "speedup_vs_reference", te->med / re->med);'

# ---- exit codes
in_files host/cli/cmd_gate.c "$T_GATE"
mutant gate-exit-code    'rc = gate_set_failures(&gs) > 0 ? EXIT_GATE_FAIL : EXIT_OK;' \
                         'rc = gate_set_failures(&gs) > 1 ? EXIT_GATE_FAIL : EXIT_OK;'

# ------------------------------------------------------------------------------------------
backup=$(mktemp -d)
current=""
restore() {
    if [ -n "$current" ] && [ -f "$backup/file" ]; then
        cp -p "$backup/file" "$ROOT/$current" && touch "$ROOT/$current"
        current=""
    fi
}
trap 'restore; rm -rf "$backup"' EXIT
trap 'echo; echo "interrupted: $current restored" >&2; exit 130' INT TERM

# Where the text is: prints the one file holding it exactly once, or exits 3 (stale) / 4 (ambiguous).
locate() {
    python3 - "$ROOT" "$1" "$2" <<'PY'
import glob, os, sys
root, pattern, old = sys.argv[1], sys.argv[2], sys.argv[3]
hits = []
for path in sorted(glob.glob(os.path.join(root, pattern))):
    n = open(path, encoding="utf-8").read().count(old)
    hits += [os.path.relpath(path, root)] * n
if not hits:
    sys.exit(3)
if len(hits) > 1:
    sys.exit(4)
print(hits[0])
PY
}
apply() {
    python3 - "$ROOT/$1" "$2" "$3" <<'PY'
import sys
path, old, new = sys.argv[1:4]
text = open(path, encoding="utf-8").read()
assert text.count(old) == 1
open(path, "w", encoding="utf-8").write(text.replace(old, new))
PY
}
build() {
    local targets=(brdfbench indep) t
    for t in $(cd "$BUILD" && ctest -N -R "$1" | sed -n 's/^ *Test *#[0-9]*: *//p'); do
        [ -f "$ROOT/tests/$t.c" ] && targets+=("$t")
    done
    cmake --build "$BUILD" -j"$JOBS" --target "${targets[@]}" >"$backup/build.log" 2>&1
}

if [ "$FILTER" = --list ]; then
    bad=0
    for i in "${!names[@]}"; do
        file=$(locate "${globs[$i]}" "${olds[$i]}")
        case $? in
        0) printf '%-20s %s\n' "${names[$i]}" "$file" ;;
        3) printf '%-20s stale: not found in %s\n' "${names[$i]}" "${globs[$i]}"; bad=1 ;;
        *) printf '%-20s ambiguous: found more than once in %s\n' "${names[$i]}" "${globs[$i]}"; bad=1 ;;
        esac
    done
    echo "${#names[@]} mutants"
    exit $bad
fi

echo "configuring and building $BUILD ..."
cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo >"$backup/build.log" 2>&1 &&
    cmake --build "$BUILD" -j"$JOBS" >>"$backup/build.log" 2>&1 || { cat "$backup/build.log"; exit 3; }

caught=0 survived=0 other=0
declare -a report
start_all=$(date +%s)
for i in "${!names[@]}"; do
    name=${names[$i]}
    [ -n "$FILTER" ] && [[ $name != *"$FILTER"* ]] && continue
    t0=$(date +%s)
    file=$(locate "${globs[$i]}" "${olds[$i]}")
    rc=$?
    if [ $rc -eq 3 ] || [ $rc -eq 4 ]; then
        what=$([ $rc -eq 3 ] && echo stale || echo ambiguous)
        other=$((other + 1))
        report+=("$(printf '%-10s %-20s %s: text %s' "$what" "$name" "${globs[$i]}" "$([ $rc -eq 3 ] && echo 'not found' || echo 'found more than once')")")
        echo "${report[-1]}"
        continue
    fi
    cp -p "$ROOT/$file" "$backup/file"
    current=$file
    apply "$file" "${olds[$i]}" "${news[$i]}" || { restore; exit 3; }
    if ! build "${tests[$i]}"; then
        verdict="no build"
        other=$((other + 1))
    else
        # Caught means a test reported a failure; ctest itself ending on a signal (another
        # process killing it, a timeout) proves nothing, so that run is repeated once.
        for attempt in 1 2; do
            (cd "$BUILD" && ctest -j"$JOBS" -R "${tests[$i]}" --stop-on-failure >"$backup/ctest.log" 2>&1)
            trc=$?
            failed=$(sed -n 's/^.*[0-9]* - \(test_[a-z_0-9]*\) (Failed).*$/\1/p' "$backup/ctest.log" | tr '\n' ' ')
            [ $trc -eq 0 ] || [ -n "$failed" ] && break
        done
        if [ $trc -eq 0 ]; then
            verdict=SURVIVED
            survived=$((survived + 1))
        elif [ -n "$failed" ]; then
            verdict=caught
            caught=$((caught + 1))
        else
            verdict="no result"
            other=$((other + 1))
            failed="(ctest exit $trc without a failed test)"
        fi
    fi
    restore
    report+=("$(printf '%-10s %-20s %s (%ss)%s' "$verdict" "$name" "$file" "$(($(date +%s) - t0))" "${failed:+ $failed}")")
    echo "${report[-1]}"
done
# leave the mutation build matching the restored tree
cmake --build "$BUILD" -j"$JOBS" >"$backup/build.log" 2>&1

total=$((caught + survived))
echo
echo "mutants: $((total + other)) ($caught caught, $survived survived, $other stale/ambiguous/no build/no result) in $(($(date +%s) - start_all)) s"
if [ $total -gt 0 ]; then
    echo "score: $caught/$total = $((100 * caught / total))%"
fi
if [ $survived -gt 0 ]; then
    echo "survived:"
    printf '%s\n' "${report[@]}" | grep '^SURVIVED' | sed 's/^/  /'
fi
[ $other -eq 0 ] && [ $total -gt 0 ] && [ $((100 * caught)) -ge $((90 * total)) ]
