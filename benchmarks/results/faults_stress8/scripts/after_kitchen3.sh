#!/bin/bash
# kitchen sensor-noise levels again at the particle fix (wip-noise8 HEAD, /tmp/n8after3)
cd /tmp/n8after3
for i in 1 2 3 4; do
PYTHONPATH=/tmp/n8after3/src timeout 590 /work/main/.venv/bin/python benchmarks/faults.py --stress --domains kitchen --seeds 0-2 --time-limit 60 --jobs 1 --strategies hpn,hpn+flexible,online+reuse+deferred --levels 'sigma=0.03,failure=0.5&miss=0.3&sigma=0.03' --store /tmp/n8/after_kitchen3.sqlite --out /tmp/n8/after_kitchen3_out >> /tmp/n8/after_kitchen3.log 2>&1 && break
done
echo DONE >> /tmp/n8/after_kitchen3.log
