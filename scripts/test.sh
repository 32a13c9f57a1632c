#!/usr/bin/env bash
# Quick start, part 2: install what Palpa needs, build it and run the whole test suite:
# the release build (unit, command-line and data tests), then the same suite built with
# AddressSanitizer and UndefinedBehaviorSanitizer, then the fuzz targets for a short run
# (PALPA_FUZZ_SECONDS each, 30 by default; docs/fuzzing.md).
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/install-deps.sh

echo "== release build and tests"
bash scripts/build.sh release
ctest --preset release

echo "== sanitizer build (ASan + UBSan) and tests"
bash scripts/build.sh dev
ctest --preset dev

echo "== fuzz targets (libFuzzer, ASan + UBSan), ${PALPA_FUZZ_SECONDS:-30} s each"
bash scripts/fuzz.sh "${PALPA_FUZZ_SECONDS:-30}"
