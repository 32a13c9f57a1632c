#!/usr/bin/env bash
# Quick start, part 1: install what Palpa needs, build it and run it on the bundled
# default case (data/cases/default.json).
#
# The trainee GUI arrives with the application issue; until then this runs the headless
# work that exists: validate the default case and fit its medial-axis body model.
set -euo pipefail
cd "$(dirname "$0")/.."
case_file=${1:-data/cases/default.json}

bash scripts/install-deps.sh
bash scripts/build.sh release

cli=build/release/app/palpa-cli
echo
echo "== palpa-cli validate $case_file"
"$cli" validate "$case_file"
echo
echo "== palpa-cli fit $case_file"
"$cli" fit "$case_file"
