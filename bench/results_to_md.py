#!/usr/bin/env python3
"""Turns Google Benchmark JSON files (rayform_bench_*) into one Markdown table
and one CSV: benchmark, ours, Embree, ratio, unit (median over repetitions
when there were several).

Every rayform benchmark reports its figures as counters: `ours`, optionally
`embree` and `ratio` (= ours / embree), with the unit as the label.

usage: results_to_md.py OUT.md OUT.csv RESULT.json... [--extra NAME=VALUE|UNIT]...
"""
import csv
import json
import sys


def clean(name):
    """Drops Google Benchmark's suffixes (manual_time, iterations:1)."""
    return "/".join(p for p in name.split("/") if p not in ("manual_time", "real_time", "iterations:1", "repeats:1"))


def load_rows(paths):
    rows = []  # (name, ours, embree, ratio, unit, extra counters, error)
    for path in paths:
        with open(path) as f:
            data = json.load(f)
        ctx = data.get("context", {})
        bench = data.get("benchmarks", [])
        labels = {}
        for b in bench:
            if b.get("run_type") == "iteration" and b.get("label"):
                labels[b["run_name"]] = b["label"]
        with_median = {b.get("run_name") for b in bench if b.get("aggregate_name") == "median"}
        seen = set()
        for b in bench:
            name = b.get("run_name", b["name"])
            if b.get("error_occurred"):
                if name not in seen:
                    seen.add(name)
                    rows.append((clean(name), None, None, None, "", {}, b.get("error_message", "error")))
                continue
            if name in with_median:
                if b.get("run_type") != "aggregate" or b.get("aggregate_name") != "median":
                    continue
            elif b.get("run_type") != "iteration":
                continue
            if name in seen:
                continue
            seen.add(name)
            extra = {k: v for k, v in b.items()
                     if isinstance(v, (int, float)) and k not in (
                         "ours", "embree", "ratio", "iterations", "real_time", "cpu_time",
                         "repetitions", "repetition_index", "threads", "family_index",
                         "per_family_instance_index")}
            rows.append((clean(name), b.get("ours"), b.get("embree"), b.get("ratio"),
                         labels.get(name, b.get("label", "")), extra, None))
        rows_ctx = ctx
    return rows, rows_ctx


def fmt(v, unit=""):
    if v is None:
        return "-"
    if unit == "ms" and v >= 100:
        return f"{v:.0f}"
    if abs(v) >= 100:
        return f"{v:.1f}"
    return f"{v:.3g}" if abs(v) < 10 else f"{v:.2f}"


def main(argv):
    extras = []
    args = []
    i = 0
    while i < len(argv):
        if argv[i] == "--extra":
            extras.append(argv[i + 1])
            i += 2
        else:
            args.append(argv[i])
            i += 1
    if len(args) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    out_md, out_csv, inputs = args[0], args[1], args[2:]
    rows, ctx = load_rows(inputs)
    for e in extras:  # NAME=VALUE|UNIT, e.g. peak RSS measured outside Google Benchmark
        name, rest = e.split("=", 1)
        value, unit = (rest.split("|", 1) + [""])[:2]
        rows.append((name, float(value), None, None, unit, {}, None))

    with open(out_csv, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["benchmark", "ours", "embree", "ratio", "unit", "mismatches", "note"])
        for name, ours, emb, ratio, unit, extra, err in rows:
            w.writerow([name, "" if ours is None else f"{ours:.6g}", "" if emb is None else f"{emb:.6g}",
                        "" if ratio is None else f"{ratio:.4f}", unit,
                        "" if "mismatches" not in extra else int(extra["mismatches"]), err or ""])

    with open(out_md, "w") as f:
        f.write("| benchmark | ours | Embree | ratio ours/Embree | unit | notes |\n")
        f.write("|---|---:|---:|---:|---|---|\n")
        for name, ours, emb, ratio, unit, extra, err in rows:
            notes = []
            if err:
                notes.append(err)
            if "mismatches" in extra:
                notes.append(f"mismatches {int(extra['mismatches'])}/{int(extra.get('rays', 0))}")
            if "embree_high" in extra:
                notes.append(f"Embree HIGH {fmt(extra['embree_high'], unit)} {unit}")
            if name.endswith("/embree_high"):
                notes.append("Embree column: RTC_BUILD_QUALITY_HIGH (one run)")
            elif name.startswith("build/"):
                notes.append("Embree column: RTC_BUILD_QUALITY_MEDIUM")
            if "prepare_ms" in extra:
                notes.append(f"prepare {fmt(extra['prepare_ms'], 'ms')} ms")
            if "Mrays_per_s" in extra:
                notes.append(f"{fmt(extra['Mrays_per_s'])} Mrays/s")
            if "embree_build_peak" in extra:
                notes.append(f"Embree build peak {fmt(extra['embree_build_peak'])} B/tri")
            f.write(f"| {name} | {fmt(ours, unit)} | {fmt(emb, unit)} | {fmt(ratio)} | {unit} | "
                    f"{'; '.join(notes)} |\n")
        if ctx:
            load = ctx.get("load_avg", [])
            f.write(f"\nMachine: {ctx.get('num_cpus', '?')} CPUs at {ctx.get('mhz_per_cpu', '?')} MHz; "
                    f"{ctx.get('date', '')}"
                    + (f"; load average {', '.join(f'{x:.1f}' for x in load)}" if load else "") + ".\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
