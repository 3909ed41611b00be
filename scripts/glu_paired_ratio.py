#!/usr/bin/env python3
"""Trimmed tessellation against GLU in paired rounds: how many times faster frontsteal is, with an interval.

Runs glu_reference_benchmark once with --benchmark_enable_random_interleaving: every repetition index is one
round in which each benchmark runs once, in a random order, so the two sides of a round see the same machine
speed (these VMs change speed under a program; medians of separate runs of each side do not pair). Per round
and grid, ratio = GLU's time / ours (the harness's wall clock, Google Benchmark's real_time); the answer is
the geometric mean of the rounds' ratios with a 95 % Student-t interval on their logarithms.

Usage: glu_paired_ratio.py [--benchmark PATH] [--rounds N] [--json FILE]
"""
import argparse
import collections
import json
import math
import statistics
import subprocess
import sys

# Two-sided 95 % Student-t quantiles by degrees of freedom (rounds - 1); beyond the table, the normal's 1.96.
T95 = {4: 2.776, 5: 2.571, 6: 2.447, 7: 2.365, 8: 2.306, 9: 2.262, 10: 2.228, 11: 2.201, 12: 2.179, 13: 2.160,
       14: 2.145, 15: 2.131, 16: 2.120, 17: 2.110, 18: 2.101, 19: 2.093, 20: 2.086, 24: 2.064, 29: 2.045}


def t95(df):
    return T95.get(df) or (T95[max(k for k in T95 if k <= df)] if df < 30 else 1.96)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--benchmark", default="build/release/tessellate/benchmarks/glu_reference_benchmark")
    ap.add_argument("--rounds", type=int, default=15, help="paired rounds (repetitions), at least 5")
    ap.add_argument("--json", help="also write the rounds and the answer here")
    args = ap.parse_args()
    if args.rounds < 5:
        ap.error("--rounds must be at least 5")
    cmd = [args.benchmark, "--benchmark_filter=trimmed_hole/", f"--benchmark_repetitions={args.rounds}",
           "--benchmark_enable_random_interleaving=true", "--benchmark_min_time=0.1", "--benchmark_format=json"]
    print(f"running {args.rounds} paired rounds of {args.benchmark} ...", file=sys.stderr, flush=True)
    try:
        out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
    except (OSError, subprocess.CalledProcessError) as e:
        sys.exit(f"glu_paired_ratio: could not run {args.benchmark}: {e} (build it: cmake --build --preset release)")
    times = collections.defaultdict(dict)  # run_name -> {round: ns}
    for b in json.loads(out)["benchmarks"]:
        if b.get("run_type") == "iteration":
            times[b["run_name"]][b["repetition_index"]] = b["real_time"]
    rows = []
    for name in sorted(times, key=lambda n: int(n.rsplit("/", 1)[1])):
        if not name.startswith("BM_ours_"):
            continue
        steps = name.rsplit("/", 1)[1]
        ours, glu = times[name], times[f"BM_glu_trimmed_hole/{steps}"]
        logs = [math.log(glu[r] / ours[r]) for r in sorted(ours) if r in glu]
        m, s = statistics.mean(logs), statistics.stdev(logs)
        h = t95(len(logs) - 1) * s / math.sqrt(len(logs))
        rows.append({"grid": f"{steps} x {steps}", "rounds": len(logs), "ratio": math.exp(m),
                     "low": math.exp(m - h), "high": math.exp(m + h), "ours_us_median": statistics.median(ours.values()) / 1e3,
                     "glu_us_median": statistics.median(glu.values()) / 1e3})
    print("Trimmed patch (bicubic, circular hole of 64 segments) against GLU, one thread, paired rounds (measured):")
    for r in rows:
        print(f"  {r['grid']:>9}: frontsteal {r['ratio']:.2f}x GLU's speed [{r['low']:.2f}, {r['high']:.2f}] (95 %, "
              f"{r['rounds']} rounds; medians {r['ours_us_median']:.1f} us vs {r['glu_us_median']:.1f} us)")
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"benchmark": args.benchmark, "rows": rows}, f, indent=1)


if __name__ == "__main__":
    main()
