#!/usr/bin/env bash
# pkg_config_consumer.sh PROGRAM.c
# The way the README tells a C user to build against an installed libbodt:
#   PKG_CONFIG_PATH=PREFIX/LIBDIR/pkgconfig
#   cc prog.c $(pkg-config --cflags --libs bodt) -Wl,-rpath,$(pkg-config --variable=libdir bodt)
# then runs the program without LD_LIBRARY_PATH.
# Environment: PREFIX LIBDIR VERSION PKG_CONFIG CC SANITIZE_FLAGS WORK_DIR.
set -euo pipefail
prog=$1
: "${PKG_CONFIG:=pkg-config}" "${CC:=cc}" "${SANITIZE_FLAGS:=}"
if [[ -z $PKG_CONFIG || $PKG_CONFIG == *NOTFOUND ]]; then
  echo "FAIL: pkg-config not found (Debian: apt-get install pkg-config)"; exit 1
fi
libdir=$PREFIX/$LIBDIR
export PKG_CONFIG_PATH=$libdir/pkgconfig
rm -rf "$WORK_DIR" && mkdir -p "$WORK_DIR"

pcdir=$("$PKG_CONFIG" --variable=pcfiledir bodt)
if [[ $(realpath -m "$pcdir") != $(realpath -m "$libdir/pkgconfig") ]]; then
  echo "FAIL: pkg-config found bodt.pc in $pcdir, not in $libdir/pkgconfig"; exit 1
fi
modversion=$("$PKG_CONFIG" --modversion bodt)
if [[ $modversion != "$VERSION" ]]; then
  echo "FAIL: pkg-config --modversion bodt says $modversion, expected $VERSION"; exit 1
fi
# The .pc file must point into the tree it was installed with, wherever that is.
for var in includedir libdir; do
  value=$("$PKG_CONFIG" --variable=$var bodt)
  case $(realpath -m "$value")/ in
    "$(realpath -m "$PREFIX")"/*) ;;
    *) echo "FAIL: bodt.pc installed under $PREFIX says $var=$value."
       echo "      The .pc file must not hard-code the configure-time CMAKE_INSTALL_PREFIX:"
       echo "      derive prefix from \${pcfiledir} (see pkgconfig/bodt.pc.in)."
       sed 's/^/      | /' "$libdir/pkgconfig/bodt.pc"
       exit 1 ;;
  esac
done

flags="$("$PKG_CONFIG" --cflags --libs bodt) -Wl,-rpath,$("$PKG_CONFIG" --variable=libdir bodt)"
echo "pkg-config --cflags --libs bodt: $flags"
# shellcheck disable=SC2086  # word splitting of the flags is intended
"$CC" -std=c99 -Wall -Wextra -Werror $SANITIZE_FLAGS "$prog" $flags -o "$WORK_DIR/prog"

unset LD_LIBRARY_PATH
resolved=$(ldd "$WORK_DIR/prog" | awk '$1 ~ /^libbodt/ {print $3}')
if [[ $(realpath -m "$resolved") != $(realpath -m "$libdir")/* ]]; then
  echo "FAIL: the program loads libbodt from '$resolved', not from $libdir"; exit 1
fi
"$WORK_DIR/prog"
