#!/usr/bin/env python3
"""Checks a dirt-compare output directory: every file, CSV rows =
configurations, JSON fields against the schema of doc/compare.md, the memory
table without repeats, the figures' data files against the rows (facets per
scene and image size, one series per technique and MMRT thickness, min-max
bars, the parity line, the agreement figure only with more than one
thickness), and the SVG/PNG plots parsed by real readers (XML parser; PNG
chunks, CRCs, IHDR and the decompressed image size).
  compare_check.py DIR SCHEMA_DOC EXPECTED_ROWS"""
import csv, json, os, re, struct, sys, zlib
import xml.etree.ElementTree as ET

d, doc, want = sys.argv[1], sys.argv[2], int(sys.argv[3])
errors = []
def err(m): errors.append(m)

PLOTS = ["memory_vs_resolution", "time_vs_resolution", "memory_vs_triangles",
         "time_vs_triangles", "ratios_per_scene", "agreement_vs_thickness"]
for f in ["table.md", "results.csv", "results.json"]:
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

# The figures drawn: those with a series of two points or more.
ok_rows = [r for r in rows if r.get("status") == "ok"]
def size(r): return "%dx%d" % (r["settings"]["width"], r["settings"]["height"])
def pixels(r): return r["settings"]["width"] * r["settings"]["height"]
scenes = list(dict.fromkeys(r["scene"]["name"] for r in ok_rows))
sizes = list(dict.fromkeys(size(r) for r in ok_rows))
def th_key(r):
    """MMRT's setting: its thickness as a fraction of the scene's diagonal
    (a series across scenes keeps it) or "default", and its march."""
    s_ = r["settings"]
    th = "default" if s_["mmrt_thickness_default"] else \
        "%.4g" % (s_["mmrt_thickness"] / r["scene"]["diagonal"])
    return "%s %s %s" % (th, s_["mmrt_march"], s_["mmrt_samples"])
def thicknesses(rs): return sorted({th_key(r) for r in rs})
def lt(r): # the light transport's settings
    s_ = r["settings"]
    return (s_["views"], s_["time"], s_["spp"], s_["bounces"])
def dirt_key(r, memory=False):
    s_ = r["settings"]
    return (s_["dirt_tile_size"], s_["dirt_buckets"]) + (lt(r)[:2] if memory else lt(r))
def mmrt_key(r, memory=False):
    s_ = r["settings"]
    return (s_["mmrt_buckets"],) + (lt(r)[:2] if memory else (th_key(r),) + lt(r))
def of(scene=None, sz=None):
    return [r for r in ok_rows if scene in (None, r["scene"]["name"]) and sz in (None, size(r))]
agree_facets = [(sc, sz) for sc in scenes for sz in sizes
                if len(thicknesses([r for r in of(sc, sz) if "agreement" in r["mmrt"]])) > 1]
drawn = {"memory_vs_resolution": any(len({size(r) for r in of(sc)}) > 1 for sc in scenes),
         "memory_vs_triangles": any(len(of(None, sz)) and len({r["scene"]["path"]
                                    for r in of(None, sz)}) > 1 for sz in sizes),
         "ratios_per_scene": bool(ok_rows), "agreement_vs_thickness": bool(agree_facets)}
drawn["time_vs_resolution"] = drawn["memory_vs_resolution"]
drawn["time_vs_triangles"] = drawn["memory_vs_triangles"]
for p in PLOTS:
    for e in (".svg", ".png", ".dat"):
        f = os.path.join(d, p + e)
        if drawn[p] and (not os.path.isfile(f) or os.path.getsize(f) == 0):
            err("missing or empty: " + p + e)
        if not drawn[p] and os.path.exists(f):
            err("%s%s drawn without a series of two points" % (p, e))

def read_dat(p):
    """{facet: {series: [(x, y, lo, hi)]}} from the block headers."""
    facets, cur = {}, None
    for line in open(os.path.join(d, p + ".dat")):
        if line.startswith("# block\t"):
            _, _, facet, series = line.rstrip("\n").split("\t")
            if series in facets.setdefault(facet, {}):
                err("%s.dat: facet %r has series %r twice" % (p, facet, series))
            cur = facets[facet].setdefault(series, [])
        elif line.strip() and not line.startswith("#"):
            cur.append(tuple(float(v) for v in line.split()))
    return facets

