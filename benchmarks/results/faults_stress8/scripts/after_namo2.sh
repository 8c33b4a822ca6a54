#!/bin/bash
# second after process: seeds 10-19 (same runs as before_namo.sh), store after2.sqlite
cd /tmp/n8after
for seeds in 10-14 15-19; do
  for i in 1 2 3 4; do
    PYTHONPATH=/tmp/n8after/src timeout 590 /work/main/.venv/bin/python benchmarks/faults.py --stress --domains namo --levels 'sigma_per_m=0.15,sigma_per_m=0.2' --seeds $seeds --time-limit 30 --jobs 1 --store /tmp/n8/after2.sqlite --out /tmp/n8/after2_out >> /tmp/n8/after_namo2.log 2>&1 && break
  done
done
echo DONE >> /tmp/n8/after_namo2.log
