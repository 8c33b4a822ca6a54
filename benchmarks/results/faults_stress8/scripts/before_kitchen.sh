#!/bin/bash
cd /tmp/n8main
for i in 1 2 3 4 5; do
PYTHONPATH=/tmp/n8main/src timeout 590 /work/main/.venv/bin/python benchmarks/faults.py --stress --domains kitchen --seeds 0-2 --time-limit 60 --jobs 1 --strategies hpn,hpn+flexible,online+reuse+deferred --levels 'failure=0.6,miss=0.5,sigma=0.03,failure=0.5&miss=0.3&sigma=0.03' --store /tmp/n8/before_kitchen.sqlite --out /tmp/n8/before_kitchen_out >> /tmp/n8/before_kitchen.log 2>&1 && break
done
echo DONE >> /tmp/n8/before_kitchen.log
