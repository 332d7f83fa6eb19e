#!/bin/sh
# tools/fuzz.sh [SECONDS] - build the libFuzzer targets and run each for SECONDS
# (default 60), one after the other on one core, then print executions and
# crashes per target. Exit status 1 when any target found a crash, a leak, a
# timeout (an input that takes over 10 s: a hang) or an out-of-memory.
#
#   tools/fuzz.sh          # what CI runs: about a minute per target
#   tools/fuzz.sh 3600     # a longer run: an hour per target
#
# Needs clang with libFuzzer (Debian: clang libclang-rt-14-dev). The corpus
# grows in build/fuzz/corpus/<target> and is reused by the next run; a crashing
# input is saved as build/fuzz/artifacts/<target>-crash-<sha1> (replay it with
# build/fuzz/fuzz/<target> <file>). See docs/reliability.md.
set -eu

seconds=${1:-60}
case $seconds in
    '' | *[!0-9]*) echo "usage: tools/fuzz.sh [SECONDS per target]" >&2; exit 2 ;;
esac
root=$(cd "$(dirname "$0")/.." && pwd)
# fuzz_scene_obj writes its three input files for every run: keep them in memory.
if [ -z "${TMPDIR:-}" ] && [ -d /dev/shm ] && [ -w /dev/shm ]; then
    export TMPDIR=/dev/shm
fi
out="$root/build/fuzz"

cd "$root"
cmake --preset fuzz > /dev/null
cmake --build --preset fuzz -j2 > "$out/build.log" 2>&1 || { cat "$out/build.log" >&2; exit 1; }

mkdir -p "$out/artifacts" "$out/logs" "$out/seeds/fuzz_scene" "$out/seeds/fuzz_scene_obj"
# Seeds: scene files go to fuzz_scene as they are; for fuzz_scene_obj, every
# scene becomes a scene part and every OBJ an OBJ part (an empty scene part
# stands for "mesh m.obj"), beside the checked-in seeds of fuzz/seeds/.
rm -f "$out"/seeds/fuzz_scene/* "$out"/seeds/fuzz_scene_obj/*
n=0
for file in scenes/*.scene scenes/models/*.obj tests/bad_inputs/* tests/bad_inputs/obj/*; do
    [ -f "$file" ] || continue
    n=$((n + 1))
    case $file in
        *.obj) { printf '\n%%%%\n'; cat "$file"; } > "$out/seeds/fuzz_scene_obj/$n" ;;
        *.mtl) { printf '\n%%%%\nmtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n%%%%\n'; cat "$file"; } \
                   > "$out/seeds/fuzz_scene_obj/$n" ;;
        *) cp "$file" "$out/seeds/fuzz_scene/$n"; cp "$file" "$out/seeds/fuzz_scene_obj/$n" ;;
    esac
done
cp fuzz/seeds/fuzz_scene/* "$out/seeds/fuzz_scene/"
cp fuzz/seeds/fuzz_scene_obj/* "$out/seeds/fuzz_scene_obj/"

status=0
summary=""
for target in fuzz_scene fuzz_scene_obj; do
    case $target in
        fuzz_scene) dict=fuzz/scene.dict ;;
        *) dict=fuzz/scene_obj.dict ;;
    esac
    corpus="$out/corpus/$target"
    mkdir -p "$corpus"
    rm -f "$out/artifacts/$target-"*
    log="$out/logs/$target.log"
    echo "fuzzing $target for $seconds s (log: $log)"
    # -timeout: an input that runs longer is a hang; -rss_limit_mb / -malloc_limit_mb:
    # a loader that allocates before checking its limits is a crash.
    if "$out/fuzz/$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=1024 \
        -max_len=8192 -dict="$dict" -print_final_stats=1 -artifact_prefix="$out/artifacts/$target-" \
        "$corpus" "$out/seeds/$target" > "$log" 2>&1; then
        result="ok"
    else
        result="FAILED: $(ls "$out/artifacts/$target-"* 2>/dev/null | head -n 1)"
        status=1
    fi
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
    time=$(sed -n 's/^Done [0-9]* runs in \([0-9]*\) second.*/\1/p' "$log" | tail -n 1)
    files=$(ls "$corpus" | wc -l)
    summary="$summary$(printf '%-16s %12s executions %6s s %8s corpus files  %s' "$target" "${runs:-?}" \
        "${time:-?}" "$files" "$result")
"
done
printf '\n%s' "$summary"
[ $status -eq 0 ] || echo "a crashing input is replayed with: build/fuzz/fuzz/<target> <artifact>" >&2
exit $status
