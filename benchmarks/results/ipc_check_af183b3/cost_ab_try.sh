#!/bin/bash
# usage: try_ipc.sh COMMIT DIR/PROBLEM...  -> nowplan plan's cost and expansions on /tmp/ipc8 pairs at COMMIT (git archive tree)
c=$1; shift; T=/tmp/measure11/trees/$c; R=/work/wt/wip-measure11; out=""
for dp in "$@"; do d=${IPC:-/tmp/ipc8}/${dp%%/*}; p=${dp##*/}
  r=$(cd $T && PYTHONPATH=$T/src $R/.venv/bin/python -c "import sys; from nowplan.cli import main; sys.exit(main())" plan $d/domain.pddl $d/$p.pddl --json 2>/dev/null | $R/.venv/bin/python -c "import json,sys; d=json.load(sys.stdin); print(f\"{d['cost']}/{d['expanded']}\")")
  out="$out $dp=$r"
done
echo "$c$out"
