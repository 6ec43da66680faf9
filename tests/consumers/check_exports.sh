#!/usr/bin/env bash
# check_exports.sh LIBRARY HEADER SONAME
# libbodt.so must export the functions bodt.h declares (BODT_API) and nothing
# else, carry SONAME SONAME, and not depend on TetGen (AGPL).
set -euo pipefail
lib=$1 header=$2 soname=$3
fail=0

exported=$(nm -D --defined-only --format=posix "$lib" | awk '{print $1}' | sed 's/@.*//' | sort -u)
echo "exported dynamic symbols: $(wc -l <<<"$exported")"
foreign=$(grep -v '^bodt_' <<<"$exported" || true)
if [[ -n $foreign ]]; then
  echo "FAIL: symbols outside the bodt_ namespace are exported:"
  sed 's/^/  /' <<<"$foreign"
  fail=1
fi

declared=$(sed -nE 's/^BODT_API[^(]*[ *](bodt_[A-Za-z0-9_]+)\(.*/\1/p' "$header" | sort -u)
if [[ -z $declared ]]; then
  echo "FAIL: found no BODT_API declarations in $header"
  fail=1
fi
missing=$(comm -23 <(echo "$declared") <(echo "$exported"))
extra=$(comm -13 <(echo "$declared") <(echo "$exported"))
if [[ -n $missing ]]; then
  echo "FAIL: declared in bodt.h but not exported:"; sed 's/^/  /' <<<"$missing"; fail=1
fi
if [[ -n $extra ]]; then
  echo "FAIL: exported but not declared in bodt.h:"; sed 's/^/  /' <<<"$extra"; fail=1
fi

actual_soname=$(readelf -d "$lib" | sed -nE 's/.*\(SONAME\).*\[(.*)\].*/\1/p')
if [[ $actual_soname != "$soname" ]]; then
  echo "FAIL: SONAME is '$actual_soname', expected '$soname'"
  fail=1
else
  echo "SONAME $actual_soname"
fi

needed=$(readelf -d "$lib" | sed -nE 's/.*\(NEEDED\).*\[(.*)\].*/\1/p')
echo "NEEDED: $(tr '\n' ' ' <<<"$needed")"
if grep -qi 'tet' <<<"$needed" || nm -D "$lib" | grep -qi 'tetgen'; then
  echo "FAIL: libbodt.so depends on TetGen (AGPL); TetGen belongs to the command and tests only"
  fail=1
fi

if ((fail)); then exit 1; fi
echo "OK: $(wc -l <<<"$declared") bodt_* functions declared and exported, nothing else"
