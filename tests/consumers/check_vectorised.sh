#!/usr/bin/env bash
# check_vectorised.sh LIBRARY
# The per-tet loops built as AVX-512 and AVX2 clones (BODT_VECTOR_CLONES in
# src/quality/tet_geometry.hpp) must really be vectorised, and must leave
# the vector registers clean for the SSE code of the rest of the library:
#   - each clone holds packed square roots or divisions.  A loop GCC cannot
#     if-convert, or whose vector width does not fit a star, falls back to
#     scalar code without a word (the guard's star loop did, until
#     -fno-trapping-math and one-width masks);
#   - each clone calls nothing and clears the upper halves (vzeroupper)
#     on its way out (a return before any vector code needs none).  A call out of a clone (std::find was one) may
#     return with them dirty, and the flip pass after a sweep then ran a
#     third slower.
# So the library's disassembly is checked.
set -euo pipefail
lib=$1
listing=$(objdump -d --no-show-raw-insn "$lib")
fail=0
for fn in first_failing star_terms block_shapes; do
  for clone in avx512f avx2; do
    read -r packed calls cleared < <(awk -v fn="$fn" -v clone="$clone" '
      />:$/ { inside = index($0, fn) > 0 && index($0, "." clone ">:") > 0; next }
      inside && /v(sqrt|div)pd/ { p++ }
      inside && /\tcall/ { c++ }
      inside && /vzeroupper/ { z++ }
      END { print p + 0, c + 0, z + 0 }' <<<"$listing")
    echo "$fn.$clone: $packed packed sqrt/div, $calls calls, $cleared vzeroupper"
    if ((packed == 0)); then
      echo "FAIL: $fn.$clone is not vectorised"
      fail=1
    fi
    if ((calls != 0 || cleared == 0)); then
      echo "FAIL: $fn.$clone calls out or never clears the upper halves"
      fail=1
    fi
  done
done
exit $fail
