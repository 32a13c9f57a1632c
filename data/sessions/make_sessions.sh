#!/usr/bin/env bash
# Regenerates the sample sessions' score cards (STYLE.score.txt) and reports
# (reports/STYLE.html with the coverage and pressure maps, .json, .xapi.json, .csv).
# The sessions themselves are kept: they are format-1 files (one row per tick), the truth
# that format-1 reading, `palpa-cli session upgrade` and the batch corpus are tested on.
# With --record the three scripted trainee styles are recorded again first on the default
# case, each with a fixed seed (reproducible up to the session id and start time). Today's
# writer makes format 2: --record replaces the format-1 samples with format-2 files, which
# the format-1 tests and make_batch_corpus.py --minutes then refuse.
# Usage: bash data/sessions/make_sessions.sh [--record] [path/to/palpa-cli]
set -euo pipefail
cd "$(dirname "$0")/../.."
record=0
if [ "${1:-}" = "--record" ]; then record=1; shift; fi
cli=${1:-build/release/app/palpa-cli}
[ -x "$cli" ] || { echo "make_sessions: $cli not found: build first (bash scripts/build.sh)" >&2; exit 1; }

for style in expert sloppy light; do
  out=data/sessions/$style.palpa
  rm -f data/sessions/reports/"$style".*  # palpa-cli never overwrites a report: this script owns these
  if [ "$record" = 1 ]; then
    rm -f "$out"
    "$cli" exercise data/cases/default.json --trainee "sample-$style" --style "$style" --seed 2026 \
      --out "$out" > /dev/null
  fi
  "$cli" score "$out" --report data/sessions/reports > "data/sessions/$style.score.txt"
  echo "make_sessions: $out"
done
