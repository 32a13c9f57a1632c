#!/usr/bin/env bash
# Renders a case's fitted top and bottom contours to a PNG with gnuplot, from the numbers
# `palpa-cli fit --eval` prints (a documentation aid until the VTK views exist).
# Usage: scripts/render-case.sh [CASE] [OUT.png] [BODY]   (needs gnuplot-nox)
set -euo pipefail
cd "$(dirname "$0")/.."
case_file=${1:-data/cases/default.json}
out=${2:-docs/images/default-case.png}
body=${3:-}
cli=build/release/app/palpa-cli
command -v gnuplot >/dev/null || { echo "render-case: needs gnuplot (apt-get install gnuplot-nox)" >&2; exit 1; }
[ -x "$cli" ] || bash scripts/build.sh release

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
n=40
awk -v n=$n 'BEGIN { print "u,v"; for (i = 0; i <= n; i++) for (j = 0; j <= n; j++) printf "%.6f,%.6f\n", i / n, j / n }' \
  > "$tmp/uv.csv"
body_opt=()
[ -n "$body" ] && body_opt=(--body "$body")
for s in top bottom skeleton; do
  # gnuplot's grid format: one block per u, blank line between blocks; z in mm.
  "$cli" fit "$case_file" "${body_opt[@]}" --surface "$s" --eval "$tmp/uv.csv" |
    awk -F, -v n=$((n + 1)) 'NR > 1 { print $3*1000, $4*1000, $5*1000; if ((NR - 1) % n == 0) print "" }' > "$tmp/$s.dat"
done
title=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["title"])' "$case_file")
gnuplot <<GP
set terminal pngcairo size 1000,700 enhanced font "DejaVu Sans,12"
set output "$out"
set title "$title: top and bottom contours fitted by palpa-cli (mm)"
set view 60, 35, 0.85, 1.5
set xyplane at 0
set xtics 40; set ytics 40; set ztics 25
set view equal xy
set xlabel "x"; set ylabel "y"; set zlabel "z"
unset key
set pm3d depthorder border lc rgb "#553322" lw 0.3
set palette defined (0 "#f3c9b0", 1 "#e79b82", 2 "#c9675a")
unset colorbox
splot "$tmp/top.dat" with pm3d, "$tmp/bottom.dat" with pm3d, "$tmp/skeleton.dat" with lines lc rgb "#3355aa" lw 0.6
GP
echo "wrote $out"
