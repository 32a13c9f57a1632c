#!/usr/bin/env bash
# Regenerates the sample sessions: the three scripted trainee styles on the default case,
# each with a fixed seed so the files are reproducible (up to their session id and start
# time). Usage: bash data/sessions/make_sessions.sh [path/to/palpa-cli]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
cli=${1:-$repo/build/release/app/palpa-cli}
[ -x "$cli" ] || { echo "make_sessions: $cli not found: build first (bash scripts/build.sh)" >&2; exit 1; }

for style in expert sloppy light; do
  out=$here/$style.palpa
  rm -f "$out"  # sessions are never overwritten by palpa-cli: this script owns these files
  (cd "$repo" && "$cli" exercise data/cases/default.json --trainee "sample-$style" --style "$style" \
     --seed 2026 --out "$out" > "$here/$style.score.txt")
  echo "make_sessions: $out"
done
