#!/usr/bin/python3
"""Charts of rt's benchmarks (docs/performance.md), from the CSV files that
bench/run.sh writes. Uses matplotlib from Debian (python3-matplotlib): run it
as /usr/bin/python3, which another python3 on PATH may shadow.

    /usr/bin/python3 bench/plot.py --data build/bench --charts docs/perf

Every chart carries the machine line of the CSV it comes from. A CSV that is
absent (an experiment not built or skipped) gives no chart and a message.
"""
import argparse
import math
import os
import sys
import textwrap

from csv_notes import read  # (beside this file)

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def num(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return math.nan


def footer(fig, notes):
    text = "machine: " + notes.get("machine", "unknown")
    if notes.get("mode", "full") != "full":
        text += "   [QUICK RUN: tiny sizes, not for conclusions]"
    fig.text(0.01, 0.005, text, fontsize=6.5, color="0.35", ha="left", va="bottom", wrap=True)


def save(fig, charts, name):
    path = os.path.join(charts, name)
    temporary = path + ".tmp.png"
    fig.savefig(temporary, dpi=110)
    os.replace(temporary, path)
    plt.close(fig)
    print("wrote", path)


SAMPLER_COLORS = {"center": "0.4", "grid": "tab:purple", "random": "tab:red", "jittered": "tab:blue",
                   "halton": "tab:green"}
# the stage-02 exercises (jittered samples, box), box filter only: drawn on the sampling charts, not the headline
STUDENT_COLOR = {"student": "tab:cyan"}


def plot_sampling(data, charts):
    path = os.path.join(data, "sampling.csv")
    if not os.path.exists(path):
        return print("sampling: no", path)
    notes, rows = read(path)
    slopes = {}
    slope_path = os.path.join(data, "sampling_slopes.csv")
    if os.path.exists(slope_path):
        for r in read(slope_path)[1]:
            slopes[(r["scene"], r["sampler"], r["filter"])] = num(r["slope"])
    for scene in sorted({r["scene"] for r in rows}):
        filters = [f for f in ["box", "tent", "gaussian", "mitchell"]
                   if any(r["scene"] == scene and r["filter"] == f for r in rows)]
        if len(filters) == 1:  # a costly scene rendered with the box alone (soft)
            fig, one = plt.subplots(1, 1, figsize=(6, 5))
            axes = [[one], [one]]
            flat = [one]
        else:
            fig, axes = plt.subplots(2, 2, figsize=(10, 8), sharex=True, sharey=True)
            flat = list(axes.flat)
        for ax, filt in zip(flat, filters):
            for sampler, color in {**SAMPLER_COLORS, **STUDENT_COLOR}.items():
                pts = [(num(r["seconds"]), num(r["rmse"]), int(r["spp"])) for r in rows
                       if r["scene"] == scene and r["filter"] == filt and r["sampler"] == sampler]
                if not pts:
                    continue
                label = sampler
                if (scene, sampler, filt) in slopes:
                    label += " (slope %.2f)" % slopes[(scene, sampler, filt)]
                ax.loglog([p[0] for p in pts], [p[1] for p in pts], "o-", color=color, label=label, ms=4)
                for s, e, spp in pts:
                    if sampler == "jittered":
                        ax.annotate(str(spp), (s, e), textcoords="offset points", xytext=(3, 3), fontsize=6,
                                    color=color)
            ax.set_title("%s filter" % filt)
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=7)
        for ax in axes[1]:
            ax.set_xlabel("render time, 1 thread (s)")
        for ax in [row[0] for row in axes]:
            ax.set_ylabel("RMSE against the reference")
        theory = ("every sampler -1/2: the light, lens and gloss samples are not stratified" if scene == "soft"
                  else "random -1/2, jittered -3/4")
        title = ("Sampling on the '%s' scene: error against time (spp 1 .. 256; slopes of RMSE vs spp; "
                 "theory: %s)" % (scene, theory))
        fig.suptitle(textwrap.fill(title, 75 if len(filters) == 1 else 140), fontsize=9)
        fig.tight_layout(rect=(0, 0.03, 1, 0.97))
        footer(fig, notes)
        save(fig, charts, "sampling-%s.png" % scene)


