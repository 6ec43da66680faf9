#!/usr/bin/env bash
# Refreshes the ABI baseline, tests/consumers/libbodt.abi (the functions and
# types, from a built libbodt.so) and tests/consumers/libbodt.constants (the
# enum and macro values of include/bodt.h), on purpose: at a release, or with a deliberate ABI change that
# CHANGELOG.md records (see docs/api.md, "ABI and SONAME in detail").  The CTest test
# consumers.abi compares every build with this baseline.
#
#   bash scripts/update-abi-baseline.sh [BUILD_DIR]     (default: build)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${1:-$root/build}
lib=$build/libbodt.so
if [[ ! -e $lib ]]; then
  echo "update-abi-baseline.sh: no $lib; build first (cmake -S . -B build && cmake --build build)" >&2
  exit 1
fi
# Only the exported functions and the types they reach; no absolute paths, so
# the file does not depend on where the tree was built.
abidw --exported-interfaces-only --headers-dir "$root/include" --drop-private-types \
      --no-corpus-path --no-comp-dir-path --short-locs \
      --out-file "$root/tests/consumers/libbodt.abi" "$lib"
bash "$root/tests/consumers/list_constants.sh" "$root/include/bodt.h" "${CC:-cc}" \
  >"$root/tests/consumers/libbodt.constants"
echo "wrote tests/consumers/libbodt.abi from $(readlink -f "$lib") and tests/consumers/libbodt.constants"
