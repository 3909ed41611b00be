#!/usr/bin/env python3
"""Compare the simulator's prediction, committed BEFORE the 16-core run, with what that run measured.

The prediction (PREDICTION_DIR/simulate-plant-N.json, written by `frontsteal-paper simulate` on the 2-core
machine from that machine's traces and calibration) and the measurement (STUDY_DIR/main/frontsteal.json, the
main job, and STUDY_DIR/fig8*/fig8.json, Fig. 8 measured, one folder per run) come from different machines, so absolute frames/s are
not compared. What is compared is how each scheduler SCALES:

  main job   speed-up over the serial loop, S(P) = T1 / T_P. Measured: 1 / the median of the paired per-repeat
             ratios T_P[r] / T1[r], with that ratio's 95 % bootstrap interval inverted. Predicted: simulated
             frames/s at P over the trace's serial frames/s (sum of per-surface costs).
  fig8       scaling against the same scheduler's own P = 1: measured frames/s(P) / frames/s(1), predicted
             simulated frames/s(P) / simulated frames/s(1) (no serial loop is run by fig8).

The four simulated models stand for static (spatial-annealing), queue-mutex, stealing/Fenced and chase-lev. For
each (scheduler, P) it reports both values, the error (predicted / measured - 1) and whether the prediction lies
inside the measured interval; then the median and worst |error| per scheduler and overall. A measured run that
the noise monitor flagged is carried over as unreliable.

usage: compare_prediction.py STUDY_DIR [--prediction DIR] [--label TEXT] [--name BASE]
       -> STUDY_DIR/BASE.{md,json,csv}, BASE.dat and BASE.gp (BASE: comparison; gnuplot BASE.gp draws
          BASE.png: measured points with intervals, predicted lines)
"""
import argparse, csv, json, math, os, statistics, sys

MODELS = [("static (spatial partition)", "spatial-annealing"), ("global queue (mutex)", "queue-mutex"),
          ("load stealing (Fenced)", "stealing/Fenced"), ("Chase-Lev", "chase-lev")]


def load(path):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, json.JSONDecodeError) as e:
        sys.exit(f"compare_prediction.py: cannot read {path}: {e}")


def predicted_curves(prediction_dir, scene):
    """{scheduler: {P: (speed-up over the trace's serial, scaling over the model's own P=1)}} for one scene."""
    name = "simulate-" + scene.replace(":", "-") + ".json"
    d = load(os.path.join(prediction_dir, name))
    s = d["scenes"][0]
    by_p = {row["workers"]: row["fps"] for row in s["simulated"]}
    out = {}
    for m, (_, sched) in enumerate(MODELS):
        one = by_p[1][m]
        out[sched] = {p: (fps[m] / s["serial_fps"], fps[m] / one) for p, fps in by_p.items()}
    return out, d


def error_row(kind, scene, sched, p, measured, low, high, predicted, reliable):
    err = predicted / measured - 1
    return {"comparison": kind, "scene": scene, "scheduler": sched, "workers": p, "measured": measured,
            "measured_ci95_low": low, "measured_ci95_high": high, "predicted": predicted, "error_pct": 100 * err,
            "inside_interval": (low is not None and low <= predicted <= high), "measured_reliable": reliable}


def main_job_rows(study, prediction_dir):
    path = os.path.join(study, "main", "frontsteal.json")
    if not os.path.isfile(path):
        return [], None
    d = load(path)
    pred, _ = predicted_curves(prediction_dir, d["scene"])
    rows = []
    for r in d["results"]:
        if r["scheduler"] not in pred or r["workers"] not in pred[r["scheduler"]]:
            continue
        v = r["vs_serial"]
        measured = 1 / v["ratio_median"]
        rows.append(error_row("main job: speed-up over the serial loop", d["scene"], r["scheduler"], r["workers"],
                              measured, 1 / v["ci95_high"], 1 / v["ci95_low"],
                              pred[r["scheduler"]][r["workers"]][0], v.get("reliable", True)))
    return rows, d


