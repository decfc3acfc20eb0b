#!/usr/bin/env bash
# The whole test suite, as CI runs it (.ci/run runs exactly this): set up and build (ci/setup.sh),
# every CTest test, then the libFuzzer targets in their reproducible CI mode (fuzz/run_ci.sh:
# clang build with ASan + UBSan, every kept regression input replayed, then each target from a
# fixed seed for a fixed number of inputs on a fresh corpus). Both parts always run; the exit
# status is non-zero when either failed.
set -uo pipefail
cd "$(dirname "$0")/.." || exit 1
bash ci/setup.sh || exit 1
status=0
ctest --test-dir build --output-on-failure -j 2 || status=1
bash fuzz/run_ci.sh || status=1
exit "${status}"
