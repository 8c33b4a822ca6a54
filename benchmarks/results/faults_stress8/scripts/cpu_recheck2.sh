#!/bin/bash
# the other 9 after runs that ended at the 30 s wall limit (reached before): after code, CPU clock, 300 s
cd /tmp
while read lvl st seed; do
  echo "$lvl $st $seed: $(PYTHONPATH=/tmp/n8after3/src timeout 300 /work/main/.venv/bin/python /tmp/n8/one.py namo "domain1?sigma_per_m=$lvl" $st $seed 300 --cpu 2>&1 | tail -1)"
done <<'LIST'
0.15 online+deferred 3
0.15 online+reuse 3
0.15 online+reuse+deferred 3
0.2 online+deferred 2
0.2 online+reuse 2
0.2 online+reuse+deferred 2
0.2 online+reuse 12
0.2 online+reuse+deferred 12
0.2 flat 9
LIST
echo DONE
