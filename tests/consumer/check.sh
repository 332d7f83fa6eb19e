#!/usr/bin/env bash
# Proves that another project can use rt: installed (find_package) and as a
# subdirectory (add_subdirectory). Usage: tests/consumer/check.sh [work-folder]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
work=${1:-$(mktemp -d)}
mkdir -p "$work"

echo "== consumer: install rt to $work/prefix"
cmake -S "$root" -B "$work/rt-build" -DRT_BUILD_TESTS=OFF -DRT_BUILD_STAGES=OFF -DRT_INSTALL=ON \
      -DCMAKE_INSTALL_PREFIX="$work/prefix" > "$work/rt-configure.log"
cmake --install "$work/rt-build" > "$work/rt-install.log"
test -f "$work/prefix/include/rt/rt.hpp"
find "$work/prefix" -name rtConfig.cmake | grep -q .

echo "== consumer: find_package(rt CONFIG REQUIRED)"
cmake -S "$root/tests/consumer" -B "$work/installed" -DCMAKE_PREFIX_PATH="$work/prefix" > "$work/installed.log"
cmake --build "$work/installed" -j2
"$work/installed/consumer" "$work/installed.png"
test -s "$work/installed.png"

echo "== consumer: add_subdirectory(rt)"
cmake -S "$root/tests/consumer" -B "$work/subdir" -DRT_SOURCE_DIR="$root" > "$work/subdir.log"
cmake --build "$work/subdir" -j2
"$work/subdir/consumer" "$work/subdir.png"
test -s "$work/subdir.png"
echo "== consumer: both ways build and run"
