#!/usr/bin/env bash
# test_report_cli.sh - `brdfbench all`, `plot` and `heatmap` end to end on small sweeps:
# the run folder and results/latest, report.md linking only files that exist, every PNG a
# PNG, redraw from JSON without a device, and the error paths (malformed or missing JSON:
# exit 2 naming the file; a picture that cannot be written: exit 3, the other pictures drawn).
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init


# is_png FILE: the 8-byte PNG signature (89 50 4E 47 0D 0A 1A 0A, RFC 2083)
is_png() { [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ]; }

# links_exist DIR: every markdown link target in DIR/report.md is a file in DIR
links_exist() {
    local dir=$1 n=0 target
    while read -r target; do
        n=$((n + 1))
        [ -f "$dir/$target" ] || { echo "report links a missing file: $target" >&2; return 1; }
    done < <(grep -oE '\]\([^)]+\)' "$dir/report.md" | sed -E 's/^\]\((.*)\)$/\1/')
    [ "$n" -gt 0 ]
}

MODELS="phong,fvol,cq2,fq:Q=0.64"
"$BIN" all --quick --models "$MODELS" --results-root "$T/results" >"$T/out" 2>"$T/err"
rc=$?
if [ $rc -eq 77 ]; then echo "no OpenCL device"; echo "0 passed, 0 failed, 1 skipped"; exit 77; fi
[ $rc -eq 0 ] && ok || bad "all --quick exit $rc: $(cat "$T/err")"
RUN="$T/results/latest"
[ -L "$RUN" ] && [ -d "$RUN/" ] && ok || bad "results/latest is not a link to a run folder"
[ -f "$RUN/report.md" ] && ok || bad "no report.md"
# progress: one line per step with the elapsed time, then the report's path on stdout
[ "$(grep -cE '^\[ *[0-9]+\.[0-9] s\] step [0-9]+/10 ' "$T/err")" -eq 10 ] && ok || bad "want 10 step lines: $(cat "$T/err")"
# the frontier step: its files, and report.md's section naming the front
[ -s "$RUN/frontier.json" ] && is_png "$RUN/frontier_max_rel.png" && is_png "$RUN/frontier_max_abs.png" && ok \
    || bad "the frontier step's files are missing"
# with --models, the frontier measures those models (it measured its own default set before)
jsoncheck report_cli_frontier_all_models "$RUN/frontier.json" && ok || bad "the frontier of all --models"
grep -q "^## Which lobe to ship" "$RUN/report.md" && grep -q "^The front: " "$RUN/report.md" && ok \
    || bad "report.md lacks the 'Which lobe to ship' section"
grep -q "report.md" "$T/out" && ok || bad "stdout lacks the report path"
links_exist "$RUN" && ok || bad "report.md links a missing file"
# every model but the self-referenced phong has a heatmap and its field; phong has none
for m in fvol cq2 fq_Q0.64; do
    is_png "$RUN/heatmap_$m.png" && [ -s "$RUN/field_$m.json" ] && ok || bad "heatmap or field of $m missing"
    grep -q "(heatmap_$m.png)" "$RUN/report.md" && ok || bad "report does not show heatmap_$m.png"
done
[ ! -e "$RUN/heatmap_phong.png" ] && ok || bad "a reference against itself got a heatmap"
for p in curves_n16_paper1_fig2 curves_n20_paper2_fig5 max_rel_error_epicentre_vs_n max_abs_error_vs_n \
         fq_max_rel_error_vs_q fq_max_abs_error_vs_q; do
    is_png "$RUN/$p.png" && ok || bad "$p.png missing or not a PNG"
done
for f in accuracy.json accuracy.csv plots.json; do [ -s "$RUN/$f" ] && ok || bad "$f missing"; done
grep -q '| `fvol` | `phong` |' "$RUN/report.md" && ok || bad "accuracy table lacks fvol"
# image passes: the sphere grid's contact sheet and a model's contact sheet are shown
grep -q '(render/spheres/contact.png)' "$RUN/report.md" && grep -q '(render/spheres/fvol_contact.png)' "$RUN/report.md" &&
    ok || bad "report lacks the image passes' contact sheets"

# redraw without a device: the same pictures come back
rm -f "$RUN/heatmap_fvol.png" "$RUN/max_abs_error_vs_n.png"
expect 0 "redrawn" plot "$RUN"
is_png "$RUN/heatmap_fvol.png" && is_png "$RUN/max_abs_error_vs_n.png" && ok || bad "plot did not redraw"
rm -f "$RUN/heatmap_cq2.png"
expect 0 "1 picture" heatmap "$RUN" --label cq2
is_png "$RUN/heatmap_cq2.png" && ok || bad "heatmap --label cq2 did not redraw"

