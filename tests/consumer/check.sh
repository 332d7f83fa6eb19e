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
test -f "$work/prefix/include/rt/vec.hpp" # the old flat paths' forwarders, for one release (CHANGELOG.md)
find "$work/prefix" -name rtConfig.cmake | grep -q .

echo "== consumer: docs/library.md's code example, as written there"
# the first ```cpp block after the readme-example marker
awk '/<!-- readme-example/ {armed = 1; next} armed && /^```cpp/ {on = 1; next} on && /^```/ {exit} on {print}' \
    "$root/docs/library.md" > "$work/readme_example.cpp"
test -s "$work/readme_example.cpp" || { echo "docs/library.md: no readme-example code block found" >&2; exit 1; }

echo "== consumer: find_package(rt CONFIG REQUIRED)"
cmake -S "$root/tests/consumer" -B "$work/installed" -DCMAKE_PREFIX_PATH="$work/prefix" \
      -DRT_README_EXAMPLE="$work/readme_example.cpp" > "$work/installed.log"
cmake --build "$work/installed" -j2
"$work/installed/consumer" "$work/installed.png"
test -s "$work/installed.png"
(cd "$work/installed" && rm -f sphere.png && ./readme_example && test -s sphere.png)
echo "== consumer: the README example wrote $work/installed/sphere.png"

echo "== consumer: add_subdirectory(rt)"
cmake -S "$root/tests/consumer" -B "$work/subdir" -DRT_SOURCE_DIR="$root" > "$work/subdir.log"
cmake --build "$work/subdir" -j2
"$work/subdir/consumer" "$work/subdir.png"
test -s "$work/subdir.png"
echo "== consumer: both ways build and run"
