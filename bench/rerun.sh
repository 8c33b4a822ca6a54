#!/bin/sh
# usage: bench/rerun.sh base|after|main|mainfix DOMAIN LEVELS STRATEGIES [SEEDS]
# base = the branch point 84a2ec1, after = this branch, main = /work/main now, mainfix = main + this branch's src diff
which=$1; dom=$2; levels=$3; strategies=$4; seeds=${5:-0-19}
case $which in
  base) src=/tmp/fnp/base/src;; after) src=/work/wt-faultsnp/src;; main) src=/work/main/src;; mainfix) src=/tmp/fnp/mainfix/src;;
esac
cd /work/wt-faultsnp && PYTHONPATH=$src timeout 590 /work/main/.venv/bin/python benchmarks/faults.py --domains $dom \
  --levels "$levels" --strategies "$strategies" --seeds "$seeds" --store bench/$which${TAG:+-$TAG}.sqlite --out bench/$which${TAG:+-$TAG}
