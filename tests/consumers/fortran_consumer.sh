#!/usr/bin/env bash
# fortran_consumer.sh PROGRAM.f90
# The way a Fortran user builds against an installed libbodt:
#   PKG_CONFIG_PATH=PREFIX/LIBDIR/pkgconfig
#   gfortran prog.f90 $(pkg-config --cflags --libs bodt-fortran) -Wl,-rpath,$(pkg-config --variable=libdir bodt)
# then runs the program without LD_LIBRARY_PATH (libbodt_fortran.so finds
# libbodt.so beside it through its own run path).
# Environment: PREFIX LIBDIR INCLUDEDIR VERSION PKG_CONFIG FC SANITIZE_FLAGS WORK_DIR.
set -euo pipefail
prog=$1
: "${PKG_CONFIG:=pkg-config}" "${FC:=gfortran}" "${SANITIZE_FLAGS:=}"
if [[ -z $PKG_CONFIG || $PKG_CONFIG == *NOTFOUND ]]; then
  echo "FAIL: pkg-config not found (Debian: apt-get install pkg-config)"; exit 1
fi
libdir=$PREFIX/$LIBDIR
export PKG_CONFIG_PATH=$libdir/pkgconfig
rm -rf "$WORK_DIR" && mkdir -p "$WORK_DIR"

if [[ ! -f $PREFIX/$INCLUDEDIR/bodt.mod ]]; then
  echo "FAIL: bodt.mod is not installed in $PREFIX/$INCLUDEDIR"; exit 1
fi
modversion=$("$PKG_CONFIG" --modversion bodt-fortran)
if [[ $modversion != "$VERSION" ]]; then
  echo "FAIL: pkg-config --modversion bodt-fortran says $modversion, expected $VERSION"; exit 1
fi
# The .pc file must point into the tree it was installed with, wherever that is.
for var in includedir libdir; do
  value=$("$PKG_CONFIG" --variable=$var bodt-fortran)
  case $(realpath -m "$value")/ in
    "$(realpath -m "$PREFIX")"/*) ;;
    *) echo "FAIL: bodt-fortran.pc installed under $PREFIX says $var=$value (see pkgconfig/bodt-fortran.pc.in)"
       exit 1 ;;
  esac
done

flags="$("$PKG_CONFIG" --cflags --libs bodt-fortran) -Wl,-rpath,$("$PKG_CONFIG" --variable=libdir bodt)"
echo "pkg-config --cflags --libs bodt-fortran: $flags"
# Compiled in the work dir: gfortran would write any .mod of the program there.
# shellcheck disable=SC2086  # word splitting of the flags is intended
(cd "$WORK_DIR" && "$FC" -std=f2018 -Wall -Wextra -Werror $SANITIZE_FLAGS "$prog" $flags -o prog)

unset LD_LIBRARY_PATH
for lib in libbodt_fortran libbodt; do
  resolved=$(ldd "$WORK_DIR/prog" | awk -v lib="$lib" '$1 ~ "^" lib "\\.so" {print $3}')
  if [[ $(realpath -m "$resolved") != $(realpath -m "$libdir")/* ]]; then
    echo "FAIL: the program loads $lib from '$resolved', not from $libdir"; exit 1
  fi
done
output=$("$WORK_DIR/prog")
echo "$output"
expected="libbodt $VERSION from Fortran: 5 vertices, 4 tets, 4 boundary faces"
if [[ $output != "$expected" ]]; then
  echo "FAIL: expected '$expected'"; exit 1
fi
