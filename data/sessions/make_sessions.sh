#!/usr/bin/env bash
# Regenerates the sample sessions: the three scripted trainee styles on the default case,
# each with a fixed seed so the files are reproducible (up to their session id and start
# time), with their score cards (STYLE.score.txt) and reports (reports/STYLE.html with the
# coverage and pressure maps, .json, .xapi.json, .csv).
# Usage: bash data/sessions/make_sessions.sh [path/to/palpa-cli]
set -euo pipefail
cd "$(dirname "$0")/../.."
cli=${1:-build/release/app/palpa-cli}
[ -x "$cli" ] || { echo "make_sessions: $cli not found: build first (bash scripts/build.sh)" >&2; exit 1; }

for style in expert sloppy light; do
  out=data/sessions/$style.palpa
  rm -f "$out" data/sessions/reports/"$style".*  # palpa-cli never overwrites a session: this script owns these
  "$cli" exercise data/cases/default.json --trainee "sample-$style" --style "$style" --seed 2026 \
    --out "$out" --report data/sessions/reports > "data/sessions/$style.score.txt"
  echo "make_sessions: $out"
done
