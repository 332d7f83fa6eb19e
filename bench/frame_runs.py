#!/usr/bin/env python3
"""frame_runs.py - the whole-frame table of docs/performance.md (section 7), from two
runs of bench_frame, so that it is never typed by hand.

    build/bench/bench_frame --shared ../shared --out /tmp/frame1
    build/bench/bench_frame --shared ../shared --out /tmp/frame2
    python3 bench/frame_runs.py /tmp/frame1 /tmp/frame2 --doc docs/performance.md

Each run folder holds frame.csv. The table (seconds a frame on one thread and on
all, the speed-up, the rays by kind, the rays per second and the build) is written
between the lines <!-- frame-runs:begin --> and <!-- frame-runs:end --> of the
document (atomically), each timing of the first run followed by the second's in
brackets. Without --doc it is printed. Python 3 standard library only.

    python3 bench/frame_runs.py --embree /tmp/frame1 /tmp/frame2 --doc docs/performance.md

writes instead the table of what a user feels, from frame_embree.csv (bench_frame
built with Embree): build + frame at each spp for rt and for Embree under the same
shading, between <!-- frame-embree-runs:begin --> and <!-- frame-embree-runs:end -->.
"""

import os
import sys

from csv_notes import read, runs_main  # beside this file

BEGIN, END = "<!-- frame-runs:begin -->", "<!-- frame-runs:end -->"
EMBREE_BEGIN, EMBREE_END = "<!-- frame-embree-runs:begin -->", "<!-- frame-embree-runs:end -->"


def load(folder):
    """One run: its notes and its rows by (scene, threads)."""
    notes, rows = read(os.path.join(folder, "frame.csv"))
    name = lambda s: s.rsplit(".", 1)[0]
    return notes, {(name(r["scene"]), int(r["threads"])): r for r in rows}


def table(first, second):
    notes, rows1 = first
    _, rows2 = second
    scenes = list(dict.fromkeys(scene for scene, _ in rows1))
    most = max(threads for _, threads in rows1)
    missing = [f"{s} ({t} thread{'s' if t > 1 else ''})" for s in scenes for t in sorted({1, most})
               if (s, t) not in rows1 or (s, t) not in rows2]
    if most < 2:
        missing.append("every scene (2 threads or more)")
    if missing:
        raise SystemExit("frame_runs.py: expected both runs to hold every scene on one thread and on "
                         f"{most}, found none for " + ", ".join(missing[:5]) +
                         "; rerun bench_frame in full on a machine of two threads or more")
    both = lambda f: "%s (%s)" % (f(rows1), f(rows2))
    out = [f"Machine: {notes.get('machine', 'not recorded')}.",
           f"Render: {notes.get('render', 'not recorded')}.", "",
           f"| scene | 1 thread (s) | {most} threads (s) | speed-up | camera rays | shadow rays "
           "| reflection rays | Mrays/s, 1 thread | BVH build (s) |",
           "|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for s in scenes:
        one, all_ = (s, 1), (s, most)
        cells = [both(lambda r: "%.3f" % float(r[one]["seconds"])),
                 both(lambda r: "%.3f" % float(r[all_]["seconds"])),
                 both(lambda r: "%.2fx" % (float(r[one]["seconds"]) / float(r[all_]["seconds"]))),
                 rows1[one]["camera_rays"], rows1[one]["shadow_rays"], rows1[one]["reflection_rays"],
                 both(lambda r: "%.1f" % float(r[one]["mrays_per_s"])),
                 both(lambda r: "%.3f" % float(r[one]["build_seconds"]))]
        label = "%s (%sx%s)" % (s, rows1[one]["width"], rows1[one]["height"])
        out.append("| %s | %s |" % (label, " | ".join(cells)))
    return "\n".join(out) + "\n"


def load_embree(folder):
    """One run of the rt-against-Embree frames: its notes and its rows by (scene, spp)."""
    notes, rows = read(os.path.join(folder, "frame_embree.csv"))
    name = lambda s: s.rsplit(".", 1)[0]
    return notes, {(name(r["scene"]), int(r["spp"])): r for r in rows}


def table_embree(first, second):
    notes, rows1 = first
    _, rows2 = second
    missing = [f"{s} ({spp} spp)" for s, spp in rows1 if (s, spp) not in rows2]
    if not rows1 or missing:
        raise SystemExit("frame_runs.py: expected both runs' frame_embree.csv to hold the same scenes and "
                         "sample counts, found " + (", ".join(missing[:5]) + " in the first only" if missing
                                                    else "no rows") + "; rerun bench_frame built with Embree")
    both = lambda f: "%s (%s)" % (f(rows1), f(rows2))
    out = [f"Machine: {notes.get('machine', 'not recorded')}.",
           f"Render: {notes.get('render', 'not recorded')}.", "",
           "| scene | spp | rt: build + frame (s) | Embree: build + frame (s) | rt / Embree | image difference "
           "| rt without spatial splits (s) | splits / none |",
           "|---|---:|---:|---:|---:|---:|---:|---:|"]
    for key in rows1:
        r = rows1[key]
        total = lambda e: lambda rows: "%.3f + %.3f" % (float(rows[key][e + "_build_seconds"]),
                                                       float(rows[key][e + "_frame_seconds"]))
        seconds = lambda rows, e: float(rows[key][e + "_build_seconds"]) + float(rows[key][e + "_frame_seconds"])
        cells = [both(total("rt")), both(total("embree")),
                 both(lambda rows: "%.2f" % float(rows[key]["ratio_rt_over_embree"])),
                 "%.1e" % float(r["mean_difference"]), both(total("rt_plain")),
                 both(lambda rows: "%.2f" % (seconds(rows, "rt") / seconds(rows, "rt_plain")))]
        label = "%s (%sx%s)" % (key[0], r["width"], r["height"])
        out.append("| %s | %d | %s |" % (label, key[1], " | ".join(cells)))
    return "\n".join(out) + "\n"


def main(argv=None):
    argv = list(sys.argv[1:] if argv is None else argv)
    if "--embree" in argv:
        argv.remove("--embree")
        return runs_main(argv, __doc__.split("\n")[0],
                         lambda first, second: table_embree(load_embree(first), load_embree(second)),
                         EMBREE_BEGIN, EMBREE_END, "frame_runs.py: wrote the rt-against-Embree table of")
    return runs_main(argv, __doc__.split("\n")[0], lambda first, second: table(load(first), load(second)),
                         BEGIN, END, "frame_runs.py: wrote the table of")


if __name__ == "__main__":
    sys.exit(main())
