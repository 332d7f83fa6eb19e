#!/usr/bin/env python3
"""embree_runs.py - the issue-17 tables of docs/performance.md (section 6), from two
runs of bench_embree, so that they are never typed by hand.

    build/bench/bench_embree --shared ../shared --out /tmp/run1
    build/bench/bench_embree --shared ../shared --out /tmp/run2
    python3 bench/embree_runs.py /tmp/run1 /tmp/run2 --doc docs/performance.md

Each run folder holds embree_rays.csv and embree_build.csv. The tables (rt/Embree
rays per second on one thread, rt's speed-up on two threads, how many sets reach
issue 17's 1.0 and 1.9x, build times) are
written between the lines <!-- embree-runs:begin --> and <!-- embree-runs:end -->
of the document (atomically: a temporary file, then a rename), each figure of the
first run followed by the second's in brackets. Without --doc they are printed.
Another machine's runs go in a block of their own, named by --block (--block
embree-runs-amd: between <!-- embree-runs-amd:begin --> and its end line).
Python 3 standard library only.

    python3 bench/embree_runs.py --dispatch NATIVE1 NATIVE2 DISPATCHED1 DISPATCHED2 --doc docs/performance.md

compares instead a build with -march=native against one without it (-DRT_BENCH_NATIVE=OFF:
the BVH path picked at run time), between <!-- dispatch-runs:begin --> and its end line:
for every set, the dispatched build's rt/Embree ratio over the native build's, each
engine's speed taken in the same run so that the machine's load cancels.
"""

import os
import sys

from csv_notes import read, runs_main  # beside this file

BEGIN, END = "<!-- embree-runs:begin -->", "<!-- embree-runs:end -->"
SETS = ["outside", "centre", "shadow", "shadow-surface", "incoherent"]


def load(folder):
    """One run: its notes, ray figures by (mesh, set, threads) and builds by mesh."""
    notes, rays = read(os.path.join(folder, "embree_rays.csv"))
    _, builds = read(os.path.join(folder, "embree_build.csv"))
    name = lambda m: m[:-4] if m.endswith(".obj") else m
    return (notes,
            {(name(r["mesh"]), r["set"], int(r["threads"])): r for r in rays},
            {name(b["mesh"]): b for b in builds})


def seconds(x):
    return "%.3f" % x if x >= 0.001 else "%.6f" % x


