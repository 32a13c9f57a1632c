#!/usr/bin/env bash
# Quick start, part 1: install what Palpa needs, build it and run it on the bundled
# default case (data/cases/default.json).
#
# The trainee GUI arrives with the application issue; until then this runs the headless
# work that exists: validate the default case, fit its medial-axis body model, and press a
# scripted finger into it through the haptic engine.
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
[ "$case_file" = data/cases/default.json ] || exit 0  # the scripted press below is made for the default case
echo
echo "== palpa-cli simulate: a scripted finger presses 30 mm into the body over the tumour"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
# Down 30 mm over the tumour of the default case in 1 s, back out in 1 s.
awk 'BEGIN { print "t,x,y,z"; for (k = 0; k <= 20; k++) { d = 0.003 * (k <= 10 ? k : 20 - k); printf "%.2f,0.0245,0.02,%.4f\n", 0.1 * k, 0.046 - d } }' \
  > "$out/press.csv"
"$cli" simulate "$case_file" --trajectory "$out/press.csv" --out "$out/samples.csv"
awk -F, 'NR > 1 { f = sqrt($5 * $5 + $6 * $6 + $7 * $7); if (f > peak) { peak = f; t = $1 }; if ($11 > depth) depth = $11 }
         END { printf "peak force %.1f N at t = %.3f s, deepest press %.1f mm (one CSV row per 1 kHz tick)\n", peak, t, depth * 1000 }' \
  "$out/samples.csv"
