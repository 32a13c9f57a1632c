#!/usr/bin/env bash
# Fuzzes what Palpa reads from outside with libFuzzer under ASan + UBSan (docs/fuzzing.md):
#   scripts/fuzz.sh [SECONDS] [TARGET...]    default: 60 s for each of the five targets
# Builds the fuzz preset (clang) and runs each target for SECONDS over its corpus
# (fuzz/corpus/TARGET, not written to: new inputs go to build/fuzz/found/TARGET), two at a
# time. A crash, a sanitizer report, a leak, an input over 10 s or 2 GB leaves the input in
# build/fuzz/artifacts/ and fails the script. CI runs it with 20 s; the long run is
# scripts/fuzz.sh 3600.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true
all=(case_loader session_scorer timed_points_csv spacemouse_report falcon_packet)
targets=("$@")
if [ $# -eq 0 ]; then targets=("${all[@]}"); fi

declare -A max_len=([case_loader]=16384 [session_scorer]=65536 [timed_points_csv]=4096
                    [spacemouse_report]=512 [falcon_packet]=1024)

cmake --preset fuzz >/dev/null
cmake --build --preset fuzz
mkdir -p build/fuzz/artifacts

run() {
  local name=$1 found=build/fuzz/found/$1
  if [ -z "${max_len[$name]:-}" ]; then
    echo "fuzz: unknown target $name (targets: ${all[*]})" >&2
    return 2
  fi
  mkdir -p "$found"
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    "build/fuzz/fuzz/fuzz_$name" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -max_len="${max_len[$name]}" -artifact_prefix="build/fuzz/artifacts/$name-" -print_final_stats=1 \
    "$found" "fuzz/corpus/$name" >"build/fuzz/$name.log" 2>&1
}

summary() {
  local name=$1 status=$2 log=build/fuzz/$1.log runs
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  if [ "$status" -eq 0 ]; then
    echo "fuzz: $name: ${runs:-?} runs in ${seconds} s, no finding"
  else
    echo "fuzz: $name: FAILED (exit $status); the end of $log:" >&2
    tail -40 "$log" >&2
  fi
}

# Two at a time (a 2-core machine): start two, then one more each time one ends.
failed=0
declare -A pid_of=()
for name in "${targets[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge 2 ]; do sleep 1; done
  run "$name" &
  pid_of[$name]=$!
done
for name in "${targets[@]}"; do
  status=0
  wait "${pid_of[$name]}" || status=$?
  summary "$name" "$status"
  [ "$status" -eq 0 ] || failed=1
done
exit $failed
