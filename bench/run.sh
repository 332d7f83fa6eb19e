#!/usr/bin/env bash
# Runs every benchmark of rt and draws the charts (docs/performance.md).
#
#   bench/run.sh           full run: CSV files to build/bench/, charts to docs/perf/
#                          (tens of minutes on a 2-core machine)
#   bench/run.sh --quick   every experiment on tiny sizes (under two minutes; CI):
#                          CSV files and charts to build/bench/quick/, docs/ untouched
#
# Options: --build DIR (a configured build tree, default build/ of the default
# preset, configured here if missing), --only NAME (one experiment: sampling,
# sphere, triangle, groups, acne, embree, frame), --jobs N (build, default 2).
# The numbers of a quick run are for checking that everything runs, not for
# conclusions. Nothing here asserts a timing.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$root/build"
quick=0
only=""
jobs=2
while (($#)); do
  case "$1" in
    --quick) quick=1 ;;
    --build) build="$(cd "$2" && pwd)"; shift ;;
    --only) only="$2"; shift ;;
    --jobs) jobs="$2"; shift ;;
    -h|--help) sed -n '2,16p' "$0"; exit 0 ;;
    *) echo "bench/run.sh: unknown option '$1'; see --help" >&2; exit 2 ;;
  esac
  shift
done

start=$(date +%s)
if [ ! -f "$build/CMakeCache.txt" ]; then
  if [ "$build" = "$root/build" ]; then
    (cd "$root" && cmake --preset default >/dev/null)
  else
    echo "bench/run.sh: $build is not a configured build tree (run cmake there first)" >&2
    exit 1
  fi
fi
cmake --build "$build" --target bench_all -j "$jobs"

if ((quick)); then
  out="$build/bench/quick"
  charts="$out/charts"
  mode=(--quick)
else
  out="$build/bench"
  charts="$root/docs/perf"
  mode=()
fi
mkdir -p "$out" "$charts"

failed=()
run() { # run NAME PROGRAM [ARGS...]
  local name="$1" program="$build/bench/$2"; shift 2
  if [ -n "$only" ] && [ "$only" != "$name" ]; then return; fi
  if [ ! -x "$program" ]; then
    echo "==== $name: skipped ($(basename "$program") was not built: $*)"
    return
  fi
  local t0; t0=$(date +%s)
  echo "==== $name: $(basename "$program") ${mode[*]:-}"
  if "$program" "${mode[@]}" --out "$out" --shared "$root/../shared"; then
    echo "==== $name: $(( $(date +%s) - t0 )) s"
  else
    echo "==== $name: FAILED" >&2
    failed+=("$name")
  fi
}

run sphere bench_sphere "see bench/CMakeLists.txt"
run sphere bench_sphere_double "not built when rt::real is double already"
run sampling bench_sampling "see bench/CMakeLists.txt"
run triangle bench_triangle "needs include/rt/bvh/accelerator.hpp (stage 04)"
run triangle bench_triangle_contract "needs include/rt/bvh/accelerator.hpp (stage 04)"
run groups bench_groups "needs include/rt/bvh/accelerator.hpp (stage 04)"
run acne bench_acne "needs include/rt/bvh/accelerator.hpp (stage 04)"
run embree bench_embree "needs Embree 3: apt-get install libembree-dev"
run frame bench_frame "needs include/rt/bvh/accelerator.hpp (stage 04)"
run path bench_path "needs include/rt/bvh/accelerator.hpp (stage 04)"

if /usr/bin/python3 -c "import matplotlib" 2>/dev/null; then
  echo "==== charts: /usr/bin/python3 bench/plot.py"
  /usr/bin/python3 "$root/bench/plot.py" --data "$out" --charts "$charts" || failed+=(charts)
else
  echo "==== charts: skipped (matplotlib missing: apt-get install python3-matplotlib)"
fi

if ((quick)) && [ -f "$out/embree_rays.csv" ]; then
  # section 6's issue-17 tables come from two full runs (see the script); here
  # the quick run stands for both, so that the script never rots
  echo "==== embree tables: bench/embree_runs.py $out $out"
  python3 "$root/bench/embree_runs.py" "$out" "$out" > "$out/embree_runs.md" || failed+=(embree_runs)
fi

echo "==== bench: $(( $(date +%s) - start )) s in total; CSV files in $out, charts in $charts"
if ((${#failed[@]})); then
  echo "bench/run.sh: failed: ${failed[*]}" >&2
  exit 1
fi
