#!/bin/bash
# usage: reg.sh TREE
cd $1
for spec in "logistics small" "logistics medium" "logistics small-failures" "marsupial single-3" "marsupial both-5" "marsupial dests-4" "marsupial origins-6" "pieces small" "namo domain1" "logistics large"; do
  set -- $spec
  for seed in 0 1; do
    for st in hpn "hpn+refine-flat"; do
      out=$(PYTHONPATH=src timeout 120 /work/main/.venv/bin/nowplan run --domain $1 --scenario $2 --strategy $st --seed $seed 2>&1 | grep -E "^outcome|execution cost|plans made" | tr '\n' ' ')
      echo "$1 $2 $st seed$seed: $out"
    done
  done
done
