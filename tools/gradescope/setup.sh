#!/usr/bin/env bash
# Gradescope runs this once, as root, when it builds the autograder's image. It installs
# what rt's build needs (unless RT_AUTOGRADER_SKIP_APT is set or the packages are there),
# creates the user the tests run as (rtgrader), closes the autograder's sources to that
# user, and prepares the grader's cache: the build every submission is graded in
# (tools/grade.py --calibrate). AUTOGRADER_ROOT replaces /autograder, to try it elsewhere.
set -euo pipefail
root="${AUTOGRADER_ROOT:-/autograder}"
source_dir="$root/source"
user=rtgrader
packages=(cmake ninja-build g++ python3 libglm-dev doctest-dev libtinyobjloader-dev util-linux)

installed() {
  command -v dpkg-query >/dev/null || return 1
  local p
  for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || return 1
  done
}

if [ -n "${RT_AUTOGRADER_SKIP_APT:-}" ]; then
  echo "setup.sh: RT_AUTOGRADER_SKIP_APT is set: no apt-get"
elif installed; then
  echo "setup.sh: ${packages[*]} are installed already"
elif command -v apt-get >/dev/null; then
  export DEBIAN_FRONTEND=noninteractive
  apt-get update
  apt-get install -y --no-install-recommends "${packages[@]}"
fi

version="$(cmake --version 2>/dev/null | head -n 1 | awk '{print $3}')"
if ! python3 -c 'import sys; v = tuple(int(x) for x in sys.argv[1].split(".")[:2]); sys.exit(v < (3, 21))' \
     "${version:-0.0}"; then
  echo "setup.sh: expected CMake 3.21 or later, found ${version:-none}; choose Ubuntu 22.04 or later as the" \
       "autograder's base image" >&2
  exit 1
fi

if ! id -u "$user" >/dev/null 2>&1; then
  useradd --system --no-create-home --shell /usr/sbin/nologin "$user"
fi
# The reference solution is in $source_dir/rt: no submission's code may read it.
chmod 700 "$source_dir"

options=()
if [ -f "$source_dir/grade_args" ]; then mapfile -t options < <(grep -v '^[[:space:]]*$' "$source_dir/grade_args"); fi
if [ -d "$source_dir/hidden" ]; then options+=(--hidden "$source_dir/hidden"); fi
if [ -f "$source_dir/weights.json" ]; then options+=(--weights "$source_dir/weights.json"); fi
python3 "$source_dir/rt/tools/grade.py" --calibrate --cache "$root/cache" --run-as "$user" "${options[@]}"