def bootstrap_ratio_ci(num, den, resamples=10000, seed=1):
    """95 % percentile-bootstrap interval of median(num) / median(den), resampling each set (unpaired: fig8's
    P = 1 and P runs are different cells)."""
    import random
    rng = random.Random(seed)
    vals = sorted(statistics.median(rng.choices(num, k=len(num))) / statistics.median(rng.choices(den, k=len(den)))
                  for _ in range(resamples))
    return vals[int(0.025 * resamples)], vals[int(0.975 * resamples) - 1]


def fig8_rows(study, prediction_dir):
    paths = sorted(os.path.join(study, e, "fig8.json") for e in os.listdir(study)
                   if e.startswith("fig8") and os.path.isfile(os.path.join(study, e, "fig8.json")))
    if not paths:
        return [], None
    rows, d = [], None
    scenes = []
    for path in paths:
        d = load(path)
        scenes += d["scenes"]
    for s in scenes:
        pred, _ = predicted_curves(prediction_dir, s["scene"])
        meas = {row["workers"]: row for row in s["measured"]}
        if 1 not in meas:
            continue
        reliable = not s.get("noise", {}).get("unreliable_verdicts", 0)
        for p, row in sorted(meas.items()):
            for m, (_, sched) in enumerate(MODELS):
                if p not in pred[sched]:
                    continue
                one = meas[1]["path_ms_per_repeat"][m]
                here = row["path_ms_per_repeat"][m]
                measured = statistics.median(one) / statistics.median(here)
                low, high = bootstrap_ratio_ci(one, here)
                rows.append(error_row("fig8: scaling over the same scheduler at P = 1", s["scene"], sched, p, measured,
                                      low, high, pred[sched][p][1], reliable))
    return rows, d


def summarize(rows):
    out = []
    keys = sorted({(r["comparison"], r["scheduler"]) for r in rows})
    for kind, sched in keys + [(k, "all") for k in sorted({r["comparison"] for r in rows})]:
        sel = [r for r in rows if r["comparison"] == kind and (sched == "all" or r["scheduler"] == sched)
               and r["workers"] > 1]
        if not sel:
            continue
        errs = [abs(r["error_pct"]) for r in sel]
        worst = max(sel, key=lambda r: abs(r["error_pct"]))
        out.append({"comparison": kind, "scheduler": sched, "cells": len(sel), "median_abs_error_pct": statistics.median(errs),
                    "worst_abs_error_pct": max(errs), "worst_at": f"{worst['scene']} P={worst['workers']}",
                    "inside_interval": sum(r["inside_interval"] for r in sel),
                    "over_predicted": sum(r["error_pct"] > 0 for r in sel)})
    return out


