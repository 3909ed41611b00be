#!/usr/bin/env python3
"""Summarize a frontsteal study: for each configuration directory (one frontsteal.json each), compare the
stealing scheduler with every other scheduler at each P through paired per-repeat ratios (repeat k of both
schedulers ran in the same interleaved round), median ratio and its 95 % percentile-bootstrap interval
(10,000 resamples, fixed seed), and a verdict: ahead (interval entirely below 1: stealing takes less time),
behind (entirely above 1) or no difference. The run's own noise verdict (frontsteal's noise monitor) is
carried over: a run the monitor called busy makes every verdict of that run "unreliable".

usage: summarize_study.py STUDY_DIR [--scheduler stealing/Fenced]   -> writes STUDY_DIR/summary.{md,json}
"""
import argparse, json, os, random, statistics, sys


def bootstrap_median_ci(values, resamples=10000, seed=1):
    rng = random.Random(seed)
    n = len(values)
    meds = sorted(statistics.median(rng.choice(values) for _ in range(n)) for _ in range(resamples))
    return meds[int(0.025 * resamples)], meds[int(0.975 * resamples) - 1]


def compare(mine, other):
    pairs = [a / b for a, b in zip(mine, other) if b > 0]
    med = statistics.median(pairs)
    lo, hi = bootstrap_median_ci(pairs)
    verdict = "ahead" if hi < 1 else "behind" if lo > 1 else "no difference"
    return {"pairs": len(pairs), "ratio_median": med, "ci95_low": lo, "ci95_high": hi, "verdict": verdict,
            "effect_pct": (med - 1) * 100}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("study_dir")
    ap.add_argument("--scheduler", default="stealing/Fenced")
    args = ap.parse_args()
    configs = sorted(d for d in os.listdir(args.study_dir)
                     if os.path.isfile(os.path.join(args.study_dir, d, "frontsteal.json")))
    if not configs:
        sys.exit(f"summarize_study.py: no */frontsteal.json under {args.study_dir}")
    out = {"schema_version": 1, "program": "summarize_study.py", "kind": "measured", "scheduler": args.scheduler,
           "method": "paired per-repeat ratio T(scheduler)/T(other), median, 95 % percentile bootstrap (10,000, seed 1)",
           "configurations": []}
    md = [f"# Study summary: `{args.scheduler}` against every other scheduler (MEASURED)", "",
          "Ratio = path time of " + args.scheduler + " / path time of the other scheduler, paired by repeat "
          "(both ran in the same interleaved round); < 1 means " + args.scheduler + " is faster. Median of the "
          "per-repeat ratios with its 95 % percentile-bootstrap interval; verdict at 95 %. A run the noise "
          "monitor flagged marks its verdicts unreliable.", ""]
    for c in configs:
        d = json.load(open(os.path.join(args.study_dir, c, "frontsteal.json")))
        noise = d.get("noise", {})
        busy = noise.get("unreliable_verdicts", 0) > 0
        rows = d["results"]
        entry = {"configuration": c, "path": d.get("path"), "interference": d.get("interference"),
                 "repeats": d.get("repeats"), "commit": d.get("commit"), "machine": d.get("machine"),
                 "serial_spread_pct": noise.get("serial_spread_pct"), "noise_warnings": noise.get("warnings", []),
                 "reliable": not busy, "comparisons": []}
        md += [f"## {c}", "",
               f"path {d.get('path')}, interference {json.dumps(d.get('interference'))}, {d.get('repeats')} repeats, "
               f"commit {d.get('commit')}, {d.get('machine')}; serial loop's spread "
               f"{noise.get('serial_spread_pct', float('nan')):.1f} %; noise monitor: "
               + ("**busy — verdicts unreliable**: " + "; ".join(noise.get("warnings", [])) if busy else "quiet"), "",
               "| P | other scheduler | ratio [95 % CI] | verdict | effect |", "|---:|---|---:|---|---:|"]
        for p in sorted({r["workers"] for r in rows}):
            mine = next((r for r in rows if r["workers"] == p and r["scheduler"] == args.scheduler), None)
            if not mine:
                continue
            for r in rows:
                if r["workers"] != p or r["scheduler"] == args.scheduler:
                    continue
                k = compare(mine["path_ms_per_repeat"], r["path_ms_per_repeat"])
                k.update({"workers": p, "other": r["scheduler"]})
                if busy:
                    k["verdict_if_reliable"], k["verdict"] = k["verdict"], "unreliable"
                entry["comparisons"].append(k)
                shown = k["verdict"] if not busy else f"unreliable ({k['verdict_if_reliable']})"
                md.append(f"| {p} | {r['scheduler']} | {k['ratio_median']:.3f} [{k['ci95_low']:.3f}, "
                          f"{k['ci95_high']:.3f}] | {shown} | {k['effect_pct']:+.1f} % |")
        md.append("")
        out["configurations"].append(entry)
    with open(os.path.join(args.study_dir, "summary.json"), "w") as f:
        json.dump(out, f, indent=1)
    with open(os.path.join(args.study_dir, "summary.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    print("\n".join(md))


if __name__ == "__main__":
    main()
