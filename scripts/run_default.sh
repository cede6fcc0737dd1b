#!/bin/bash
# Quick start 1: install what is missing, configure and build in Release, and
# run the default scene (the reference benchmark, h = 1/32, k = 1/64), which
# writes into output/default/.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/install_dependencies.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build --target viscoplastic_contact -- -j"$(nproc)"
# The scene with Overwrite = true, so that running this script again
# replaces the earlier run's results (exactly the files its manifest lists)
# instead of being refused.
printf 'include %s\nsubsection Output\n  set Overwrite = true\nend\n' \
  "$PWD/parameters/default.prm" > build/default_scene.prm
./build/viscoplastic_contact build/default_scene.prm
