#!/usr/bin/env python3
"""Checks a dirt-compare output directory: every file, CSV rows =
configurations, JSON fields against the schema of doc/compare.md, and the
SVG/PNG plots parsed by real readers (XML parser; PNG chunks, CRCs, IHDR and
the decompressed image size).
  compare_check.py DIR SCHEMA_DOC EXPECTED_ROWS"""
import csv, json, os, re, struct, sys, zlib
import xml.etree.ElementTree as ET

d, doc, want = sys.argv[1], sys.argv[2], int(sys.argv[3])
errors = []
def err(m): errors.append(m)

PLOTS = ["memory_vs_resolution", "time_vs_resolution", "memory_vs_triangles",
         "time_vs_triangles", "ratios_per_scene", "agreement_vs_thickness"]
for f in ["table.md", "results.csv", "results.json"] + \
         [p + e for p in PLOTS for e in (".svg", ".png")]:
    if not os.path.isfile(os.path.join(d, f)) or os.path.getsize(os.path.join(d, f)) == 0:
        err("missing or empty: " + f)

# The documented schema: lines "path type [ok]" between the markers.
text = open(doc).read()
m = re.search(r"<!-- schema-begin -->(.*?)<!-- schema-end -->", text, re.S)
fields = []
for line in (m.group(1) if m else "").splitlines():
    line = line.strip().strip("`")
    if not line or line.startswith("```"):
        continue
    parts = line.split()
    fields.append((parts[0], parts[1], len(parts) > 2 and parts[2] == "ok"))
if len(fields) < 20:
    err("schema in %s has only %d fields" % (doc, len(fields)))
TYPES = {"string": str, "number": (int, float), "bool": bool, "array": list,
         "object": dict, "string|null": (str, type(None))}

def lookup(o, path):
    for k in path.split("."):
        if not isinstance(o, dict) or k not in o:
            raise KeyError(path)
        o = o[k]
    return o

j = json.load(open(os.path.join(d, "results.json")))
rows = j.get("configurations", [])
if len(rows) != want:
    err("results.json: %d configurations, want %d" % (len(rows), want))
for path, typ, only_ok in fields:
    targets = [j] if path.startswith("$.") else rows
    p = path[2:] if path.startswith("$.") else path
    for i, r in enumerate(targets):
        if only_ok and r.get("status") != "ok":
            continue
        try:
            v = lookup(r, p)
        except KeyError:
            err("row %d: missing %s" % (i, path)); continue
        if not isinstance(v, TYPES[typ]) or (typ == "number" and isinstance(v, bool)):
            err("row %d: %s is %r, want %s" % (i, path, type(v).__name__, typ))
for i, r in enumerate(rows):
    if r.get("status") != "ok":
        err("row %d failed: %s" % (i, r.get("reason")))
        continue
    for e in ("dirt", "mmrt"):
        f = r[e]["memory"]["formula"]
        if not f["equal"]:
            err("row %d %s: measured %s != formula %s" % (i, e, f["exact_part_measured"],
                                                         f["exact_part_formula"]))
        for p in r[e]["passes"]:
            if p["clock"] != r["environment"]["clock"]:
                err("row %d %s pass %s clock %s" % (i, e, p["name"], p["clock"]))
            if not p["min_ms"] <= p["median_ms"] <= p["max_ms"]:
                err("row %d %s pass %s: min/median/max out of order" % (i, e, p["name"]))

with open(os.path.join(d, "results.csv"), newline="") as f:
    data = list(csv.reader(f))
if len(data) - 1 != want:
    err("results.csv: %d rows, want %d" % (len(data) - 1, want))
if data and any(len(x) != len(data[0]) for x in data):
    err("results.csv: ragged rows")
table = open(os.path.join(d, "table.md")).read()
n_table = sum(1 for l in table.split("## ")[1].splitlines() if l.startswith("| ") and
              not l.startswith("| scene")) if "## " in table else 0
first = table.split("## ")[0]
if sum(1 for l in first.splitlines() if l.startswith("| ") and not l.startswith("| scene")) != want:
    err("table.md: Table 2 rows != %d" % want)

def check_png(path):
    b = open(path, "rb").read()
    if b[:8] != b"\x89PNG\r\n\x1a\n":
        return "bad signature"
    pos, idat, ihdr = 8, b"", None
    while pos < len(b):
        n, typ = struct.unpack(">I4s", b[pos:pos + 8])
        body = b[pos + 8:pos + 8 + n]
        crc = struct.unpack(">I", b[pos + 8 + n:pos + 12 + n])[0]
        if zlib.crc32(typ + body) & 0xffffffff != crc:
            return "bad CRC in " + typ.decode()
        if typ == b"IHDR":
            ihdr = struct.unpack(">IIBBBBB", body)
        elif typ == b"IDAT":
            idat += body
        elif typ == b"IEND":
            break
        pos += 12 + n
    if not ihdr:
        return "no IHDR"
    w, h, depth, ctype = ihdr[:4]
    if w < 100 or h < 100:
        return "tiny image %dx%d" % (w, h)
    ch = {0: 1, 2: 3, 3: 1, 4: 2, 6: 4}[ctype]
    raw = zlib.decompress(idat)
    if ihdr[6] == 0 and len(raw) != h * (1 + (w * ch * depth + 7) // 8):
        return "pixel data %d bytes for %dx%d" % (len(raw), w, h)
    return None

for p in PLOTS:
    png = os.path.join(d, p + ".png")
    if os.path.isfile(png):
        why = check_png(png)
        if why:
            err(p + ".png: " + why)
    svg = os.path.join(d, p + ".svg")
    if os.path.isfile(svg):
        try:
            root = ET.parse(svg).getroot()
            if not root.tag.endswith("svg"):
                err(p + ".svg: root is " + root.tag)
            if not any(e.tag.endswith(("path", "polyline", "line", "use")) for e in root.iter()):
                err(p + ".svg: nothing drawn")
        except ET.ParseError as e:
            err(p + ".svg: " + str(e))

# plot.dat: the per-configuration plot's x is the row number across the
# scene blocks (gnuplot's column 0 restarts in every block, which stacked
# every scene's points on the first ones), labelled with its scene and S.
dat = os.path.join(d, "plot.dat")
if os.path.isfile(dat):
    import shlex
    lines = [shlex.split(l) for l in open(dat) if l.strip() and not l.startswith("#")]
    if any(len(l) != 28 for l in lines):
        err("plot.dat: lines of %s columns, want 28" % sorted({len(l) for l in lines}))
        lines = []
    rows_x = [int(l[-2]) for l in lines]
    if rows_x != list(range(len(lines))):
        err("plot.dat: row numbers %s, want 0..%d" % (rows_x, len(lines) - 1))
    for l in lines:
        if not l[-1].startswith(l[0] + " "):
            err("plot.dat: label %r of a %r row" % (l[-1], l[0]))

for e in errors:
    print("FAIL:", e, file=sys.stderr)
sys.exit(1 if errors else 0)
