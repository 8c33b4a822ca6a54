#!/bin/bash
# HPN's regression search: 617dab3 (issue 19's "today", with b247c19's planner_profile.py, no --tag there) and
# af183b3 alternately; rows to OUT_DIR/pernode_ab_<commit>.jsonl
R=/work/wt/wip-measure11; OUT=$1; ROUNDS=${2:-2}
for i in $(seq $ROUNDS); do for c in 617dab3 af183b3; do T=/tmp/measure11/trees/$c
  (cd $T && PYTHONPATH=$T/src $R/.venv/bin/python benchmarks/planner_profile.py --regimes single,both --sizes 3,5,8 --trials 0,1 --strategies hpn --logistics 20 --out $OUT/pernode_ab_$c.jsonl > /dev/null)
done; done
