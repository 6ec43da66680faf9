#!/usr/bin/env bash
# check_abi.sh LIBRARY HEADER BASELINE CONSTANTS [CC]
# Compares the ABI of the built libbodt.so with the baseline kept in the
# repository:
#   - with abidiff (Debian: abigail-tools), its exported functions and the
#     types they reach, from the C API's debug information, against BASELINE
#     (libbodt.abi);
#   - the value of every enumerator and integer macro of HEADER
#     (list_constants.sh), against CONSTANTS (libbodt.constants).
# No change, or only functions and constants added: passes (additions are
# compatible; the baseline is refreshed when a version is released).
# Anything else (a function removed or changed, a struct's layout changed, an
# enum value changed or removed, another SONAME) fails.  If the change is
# meant, refresh the baseline on purpose: scripts/update-abi-baseline.sh (see
# docs/api.md, "ABI and SONAME in detail").
set -uo pipefail
lib=$1 header=$2 baseline=$3 constants=$4 cc=${5:-cc}
headers=$(dirname "$header")
here=$(dirname "${BASH_SOURCE[0]}")
if ! command -v abidiff >/dev/null 2>&1; then
  echo "FAIL: abidiff not found (Debian: apt-get install abigail-tools)"; exit 1
fi
for f in "$baseline" "$constants"; do
  if [[ ! -f $f ]]; then
    echo "FAIL: no ABI baseline at $f; make one with scripts/update-abi-baseline.sh"; exit 1
  fi
done

# Constants first: a changed or removed value fails, a new one is fine.
now=$(bash "$here/list_constants.sh" "$header" "$cc") || { echo "FAIL: cannot list the constants of $header"; exit 1; }
lost=$(comm -23 <(sort "$constants") <(sort <<<"$now"))
if [[ -n $lost ]]; then
  echo "FAIL: enum or macro values of the baseline that $header no longer has (NAME VALUE):"
  sed 's/^/  /' <<<"$lost"
  echo "      If the change is intended, refresh the baseline on purpose with scripts/update-abi-baseline.sh"
  exit 1
fi
echo "constants: $(wc -l <"$constants") of the baseline kept, $(comm -13 <(sort "$constants") <(sort <<<"$now") | grep -c .) added"

report=$(abidiff --headers-dir2 "$headers" --exported-interfaces-only --no-show-locs \
                 "$baseline" "$lib" 2>&1)
rc=$?
echo "abidiff $(basename "$baseline") $(basename "$lib"): exit $rc"
[[ -n $report ]] && sed 's/^/  | /' <<<"$report"

# abidiff's exit status is a bit field: 1 error, 2 usage error, 4 ABI change,
# 8 incompatible ABI change.
if ((rc == 0)); then
  echo "OK: the ABI is the baseline's"; exit 0
fi
if ((rc & 3)); then
  echo "FAIL: abidiff could not compare (exit $rc)"; exit 1
fi
if ((rc & 8)); then
  echo "FAIL: incompatible ABI change (a function or variable was removed)"; exit 1
fi
# Only additions?  "Functions changes summary: 0 Removed, 0 Changed, 2 Added functions"
if grep -qE '^Functions changes summary: 0 Removed, 0 Changed(, [0-9]+ Added functions?)?$' <<<"$report" &&
   grep -qE '^Variables changes summary: 0 Removed, 0 Changed' <<<"$report" &&
   ! grep -qE 'SONAME changed|changed from .* to ' <<<"$report"; then
  echo "OK: functions were added since the baseline (compatible); refresh it at the next release"
  exit 0
fi
echo "FAIL: the ABI changed (see above).  If the change is intended, refresh the"
echo "      baseline on purpose with scripts/update-abi-baseline.sh and say so in CHANGELOG.md"
exit 1
