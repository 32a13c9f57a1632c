#!/usr/bin/env bash
# Quick start, part 1: install what Palpa needs, build it and run it on the bundled
# default case (data/cases/default.json).
#
# With a display ($DISPLAY or $WAYLAND_DISPLAY) it opens the trainee window on the case:
# palpate with the mouse, mark with M, Finish for the score card. Without one it runs the
# headless demo exercise instead: an expert scripted trainee palpates the case through the
# haptic engine, the session is recorded and scored, and the report (HTML with coverage
# and pressure maps) is written beside it.
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
echo
if [ -n "${DISPLAY:-}" ] || [ -n "${WAYLAND_DISPLAY:-}" ]; then
  echo "== palpa --case $case_file (trainee mode)"
  exec build/release/app/gui/palpa --case "$case_file"
fi
echo "no display: running the headless demo exercise instead"
sessions=${PALPA_SESSIONS:-${XDG_DATA_HOME:-$HOME/.local/share}/palpa/sessions}
mkdir -p "$sessions"
session=$sessions/demo-$(date -u +%Y%m%dT%H%M%SZ).palpa
"$cli" exercise "$case_file" --trainee demo --style expert --out "$session" --report "$sessions"
echo
echo "Session recorded in $session"
echo "Re-score it with: $cli score $session"
