#!/bin/bash
# usage: try.sh COMMIT -> prints the cost of a few classical instances at COMMIT (git archive + this tree's kernel .so)
set -e
c=$1; T=/tmp/measure11/trees/$c
R=/work/wt/wip-measure11
if [ ! -d $T ]; then mkdir -p $T; git -C $R archive $c | tar -x -C $T; cp $R/src/nowplan/planning/_kernel.cpython-311-x86_64-linux-gnu.so $T/src/nowplan/planning/; fi
out=""
for d in ${INST:-barman:p01 floortile:p04 visitall:p04 rovers:p04 zenotravel:p05}; do dom=${d%%:*}; p=${d##*:}
  cost=$(cd $T && PYTHONPATH=$T/src $R/.venv/bin/python -c "import sys; from nowplan.cli import main; sys.exit(main())" plan $R/benchmarks/classical/$dom/domain.pddl $R/benchmarks/classical/$dom/$p.pddl --json 2>/dev/null | $R/.venv/bin/python -c "import json,sys; print(json.load(sys.stdin)['cost'])")
  out="$out $d=$cost"
done
echo "$c$out"
