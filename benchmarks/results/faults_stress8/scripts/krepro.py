import sys, json
from nowplan.domains.kitchen.repro import trial
tasks = sys.argv[1].split(","); idx = [int(x) for x in sys.argv[2].split(",")]; variant = sys.argv[3]; cap = float(sys.argv[4])
easy = len(sys.argv) > 5 and sys.argv[5] == "easy"
for t in tasks:
    for i in idx:
        r = trial(t, i, variant, cap, easy=easy)
        print(json.dumps({k: (round(v, 2) if isinstance(v, float) else v) for k, v in r.items()}), flush=True)