def tables(first, second):
    notes, rays1, builds1 = first
    _, rays2, builds2 = second
    meshes = list(builds1)
    old = [m for m in meshes for b in (builds1, builds2)
           if m in b and "embree_build_seconds_1_thread_high_quality" not in b[m]]
    if old:
        raise SystemExit("embree_runs.py: expected embree_build.csv to hold Embree's high-quality build time, found "
                         "none for " + old[0] + "; rerun bench_embree (runs before its column cannot be tabled)")
    missing = [m for m in meshes if m not in builds2] + \
        [f"{m} {s}" for m in meshes for s in SETS for t in (1, 2)
         if (m, s, t) not in rays1 or (m, s, t) not in rays2]
    if missing:
        raise SystemExit("embree_runs.py: expected both runs to hold every mesh and set (one and two "
                         "threads), found none for " + ", ".join(missing[:5]) + "; rerun bench_embree in full")
    both = lambda f: lambda m, s: "%s (%s)" % (f(rays1, m, s), f(rays2, m, s))
    ratio = both(lambda r, m, s: "%.2f" % float(r[(m, s, 1)]["ratio_rt_over_embree"]))
    out = [f"Machine: {notes.get('machine', 'not recorded')}.", "",
           "rt/Embree rays per second, one thread, first run (second run):", "",
           "| mesh | " + " | ".join(SETS) + " |", "|---|" + "---:|" * len(SETS)]
    out += ["| %s | %s |" % (m, " | ".join(ratio(m, s) for s in SETS)) for m in meshes]
    # issue 17's counts, from the unrounded figures (a 0.996 shows as 1.00 above but is not counted)
    pairs = [(m, s) for m in meshes for s in SETS]
    ahead = sum(all(float(r[(m, s, 1)]["ratio_rt_over_embree"]) >= 1 for r in (rays1, rays2)) for m, s in pairs)
    gain = lambda r, m, s: float(r[(m, s, 2)]["rt_mrays_per_s"]) / float(r[(m, s, 1)]["rt_mrays_per_s"])
    scaled = lambda r: sum(gain(r, m, s) >= 1.9 for m, s in pairs)
    gains = [gain(r, m, s) for r in (rays1, rays2) for m, s in pairs]
    spread = "%.2fx-%.2fx" % (min(gains), max(gains)) if gains else "none measured"  # runs without meshes (CI)
    out += ["", "Sets at 1.0 or more of Embree on one thread in both runs: %d of %d. rt's speed-up from one to two "
            "threads: %s over the sets of both runs, 1.9x or more on %d (%d) of %d." % (
                ahead, len(pairs), spread, scaled(rays1), scaled(rays2), len(pairs))]
    out += ["", "Builds, seconds:", "",
            "| mesh | rt, 1 thread | rt, 2 threads | rt, 1 thread, no spatial splits | Embree, 1 thread "
            "| rt/Embree, 1 thread | rt/Embree, no spatial splits | rt speed-up on 2 threads "
            "| Embree high quality, 1 thread | rt/Embree high quality |",
            "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    high = "embree_build_seconds_1_thread_high_quality"
    one = lambda b: float(b["rt_build_seconds_1_thread"]) / float(b["embree_build_seconds_1_thread"])
    plain = lambda b: (float(b["rt_build_seconds_1_thread_without_spatial_splits"]) /
                       float(b["embree_build_seconds_1_thread"]))
    speed = lambda b: float(b["rt_build_seconds_1_thread"]) / float(b["rt_build_seconds_all_threads"])
    versus = lambda b: float(b["rt_build_seconds_1_thread"]) / float(b[high])
    for m in meshes:
        cells = []
        for column in ("rt_build_seconds_1_thread", "rt_build_seconds_all_threads",
                       "rt_build_seconds_1_thread_without_spatial_splits", "embree_build_seconds_1_thread"):
            cells.append("%s (%s)" % (seconds(float(builds1[m][column])), seconds(float(builds2[m][column]))))
        cells.append("%.2f (%.2f)" % (one(builds1[m]), one(builds2[m])))
        cells.append("**%.2f** (%.2f)" % (plain(builds1[m]), plain(builds2[m])))
        cells.append("%.2fx (%.2fx)" % (speed(builds1[m]), speed(builds2[m])))
        cells.append("%s (%s)" % (seconds(float(builds1[m][high])), seconds(float(builds2[m][high]))))
        cells.append("**%.2f** (%.2f)" % (versus(builds1[m]), versus(builds2[m])))
        out.append("| %s | %s |" % (m, " | ".join(cells)))
    # issue 43's targets, like for like (the bold columns), from the unrounded figures
    at_most = lambda f: sum(all(f(b[m]) <= 1 for b in (builds1, builds2)) for m in meshes)
    out += ["", "Builds like for like on one thread, in both runs: rt with spatial splits at or under Embree's "
            "high quality on %d of %d meshes, rt without them at or under Embree's default on %d of %d." % (
                at_most(versus), len(meshes), at_most(plain), len(meshes))]
    return "\n".join(out) + "\n"


def dispatch_table(native1, native2, dispatched1, dispatched2):
    runs = [native1, native2, dispatched1, dispatched2]
    meshes = list(native1[2])
    missing = [f"{m} {s}" for m in meshes for s in SETS for run in runs if (m, s, 1) not in run[1]]
    if missing:
        raise SystemExit("embree_runs.py: expected all four runs to hold every mesh and set, found none for " +
                         ", ".join(missing[:5]) + "; rerun bench_embree in full")
    ratio = lambda run, m, s: float(run[1][(m, s, 1)]["ratio_rt_over_embree"])
    relative = lambda native, dispatched, m, s: ratio(dispatched, m, s) / ratio(native, m, s)
    out = [f"Native: {native1[0].get('machine', 'not recorded')}.",
           f"Dispatched: {dispatched1[0].get('machine', 'not recorded')}.", "",
           "The dispatched build's rt/Embree rays per second over the native build's, one thread, first "
           "pair of runs (second pair):", "",
           "| mesh | " + " | ".join(SETS) + " |", "|---|" + "---:|" * len(SETS)]
    for m in meshes:
        out.append("| %s | %s |" % (m, " | ".join(
            "%.2f (%.2f)" % (relative(native1, dispatched1, m, s), relative(native2, dispatched2, m, s))
            for s in SETS)))
    pairs = [(m, s) for m in meshes for s in SETS]
    within = sum(all(relative(n, d, m, s) >= 0.95 for n, d in ((native1, dispatched1), (native2, dispatched2)))
                 for m, s in pairs)
    out += ["", "Sets within 5%% of the native build (0.95 or more) in both pairs: %d of %d." % (within, len(pairs))]
    return "\n".join(out) + "\n"


def main(argv=None):
    argv = list(sys.argv[1:] if argv is None else argv)
    if "--dispatch" in argv:
        argv.remove("--dispatch")
        return runs_main(argv, __doc__.split("\n")[0],
                         lambda *folders: dispatch_table(*(load(f) for f in folders)),
                         "<!-- dispatch-runs:begin -->", "<!-- dispatch-runs:end -->",
                         "embree_runs.py: wrote the dispatch table of",
                         runs=("native1", "native2", "dispatched1", "dispatched2"))
    return runs_main(argv, __doc__.split("\n")[0], lambda first, second: tables(load(first), load(second)),
                         BEGIN, END, "embree_runs.py: wrote the tables of")


if __name__ == "__main__":
    sys.exit(main())