def sphere_rows(data):
    rows, notes = [], {}
    for precision in ("float", "double"):
        path = os.path.join(data, "sphere_%s.csv" % precision)
        if os.path.exists(path):
            n, r = read(path)
            notes = notes or n  # the float program's machine line (both builds share the machine)
            rows += r
    return notes, rows


def plot_sphere(data, charts):
    notes, rows = sphere_rows(data)
    if not rows:
        return print("sphere: no sphere_float.csv / sphere_double.csv in", data)
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.6))
    styles = {("float", "textbook"): ("tab:red", "o--"), ("float", "stable"): ("tab:blue", "o-"),
              ("double", "textbook"): ("tab:orange", "s--"), ("double", "stable"): ("tab:green", "s-")}
    for (precision, method), (color, style) in styles.items():
        pts = [r for r in rows if r["precision"] == precision and r["method"] == method]
        if not pts:
            continue
        d = [num(r["distance"]) for r in pts]
        label = "%s %s" % (method, precision)
        tiny = 1e-9  # zero on a log axis
        axes[0].loglog(d, [max(num(r["misclassified_fraction"]), tiny) for r in pts], style, color=color,
                       label=label)
        axes[1].loglog(d, [max(num(r["depth_error_median"]), 1e-18) for r in pts], style, color=color, label=label)
        err = [max(num(r["depth_error_median"]), 1e-18) for r in pts]
        speed = [num(r["mrays_per_s"]) for r in pts]
        axes[2].semilogx(err, speed, style, color=color, label=label)
        for e, s, dist in zip(err, speed, d):
            axes[2].annotate("1e%d" % round(math.log10(dist)), (e, s), textcoords="offset points", xytext=(2, 3),
                             fontsize=6, color=color)
    axes[0].set_title("rays answered hit/miss wrongly")
    axes[0].set_ylabel("fraction (1e-9 = none)")
    axes[1].set_title("median depth error |t - t_ref| / R")
    for ax in axes[:2]:
        ax.set_xlabel("distance of the unit sphere")
    axes[2].set_title("speed against error (labels: distance)")
    axes[2].set_xlabel("median depth error / R")
    axes[2].set_ylabel("Mrays/s, 1 thread")
    for ax in axes:
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle("Sphere intersection: textbook quadratic vs stable (Ray Tracing Gems ch. 7), float vs double",
                 fontsize=10)
    fig.tight_layout(rect=(0, 0.04, 1, 0.95))
    footer(fig, notes)
    save(fig, charts, "sphere.png")


def plot_triangle(data, charts):
    path = os.path.join(data, "triangle.csv")
    if not os.path.exists(path):
        return print("triangle: no", path)
    notes, rows = read(path)
    contract = os.path.join(data, "triangle_contract.csv")
    if os.path.exists(contract):
        rows += [r for r in read(contract)[1] if r["method"].startswith("watertight")]
    sets = {"surface": "o", "edges": "s", "vertices": "D"}
    colors = {"moller_trumbore": "tab:red", "watertight": "tab:blue", "watertight_per_ray": "tab:green",
               "watertight+fma": "tab:orange", "watertight_per_ray+fma": "gold"}
    none = 3e-6  # where "no leak at all" is drawn on the log axis
    fig, ax = plt.subplots(figsize=(9, 5.5))
    for method, color in colors.items():
        for ray_set, marker in sets.items():
            pts = [r for r in rows if r["rays"] == ray_set and r["method"] == method]
            if not pts:
                continue
            # all meshes together: leaks over rays, and tests per second over the total time
            leaks = sum(num(r["leaks"]) for r in pts) / sum(num(r["ray_count"]) for r in pts)
            tests = sum(num(r["ray_count"]) * num(r["triangles"]) for r in pts)
            speed = tests / sum(num(r["seconds"]) for r in pts) / 1e6
            ax.semilogx([max(leaks, none)], [speed], marker, color=color, ms=8, mec="k", mew=0.5,
                        label="%s, %s" % (method.replace("_", " "), ray_set))
    ax.axvline(none * 1.7, color="0.6", lw=0.8, ls=":")
    ax.set_xlim(none / 2, 1)
    ticks = [none] + [10.0 ** e for e in range(-5, 1)]
    ax.set_xticks(ticks)
    ax.set_xticklabels(["none"] + ["1e%d" % e for e in range(-5, 1)])
    ax.set_xlabel("leak rate: rays from inside a closed mesh that hit none of its triangles")
    ax.set_ylabel("million ray-triangle tests per second, 1 thread")
    ax.set_title("Triangle intersection: speed against leaks (icosphere and double cone, all rays aimed "
                 "at surface, edges or vertices)", fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=6.5, ncol=2)
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    footer(fig, notes)
    save(fig, charts, "triangle.png")


