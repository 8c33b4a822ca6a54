#!/bin/bash
# HPN's planning CPU on marsupial for two source trees, alternating per regime and size
# (issue 19 target 3; ratios within one run, the machine is shared).
#
#   benchmarks/planner_profile_ab.sh BEFORE_SRC AFTER_SRC OUT.jsonl [TRIALS] [SIZES]
#
# BEFORE_SRC / AFTER_SRC are `src` folders (e.g. a `git archive HEAD src` copy of main with its
# compiled kernel copied in, and this tree's src); rows are tagged `before` / `after`.
# Growth per tag: benchmarks/planner_profile.py --summarize OUT.jsonl --fit
set -euo pipefail
BEFORE=$1; AFTER=$2; OUT=$3; TRIALS=${4:-0,1}; SIZES=${5:-3,5,8,12,16,20}
HERE=$(cd "$(dirname "$0")" && pwd)
PY=${PYTHON:-python}
for regime in single both; do
  for n in ${SIZES//,/ }; do
    for tag in before after; do
      if [ "$tag" = before ]; then SRC=$BEFORE; else SRC=$AFTER; fi
      PYTHONPATH=$SRC $PY "$HERE/planner_profile.py" --regimes "$regime" --sizes "$n" --trials "$TRIALS" \
        --strategies hpn --no-logistics --tag "$tag" --out "$OUT" > /dev/null
    done
  done
done
