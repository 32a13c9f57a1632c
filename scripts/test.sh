#!/usr/bin/env bash
# Quick start, part 2: install what Palpa needs, build it and run the whole test suite:
# the release build (unit, command-line, data and GUI tests), then the same suite without
# the GUI built with AddressSanitizer and UndefinedBehaviorSanitizer (core, devices, store,
# reports and every command-line test), then the fuzz targets for a short run
# (PALPA_FUZZ_SECONDS each, 20 by default; docs/fuzzing.md). The sanitized run leaves out
# cli.bench and the GUI, to keep the whole near 40 minutes on two cores: compiling the
# Qt/VTK windows under the sanitizers and running their tests there took about a third of
# it. The GUI's sanitized run is on demand: bash scripts/build.sh dev-gui && ctest --preset dev-gui.
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
