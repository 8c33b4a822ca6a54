#!/bin/bash
# A/B in one run: BASE=checkout NEW=checkout bash ab.sh (from the repo root; each checkout with its kernel built)
for d in ${DOMS:-logistics zenotravel driverlog}; do
  for t in $BASE $NEW $BASE $NEW; do
    echo "$d $(basename $t) auto $(/work/main/.venv/bin/python benchmarks/results/lm_per_call/run.py $t $d run auto)"
  done
  for t in $BASE $NEW; do
    echo "$d $(basename $t) flat $(/work/main/.venv/bin/python benchmarks/results/lm_per_call/run.py $t $d run flat)"
  done
done