def approx(a, b): return abs(a - b) <= 1e-6 * max(1.0, abs(a), abs(b))
def stat(r, e, q): return tuple(r[e][q][k] for k in ("median_ms", "min_ms", "max_ms"))
QUANT = ("build", "trace", "frame")

def check_series(p, facet, series, rs, xkey, what):
    """A series of `facet`: DIRT's, or MMRT's at ONE thickness; each point
    equals one row's figures (what(row, tech) -> (y, lo, hi)) at that x."""
    tech = "dirt" if series.startswith("DIRT") else "mmrt" if series.startswith("MMRT") else None
    pts = facet_data[facet][series]
    if tech is None:
        err("%s: facet %r: series %r is of no technique" % (p, facet, series)); return None
    if [x for x, _, _, _ in pts] != sorted(x for x, _, _, _ in pts):
        err("%s: facet %r series %r: x not increasing %s" % (p, facet, series, pts))
    th = set()
    for x, y, lo, hi in pts:
        if not lo <= y <= hi:
            err("%s: facet %r series %r: bar [%g, %g] without %g" % (p, facet, series, lo, hi, y))
        match = [r for r in rs if approx(xkey(r), x) and
                 all(approx(a, b) for a, b in zip(what(r, tech), (y, lo, hi)))]
        if not match:
            err("%s: facet %r series %r: point %s is no row's" % (p, facet, series, (x, y, lo, hi)))
        th.add(tuple(sorted({th_key(r) for r in match})))
    return tech, th

for p in ("memory_vs_resolution", "time_vs_resolution", "memory_vs_triangles",
          "time_vs_triangles"):
    if not drawn[p] or not os.path.isfile(os.path.join(d, p + ".dat")):
        continue
    facet_data = read_dat(p)
    by_size = p.endswith("resolution")
    groups = scenes if by_size else sizes
    quants = QUANT if p.startswith("time") else (None,)
    want = {(g, q) for g in groups for q in quants}
    got = set()
    for facet in facet_data:
        g, _, q = facet.partition(": ") if quants[0] else (facet, "", None)
        g = g.split(" (")[0] if by_size else g
        got.add((g, q or None))
    if got != want:
        err("%s: facets %s, want one per %s%s %s" % (p, sorted(facet_data), "scene" if by_size
            else "image size", " and quantity" if quants[0] else "", sorted(want)))
        continue
    for facet, series in facet_data.items():
        g = facet.split(": ")[0]
        q = facet.split(": ")[1] if quants[0] else None
        rs = of(g.split(" (")[0]) if by_size else of(None, g)
        xkey = pixels if by_size else (lambda r: r["scene"]["triangles"])
        if q:
            what = lambda r, e: stat(r, e, q)
        else:
            what = lambda r, e: (r[e]["memory"]["structure_used"] / 1048576.0,) * 3
        techs = {"dirt": 0, "mmrt": 0}
        for name in series:
            got_s = check_series(p, facet, name, rs, xkey, what)
            if not got_s:
                continue
            tech, th = got_s
            techs[tech] += 1
            # times: every point of an MMRT series at one thickness
            if q and tech == "mmrt" and not set.intersection(*[set(t) for t in th] or [set()]):
                err("%s: facet %r series %r joins thicknesses %s" % (p, facet, name, th))
            # a point per image size (per scene in the triangles' figures)
            pk = {size(r) if by_size else r["scene"]["path"] for r in rs}
            if len(series[name]) != len(pk):
                err("%s: facet %r series %r: %d points, want %d" % (p, facet, name,
                    len(series[name]), len(pk)))
        # a series per setting; memory depends on neither MMRT's thickness
        # nor its march, nor spp and bounces
        want = {"dirt": len({dirt_key(r, not q) for r in rs}),
                "mmrt": len({mmrt_key(r, not q) for r in rs})}
        if techs != want:
            err("%s: facet %r: series %s, want %s" % (p, facet, techs, want))
    if p.startswith("time") and any(r["settings"]["repeat"] > 1 for r in ok_rows) and \
            not any(lo < hi for f in facet_data.values()
                                        for s_ in f.values() for _, _, lo, hi in s_):
        err(p + ": no min-max bar anywhere")

