# claims.sh - bad-input rows of the claims part: claims.json, q_sweep.json and physical.json of
# the previous version (read through their upgrade functions, host/results/upgrade/) and of this
# one (read by their rows member), broken one way each: refused with one line naming the file,
# the member and what is accepted, exit 2. Fixture: tests/fixtures/claims-v-previous (the
# previous version's files), edited copies made here. Sourced by tests/test_cli_errors.sh.
mkdir -p clv1 && tar -C clv1 -xJf "$SRC/tests/fixtures/claims-v-previous/run.tar.xz"
# cl FILE OUT PYTHON: a copy of the fixture's FILE as clv1/OUT with d edited by PYTHON
cl() {
    python3 - "clv1/$1" "clv1/$2" "$3" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
exec(sys.argv[3])
json.dump(d, open(sys.argv[2], "w"))
PY
}
cl claims.json noid.json "del d['claims'][0]['id']"
t 2 "^brdfbench rows: clv1/noid.json:[0-9]+:[0-9]+: member \"id\" is missing" rows clv1/noid.json
cl claims.json esc.json "d['claims'][1]['note'] = 'a\x1b[2Jb'"
t 2 "^brdfbench rows: clv1/esc.json:[0-9]+:[0-9]+: \"note\" holds a control character \(accepted: text" rows clv1/esc.json
cl claims.json strmeasured.json "d['claims'][0]['measured'] = '1.1'"
t 2 "^brdfbench rows: clv1/strmeasured.json:[0-9]+:[0-9]+: \"measured\" is not a number \(accepted: a number in \[-1e\+100, 1e\+100\], or null" rows clv1/strmeasured.json
cl q_sweep.json qlen.json "d['max_rel'] = d['max_rel'][:-1]"
t 2 "^brdfbench rows: clv1/qlen.json:[0-9]+:[0-9]+: \"max_rel\" holds [0-9]+ values, \"Q\" [0-9]+ \(accepted: one per Q\)" rows clv1/qlen.json
cl q_sweep.json qneg.json "d['max_abs'][2] = -0.5"
t 2 "^brdfbench rows: clv1/qneg.json:[0-9]+:[0-9]+: \"max_abs\" holds -0.5 \(accepted: an error in \[0, 1e\+100\], or null" rows clv1/qneg.json
cl q_sweep.json qnobest.json "del d['best']"
t 2 "^brdfbench rows: clv1/qnobest.json:[0-9]+:[0-9]+: no context grid, \"f2\" or \"best\" object" rows clv1/qnobest.json
cl physical.json nohe.json "del d['he_terms']"
t 2 "^brdfbench rows: clv1/nohe.json:[0-9]+:[0-9]+: \"he_terms\" without its theta_deg" rows clv1/nohe.json
cl physical.json negrate.json "d['cost']['rows'][0]['evaluations_per_s'] = -1"
t 2 "^brdfbench rows: clv1/negrate.json:[0-9]+:[0-9]+: \"evaluations_per_s\" is -1 \(accepted: a rate in \[0, 1e\+18\]" rows clv1/negrate.json
# a file of this version is read by its rows: without them it is refused
cl claims.json norows.json "d['schema'] = 'brdfbench.claims/2'"
t 2 "^brdfbench rows: clv1/norows.json: schema \"brdfbench.claims/2\" without its \"rows\"" rows clv1/norows.json
