#!/usr/bin/env bash
# test_run_object.sh - what the steps of one run share is held by its run object
# (host/core/run.h), not read back from the files it wrote:
#   - `all`'s f_Q-against-Q plots show the claims check's own Q sweep, handed over in memory:
#     every point of the two plots and the f2 line are the figures of q_sweep.json (which the
#     claims check writes from the same sweep: the two must agree value for value), and the Q
#     step says it took the claims check's sweep;
#   - q_sweep.json is still written, as a result file;
#   - report.md is the page `brdfbench report` rebuilds from the folder, byte for byte.
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init

"$BIN" all --quick --quiet --models fq2 --out "$T/run" >"$T/out" 2>"$T/err"
rc=$?
if [ $rc -eq 77 ]; then echo "no OpenCL device"; echo "0 passed, 0 failed, 1 skipped"; exit 77; fi
[ $rc -eq 0 ] && ok || bad "all --quick exit $rc: $(head -c 600 "$T/err")"
[ -s "$T/run/q_sweep.json" ] && ok || bad "q_sweep.json is not written"

python3 - "$T/run" <<'PY' && ok || bad "the Q plots are not the claims check's Q sweep"
import json, sys
run = sys.argv[1]
q = json.load(open(f"{run}/q_sweep.json"))
figs = {f["file"]: f for f in json.load(open(f"{run}/plots.json"))["figures"]}
bad = []
for file, key, f2 in (("fq_max_rel_error_vs_q.png", "max_rel", q["f2"]["max_rel"]),
                      ("fq_max_abs_error_vs_q.png", "max_abs", q["f2"]["max_abs"])):
    series = figs[file]["series"]
    fq = [s for s in series if s["label"] == "fq (f_Q)"][0]
    if fq["x"] != q["Q"] or fq["y"] != q[key]:
        bad.append(f"{file}: f_Q series differs from q_sweep.json's Q and {key}")
    line = [s for s in series if s["label"].startswith("cq2")]
    if not line or set(line[0]["y"]) != {f2}:
        bad.append(f"{file}: the f2 line is not q_sweep.json's f2.{key} = {f2}")
steps = json.load(open(f"{run}/run.json"))["steps"]
qstep = [s for s in steps if s["name"] == "Q sweep"]
if not qstep or "the claims check's" not in qstep[0]["message"]:
    bad.append(f"the Q step does not say it took the claims check's sweep: {qstep}")
print("\n".join(bad), file=sys.stderr)
sys.exit(1 if bad else 0)
PY

"$BIN" report "$T/run" --output "$T/again.md" >/dev/null 2>"$T/err" && cmp -s "$T/again.md" "$T/run/report.md" && ok \
    || bad "report RUN differs from all's report.md: $(head -c 300 "$T/err")"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
