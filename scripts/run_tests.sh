#!/bin/bash
# Quick start 2: install what is missing, configure a build with both Debug
# (deal.II assertions on) and Release variants, without debug information
# (the tests need no debugger; it saves a fifth of the build) and with the
# small sources of the library and of the unit tests compiled in batches
# (a third of the library's build; the unit tests' 407 s of compiling on
# one core became 125 s), build everything,
# and run the test suite with ctest: the default tier (what CI runs), or
# with --all also the tests labelled "extended" (tests/README.md).
set -euo pipefail
cd "$(dirname "$0")/.."

tier=(-LE extended)
case "${1:-}" in
  "") ;;
  --all) tier=() ;;
  *)
    echo "usage: $0 [--all]  (--all also runs the tests labelled extended)" >&2
    exit 1
    ;;
esac

bash scripts/install_dependencies.sh
cmake -S . -B build-tests -DCMAKE_BUILD_TYPE=DebugRelease -DVC_DEBUG_INFO=OFF \
  -DVC_UNITY_BUILD=ON
cmake --build build-tests -- -j"$(nproc)"
cd build-tests
ctest --output-on-failure -j"$(nproc)" "${tier[@]}"