def write_plot(study, rows, name):
    scenes = []
    for r in rows:
        key = (r["comparison"], r["scene"])
        if key not in scenes:
            scenes.append(key)
    dat, gp = [], ["set terminal pngcairo size 1600,900 font 'sans,10'", f"set output '{name}.png'",
                   f"set multiplot layout 1,{len(scenes)} title \"Simulator prediction (lines, SIMULATED before the "
                   "run) against the 16-core measurement (points with 95 % intervals, MEASURED)\"",
                   "set key top left", "set grid", "set xlabel 'P (workers)'", "set xrange [0:17]"]
    block = 0
    for kind, scene in scenes:
        ylabel = "speed-up over the serial loop" if kind.startswith("main") else "frames/s over the same scheduler at P = 1"
        plots = []
        for m, (label, sched) in enumerate(MODELS):
            sel = sorted((r for r in rows if r["comparison"] == kind and r["scene"] == scene and r["scheduler"] == sched),
                         key=lambda r: r["workers"])
            if not sel:
                continue
            dat.append(f"# {kind} | {scene} | {sched}: P measured low high predicted")
            dat += [f"{r['workers']} {r['measured']:.5f} {r['measured_ci95_low']:.5f} {r['measured_ci95_high']:.5f} "
                    f"{r['predicted']:.5f}" for r in sel]
            dat += ["", ""]
            plots.append(f"'{name}.dat' index {block} using 1:2:3:4 with yerrorbars lc {m + 1} pt 7 "
                         f"title '{sched} measured'")
            plots.append(f"'' index {block} using 1:5 with lines lc {m + 1} dt 2 title '{sched} predicted'")
            block += 1
        short = "main job" if kind.startswith("main") else "fig8"
        gp += [f"set title '{short}: {scene}'", f"set ylabel '{ylabel}'",
               "plot x with lines lc rgb '#bbbbbb' title 'ideal', " + ", ".join(plots)]
    gp.append("unset multiplot")
    with open(os.path.join(study, name + ".dat"), "w") as f:
        f.write("\n".join(dat) + "\n")
    with open(os.path.join(study, name + ".gp"), "w") as f:
        f.write("\n".join(gp) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("study_dir")
    ap.add_argument("--prediction", help="folder of simulate-*.json (default STUDY_DIR/prediction)")
    ap.add_argument("--label", default="prediction committed before the run",
                    help="what the prediction is, for the headings")
    ap.add_argument("--name", default="comparison", help="base name of the files written (default comparison)")
    args = ap.parse_args()
    study = args.study_dir
    prediction = args.prediction or os.path.join(study, "prediction")
    main_rows, main_d = main_job_rows(study, prediction)
    fig8_rows_, fig8_d = fig8_rows(study, prediction)
    rows = main_rows + fig8_rows_
    if not rows:
        sys.exit(f"compare_prediction.py: no main/frontsteal.json or fig8*/fig8.json under {study}")
    summary = summarize(rows)
    machine = (main_d or fig8_d).get("machine", "?")
    doc = {"schema_version": 1, "program": "compare_prediction.py", "kind": "measured against simulated",
           "prediction": prediction, "prediction_label": args.label, "measured_machine": machine,
           "measured_commit": (main_d or fig8_d).get("commit"), "summary": summary, "cells": rows}
    with open(os.path.join(study, args.name + ".json"), "w") as f:
        json.dump(doc, f, indent=1)
    with open(os.path.join(study, args.name + ".csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    md = [f"# Simulator prediction against the 16-core measurement", "",
          f"Prediction: `{prediction}` ({args.label}; SIMULATED). Measured on: {machine} (MEASURED). "
          "Error = predicted / measured − 1 on the scaling (not on absolute frames/s: the two machines differ). "
          "\"in CI\": the prediction lies inside the measured 95 % interval.", "",
          "## Summary (P > 1)", "", "| comparison | scheduler | cells | median abs. error | worst abs. error (where) "
          "| prediction in CI | over-predicted |", "|---|---|---:|---:|---:|---:|---:|"]
    for s in summary:
        md.append(f"| {s['comparison']} | {s['scheduler']} | {s['cells']} | {s['median_abs_error_pct']:.1f} % | "
                  f"{s['worst_abs_error_pct']:.1f} % ({s['worst_at']}) | {s['inside_interval']} / {s['cells']} | "
                  f"{s['over_predicted']} / {s['cells']} |")
    for kind in sorted({r["comparison"] for r in rows}):
        md += ["", f"## {kind}", "", "| scene | scheduler | P | measured [95 % CI] | predicted | error | in CI | "
               "measured run reliable |", "|---|---|---:|---:|---:|---:|---|---|"]
        for r in (r for r in rows if r["comparison"] == kind):
            md.append(f"| {r['scene']} | {r['scheduler']} | {r['workers']} | {r['measured']:.2f} "
                      f"[{r['measured_ci95_low']:.2f}, {r['measured_ci95_high']:.2f}] | {r['predicted']:.2f} | "
                      f"{r['error_pct']:+.1f} % | {'yes' if r['inside_interval'] else 'no'} | "
                      f"{'yes' if r['measured_reliable'] else 'NO (noise monitor)'} |")
    with open(os.path.join(study, args.name + ".md"), "w") as f:
        f.write("\n".join(md) + "\n")
    write_plot(study, rows, args.name)
    print("\n".join(md[:8 + len(summary)]))
    print(f"\nwrote {study}/{args.name}.md, .json, .csv, .dat, .gp")


if __name__ == "__main__":
    main()
