#!/bin/bash
cd /work/main
ST=hpn,hpn+peephole,hpn+monitor,hpn+selective,hpn+flexible+serendipity+selective+foresight
run() { # script example levels
  for t in before after; do
    if [ $t = before ]; then PP=/tmp/prof/src_before; else PP=src; fi
    PYTHONPATH=$PP:examples/$2:benchmarks timeout 1500 .venv/bin/python benchmarks/$1.py --levels $3 --strategies $ST --seeds 0-4 --time-limit 10 --out /tmp/ab2/$1_$t.jsonl > /tmp/ab2/$1_$t.log 2>&1
  done
}
run heldout15 ferry clean,x0.2-b0.1
run heldout14 tidy clean,f0.2-drop0.1
run heldout12 greenhouse small-clean,small-f0.2-n0.1
run heldout9 warehouse small-clean,medium-f0.2-frag0.3
run heldout13 mine clean,f0.2-m0.1-fp0.1
echo done > /tmp/ab2/DONE
