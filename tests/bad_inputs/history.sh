# bad_inputs/history.sh - rows of the history part (issue 33): rows' exports, store and history.
# Fixtures: R0 (a run with throughput.json) and base (an accuracy run) of test_cli_errors.sh,
# and files made here.
t 2 "^brdfbench rows: --format: 'junit' is not a format \(accepted: md, csv, json\) nor an export \(gbench, bmf, action, action-smaller\)" rows R0 --format junit
t 2 "^brdfbench rows: --format gbench: accuracy.json holds no timed figure \(gbench takes rates" rows base --format gbench
t 2 "^brdfbench rows: --format action: accuracy.json holds no figure where higher is better \(try --format action-smaller\)" rows base --format action
t 2 "^brdfbench rows: --format bmf writes one document and R0 holds [0-9]+ \(name one with --kind" rows R0 --format bmf
t 2 "^brdfbench store: expected a store command \(accepted: add, list, export\)" store
t 2 "^brdfbench store: 'frob' is not a store command \(accepted: add, list, export\)" store frob
t 2 "^brdfbench store add: expected RUN_DIR\|FILE\.\.\. \(run folders or result files\)" store add --db st.sqlite
t 2 "^brdfbench store add: nothere: no such file or folder \(accepted: a run folder, a result file or a rows document\)" store add nothere --db st.sqlite
t 2 "^brdfbench store add: --kind: 'plots' is not a kind of result \(accepted: throughput, accuracy, render, fit, frontier" store add R0 --kind plots --db st.sqlite
t 2 "^brdfbench store add: base: no result file of kind render \(accepted: a run folder with any of throughput.json, accuracy.json, render.json, fit.json, frontier.json, claims.json, q_sweep.json, physical.json, energy.json, measured.json," store add base --kind render --db st.sqlite
t 2 "^brdfbench store add: --db: " store add R0 --db ""
t 2 "^brdfbench store list: nostore.sqlite: no such store \(No such file or directory; brdfbench store add makes one\)" store list --db nostore.sqlite
printf 'these words are not an SQLite database, whatever the name says\n' >junk.sqlite
t 2 "^brdfbench store list: junk.sqlite: not an SQLite database \(file is not a database\)" store list --db junk.sqlite
t 2 "^brdfbench store add: junk.sqlite: not an SQLite database" store add R0 --db junk.sqlite
mkdir -p dbdir
t 2 "^brdfbench store list: dbdir: not a regular file \(a store is an SQLite file\)" store list --db dbdir
t 2 "^brdfbench store export: --out DIR is required" store export --db junk.sqlite
t 2 "^brdfbench store list: unexpected argument 'x'" store list x --db junk.sqlite
t 2 "^brdfbench history: --db and run folders or files given together \(accepted: one of them\)" history --db junk.sqlite R0
t 2 "^brdfbench history: 1 run folders or files holds 1 run of kind throughput \(a history takes 2 or more\)" history R0 --out hist_out
t 2 "^brdfbench history: base: no throughput.json in the folder \(accepted: a run folder with one, or --kind\)" history base base --out hist_out
t 2 "^brdfbench history: --kind: 'plots' is not a kind of result" history R0 R0 --kind plots
t 2 "^brdfbench history: --fail-if-slower: '150' is (not|out)" history R0 R0 --fail-if-slower 150
t 2 "^brdfbench history: --min-change: '-1' is (not|out)" history R0 R0 --min-change -1
t 2 "^brdfbench history: --alpha: '0.9' is (not|out)" history R0 R0 --alpha 0.9
t 2 "^brdfbench history: nostore.sqlite: no such store" history --db nostore.sqlite
t 2 "^brdfbench history: junk.sqlite: not an SQLite database" history --db junk.sqlite
t 2 "^brdfbench store add: --commit-date: 'yesterday' is not a date and time with its zone \(accepted: ISO 8601" store add R0 --db st.sqlite --commit-date yesterday
t 2 "^brdfbench store add: --commit-date: '2026-13-01T00:00:00Z' is not a date and time with its zone" store add R0 --db st.sqlite --commit-date 2026-13-01T00:00:00Z
t 2 "^brdfbench store add: --commit-date: '2026-03-01T10:00:00' is not a date and time with its zone" store add R0 --db st.sqlite --commit-date 2026-03-01T10:00:00
printf 'not a folder\n' >hist_file
t 2 "^brdfbench history: --out: hist_file is not a folder" history R0 R0 --out hist_file