if drawn["ratios_per_scene"] and os.path.isfile(os.path.join(d, "ratios_per_scene.dat")):
    p = "ratios_per_scene"
    facet_data = read_dat(p)
    want = {(sc, sz) for sc in scenes for sz in sizes if of(sc, sz)}
    got = {(f.split(" (")[0], f.rsplit(", ", 1)[-1]) for f in facet_data}
    if got != want or len(facet_data) != len(want):
        err("%s: facets %s, want one per scene and size" % (p, sorted(facet_data)))
    CAT = ("records", "memory", "build", "trace", "frame")
    for facet, series in facet_data.items():
        rs = of(facet.split(" (")[0], facet.rsplit(", ", 1)[-1])
        parity = [n for n in series if n.startswith("parity")]
        if len(parity) != 1 or any(y != 1 for _, y, _, _ in series[parity[0]]) or \
                len(series[parity[0]]) < 2:
            err("%s: facet %r: no parity line at 1 (%s)" % (p, facet, parity))
        others = [n for n in series if not n.startswith("parity")]
        pairs = len({(dirt_key(r), mmrt_key(r)) for r in rs})
        if len(others) != pairs:
            err("%s: facet %r: %d series, want one per DIRT and MMRT setting (%d)" % (
                p, facet, len(others), pairs))
        for n in others:
            pts = series[n]
            if [x for x, _, _, _ in pts] != [1, 2, 3, 4, 5]:
                err("%s: facet %r series %r: x %s" % (p, facet, n, [x for x, _, _, _ in pts]))
                continue
            # one row's ratios, bars from its repeats' extremes
            match = [r for r in rs if all(approx(r["ratios"][c], pt[1]) for c, pt in zip(CAT, pts))]
            if len({(dirt_key(r), mmrt_key(r)) for r in match}) != 1:
                err("%s: facet %r series %r: the ratios of no single thickness" % (p, facet, n))
                continue
            r = match[0]
            for c, (x, y, lo, hi) in zip(CAT, pts):
                if c in QUANT:
                    w = (r["dirt"][c]["min_ms"] / r["mmrt"][c]["max_ms"],
                         r["dirt"][c]["max_ms"] / r["mmrt"][c]["min_ms"])
                    if not (approx(lo, w[0]) and approx(hi, w[1]) and lo <= y <= hi):
                        err("%s: facet %r series %r %s: bar [%g, %g], want %s" % (p, facet, n, c,
                            lo, hi, w))

if drawn["agreement_vs_thickness"] and \
        os.path.isfile(os.path.join(d, "agreement_vs_thickness.dat")):
    p = "agreement_vs_thickness"
    facet_data = read_dat(p)
    got = {(f.split(" (")[0], f.rsplit(", ", 1)[-1]) for f in facet_data}
    if got != set(agree_facets):
        err("%s: facets %s, want those of two thicknesses or more %s" % (p, sorted(facet_data),
            agree_facets))
    for facet, series in facet_data.items():
        rs = of(facet.split(" (")[0], facet.rsplit(", ", 1)[-1])
        if len(series) != 5 or any(len(v) != len(thicknesses(rs)) for v in series.values()):
            err("%s: facet %r: series %s, want 5 (ray types) of %d points" % (p, facet,
                {k: len(v) for k, v in series.items()}, len(thicknesses(rs))))

# The memory table: one line per structure, no repeats.
mem = table.split("## Memory")[1].split("\n## ")[0] if "## Memory" in table else ""
lines = [l for l in mem.splitlines() if l.startswith("| ") and not l.startswith("| scene")]
structures = set()
for r in ok_rows:
    s_ = r["settings"]
    base = (r["scene"]["path"], size(r), s_["views"], s_["time"])
    structures.add(base + ("dirt", s_["dirt_tile_size"], s_["dirt_buckets"], s_["dirt_large"]))
    structures.add(base + ("mmrt", s_["mmrt_buckets"]))
if len(lines) != len(set(lines)) or len(lines) != len(structures):
    err("table.md memory: %d lines (%d distinct), want one per structure (%d)" % (
        len(lines), len(set(lines)), len(structures)))

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

for e in errors:
    print("FAIL:", e, file=sys.stderr)
sys.exit(1 if errors else 0)
