#!/usr/bin/env bash
# test_ci_matrix.sh - the matrix workflow of docs/ci.md (between its ci-matrix markers): the
# YAML is parsed (PyYAML) and checked for what the page promises (a job per driver, PoCL,
# rusticl and a GPU runner by label, each uploading its run folder; a history job that needs
# them, adds their runs to the store kept in the cache and runs history --fail-if-slower), then
# its steps run on this machine as a local script: the `run:` scripts as written (bash -eo
# pipefail, as GitHub runs them), with the artefact and cache actions done by copying folders,
# the checkout, dependency and build steps left out (the suite runs from that build). Two
# workflow runs: PoCL and rusticl, then PoCL again, the store carried by the cache between
# them. Asserted: every step exits 0, the store holds the three runs, history.json the three
# runs and each device's rows. No timing is asserted: two runs of a row cannot make a change
# (a segment inside the series holds two runs), so history's exit is 0 by construction.
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init
PY=/usr/bin/python3
export MESA_SHADER_CACHE_DIR="$T/mesa-cache"
mkdir -p "$MESA_SHADER_CACHE_DIR"

if ! "$BIN" list >/dev/null 2>&1; then echo "no OpenCL device"; echo "0 passed, 0 failed, 1 skipped"; exit 77; fi
drivers=pocl
if RUSTICL_ENABLE=llvmpipe "$BIN" list 2>/dev/null | grep -q "^  platform [0-9]*: rusticl"; then
    drivers="pocl,rusticl"
else
    echo "rusticl with llvmpipe is not installed here: the rusticl job is left out"
fi

sed -n '/<!-- ci-matrix:begin -->/,/<!-- ci-matrix:end -->/p' "$SRC/docs/ci.md" | sed '1,2d;$d' | sed '$d' >"$T/matrix.yml"

"$PY" - "$T" "$BIN" "$drivers" <<'EOF'
import fnmatch, os, re, shutil, subprocess, sys
import yaml

T, BIN, drivers = sys.argv[1], sys.argv[2], sys.argv[3].split(",")
wf = yaml.safe_load(open(T + "/matrix.yml"))
fails = []
def check(cond, what):
    if not cond:
        fails.append(what)
        print("FAIL: " + what, file=sys.stderr)
    return cond

# ---- what the page promises ----
jobs = wf["jobs"]
bench, hist = jobs["bench"], jobs["history"]
inc = bench["strategy"]["matrix"]["include"]
check([e["driver"] for e in inc] == ["pocl", "rusticl", "gpu"], "matrix drivers: %s" % [e["driver"] for e in inc])
check("gpu" in yaml.safe_load(inc[2]["runner"]), "the GPU job runs on a runner labelled gpu")
check("matrix.runner" in bench["runs-on"], "bench runs on the matrix's runner")
check(any(s.get("uses", "").startswith("actions/upload-artifact") and "matrix.driver" in s["with"]["name"]
          for s in bench["steps"]), "each bench job uploads its run folder")
check(hist["needs"] == "bench", "history needs the bench jobs")
runs = "\n".join(s.get("run", "") for s in hist["steps"])
check("store add runs/run-*" in runs, "history adds the runs to the store")
check(re.search(r'history --db \S+ .*--fail-if-slower', runs) is not None, "history runs with --fail-if-slower")
check(any(s.get("uses", "").startswith("actions/cache/restore") for s in hist["steps"]) and
      any(s.get("uses", "").startswith("actions/cache/save") for s in hist["steps"]), "the store is kept in the cache")

# ---- the steps, run here ----
ART, CACHE = T + "/artifacts", T + "/cache"
os.makedirs(ART, exist_ok=True)
os.makedirs(CACHE, exist_ok=True)
# the commits the two workflow runs measured: the second one committed first (a re-run of an
# older commit), so the commit dates, not the run dates, must order the history
COMMIT_DATES = {"1001": "2026-03-02T12:00:00+01:00", "1002": "2026-03-01T09:00:00+00:00"}
TINY = "--models cq2 --reps 5 --min-time 0.002 --work-items 8 --variants default --no-host-c --no-sweep"

def subst(s, matrix, run_id):
    def rep(m):
        e = m.group(1).strip()
        if e.startswith("matrix."):
            return str(matrix[e[len("matrix."):]])
        if e == "github.run_id":
            return run_id
        if e in ("!cancelled()", "always()"):
            return "true"
        raise ValueError("an expression this test does not know: " + e)
    return re.sub(r"\$\{\{(.*?)\}\}", rep, s)

def copy(src, dst):
    if os.path.isdir(src):
        shutil.copytree(src, dst, dirs_exist_ok=True)
    elif os.path.exists(src):
        os.makedirs(os.path.dirname(dst), exist_ok=True)
        shutil.copy2(src, dst)

