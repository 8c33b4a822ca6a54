#!/bin/bash
# before = main at 19aa193 (git archive in /tmp/n8main); NAMO sigma 0.15/0.2, seeds 0-19, every strategy
cd /tmp/n8main
for seeds in 0-4 5-9 10-14 15-19; do
  for i in 1 2 3; do
    PYTHONPATH=/tmp/n8main/src timeout 590 /work/main/.venv/bin/python benchmarks/faults.py --stress --domains namo --levels 'sigma_per_m=0.15,sigma_per_m=0.2' --seeds $seeds --time-limit 30 --jobs 1 --store /tmp/n8/before.sqlite --out /tmp/n8/before_out >> /tmp/n8/before_namo.log 2>&1 && break
  done
done
echo DONE >> /tmp/n8/before_namo.log
