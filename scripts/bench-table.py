#!/usr/bin/env python3
"""Turns tessera_workload_bench's JSON output (--benchmark_out=FILE) into Markdown tables of
median milliseconds per frame: one table per sample count and colour mode, a row per workload,
a column per SIMD target (and llvmpipe, in the colour tables, when the run drove it) and
thread count."""
import json
import sys


def main(path):
    with open(path) as f:
        runs = json.load(f)["benchmarks"]
    cells = {}
    columns = []
    for r in runs:
        if r.get("run_type") == "aggregate" or "error_occurred" in r:
            continue
        parts = r["name"].split("/")
        if parts[1] == "llvmpipe":  # workload/llvmpipe/threads:T/samples:S
            workload, target, rest = parts[0], "llvmpipe", parts[2:]
        else:  # workload/fast/target/threads:T/samples:S[/depth_only]
            workload, target, rest = parts[0], parts[2], parts[3:]
        threads = rest[0].split(":")[1]
        samples = rest[1].split(":")[1]
        mode = "depth only" if "depth_only" in parts else "colour"
        column = f"{target} {threads}t"
        if column not in columns:
            columns.append(column)
        # The median frame (the harness's median_ms counter); older outputs had only the mean.
        cells[(samples, mode, workload, column)] = r.get("median_ms", r["real_time"])
    for samples in ("1", "4"):
        for mode in ("colour", "depth only"):
            workloads = [w for w in ("tiny", "small", "medium", "large", "huge", "grid")
                         if any(k[:3] == (samples, mode, w) for k in cells)]
            if not workloads:
                continue
            print(f"\n{samples} sample{'s' if samples != '1' else ''}, {mode}: ms per frame\n")
            here = [c for c in columns if any((samples, mode, w, c) in cells for w in workloads)]
            print("| workload | " + " | ".join(here) + " |")
            print("| --- |" + " ---: |" * len(here))
            for w in workloads:
                row = [cells.get((samples, mode, w, c)) for c in here]
                print(f"| {w} | " + " | ".join("" if v is None else f"{v:.1f}" for v in row) + " |")


if __name__ == "__main__":
    main(sys.argv[1])
