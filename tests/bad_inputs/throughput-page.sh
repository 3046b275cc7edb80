# bad_inputs/throughput-page.sh - rows of the throughput page (issue 32): report.md's Throughput
# section is drawn from throughput.json's rows, so a run folder whose throughput.json cannot be
# read as rows is named, whatever its throughput.md. Fixture: R0 (all --quick) of
# test_cli_errors.sh, copied by its ff and ej helpers.
ff Q throughput.json
t 2 "^brdfbench report: Q/throughput.json: is a FIFO, not a regular file" report Q
ej Q throughput.json "del d['rows']"
t 2 "^brdfbench report: Q/throughput.json: schema \"brdfbench.throughput/5\" without its \"rows\"" report Q
ej Q throughput.json "d['rows']['rows'][1]['metrics'] = 5"
t 2 "^brdfbench report: Q/throughput.json:1:[0-9]+: " report Q
rm -rf Q && cp -r R0 Q && rm Q/throughput.json
WHAT='Q/throughput.json: removed'
t 2 "^brdfbench report: Q/throughput.json: missing \(run.json records its part as done\)" report Q
