#!/usr/bin/env python3
"""Summarises scripts/bench-accuracy's CSV: per spp, the total time over all scenes and the
mean RMSE and worst max error; marks the Pareto front (no other setting is both faster and
more accurate); writes results.md, the gnuplot data files and plot.gp."""
import csv
import sys
from collections import defaultdict

csv_path, out = sys.argv[1], sys.argv[2]
rows = list(csv.DictReader(open(csv_path)))
by_spp = defaultdict(list)
for r in rows:
    by_spp[int(r["spp"])].append(r)

summary = []
for spp in sorted(by_spp):
    rs = by_spp[spp]
    t = sum(float(r["seconds"]) for r in rs)
    rmse = sum(float(r["rmse"]) for r in rs) / len(rs)
    mx = max(float(r["max_error"]) for r in rs)
    summary.append((spp, t, rmse, mx))

def pareto(points):
    front = []
    for p in points:
        dominated = any(q[1] <= p[1] and q[2] <= p[2] and (q[1] < p[1] or q[2] < p[2]) for q in points)
        front.append(not dominated)
    return front

front = pareto(summary)
with open(f"{out}/results.md", "w") as f:
    f.write("| spp | total time (s, all scenes) | mean RMSE | worst max error | Pareto |\n|---:|---:|---:|---:|:---:|\n")
    for (spp, t, rmse, mx), on in zip(summary, front):
        f.write(f"| {spp} | {t:.2f} | {rmse:.5f} | {mx:.4f} | {'yes' if on else ''} |\n")
    f.write("\nPer scene (seconds / RMSE):\n\n| scene | " + " | ".join(str(s) for s in sorted(by_spp)) + " |\n")
    f.write("|---|" + "---:|" * len(by_spp) + "\n")
    scenes = sorted({(r["dialect"], r["scene"]) for r in rows})
    for d, s in scenes:
        cells = []
        for spp in sorted(by_spp):
            r = next(r for r in by_spp[spp] if r["dialect"] == d and r["scene"] == s)
            cells.append(f"{float(r['seconds']):.2f} / {float(r['rmse']):.4f}")
        f.write(f"| {d} {s} | " + " | ".join(cells) + " |\n")
with open(f"{out}/summary.dat", "w") as f:
    for (spp, t, rmse, mx), on in zip(summary, front):
        f.write(f"{t} {rmse} {spp} {1 if on else 0}\n")
with open(f"{out}/pareto.dat", "w") as f:
    for (spp, t, rmse, mx), on in sorted(zip(summary, front), key=lambda x: x[0][1]):
        if on:
            f.write(f"{t} {rmse}\n")
with open(f"{out}/plot.gp", "w") as f:
    f.write("""set terminal pngcairo size 900,600
set output 'time_vs_error.png'
set title 'rayform: run time against error (course scenes, 2012 + 2019)'
set xlabel 'total render time over all scenes (s)'
set ylabel 'mean RMSE against the reference'
set logscale xy
set grid
plot 'summary.dat' using 1:2:(sprintf('%d spp', $3)) with labels offset 1,1 notitle, \\
     'summary.dat' using 1:2 with points pt 7 ps 1.5 title 'spp setting', \\
     'pareto.dat' using 1:2 with lines lw 2 title 'Pareto front'
""")