def run_job(name, job, ws, matrix, run_id):
    os.makedirs(ws, exist_ok=True)
    env = dict(os.environ)
    for scope in (wf.get("env", {}), job.get("env", {})):
        env.update({k: subst(str(v), matrix, run_id) for k, v in scope.items()})
    env["BRDFBENCH"] = BIN        # the suite's build, not one made by the build step
    env["TP_FLAGS"] = TINY        # a short run instead of --reps 10 over every model
    if not env.get("RUSTICL_ENABLE"):
        env.pop("RUSTICL_ENABLE", None)
    for step in job["steps"]:
        sname = step.get("name", step.get("uses", "?"))
        w = {k: subst(str(v), matrix, run_id) for k, v in step.get("with", {}).items()}
        u = step.get("uses", "")
        if u.startswith("actions/checkout"):
            # a checkout: a git repository whose HEAD is the workflow run's commit, at its date
            cenv = dict(env, GIT_COMMITTER_DATE=COMMIT_DATES[run_id], GIT_AUTHOR_DATE=COMMIT_DATES[run_id])
            for cmd in (["git", "init", "-q"], ["git", "-c", "user.name=ci", "-c", "user.email=ci@localhost",
                                                 "commit", "-q", "--allow-empty", "-m", "run " + run_id]):
                subprocess.run(cmd, cwd=ws, env=cenv, check=True, capture_output=True)
            continue
        if u.startswith("actions/upload-artifact"):
            for p in w["path"].split():
                copy(os.path.join(ws, p), os.path.join(ART, w["name"], p))
            check(os.path.isdir(os.path.join(ART, w["name"])), "%s: %s uploaded nothing" % (name, w["name"]))
            continue
        if u.startswith("actions/download-artifact"):
            for a in sorted(os.listdir(ART)):
                if fnmatch.fnmatch(a, w["pattern"]):
                    # download-artifact@v4 without merge-multiple: PATH/<artifact>/<its files>
                    src = os.path.join(ART, a)
                    inner = os.listdir(src)
                    copy(os.path.join(src, inner[0]) if inner == [a] else src, os.path.join(ws, w["path"], a))
            continue
        if u.startswith("actions/cache/restore"):
            keys = sorted(k for k in os.listdir(CACHE) if k == w["key"] or k.startswith(w.get("restore-keys", "\0")))
            if keys:
                copy(os.path.join(CACHE, keys[-1], w["path"]), os.path.join(ws, w["path"]))
            continue
        if u.startswith("actions/cache/save"):
            copy(os.path.join(ws, w["path"]), os.path.join(CACHE, w["key"], w["path"]))
            continue
        if u:
            check(False, "%s: an action this test does not run: %s" % (name, u))
            continue
        if sname.startswith("dependencies") or sname == "build":
            continue   # the suite's own build stands for them
        r = subprocess.run(["bash", "--noprofile", "--norc", "-eo", "pipefail", "-c", step["run"]], cwd=ws, env=env,
                           capture_output=True, text=True)
        open(T + "/log", "a").write("== %s / %s (exit %d)\n%s\n%s\n" % (name, sname, r.returncode, r.stdout, r.stderr))
        if not check(r.returncode == 0, "%s: step '%s' exit %d: %s" % (name, sname, r.returncode, r.stderr[-600:])):
            return False
    return True

def workflow(run_id, drivers_now):
    for e in inc:
        if e["driver"] in drivers_now:
            run_job("bench " + e["driver"], bench, "%s/ws-%s-%s" % (T, run_id, e["driver"]), e, run_id)
    return run_job("history", hist, "%s/ws-%s-history" % (T, run_id), {}, run_id)

for d in os.listdir(ART):
    shutil.rmtree(os.path.join(ART, d))
workflow("1001", drivers)
shutil.rmtree(ART)
os.makedirs(ART)
workflow("1002", ["pocl"])

# ---- what the second workflow run left ----
import json, sqlite3
ws = T + "/ws-1002-history"
n_docs = len(drivers) + 1
db = sqlite3.connect(ws + "/history-store/history.sqlite")
check(db.execute("select count(*) from runs").fetchone()[0] == n_docs, "the store holds %d runs" % n_docs)
check(os.path.isdir(CACHE + "/brdfbench-history-1002/history-store"), "the store was saved to the cache")
h = json.load(open(ws + "/history/history.json"))
check(len(h["runs"]) == n_docs, "history.json lists %d runs" % n_docs)
devices = {r["device"] for r in h["rows"]}
check(len(devices) == len(drivers), "history rows of %d devices: %s" % (len(drivers), devices))
check(any(r["label"] == "cq2 | default | n uniform" for r in h["rows"]), "cq2's row is in the history")
check(h["changes"] == [], "two runs of a row make no change")
# ordered by commit date (in UTC): the second workflow run's pocl run first
check(h["order"] == "commit date", "history ordered by %s" % h["order"])
check([r["commit_date"] for r in h["runs"]] == ["2026-03-01T09:00:00Z"] + ["2026-03-02T11:00:00Z"] * len(drivers),
      "commit dates %s" % [r["commit_date"] for r in h["runs"]])
check(os.path.isfile(ART + "/history/history/history.md") and os.path.isfile(ART + "/history/history-store/history.sqlite"),
      "the history artefact holds history.md and the store")
print("%d checks failed" % len(fails))
sys.exit(1 if fails else 0)
EOF
rc=$?
[ $rc -eq 0 ] && ok || bad "the matrix workflow: see the FAIL lines above; log: $(tail -c 1500 "$T/log" 2>/dev/null)"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
