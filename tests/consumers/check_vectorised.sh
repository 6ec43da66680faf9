#!/usr/bin/env bash
# check_vectorised.sh LIBRARY
# The per-tet loops built as AVX-512 and AVX2 clones (BODT_VECTOR_CLONES in
# src/quality/tet_geometry.hpp) must really be vectorised: each clone holds
# packed square roots or divisions.  A loop GCC cannot if-convert or whose
# vector width does not fit a star falls back to scalar code without a word
# (it did, for the guard's star loop, until -fno-trapping-math and
# one-width masks), so the library's disassembly is checked.
set -euo pipefail
lib=$1
listing=$(objdump -d --no-show-raw-insn "$lib")
fail=0
for fn in first_failing star_terms block_shapes; do
  for clone in avx512f avx2; do
    packed=$(awk -v fn="$fn" -v clone="$clone" '
      />:$/ { inside = index($0, fn) > 0 && index($0, "." clone ">:") > 0; next }
      inside && /v(sqrt|div)pd/ { n++ }
      END { print n + 0 }' <<<"$listing")
    echo "$fn.$clone: $packed packed sqrt/div"
    if ((packed == 0)); then
      echo "FAIL: $fn.$clone is not vectorised"
      fail=1
    fi
  done
done
exit $fail
