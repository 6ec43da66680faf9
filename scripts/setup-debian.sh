#!/usr/bin/env bash
# Installs the Debian 12 packages that libbodt's build, tests and demo need,
# if any is missing.  Idempotent: when everything is installed it only asks
# dpkg and never runs apt-get.  Needs root (or sudo) only when it installs.
set -euo pipefail

packages=(
  build-essential   # gcc, g++, make, libc headers (and the ASan/UBSan runtimes)
  cmake             # >= 3.20
  pkg-config        # the install test compiles against bodt.pc
  binutils          # nm, readelf (export checks)
  libeigen3-dev     # MPL-2.0, header-only, used by the core
  libopenmesh-dev   # BSD-3-Clause, used by the core
  libcmocka-dev     # Apache-2.0, unit tests
  zlib1g-dev        # zlib, in libbodt.so: reads zlib-compressed .vtu (ParaView's and meshio's default)
  libtet1.5-dev     # AGPL-3, command-line tool and tests only (never libbodt.so)
  gfortran          # the Fortran module (bindings/fortran) and its tests
  python3           # tests may parse JSON with /usr/bin/python3
  python3-numpy     # the Python package (bindings/python) and its tests
  python3-cffi      # the tests of bodt.cffi_cdef() and the README's cffi recipe
  python3-gmsh      # python.gmsh_files: Gmsh itself opens the .msh files bodt writes
  python3-meshio    # meshio reads the files we write, writes the ones we read; bodt.from_meshio / to_meshio
  python3-venv      # the test of `pip install ./bindings/python` (a venv, with pip from python3-pip-whl)
  calculix-ccx      # interop_calculix: CalculiX solves a bar from our .inp
  abigail-tools     # abidiff: the ABI check against tests/consumers/libbodt.abi
  chromium          # renders the HTML report headless in its test (screenshot)
  clang             # clang++ for the libFuzzer targets of the readers (tests/fuzz)
  libclang-rt-14-dev # libFuzzer and the sanitizer runtimes for clang 14
)

if ! command -v dpkg-query >/dev/null 2>&1; then
  echo "setup-debian.sh: not a Debian system (no dpkg-query); install the equivalents of:" >&2
  echo "  ${packages[*]}" >&2
  exit 0
fi

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${db:Status-Abbrev}' "$p" 2>/dev/null || true)
  [[ $status == ii* ]] || missing+=("$p")
done

if ((${#missing[@]} == 0)); then
  echo "setup-debian.sh: all ${#packages[@]} required packages are installed"
  exit 0
fi

echo "setup-debian.sh: installing ${missing[*]}"
sudo=()
if [[ $(id -u) -ne 0 ]]; then
  if command -v sudo >/dev/null 2>&1; then
    sudo=(sudo)
  else
    echo "setup-debian.sh: run as root, or install: apt-get install ${missing[*]}" >&2
    exit 1
  fi
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update </dev/null
"${sudo[@]}" apt-get install -y --no-install-recommends "${missing[@]}" </dev/null
