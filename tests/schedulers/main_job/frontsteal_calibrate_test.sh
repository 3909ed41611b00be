#!/bin/sh
# frontsteal_calibrate_test.sh — the main job's rounds and calibration arms end to end.
#   fast: a short --calibrate run writes the answer first, the calibration files with every arm, and its planted
#         work is seen by the harness's clock (realized > 0 where the scheduler's own clock cannot see it: the
#         work runs after run_frame returns); frontsteal-calibration-summary reads the file back (one real
#         experiment, and resampled ones from the same file as a long run); a file without arms is refused.
#         Instances: every arm names the scheduler instance of each round, a fresh one every pass here (the path
#         is shorter than --instance-frames), and each comparison counts those clusters; with --instance-frames 2
#         a fresh one every segment; with 0 one per run and no names (rounds analysed as independent).
#   slow: the method on the real workload: +10 % planted must be found (the interval above 0) and the A/A twin
#         must not be called faster or slower, at P = 1 and P = cores; up to 3 runs (a generous bound: each
#         requirement fails by chance in a few % of runs at most).
# usage: frontsteal_calibrate_test.sh fast|slow FRONTSTEAL SUMMARY OUT_DIR
set -u
tier=$1 bin=$2 summary=$3 out=$4
mkdir -p "$out"
if [ "$tier" = fast ]; then
  log=$("$bin" --scene plant:1201 --schedulers stealing/Fenced --threads 1,2 --frames 4 --round-frames 2 --repeats 3 \
        --calibrate --no-plot --quiet --out "$out/fast" 2>&1)
  rc=$?
  echo "$log" | sed -n '/^ANSWER/,/^$/p'
  [ $rc -eq 0 ] || { echo "FAIL: exit $rc"; echo "$log" | tail -20; exit 1; }
  echo "$log" | grep -q '^ANSWER (measured on' || { echo "FAIL: no answer"; exit 1; }
  [ "$(echo "$log" | grep -n '^ANSWER' | cut -d: -f1)" -lt "$(echo "$log" | grep -n '^| P |' | head -1 | cut -d: -f1)" ] ||
    { echo "FAIL: the answer does not come before the table"; exit 1; }
  for f in frontsteal.json frontsteal-calibration.md frontsteal-calibration.json; do
    [ -s "$out/fast/$f" ] || { echo "FAIL: $f missing"; exit 1; }
  done
  python3 - "$out/fast/frontsteal-calibration.json" <<'PY' || exit 1
import json, sys
doc = json.load(open(sys.argv[1]))
arms = doc["arms"]
names = sorted({(a["workers"], round(a["planted_pct"])) for a in arms})
want = sorted({(p, x) for p in {1, doc["hardware_threads"]} for x in (0, 2, 5, 10, -5)})
assert names == want, f"arms {names}, expected {want}"
for a in arms:
    n = len(a["rounds"]["candidate"]["ms"])
    assert n == 6, f"{a['arm']}: {n} rounds, expected 3 passes x 2 segments"
    if a["planted_pct"] == 10:
        assert a["realized_pct"] > 3, f"{a['arm']}: realized {a['realized_pct']} %: the harness's clock missed the planted work"
    if a["planted_pct"] == 0:
        assert a["realized_pct"] == 0
    for side in ("candidate", "reference"):
        inst = a["rounds"][side]["instance"]
        assert inst == [0, 0, 1, 1, 2, 2], f"{a['arm']} {side}: instances {inst}, expected a fresh one every pass"
    assert a["comparison"]["clusters"] == 3, f"{a['arm']}: {a['comparison']['clusters']} clusters, expected 3"
print("calibration file: every arm present, 6 rounds each, planted work seen by the harness's clock, "
      "a fresh instance every pass")
PY
  for frames in 2 0; do
    "$bin" --scene plant:1201 --schedulers queue-mutex,stealing/Fenced --threads 2 --frames 4 --round-frames 2 \
      --repeats 2 --instance-frames $frames --no-plot --quiet --out "$out/instances-$frames" > "$out/instances-$frames.log" 2>&1 ||
      { echo "FAIL: --instance-frames $frames: exit $?"; tail "$out/instances-$frames.log"; exit 1; }
    python3 - "$out/instances-$frames/frontsteal.json" "$frames" <<'PY' || exit 1
import json, sys
doc, frames = json.load(open(sys.argv[1])), int(sys.argv[2])
assert doc["design"]["instance_frames"] == frames
assert doc["serial"]["rounds"]["instance"] == [-1] * 4, "the serial loop has no instance"
for r in doc["results"]:
    if r["scheduler"] == "serial":
        continue
    inst = r["rounds"]["instance"]
    want = [0, 1, 2, 3] if frames == 2 else [-1] * 4
    assert inst == want, f"{r['scheduler']}: instances {inst}, expected {want}"
print(f"--instance-frames {frames}: instances as expected")
PY
  done
  "$summary" "$out/fast/frontsteal-calibration.json" --long "$out/fast/frontsteal-calibration.json" --rounds 4 \
    --experiments 20 --out "$out/summary" > "$out/summary.log" 2>&1 || { echo "FAIL: summary"; cat "$out/summary.log"; exit 1; }
  grep -q 'P=2 A/A twin' "$out/summary/calibration.md" && grep -q 'Resampled: 20 experiments of 4 rounds' "$out/summary/calibration.md" ||
    { echo "FAIL: summary report"; cat "$out/summary.log"; exit 1; }
  echo '{"arms": []}' > "$out/empty.json"
  "$summary" "$out/empty.json" --out "$out/summary-bad" > "$out/bad.log" 2>&1
  [ $? -eq 1 ] && grep -q 'no calibration arms' "$out/bad.log" || { echo "FAIL: a file without arms was not refused"; exit 1; }
  echo "PASS"
  exit 0
fi
for attempt in 1 2 3; do
  "$bin" --scene plant:5302 --schedulers queue-mutex --threads 1 --calibrate --repeats 10 --no-plot --quiet \
    --out "$out/slow-$attempt" > "$out/slow-$attempt.log" 2>&1 || { echo "FAIL: run exited non-zero"; tail "$out/slow-$attempt.log"; exit 1; }
  if python3 - "$out/slow-$attempt/frontsteal-calibration.json" <<'PY'
import json, sys
arms = json.load(open(sys.argv[1]))["arms"]
ok = True
for a in arms:
    c = a["comparison"]
    print(f"P={a['workers']} {a['arm']}: {c['verdict']} {c['effect_pct']:+.2f} % [{100*(c['ci95_low']-1):+.2f}, {100*(c['ci95_high']-1):+.2f}], realized {a['realized_pct']:.2f} %")
    if a["planted_pct"] == 10 and not a["found"]: ok = False
    if a["planted_pct"] == 0 and c["verdict_if_reliable"] in ("faster", "slower"): ok = False
sys.exit(0 if ok else 1)
PY
  then echo "PASS (run $attempt)"; exit 0; fi
done
echo "FAIL: three runs, none found +10 % at P = 1 and P = cores with the A/A twin neither faster nor slower"
exit 1