def plot_groups(data, charts):
    path = os.path.join(data, "groups.csv")
    if not os.path.exists(path):
        return print("groups: no", path)
    notes, rows = read(path)
    fig, ax = plt.subplots(figsize=(8, 5.2))
    for kind, color in (("flat", "tab:red"), ("bvh", "tab:blue"), ("automatic", "tab:green")):
        pts = sorted((num(r["primitives"]), num(r["ns_per_ray"])) for r in rows if r["kind"] == kind)
        if pts:
            ax.loglog([p[0] for p in pts], [p[1] for p in pts], "o-" if kind != "automatic" else "x:",
                      color=color, label=kind)
    crossover = num(notes.get("measured crossover", "nan").split()[0]) if "measured crossover" in notes else math.nan
    if not math.isnan(crossover):
        ax.axvline(crossover, color="0.3", ls="--", lw=1)
        ax.annotate("measured crossover %.0f" % crossover, (crossover, ax.get_ylim()[1]), fontsize=7,
                    xytext=(4, -12), textcoords="offset points")
    threshold = notes.get("automatic threshold", "")
    ax.set_xlabel("primitives in the scene")
    ax.set_ylabel("ns per ray (closest hit), 1 thread")
    ax.set_title("Groups: flat list vs BVH" + (" (automatic switches at %s)" % threshold if threshold else ""),
                 fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    footer(fig, notes)
    save(fig, charts, "groups.png")


def plot_acne(data, charts):
    path = os.path.join(data, "acne.csv")
    if not os.path.exists(path):
        return print("acne: no", path)
    notes, rows = read(path)
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5))
    # robust_offset: the name of the Ray Tracing Gems row in CSV files from before issue 19
    colors = {"no_offset": "0.5", "fixed_epsilon": "tab:red", "rtg_offset": "tab:blue", "robust_offset": "tab:blue",
               "error_bounds": "tab:green", "light_visible": "tab:purple"}
    styles = {"light_visible": "s--"}
    for method, color in colors.items():
        pts = sorted((num(r["scale"]), num(r["acne_fraction"]), num(r["leak_fraction"])) for r in rows
                     if r["method"] == method)
        if not pts:
            continue
        label = {"no_offset": "no offset", "fixed_epsilon": "fixed epsilon 1e-4",
                 "rtg_offset": "Ray Tracing Gems ch. 6 offset (offset_ray_origin)",
                 "robust_offset": "Ray Tracing Gems ch. 6 offset (light_visible before issue 19)",
                 "error_bounds": "PBR error bounds (spawn_ray)",
                 "light_visible": "light_visible (spawn_ray_to)"}.get(method, method)
        style = styles.get(method, "o-")
        axes[0].loglog([p[0] for p in pts], [max(p[1], 1e-6) for p in pts], style, color=color, label=label)
        axes[1].loglog([p[0] for p in pts], [max(p[2], 1e-6) for p in pts], style, color=color, label=label)
    axes[0].set_title("acne: lit points wrongly in shadow")
    axes[1].set_title("leaks: shadowed points wrongly lit")
    for ax in axes:
        ax.set_xlabel("scene scale")
        ax.set_ylabel("fraction (1e-6 = none)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle("Self-intersection of shadow rays against scene scale", fontsize=10)
    fig.tight_layout(rect=(0, 0.04, 1, 0.95))
    footer(fig, notes)
    save(fig, charts, "acne.png")


def plot_embree(data, charts):
    path = os.path.join(data, "embree_rays.csv")
    if not os.path.exists(path):
        return print("embree: no", path)
    notes, rows = read(path)
    one = [r for r in rows if r["threads"] == "1"]
    meshes = list(dict.fromkeys(r["mesh"] for r in one))
    sets = ["outside", "centre", "shadow", "shadow-surface", "incoherent"]
    colors = {"outside": "tab:blue", "centre": "tab:orange", "shadow": "tab:gray", "shadow-surface": "tab:olive",
               "incoherent": "tab:red"}
    # the builds like for like (issue 43): rt without spatial splits against Embree's
    # default, rt with them against Embree's high quality, which splits too
    builds, against_high = {}, {}
    build_path = os.path.join(data, "embree_build.csv")
    if os.path.exists(build_path):
        for r in read(build_path)[1]:
            plain = r.get("rt_build_seconds_1_thread_without_spatial_splits")  # absent from older runs' CSV files
            builds[r["mesh"]] = (num(plain) / num(r["embree_build_seconds_1_thread"]) if plain
                                 else num(r["ratio_rt_over_embree_1_thread"]))
            if r.get("embree_build_seconds_1_thread_high_quality"):
                against_high[r["mesh"]] = (num(r["rt_build_seconds_1_thread"]) /
                                           num(r["embree_build_seconds_1_thread_high_quality"]))
    fig, axes = plt.subplots(1, 2, figsize=(13, 4.8), gridspec_kw={"width_ratios": [3, 1]})
    width = 0.8 / len(sets)
    for k, s in enumerate(sets):
        values = []
        for m in meshes:
            match = [r for r in one if r["mesh"] == m and r["set"] == s]
            values.append(num(match[0]["ratio_rt_over_embree"]) if match else math.nan)
        axes[0].bar([i + (k - 1.5) * width for i in range(len(meshes))], values, width, color=colors[s], label=s)
    axes[0].axhline(1.0, color="k", ls="--", lw=1)
    axes[0].annotate("target 1.0", (len(meshes) - 0.6, 1.02), fontsize=7)
    axes[0].set_xticks(range(len(meshes)))
    axes[0].set_xticklabels([m.replace(".obj", "") for m in meshes], fontsize=7, rotation=15)
    axes[0].set_ylabel("rt rays/s / Embree rays/s, 1 thread")
    axes[0].set_title("Traversal speed, same rays (higher is better)")
    axes[0].legend(fontsize=7)
    axes[0].grid(True, axis="y", alpha=0.3)
    if builds:
        shift = 0.2 if against_high else 0.0
        axes[1].bar([i - shift for i in range(len(meshes))], [builds.get(m, math.nan) for m in meshes],
                    0.4 if against_high else 0.8, color="tab:purple",
                    label="rt without spatial splits / Embree's default")
        if against_high:
            axes[1].bar([i + shift for i in range(len(meshes))], [against_high.get(m, math.nan) for m in meshes],
                        0.4, color="tab:pink",
                        label="rt with spatial splits / Embree's high quality")
            axes[1].legend(fontsize=6, loc="upper left")
        axes[1].axhline(1, color="k", ls="--", lw=1)
        axes[1].annotate("target 1", (len(meshes) - 1.2, 1.03), fontsize=7)
        tallest = max([v for v in list(builds.values()) + list(against_high.values()) if v == v] + [1.0])
        axes[1].set_ylim(0, 1.45 * tallest)  # room for the legend above the target line
        axes[1].set_xticks(range(len(meshes)))
        axes[1].set_xticklabels([m.replace(".obj", "") for m in meshes], fontsize=7, rotation=30)
        axes[1].set_ylabel("rt build time / Embree build time (1 thread)")
        axes[1].set_title("BVH build (lower is better)")
        axes[1].grid(True, axis="y", alpha=0.3)
    fig.suptitle("rt's BVH against %s" % notes.get("embree", "Embree 3").split(" (")[0], fontsize=10)
    fig.tight_layout(rect=(0, 0.04, 1, 0.95))
    footer(fig, notes)
    save(fig, charts, "embree.png")


def plot_frame(data, charts):
    path = os.path.join(data, "frame.csv")
    if not os.path.exists(path):
        return print("frame: no", path)
    notes, rows = read(path)
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.6))
    for k, threads in enumerate(sorted({r["threads"] for r in rows}, key=int)):
        pts = [next((r for r in rows if r["scene"] == s and r["threads"] == threads), None) for s in scenes]
        axes[0].bar([i + (k - 0.5) * 0.4 for i in range(len(scenes))], [num(p["seconds"]) if p else math.nan
                                                                         for p in pts], 0.4,
                    label="%s thread(s)" % threads)
    axes[0].set_xticks(range(len(scenes)))
    axes[0].set_xticklabels([s.replace(".obj", "") for s in scenes], fontsize=7, rotation=15)
    axes[0].set_ylabel("seconds per frame")
    axes[0].set_title("Whole frame: time")
    axes[0].legend(fontsize=7)
    kinds = ["camera", "shadow", "reflection"]
    one = [next((r for r in rows if r["scene"] == s and r["threads"] == "1"), None) for s in scenes]
    bottom = [0.0] * len(scenes)
    for kind in kinds:
        values = [num(p["%s_rays" % kind]) / num(p["seconds"]) / 1e6 if p else 0 for p in one]
        axes[1].bar(range(len(scenes)), values, 0.6, bottom=bottom, label=kind)
        bottom = [b + v for b, v in zip(bottom, values)]
    axes[1].set_xticks(range(len(scenes)))
    axes[1].set_xticklabels([s.replace(".obj", "") for s in scenes], fontsize=7, rotation=15)
    axes[1].set_ylabel("Mrays/s by kind, 1 thread")
    axes[1].set_title("Whole frame: rays per second")
    axes[1].legend(fontsize=7)
    for ax in axes:
        ax.grid(True, axis="y", alpha=0.3)
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    footer(fig, notes)
    save(fig, charts, "frame.png")


