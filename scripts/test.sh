#!/usr/bin/env bash
# Builds and tests everything twice on a fresh Debian 12 machine:
#   1. Release with tests and the reader fuzzers (30 s each) in build/, ctest
#   2. -DBODT_SANITIZE=ON (ASan + UBSan, RelWithDebInfo) in build-asan/, ctest
# Both steps always run; the script exits nonzero if any build or test failed.
#
#   bash scripts/test.sh [extra cmake -D options for both builds]
set -uo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"

bash scripts/setup-debian.sh || exit 1

jobs=$(nproc)
# Sanitizers: stop at the first error, with a stack; report leaks.  Values
# already in the environment win.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:halt_on_error=1:abort_on_error=0:strict_init_order=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}

failures=()
passed_total=0
failed_total=0

# run_suite NAME BUILD_DIR CMAKE_ARGS...
run_suite() {
  local name=$1 dir=$2
  shift 2
  echo
  echo "================ $name: configure ($dir)"
  if ! cmake -S . -B "$dir" -DBODT_BUILD_TESTS=ON "$@"; then
    failures+=("$name: configure"); return
  fi
  echo "================ $name: build"
  if ! cmake --build "$dir" -j"$jobs"; then
    failures+=("$name: build"); return
  fi
  echo "================ $name: ctest"
  local log="$dir/ctest-summary.log" rc
  (cd "$dir" && ctest --output-on-failure --no-tests=error --timeout 1500 -j"$jobs") 2>&1 | tee "$log"
  rc=${PIPESTATUS[0]}
  # "100% tests passed, 0 tests failed out of 42"
  local line total failed
  line=$(grep -E '^[0-9]+% tests passed, [0-9]+ tests? failed out of [0-9]+' "$log" | tail -n 1)
  if [[ -n $line ]]; then
    total=${line##* out of }
    failed=$(sed -E 's/.* passed, ([0-9]+) tests? failed.*/\1/' <<<"$line")
    passed_total=$((passed_total + total - failed))
    failed_total=$((failed_total + failed))
  fi
  if ((rc != 0)); then failures+=("$name: ctest (exit $rc)"); fi
}

run_suite "Release" build -DCMAKE_BUILD_TYPE=Release -DBODT_SANITIZE=OFF -DBODT_BUILD_FUZZERS=ON "$@"
run_suite "ASan+UBSan" build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBODT_SANITIZE=ON "$@"

echo
echo "================ summary"
if ((${#failures[@]})); then
  printf 'FAILED: %s\n' "${failures[@]}"
fi
echo "total: $passed_total passed, $failed_total failed"
((${#failures[@]} == 0))
