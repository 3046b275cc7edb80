#!/usr/bin/env bash
# main.sh - set-up, build, then the main job: every model on the default grids, with
# results, pictures and report.md in a new folder results/<date-time>/ (results/latest).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
export POCL_AFFINITY=${POCL_AFFINITY:-1}
exec ./build/brdfbench all "$@"