# input errors: exit 2, the file named
cp -r "$RUN/" "$T/broken"
printf '{"schema": "brdfbench.plots/1", "figures": [\n  {"file": "a.png",}\n]}\n' >"$T/broken/plots.json"
expect 2 "plots.json:2:.*trailing comma" plot "$T/broken"
rm "$T/broken/plots.json"
expect 2 "plots.json: cannot open" plot "$T/broken"
printf '{"schema": "brdfbench.field/1"}' >"$T/broken/field_fvol.json"
expect 2 "field_fvol.json:1:1: member \"model\" is missing" heatmap "$T/broken"
expect 2 "--label nosuch: .* has no model of that label \(accepted: .*cq2" heatmap "$RUN" --label nosuch
expect 2 "not a folder" plot "$T/none"
expect 2 "unknown option" all --frobnicate
expect 2 "unknown model" all --models nosuch

# an --out folder holding something no run writes (here a folder where a picture goes) is
# refused before any work (exit 2, the entry named) and left as it was: all replaces its folder
# as a whole when the run is complete (docs/architecture.md, habit 5)
mkdir -p "$T/out3/heatmap_fvol.png/keep"
expect 2 "--out: .*out3 holds 'heatmap_fvol.png', which is no part of a brdfbench run" \
    all --quick --models fvol,cq2 --out "$T/out3"
[ "$(cd "$T/out3" && find . | sort | tr '\n' ' ')" = ". ./heatmap_fvol.png ./heatmap_fvol.png/keep " ] && ok ||
    bad "the refused --out folder changed: $(cd "$T/out3" && find .)"
# redraw into a folder where one picture cannot be written: exit 3, the rest redrawn
cp -r "$RUN/." "$T/out4"
rm -f "$T/out4/heatmap_fvol.png" "$T/out4/heatmap_cq2.png"
mkdir -p "$T/out4/heatmap_fvol.png/keep"
expect 3 "heatmap_fvol.png" heatmap "$T/out4"
is_png "$T/out4/heatmap_cq2.png" && ok || bad "heatmap_cq2.png not redrawn beside a failing one"


# a --quick run says so at the top of its report, and shows the side-by-side heatmap page
grep -q '^\*\*Coarse grids (`--quick`): a trial run, not for figures.\*\*' "$RUN/report.md" && ok ||
    bad "report.md of a --quick run lacks its trial-run line"
grep -q '(heatmaps_shared_scale.png)' "$RUN/report.md" && [ -s "$RUN/heatmaps_shared_scale.png" ] && ok ||
    bad "report.md lacks the shared-scale heatmap page"
# report RUN_DIR rebuilds report.md from the run folder alone: the page all wrote, to the byte
"$BIN" report "$RUN" --output "$T/rebuilt.md" && cmp -s "$T/rebuilt.md" "$RUN/report.md" && ok ||
    bad "report --output differs from the report.md all wrote: $(diff "$T/rebuilt.md" "$RUN/report.md" | head -5)"
# ... in a copy of the folder with report.md deleted, in place (the folder's name in the text
# is the one run.json records, so the copy's page is the same)
cp -r "$RUN/." "$T/copy"
rm "$T/copy/report.md"
"$BIN" report "$T/copy" && cmp -s "$T/copy/report.md" "$RUN/report.md" && ok ||
    bad "report in a copied folder differs: $(diff "$T/copy/report.md" "$RUN/report.md" | head -5)"
"$BIN" report "$RUN" --output - | cmp -s - "$RUN/report.md" && ok || bad "report --output - differs"
[ -s "$RUN/run.json" ] && grep -q '"schema": "brdfbench.run/1"' "$RUN/run.json" && ok || bad "no run.json"
# every section page report.md takes in is there
for f in claims.md throughput.md frontier.md; do [ -s "$RUN/$f" ] && ok || bad "$f missing"; done
# what report cannot rebuild is named: exit 2
expect 2 "run.json: .*No such file" report "$T/out3"
cp -r "$RUN/." "$T/broken"
rm "$T/broken/throughput.json"
expect 2 "throughput.json: .*run.json records its part as done" report "$T/broken" --output -
printf '{"schema": "brdfbench.run/1", "command": 3}\n' >"$T/broken/run.json"
expect 2 "run.json:1:[0-9]+: member \"command\" is a number, a string expected" report "$T/broken"
expect 2 "RUN_DIR '$T/nosuch' is not a folder" report "$T/nosuch"
expect 2 "--output: " report "$RUN" --output "$T/nosuch/report.md"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
