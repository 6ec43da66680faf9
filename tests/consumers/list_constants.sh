#!/usr/bin/env bash
# list_constants.sh HEADER [CC]
# Prints "NAME VALUE" for every enumerator and integer macro of bodt.h (but
# the version macros), sorted, with the values the C compiler gives them.
# Enum values are part of the ABI, yet the functions take plain ints, so
# abidiff never sees them: check_abi.sh compares this list with
# libbodt.constants.
set -euo pipefail
header=$1 cc=${2:-cc}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

names=$( { awk '/^(typedef )?enum /,/^}/' "$header" | sed -nE 's/^[[:space:]]+(BODT_[A-Z0-9_]+)[[:space:]]*=.*/\1/p'
           sed -nE 's/^#define (BODT_[A-Z0-9_]+)[[:space:]]+\(?-?[0-9].*/\1/p' "$header" | grep -v '^BODT_VERSION_'
         } | sort -u)
{
  echo '#include <stdio.h>'
  echo "#include \"$header\""
  echo 'int main(void) {'
  for n in $names; do echo "    printf(\"$n %lld\\n\", (long long)($n));"; done
  echo '    return 0;'
  echo '}'
} >"$work/constants.c"
"$cc" -std=c99 -o "$work/constants" "$work/constants.c"
"$work/constants"
