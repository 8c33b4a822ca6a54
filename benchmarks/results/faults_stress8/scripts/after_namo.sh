#!/bin/bash
# after = wip-noise8 at 0a1afe8 (git archive in /tmp/n8after); same runs as before_namo.sh
cd /tmp/n8after
for seeds in 0-4 5-9 10-14 15-19; do
  for i in 1 2 3 4; do
    PYTHONPATH=/tmp/n8after/src timeout 590 /work/main/.venv/bin/python benchmarks/faults.py --stress --domains namo --levels 'sigma_per_m=0.15,sigma_per_m=0.2' --seeds $seeds --time-limit 30 --jobs 1 --store /tmp/n8/after.sqlite --out /tmp/n8/after_out >> /tmp/n8/after_namo.log 2>&1 && break
  done
done
echo DONE >> /tmp/n8/after_namo.log
