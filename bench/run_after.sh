#!/bin/sh
# the after-measurement of the monitor work (issue 14), run from the worktree
cd /work/wt-monitor
MON=hpn,hpn+monitor,hpn+monitor-restore,hpn+monitor-cost,hpn+monitor-goal,hpn+monitor-rule-cost
PYTHONPATH=src /work/main/.venv/bin/python benchmarks/faults.py --domains logistics --strategies $MON --seeds 0-19 \
  --store bench/final_logistics.sqlite --out bench/final_logistics > bench/final_logistics.log 2>&1
PYTHONPATH=src /work/main/.venv/bin/python benchmarks/faults.py --domains marsupial --strategies $MON --seeds 0-19 \
  --store bench/final_marsupial.sqlite --out bench/final_marsupial > bench/final_marsupial.log 2>&1