PATH_COLORS = {"uniform": "tab:red", "cosine": "tab:orange", "nee": "tab:blue", "mis": "tab:green"}


def plot_path(data, charts):
    path = os.path.join(data, "path.csv")
    if not os.path.exists(path):
        return print("path: no", path)
    notes, rows = read(path)
    fig, ax = plt.subplots(figsize=(7.5, 4.8))
    for strategy, color in PATH_COLORS.items():
        for adaptive, style, label in (("no", "-o", "%s"), ("yes", "--s", "%s, adaptive")):
            pts = [r for r in rows if r["strategy"] == strategy and r["adaptive"] == adaptive]
            if not pts:
                continue
            pts.sort(key=lambda r: num(r["seconds"]))
            ax.plot([num(r["seconds"]) for r in pts], [num(r["rmse"]) for r in pts], style, color=color,
                    label=label % strategy, markersize=4)
            if adaptive == "no":
                for r in pts:
                    ax.annotate(r["spp"], (num(r["seconds"]), num(r["rmse"])), fontsize=6, color=color,
                                xytext=(3, 3), textcoords="offset points")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("render time, seconds (1 thread)")
    ax.set_ylabel("RMSE against the reference")
    ax.set_title("Path tracing the Cornell box: noise against time (numbers: samples per pixel)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    footer(fig, notes)
    save(fig, charts, "path.png")


def plot_headline(data, charts):
    """The README's chart: speed against accuracy for the methods a student chooses between."""
    notes, spheres = sphere_rows(data)
    tri_path = os.path.join(data, "triangle.csv")
    samp_path = os.path.join(data, "sampling.csv")
    if not spheres or not os.path.exists(samp_path):
        return print("headline: needs sphere and sampling results")
    panels = 3 if os.path.exists(tri_path) else 2
    fig, axes = plt.subplots(1, panels, figsize=(5 * panels, 4.4))
    # sampling: edges scene, box filter
    _, rows = read(samp_path)
    for sampler, color in SAMPLER_COLORS.items():
        pts = [(num(r["seconds"]), num(r["rmse"])) for r in rows
               if r["scene"] == "edges" and r["filter"] == "box" and r["sampler"] == sampler]
        if pts:
            axes[0].loglog([p[0] for p in pts], [p[1] for p in pts], "o-", color=color, label=sampler, ms=4)
    axes[0].set_title("Antialiasing: error vs time (edges, box filter)", fontsize=9)
    axes[0].set_xlabel("render time (s)")
    axes[0].set_ylabel("RMSE")
    # sphere: at 1e4
    for (precision, method), color in {("float", "textbook"): "tab:red", ("float", "stable"): "tab:blue",
                                        ("double", "textbook"): "tab:orange",
                                        ("double", "stable"): "tab:green"}.items():
        pts = [r for r in spheres if r["precision"] == precision and r["method"] == method]
        if pts:
            axes[1].semilogx([max(num(r["depth_error_median"]), 1e-18) for r in pts],
                             [num(r["mrays_per_s"]) for r in pts], "o-", color=color,
                             label="%s %s" % (method, precision), ms=4)
    axes[1].set_title("Spheres at 1e1..1e6: speed vs depth error", fontsize=9)
    axes[1].set_xlabel("median depth error / R")
    axes[1].set_ylabel("Mrays/s")
    if panels == 3:
        _, rows = read(tri_path)
        contract = os.path.join(data, "triangle_contract.csv")
        if os.path.exists(contract):
            rows += [r for r in read(contract)[1] if r["method"] == "watertight+fma"]
        for method, color in (("moller_trumbore", "tab:red"), ("watertight", "tab:blue"),
                               ("watertight+fma", "tab:orange")):
            for ray_set, marker in (("surface", "o"), ("edges", "s"), ("vertices", "D")):
                pts = [r for r in rows if r["method"] == method and r["rays"] == ray_set]
                if not pts:
                    continue
                leaks = sum(num(r["leaks"]) for r in pts) / sum(num(r["ray_count"]) for r in pts)
                speed = sum(num(r["ray_count"]) * num(r["triangles"]) for r in pts) / sum(
                    num(r["seconds"]) for r in pts) / 1e6
                axes[2].semilogx([max(leaks, 3e-6)], [speed], marker, color=color, ms=7,
                                 label="%s, %s" % (method.replace("_", "-"), ray_set))
        axes[2].set_xticks([3e-6, 1e-4, 1e-2, 1])
        axes[2].set_xticklabels(["none", "1e-4", "1e-2", "1"])
        axes[2].set_title("Triangles: speed vs leaks (closed meshes)", fontsize=9)
        axes[2].set_xlabel("leak rate")
        axes[2].set_ylabel("M tests/s")
    for ax in axes:
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle("rt: what each method costs and what it buys", fontsize=10)
    fig.tight_layout(rect=(0, 0.05, 1, 0.95))
    footer(fig, notes)
    save(fig, charts, "headline.png")


TARGET_MESHES = ["stanford-bunny.obj", "bunny-loop2.obj", "conference.obj", "sibenik.obj", "sponza-dabrovic.obj"]


def write_tables(data, charts):
    """tables.md: the Embree table with the issue's targets checked, and the sampling slopes."""
    out = []
    rays_path = os.path.join(data, "embree_rays.csv")
    build_path = os.path.join(data, "embree_build.csv")
    if os.path.exists(rays_path) and os.path.exists(build_path):
        notes, rows = read(rays_path)
        builds = {r["mesh"]: r for r in read(build_path)[1]}
        out.append("Machine: " + notes.get("machine", "unknown") + "  ")
        out.append(notes.get("embree", "") + "; " + notes.get("rays", "") + ".\n")
        out.append("| mesh | triangles | set | rt Mrays/s (1 thr) | Embree Mrays/s (1 thr) | rt/Embree (1 thr) "
                   "| rt/Embree (all thr) | hits rt / Embree | mismatches (hit, depth) |")
        out.append("|---|---:|---|---:|---:|---:|---:|---:|---:|")
        for r in rows:
            if r["threads"] != "1":
                continue
            other = [x for x in rows if x["mesh"] == r["mesh"] and x["set"] == r["set"] and x["threads"] != "1"]
            all_ratio = "%.2f" % num(other[0]["ratio_rt_over_embree"]) if other else "-"
            out.append("| %s | %s | %s | %.2f | %.2f | **%.2f** | %s | %s / %s | %s, %s |" % (
                r["mesh"].replace(".obj", ""), r["triangles"], r["set"], num(r["rt_mrays_per_s"]),
                num(r["embree_mrays_per_s"]), num(r["ratio_rt_over_embree"]), all_ratio, r["rt_hits"],
                r["embree_hits"], r["hit_mismatch"], r["depth_mismatch"]))
        out.append("")
        out.append("| mesh | rt build, 1 thread (s) | rt build, all threads (s) | rt, 1 thread, no spatial splits (s) "
                   "| Embree build, 1 thread (s) | Embree build, all threads (s) | rt/Embree (1 thr) "
                   "| rt speed-up on all threads |")
        out.append("|---|---:|---:|---:|---:|---:|---:|---:|")
        for m, b in builds.items():
            out.append("| %s | %.4f | %.4f | %.4f | %.4f | %.4f | **%.2f** | %.2fx |" % (
                m.replace(".obj", ""), num(b["rt_build_seconds_1_thread"]), num(b["rt_build_seconds_all_threads"]),
                num(b.get("rt_build_seconds_1_thread_without_spatial_splits", "nan")),
                num(b["embree_build_seconds_1_thread"]), num(b["embree_build_seconds_all_threads"]),
                num(b["ratio_rt_over_embree_1_thread"]), num(b["rt_speedup_all_threads"])))
        out.append("")
        out.append("Targets (issue 17, single thread): closest hit and any hit at least 1.0x Embree on every set, "
                   "build at most 1.0x Embree's one-thread build, and at least 1.8x faster on two threads than on one.\n")
        out.append("| mesh | outside | centre | incoherent | shadow | shadow-surface | build | build speed-up |")
        out.append("|---|---|---|---|---|---|---|---|")
        for m in TARGET_MESHES:
            cells = []
            for s in ("outside", "centre", "incoherent", "shadow", "shadow-surface"):
                match = [r for r in rows if r["mesh"] == m and r["set"] == s and r["threads"] == "1"]
                if not match:
                    cells.append("-")
                    continue
                ratio = num(match[0]["ratio_rt_over_embree"])
                cells.append("%.2f %s" % (ratio, "met" if ratio >= 1.0 else "**missed by %.0f%%**" %
                                          (100 * (1.0 - ratio))))
            if m in builds:
                ratio = num(builds[m]["ratio_rt_over_embree_1_thread"])
                cells.append("%.2f %s" % (ratio, "met" if ratio <= 1.0 else "**missed**"))
                speedup = num(builds[m]["rt_speedup_all_threads"])
                cells.append("%.2fx %s" % (speedup, "met" if speedup >= 1.8 else "**missed**"))
            else:
                cells += ["-", "-"]
            out.append("| %s | %s |" % (m.replace(".obj", ""), " | ".join(cells)))
        out.append("")
        for key, value in notes.items():
            if "mismatches" in key:
                out.append("- %s: %s" % (key, value))
        out.append("")
    slopes_path = os.path.join(data, "sampling_slopes.csv")
    if os.path.exists(slopes_path):
        _, rows = read(slopes_path)
        out.append("| scene | filter | grid | random (theory -0.5) | jittered (theory -0.75) | halton "
                   "| student, stage 02 (box only) |")
        out.append("|---|---|---:|---:|---:|---:|---:|")
        for scene in dict.fromkeys(r["scene"] for r in rows):
            for filt in ("box", "tent", "gaussian", "mitchell"):
                get = {r["sampler"]: num(r["slope"]) for r in rows if r["scene"] == scene and r["filter"] == filt}
                out.append("| %s | %s | %s |" % (scene, filt, " | ".join(
                    "%.2f" % get[s] if s in get else "-" for s in ("grid", "random", "jittered", "halton", "student"))))
        out.append("")
    if out:
        path = os.path.join(charts, "tables.md")
        with open(path + ".tmp", "w") as f:
            f.write("\n".join(out) + "\n")
        os.replace(path + ".tmp", path)
        print("wrote", path)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--data", required=True, help="folder of the CSV files")
    parser.add_argument("--charts", required=True, help="folder for the PNG charts")
    args = parser.parse_args()
    os.makedirs(args.charts, exist_ok=True)
    for plot in (plot_sampling, plot_sphere, plot_triangle, plot_groups, plot_acne, plot_embree, plot_frame,
                 plot_path, plot_headline, write_tables):
        plot(args.data, args.charts)
    return 0


if __name__ == "__main__":
    sys.exit(main())
