#!/bin/bash
# HPN on logistics-20 (seeds 0,1): 1863a48 and af183b3 alternately, ROUNDS rounds, rows appended to OUT
R=/work/wt/wip-measure11; OUT=$1; ROUNDS=${2:-4}
for i in $(seq $ROUNDS); do for c in 1863a48 af183b3; do T=/tmp/measure11/trees/$c
  (cd $T && PYTHONPATH=$T/src $R/.venv/bin/python benchmarks/planner_profile.py --no-marsupial --logistics 20 --logistics-seeds 0,1 --tag $c --out $OUT > /dev/null)
done; done
