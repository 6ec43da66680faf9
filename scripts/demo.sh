#!/usr/bin/env bash
# The main job, end to end on a fresh Debian 12 machine: install what is
# missing, build the `bodt` command (Release, in build/), and improve a small,
# visibly bad tet mesh bundled in examples/data/ with B-ODT (the default
# mode), printing the quality before and after and writing the HTML report
# build/demo/report.html, then compare the two.
#
#   bash scripts/demo.sh [extra cmake -D options]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"

bash scripts/setup-debian.sh

echo "== configure and build (Release, build/)"
# Only the command is needed: the test suite is left out (scripts/test.sh
# turns it back on in the same build/).
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DBODT_BUILD_TESTS=OFF "$@"
cmake --build build --target bodt_cli -j"$(nproc)"

in=examples/data/stellar_house2.node
out=build/demo/stellar_house2-bodt.mesh
mkdir -p build/demo
report=build/demo/report.html
echo
echo "== bodt improve $in $out --mode bodt --iterations 20 --report $report"
echo "   (Stellar's house2: 400 vertices, 1389 tets; angles in degrees)"
build/bodt improve "$in" "$out" --mode bodt --iterations 20 --report "$report"
echo
echo "== bodt compare $in $out"
build/bodt compare "$in" "$out"
echo "open $report in a browser: quality, histograms, the worst tets in three views, the run's steps"
