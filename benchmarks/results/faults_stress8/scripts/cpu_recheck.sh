#!/bin/bash
# the after runs that ended at the 30 s wall limit (reached before): again on the after code with the CPU clock
cd /tmp
while read lvl st seed; do
  echo "$lvl $st $seed: $(PYTHONPATH=/tmp/n8after3/src timeout 300 /work/main/.venv/bin/python /tmp/n8/one.py namo "domain1?sigma_per_m=$lvl" $st $seed 300 --cpu 2>&1 | tail -1)"
done <<'LIST'
0.2 hpn 12
0.2 hpn 6
0.2 hpn+foresight 6
0.2 hpn+nodirect 12
0.2 hpn+peephole 12
0.2 hpn+peephole 5
0.2 hpn+peephole+flexible 11
0.2 hpn+peephole+flexible 12
0.2 hpn+peephole+flexible 5
0.2 hpn+refine-flat 12
0.2 hpn+serendipity 12
0.2 online 2
0.2 flat 2
0.15 online 3
LIST
echo DONE
