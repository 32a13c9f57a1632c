#!/usr/bin/env bash
# Quick start, part 2: install what Palpa needs, build it and run the whole test suite:
# the release build (unit, command-line and data tests), then the same suite built with
# AddressSanitizer and UndefinedBehaviorSanitizer, then the fuzz targets for a short run
# (PALPA_FUZZ_SECONDS each, 20 by default; docs/fuzzing.md). The sanitized run leaves out
# cli.bench and ui.acceptance (minutes of timing-driven runs that the release suite has
# just made; the ui unit tests still run sanitized), to keep the whole under 40 minutes.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/install-deps.sh

echo "== release build and tests"
bash scripts/build.sh release
ctest --preset release

echo "== sanitizer build (ASan + UBSan) and tests"
bash scripts/build.sh dev
ctest --preset dev

echo "== fuzz targets (libFuzzer, ASan + UBSan), ${PALPA_FUZZ_SECONDS:-20} s each"
bash scripts/fuzz.sh "${PALPA_FUZZ_SECONDS:-20}"
