#!/usr/bin/env bash
# Installs BUILD_DIR with `cmake --install --prefix PREFIX` (a scratch
# directory in the build tree, never the system prefix) and checks the tree.
# Environment: CMAKE BUILD_DIR SOURCE_DIR PREFIX LIBDIR INCLUDEDIR BINDIR
# VERSION SOVERSION, and WITH_FORTRAN (ON: the Fortran module is built) and
# PYTHON_DIR (where the Python package goes; empty: not built).  Exit 77 (skipped) if the install dirs are absolute,
# since --prefix would not redirect them.
set -euo pipefail
: "${CMAKE:=cmake}"
for d in "$LIBDIR" "$INCLUDEDIR" "$BINDIR"; do
  if [[ $d == /* ]]; then
    echo "SKIP: install directory '$d' is absolute; cmake --install --prefix cannot redirect it"
    exit 77
  fi
done
case $PREFIX in
  ""|/|/usr|/usr/local) echo "FAIL: refusing to install into '$PREFIX'"; exit 1 ;;
esac
if [[ ! -e $BUILD_DIR/cmake_install.cmake ]]; then
  echo "FAIL: $BUILD_DIR is not a configured build tree"; exit 1
fi

unset DESTDIR
rm -rf "$PREFIX"
"$CMAKE" --install "$BUILD_DIR" --prefix "$PREFIX"

fail=0
check() {  # check DESCRIPTION TEST-ARGS...
  local what=$1; shift
  if test "$@"; then echo "ok   $what"; else echo "FAIL $what"; fail=1; fi
}
lib=$PREFIX/$LIBDIR
check "header $INCLUDEDIR/bodt.h" -f "$PREFIX/$INCLUDEDIR/bodt.h"
if ! cmp -s "$SOURCE_DIR/include/bodt.h" "$PREFIX/$INCLUDEDIR/bodt.h"; then
  echo "FAIL the installed bodt.h differs from include/bodt.h"; fail=1
fi
check "$LIBDIR/pkgconfig/bodt.pc" -f "$lib/pkgconfig/bodt.pc"
# check_library NAME: the file, the SONAME link and the development link
check_library() {
  local name=$1
  check "$LIBDIR/$name.so.$VERSION is a file" -f "$lib/$name.so.$VERSION" -a ! -L "$lib/$name.so.$VERSION"
  check "$LIBDIR/$name.so.$SOVERSION -> $name.so.$VERSION" \
    -L "$lib/$name.so.$SOVERSION" -a "$(readlink "$lib/$name.so.$SOVERSION" 2>/dev/null)" = "$name.so.$VERSION"
  check "$LIBDIR/$name.so -> $name.so.$SOVERSION" \
    -L "$lib/$name.so" -a "$(readlink "$lib/$name.so" 2>/dev/null)" = "$name.so.$SOVERSION"
}
check_library libbodt
if [[ ${WITH_FORTRAN:-OFF} == ON ]]; then
  check "module $INCLUDEDIR/bodt.mod" -f "$PREFIX/$INCLUDEDIR/bodt.mod"
  check_library libbodt_fortran
  check "$LIBDIR/pkgconfig/bodt-fortran.pc" -f "$lib/pkgconfig/bodt-fortran.pc"
fi
if [[ -n ${PYTHON_DIR:-} ]]; then
  for f in __init__.py mesh.py _library.py _paths.py _version.py; do
    check "Python package $PYTHON_DIR/bodt/$f" -f "$PREFIX/$PYTHON_DIR/bodt/$f"
  done
fi
for f in bodtConfig.cmake bodtConfigVersion.cmake bodtTargets.cmake; do
  check "$LIBDIR/cmake/bodt/$f" -f "$lib/cmake/bodt/$f"
done
per_config=$(find "$lib/cmake/bodt" -name 'bodtTargets-*.cmake' 2>/dev/null | head -n 1)
check "$LIBDIR/cmake/bodt/bodtTargets-<config>.cmake" -n "$per_config"
check "$BINDIR/bodt" -x "$PREFIX/$BINDIR/bodt"

# The installed command and libbodt_fortran.so find libbodt.so through their
# run paths ($ORIGIN-relative), without LD_LIBRARY_PATH, also after the
# tree is moved.
unset LD_LIBRARY_PATH
if [[ -x $PREFIX/$BINDIR/bodt ]]; then
  got=$("$PREFIX/$BINDIR/bodt" --version 2>&1 || true)
  check "installed 'bodt --version' says 'bodt $VERSION' (got '$got')" "$got" = "bodt $VERSION"
  out=$PREFIX.improved.mesh
  "$PREFIX/$BINDIR/bodt" improve "$SOURCE_DIR/tests/data/box2.mesh" "$out" --iterations 2 --quiet
  check "installed 'bodt improve' wrote $out" -s "$out"
  rm -f "$out"
  moved=$PREFIX.moved
  rm -rf "$moved" && cp -a "$PREFIX" "$moved"
  got=$("$moved/$BINDIR/bodt" --version 2>&1 || true)
  check "'bodt --version' of the tree copied to $moved says 'bodt $VERSION' (got '$got')" "$got" = "bodt $VERSION"
  rm -rf "$moved"
fi
if [[ ${WITH_FORTRAN:-OFF} == ON ]]; then
  needs=$(ldd "$lib/libbodt_fortran.so.$VERSION" | awk '$1 ~ /^libbodt\.so/ {print $3}')
  check "libbodt_fortran.so finds libbodt.so beside it (got '$needs')" \
    "$(realpath -m "$needs")" = "$(realpath -m "$lib/libbodt.so.$SOVERSION")"
fi

echo "installed tree:"
(cd "$PREFIX" && find . \( -type f -o -type l \) | sort | sed 's/^/  /')
if ((fail)); then exit 1; fi
echo "OK: installed into $PREFIX"
