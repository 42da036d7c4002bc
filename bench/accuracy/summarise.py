#!/usr/bin/env python3
"""Summarises scripts/bench-accuracy's CSV: per sampler (stratified, random, adaptive) and
setting (spp, or target error), the total time over all scenes, the mean RMSE, the worst max
error and the mean samples per pixel; marks each sampler's Pareto front (no other setting of
any sampler both faster and more accurate); interpolates the total time each sampler needs
to reach a few mean-RMSE levels; writes results.md, the gnuplot data files and plot.gp."""
import csv
import math
import sys
from collections import defaultdict

csv_path, out = sys.argv[1], sys.argv[2]
rows = list(csv.DictReader(open(csv_path)))
samplers = [s for s in ("stratified", "random", "adaptive") if any(r["sampler"] == s for r in rows)]
by_setting = defaultdict(list)
for r in rows:
    by_setting[(r["sampler"], r["setting"])].append(r)
scenes = sorted({(r["dialect"], r["scene"]) for r in rows})


def setting_key(sampler, setting):
    # spp ascending; target error descending (more samples last).
    return float(setting) if sampler != "adaptive" else -float(setting)


summary = []  # (sampler, setting, time, rmse, max, spp)
for sampler in samplers:
    settings = sorted({s for (sa, s) in by_setting if sa == sampler}, key=lambda s: setting_key(sampler, s))
    for setting in settings:
        rs = by_setting[(sampler, setting)]
        if len(rs) != len(scenes):
            continue  # a setting some scene lacks (interrupted run) is not comparable
        t = sum(float(r["seconds"]) for r in rs)
        rmse = sum(float(r["rmse"]) for r in rs) / len(rs)
        mx = max(float(r["max_error"]) for r in rs)
        spp = sum(float(r["samples_per_pixel"] or 0) for r in rs) / len(rs)
        summary.append((sampler, setting, t, rmse, mx, spp))


def dominated(p, points):
    return any(q[2] <= p[2] and q[3] <= p[3] and (q[2] < p[2] or q[3] < p[3]) for q in points)


def time_to_reach(sampler, level, cost=2):
    """Total time (cost=2; cost=5: mean samples per pixel) at which the sampler's curve
    (points by cost) first reaches mean RMSE `level`, interpolated linearly in log cost
    against log RMSE; None if it never does."""
    pts = sorted((p[cost], p[3]) for p in summary if p[0] == sampler)
    for (t0, e0), (t1, e1) in zip(pts, pts[1:]):
        if e0 <= level:
            return t0
        if e1 <= level:
            f = (math.log(level) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(t0) + f * (math.log(t1) - math.log(t0)))
    return pts[0][0] if pts and pts[0][1] <= level else None


levels = [4e-3, 2e-3, 1e-3, 5e-4]
with open(f"{out}/results.md", "w") as f:
    f.write(f"Scenes ({len(scenes)}): " + ", ".join(f"{d} {s}" for d, s in scenes) + "\n\n")
    f.write("| sampler | setting | total time (s, all scenes) | mean RMSE | worst max error | mean samples/pixel | Pareto |\n")
    f.write("|---|---:|---:|---:|---:|---:|:---:|\n")
    for p in summary:
        sampler, setting, t, rmse, mx, spp = p
        name = f"{setting} spp" if sampler != "adaptive" else f"E = {setting}"
        f.write(f"| {sampler} | {name} | {t:.2f} | {rmse:.5f} | {mx:.4f} | {spp:.1f} | {'' if dominated(p, summary) else 'yes'} |\n")
    for cost, what, fmt in ((2, "Total render time (s, all scenes)", "{:.2f}"), (5, "Mean samples per pixel", "{:.1f}")):
        f.write(f"\n{what} to reach a mean RMSE (interpolated on the log-log curves; - : not reached):\n\n")
        f.write("| mean RMSE | " + " | ".join(samplers) + " | adaptive / stratified |\n|---:|" + "---:|" * (len(samplers) + 1) + "\n")
        for level in levels:
            got = {s: time_to_reach(s, level, cost) for s in samplers}
            cells = [fmt.format(got[s]) if got[s] is not None else "-" for s in samplers]
            ratio = "-"
            if got.get("adaptive") is not None and got.get("stratified") is not None:
                ratio = f"{got['adaptive'] / got['stratified']:.2f}"
            f.write(f"| {level:g} | " + " | ".join(cells) + f" | {ratio} |\n")
    f.write("\nPer scene (seconds / RMSE / samples per pixel):\n\n")
    settings = [(p[0], p[1]) for p in summary]
    f.write("| scene | " + " | ".join(f"{sa} {se}" for sa, se in settings) + " |\n")
    f.write("|---|" + "---:|" * len(settings) + "\n")
    for d, s in scenes:
        cells = []
        for sa, se in settings:
            r = next(r for r in by_setting[(sa, se)] if r["dialect"] == d and r["scene"] == s)
            cells.append(f"{float(r['seconds']):.2f} / {float(r['rmse']):.4f} / {float(r['samples_per_pixel'] or 0):.0f}")
        f.write(f"| {d} {s} | " + " | ".join(cells) + " |\n")

for sampler in samplers:
    with open(f"{out}/{sampler}.dat", "w") as f:
        for p in sorted((p for p in summary if p[0] == sampler), key=lambda p: p[2]):
            label = f"{p[1]}" if sampler != "adaptive" else f"E={p[1]}"
            f.write(f"{p[2]} {p[3]} {label}\n")
colors = {"stratified": "#1f77b4", "random": "#d62728", "adaptive": "#2ca02c"}
titles = {"stratified": "uniform stratified (label: spp)", "random": "uniform random, not stratified (label: spp)",
          "adaptive": "adaptive, -target-error E, max 256 spp"}
plots = []
for sampler in samplers:
    c = colors[sampler]
    plots.append(f"'{sampler}.dat' using 1:2 with linespoints lw 2 pt 7 lc rgb '{c}' title '{titles[sampler]}'")
    plots.append(f"'{sampler}.dat' using 1:2:3 with labels offset 0.8,0.6 font ',8' tc rgb '{c}' notitle")
with open(f"{out}/plot.gp", "w") as f:
    f.write(f"""set terminal pngcairo size 1000,650
set output 'time_vs_error.png'
set title 'rayform: run time against error ({len(scenes)} course scenes, 1024-spp stratified references)'
set xlabel 'total render time over all scenes (s)'
set ylabel 'mean RMSE against the reference'
set logscale xy
set grid
set key top right
plot """ + ", \\\n     ".join(plots) + "\n")
