#!/usr/bin/env python3
"""triangle_runs.py - the triangle table of docs/performance.md (section 3), from one
run of bench_triangle and bench_triangle_contract, so that it is never typed by hand.

    build/bench/bench_triangle --out /tmp/triangle
    build/bench/bench_triangle_contract --out /tmp/triangle
    python3 bench/triangle_runs.py /tmp/triangle --doc docs/performance.md

The folder holds triangle.csv and triangle_contract.csv (bench/run.sh writes both
into one). Per method, the leaks of the rays aimed at the surface, at edges and at
vertices (both meshes together) and the tests per second over all sets, written
between the lines <!-- triangle-runs:begin --> and <!-- triangle-runs:end --> of the
document (atomically). Without --doc it is printed. Python 3 standard library only.
"""

import os
import sys

from csv_notes import read, runs_main  # beside this file

BEGIN, END = "<!-- triangle-runs:begin -->", "<!-- triangle-runs:end -->"
SETS = ("surface", "edges", "vertices")
NAMES = {"moller_trumbore": "Moller-Trumbore", "watertight": "watertight, `hit_triangle`",
         "watertight_per_ray": "watertight, set-up per ray (as in the BVH)"}


def load(folder):
    """(notes, rows): triangle.csv's, then triangle_contract.csv's rows."""
    paths = [os.path.join(folder, name) for name in ("triangle.csv", "triangle_contract.csv")]
    missing = [p for p in paths if not os.path.exists(p)]
    if missing:
        raise SystemExit("triangle_runs.py: expected " + " and ".join(missing) +
                         "; run bench_triangle and bench_triangle_contract with --out " + folder)
    notes, rows = read(paths[0])
    contract_notes, contract_rows = read(paths[1])
    notes["contract machine"] = contract_notes.get("machine", "not recorded")
    return notes, rows + contract_rows


def name(method):
    plain = method.replace("+fma", "")
    label = NAMES.get(plain, plain.replace("_", " "))
    return label + (", FMA contraction" if method.endswith("+fma") else "")


def table(run):
    notes, rows = run
    methods = list(dict.fromkeys(r["method"] for r in rows))
    out = [f"Machine: {notes.get('machine', 'not recorded')}.",
           f"The FMA contraction rows (bench_triangle_contract): {notes['contract machine']}.", "",
           "| method | leaks, surface | leaks, edges | leaks, vertices | M tests/s (all sets, 1 thread) |",
           "|---|---:|---:|---:|---:|"]
    for method in methods:
        mine = [r for r in rows if r["method"] == method]
        cells = []
        for ray_set in SETS:
            those = [r for r in mine if r["rays"] == ray_set]
            leaks = sum(int(r["leaks"]) for r in those)
            rays = sum(int(r["ray_count"]) for r in those)
            if not those:
                cells.append("-")
            elif leaks == 0:
                cells.append(f"0 / {rays}")
            else:
                cells.append(f"{leaks} / {rays} ({100 * leaks / rays:.1f}%)")
        tests = sum(int(r["ray_count"]) * int(r["triangles"]) for r in mine)
        seconds = sum(float(r["seconds"]) for r in mine)
        cells.append("%.0f" % (tests / seconds / 1e6) if seconds > 0 else "-")
        out.append("| %s | %s |" % (name(method), " | ".join(cells)))
    return "\n".join(out) + "\n"


def main(argv=None):
    return runs_main(argv, __doc__.split("\n")[0], lambda folder: table(load(folder)), BEGIN, END,
                     "triangle_runs.py: wrote the table of", runs=("run",))


if __name__ == "__main__":
    sys.exit(main())
