#!/usr/bin/env python3
"""usage: json_check.py FILE EXPR...  Each EXPR is a Python expression over
the parsed JSON document `d`; prints the ones that are false (or fail) and
exits 1 if any does. The file must be valid JSON."""
import json
import sys

try:
    with open(sys.argv[1], encoding="utf-8") as f:
        d = json.load(f)
except (OSError, ValueError) as e:
    print("%s: not valid JSON: %s" % (sys.argv[1], e))
    sys.exit(1)
bad = 0
for expr in sys.argv[2:]:
    try:
        ok = eval(expr, {"d": d, "sum": sum, "len": len, "all": all, "isinstance": isinstance,
                         "int": int, "float": float})
    except Exception as e:  # a missing key is a failed check
        ok, expr = False, "%s (%s: %s)" % (expr, type(e).__name__, e)
    if not ok:
        print("%s: false: %s" % (sys.argv[1], expr))
        bad += 1
sys.exit(1 if bad else 0)
