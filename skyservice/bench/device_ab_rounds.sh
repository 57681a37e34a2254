#!/bin/bash
# A/B of two sky-bench builds in one device call (BENCHMARKS.md): two rounds
# of every scene at 1920x1080 reprojected, full mode at 1920x1080, 3840x2160 reprojected, 1920x1080 at
# 250 m/s, then each scene of SKY_BENCH_ALONE timed on its own (a GPU may clock down in long runs:
# summarize.py clocks names the affected runs). Each run writes under /tmp/r, all of it returns as
# $OUT/r.tgz with the printed tables in $OUT/summary.txt (the device tool returns few files).
# Usage on the device: bash skyservice/bench/device_ab_rounds.sh LABEL_A LABEL_B, with
# .gpu/builds/LABEL_A/ and LABEL_B/ made by device_prepare.sh (SKY_BENCH_BUILDS="LABEL_A=DIR ...") and
# no other folder in .gpu/builds.
set -u
A=${1:?label of the first build}
B=${2:?label of the second build}
ALONE=${SKY_BENCH_ALONE:-inside-cloud above-deck-FL350 sunset cumulonimbus}
export SKY_BENCH_DEVICE_BUILD=0 SKY_BENCH_MODE=builds SKY_BENCH_RUN_LIMIT_S=150
R=/tmp/r
FINAL=$OUT
S=skyservice/bench/summarize.py
RUN=skyservice/bench/device_run.sh
mkdir -p $R
for i in 1 2; do mkdir -p $R/r$i; OUT=$R/r$i bash $RUN > /dev/null 2>&1; done
mkdir -p $R/f; OUT=$R/f SKY_BENCH_AB_MODES=full bash $RUN > /dev/null 2>&1
mkdir -p $R/k; OUT=$R/k SKY_BENCH_AB_SIZES=3840x2160 bash $RUN > /dev/null 2>&1
mkdir -p $R/v; OUT=$R/v SKY_BENCH_SCENES=scattered-cumulus,stratocumulus-deck,cumulonimbus,inside-cloud,above-deck-FL350,sunset \
  SKY_BENCH_VARIANTS="--speed 250" bash $RUN > /dev/null 2>&1
for sc in $ALONE; do mkdir -p $R/x-$sc; OUT=$R/x-$sc SKY_BENCH_SCENES=$sc bash $RUN > /dev/null 2>&1; done
tar czf $FINAL/r.tgz -C $R .
{
  for i in 1 2; do
    echo "== 1080p reprojected round $i"
    python3 $S table $A=$R/r$i/bench-$A-1920x1080-v0.json $B=$R/r$i/bench-$B-1920x1080-v0.json
  done
  echo "== 1080p full"; python3 $S table $A=$R/f/bench-$A-full-1920x1080-v0.json $B=$R/f/bench-$B-full-1920x1080-v0.json
  echo "== 4K reprojected"; python3 $S table $A=$R/k/bench-$A-3840x2160-v0.json $B=$R/k/bench-$B-3840x2160-v0.json
  echo "== 1080p 250 m/s"; python3 $S table $A=$R/v/bench-$A-1920x1080-v0.json $B=$R/v/bench-$B-1920x1080-v0.json
  for sc in $ALONE; do
    echo "== alone: $sc"
    python3 $S table $A=$R/x-$sc/bench-$A-1920x1080-v0.json $B=$R/x-$sc/bench-$B-1920x1080-v0.json | tail -1
  done
  python3 $S clocks $R/r1 $R/r2 $R/f $R/k $R/v $R/x-*
  grep -h "FULL\|1/16 (" $R/*/baseline.txt
  python3 -c "import json, sys; [print(f, 'memory bytes', json.load(open(f))['memory']['totalBytes']) for f in sys.argv[1:]]" \
    $R/r1/bench-$A-1920x1080-v0.json $R/r1/bench-$B-1920x1080-v0.json
} > $FINAL/summary.txt 2>&1
cat $FINAL/summary.txt
