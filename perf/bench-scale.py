#!/usr/bin/env python3
"""How time and memory grow with triangles and with pixels, for every engine
(issue 24, item 5): dirt-render on a family of generated closed rooms full
of objects (perf/make-scale-scene.py) from 10^4 to 10^7 triangles at one
image size, and on one room at images from 0.1 to 8 megapixels. Each run
renders --frames frames (default 1; 2 measures the steady second frame: the
scene is static, the first frame also sizes the buffers) of one sample
with the path tracer's defaults (4 bounces, seed 1) for the path-tracing
engines (dirt: DIRT with the device's default build; dirt-raster and
dirt-compute: each build; mmrt; embree) and the preview for raster.

Per run it keeps: the last frame's time (the sum of the passes dirt-render
--stats reports, with the clock that measured them: the CPU clock around
glFinish on a software renderer, GPU timer queries on a GPU), the first
frame's, the whole process's wall time (load and setup included) and peak
resident memory (the GPU's memory is the process's on a software renderer),
the engine's own GPU bytes (--stats bytes_allocated) and, for DIRT and
MMRT, the relative MSE of the last frame against Embree's with the same
seed. DIRT's must be below --max-rel-mse (default 1e-2: at one sample a
path that meets a shared edge on the other triangle goes elsewhere, so
equal hits still give about 1e-3 with millions of triangles; a broken
trace gives 0.1 and more); MMRT's is approximate and only recorded. Runs
are interleaved: every round runs every configuration and engine once in
turn, so load changes hit all alike; the figures are the minimum over the
rounds (--repeat).

    perf/bench-scale.py OUT [--render build/src/app/dirt-render]
        [--triangles 1e4,1e5,1e6,1e7] [--fixed-res 320x240]
        [--res 368x276,816x612,1632x1224,3264x2448] [--fixed-triangles 1e4]
        [--engines dirt,mmrt,embree,raster] [--frames 1] [--repeat 1]
        [--max-mp mmrt=2] [--timeout 1800] [--max-rel-mse 1e-2] [--quick]
        [--scenes DIR]

The default grid (0.08 MP for the triangle sweep; 0.1, 0.5, 2 and 8 MP of
a room of 10^4 triangles, MMRT up to 2 MP: --max-mp) takes about 10
minutes on llvmpipe on 2 cores (MMRT alone takes 3 minutes at 2 MP there;
--max-mp '' runs it at 8 MP too, for an hour or more); on a GPU use larger
images (perf/gpu-check.sh). Runs past --max-mp are "skipped" in the
results, not failures. OUT gets results.json
(every run, with the command, machine and device), results.csv and
table.md (the minimum per configuration and engine, engines side by
side), plot.dat, plots.gp and time_vs_triangles, memory_vs_triangles,
time_vs_megapixels and memory_vs_megapixels as PNG and SVG (gnuplot). The
scenes are written to --scenes (default OUT/scenes; made once, reused;
10^7 triangles is a 240 MB file): keep them out of the repository.
--quick: 10^4 and 3 x 10^4 triangles at 160x120 and images of 0.02 and
0.08 megapixels (a check of the script, or a dry run of perf/gpu-check.sh).
Exit status: 0 when every run succeeded and agreed, 1 otherwise (the
failures are in the results), 2 on bad arguments.
"""
import argparse
import csv
import json
import math
import os
import platform
import subprocess
import sys
import tempfile
import time

ENGINES = ("dirt", "dirt-raster", "dirt-compute", "mmrt", "embree", "raster")
DEFAULT_ENGINES = "dirt,mmrt,embree,raster"
# dirt-render's options per engine: dirt is DIRT with the build the device
# gets by default (--build auto), dirt-raster and dirt-compute each build
ENGINE_ARGS = {"dirt": ["--engine", "dirt"],
               "dirt-raster": ["--engine", "dirt", "--build", "raster"],
               "dirt-compute": ["--engine", "dirt", "--build", "compute"],
               "mmrt": ["--engine", "mmrt"], "embree": ["--engine", "embree"],
               "raster": ["--engine", "raster"]}


def parse_count(s):
    return int(float(s))


def make_scenes(counts, scene_dir, root):
    os.makedirs(scene_dir, exist_ok=True)
    paths = {}
    for n in counts:
        p = os.path.join(scene_dir, "room_%d.glb" % n)
        if not os.path.exists(p):
            r = subprocess.run([sys.executable, os.path.join(root, "perf", "make-scale-scene.py"),
                                p, str(n)], stdout=subprocess.DEVNULL)
            if r.returncode != 0:
                return None  # the generator said why
        paths[n] = p
    return paths


def run_one(render, scene, w, h, engine, ref, timeout, tmp, frames):
    """One dirt-render process: `frames` frames of one sample. Returns a dict."""
    tag = "%s_%dx%d_%s" % (os.path.basename(scene).split(".")[0], w, h, engine)
    out = os.path.join(tmp, tag + "_#.exr")
    stats, log = os.path.join(tmp, tag + ".json"), os.path.join(tmp, tag + ".jsonl")
    for p in (stats, log):
        if os.path.exists(p):
            os.remove(p)
    cmd = [render, scene, "-o", out, "-W", str(w), "-H", str(h), "--spp", "1",
           "--frames", "0:%d" % (frames - 1)] + ENGINE_ARGS[engine] + [
           "--seed", "1", "--stats", stats, "--log", log, "--max-scene-memory", "16G", "-q"]
    if ref:
        cmd += ["--mse-reference", ref]
    rec = {"engine": engine, "scene": scene, "width": w, "height": h, "cmd": " ".join(cmd)}
    t0 = time.monotonic()
    with open(os.path.join(tmp, tag + ".err"), "w+") as err:
        p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=err)
        deadline = t0 + timeout
        while True:
            pid, status, usage = os.wait4(p.pid, os.WNOHANG)
            if pid:
                break
            if time.monotonic() > deadline:
                p.kill()
                pid, status, usage = os.wait4(p.pid, 0)
                rec["timed_out"] = True
                break
            time.sleep(0.05)
        err.seek(0)
        errors = [l.strip() for l in err if "error" in l]
    rec["wall_s"] = time.monotonic() - t0
    rec["peak_rss_mb"] = usage.ru_maxrss / 1024.0  # kilobytes on Linux
    code = os.waitstatus_to_exitcode(status)
    rec["exit"] = code
    if code != 0 or not os.path.exists(stats):
        rec["status"] = "failed"
        rec["reason"] = ("timed out after %d s" % timeout if rec.get("timed_out")
                         else (errors[-1] if errors else "exit %d" % code))
        return rec
    with open(stats) as f:
        st = json.load(f)
    frames = st["frames"]
    steady, first = frames[-1], frames[0]

    def passes_ms(fr):
        return sum(p["ms"] for p in fr.get("passes", []) if p["ms"] >= 0)

    rec.update(status="ok", frame_ms=passes_ms(steady), first_frame_ms=passes_ms(first),
               clock=sorted(set(p["clock"] for p in steady.get("passes", []))),
               gpu_mb=steady.get("bytes_allocated", 0) / 1e6, rays=steady.get("rays", 0),
               aborted=steady.get("aborted_rays", 0), triangles=None,
               device=st.get("device", ""))
    if ref and os.path.exists(log):
        with open(log) as f:
            lines = [json.loads(l) for l in f if l.strip()]
        mses = [l["rel_mse"] for l in lines if "rel_mse" in l]
        if mses:
            rec["rel_mse"] = mses[-1]
    return rec


def configs(a):
    out = []
    for n in a.triangles:
        out.append(("triangles", n, a.fixed_res))
    for r in a.res:
        out.append(("pixels", a.fixed_triangles, r))
    seen, uniq = set(), []
    for c in out:
        key = (c[1], c[2])
        if key not in seen:
            seen.add(key)
            uniq.append(c)
    return uniq


def write_outputs(outdir, runs, a, scenes_tris):
    best = {}
    for r in runs:
        if r["status"] != "ok":
            continue
        key = (r["triangles"], r["width"], r["height"], r["engine"])
        b = best.get(key)
        if b is None:
            best[key] = dict(r)
        else:  # minimum over the rounds, each figure on its own
            for k in ("frame_ms", "first_frame_ms", "wall_s", "peak_rss_mb", "gpu_mb"):
                b[k] = min(b[k], r[k])
    failed = {(r["triangles"], r["width"], r["height"], r["engine"]): r for r in runs
              if r["status"] != "ok"}
    engines = [e for e in ENGINES if e in a.engines]
    keys = sorted({(k[0], k[1], k[2]) for k in list(best) + list(failed)},
                  key=lambda k: (k[0], k[1] * k[2]))
    with open(os.path.join(outdir, "results.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["triangles", "width", "height", "megapixels", "engine", "status",
                    "frame_ms", "first_frame_ms", "wall_s", "peak_rss_mb", "gpu_mb",
                    "rel_mse_vs_embree", "clock", "reason"])
        for k in keys:
            for e in engines:
                r = best.get(k + (e,)) or failed.get(k + (e,))
                if not r:
                    continue
                ok = r["status"] == "ok"
                w.writerow([k[0], k[1], k[2], "%.3f" % (k[1] * k[2] / 1e6), e, r["status"],
                            "%.1f" % r["frame_ms"] if ok else "",
                            "%.1f" % r["first_frame_ms"] if ok else "",
                            "%.1f" % r["wall_s"] if "wall_s" in r else "",
                            "%.0f" % r["peak_rss_mb"] if "peak_rss_mb" in r else "",
                            "%.1f" % r["gpu_mb"] if ok else "",
                            "%.3g" % r["rel_mse"] if "rel_mse" in r else "",
                            "+".join(r.get("clock", [])), r.get("reason", "")])
    # table.md: one row per configuration, the engines side by side
    with open(os.path.join(outdir, "table.md"), "w") as f:
        f.write("| triangles | image | MP | " + " | ".join(
            "%s frame ms | %s peak MB" % (e, e) for e in engines) + " | DIRT relMSE vs Embree |\n")
        f.write("|---|---|---|" + "---|---|" * len(engines) + "---|\n")
        for k in keys:
            cells = []
            rel = ""
            for e in engines:
                r = best.get(k + (e,))
                if r:
                    cells += ["%.0f" % r["frame_ms"], "%.0f" % r["peak_rss_mb"]]
                    if e.startswith("dirt") and "rel_mse" in r and not rel:
                        rel = "%.2g" % r["rel_mse"]
                elif k + (e,) in failed:
                    cells += [failed[k + (e,)]["status"], ""]
                else:
                    cells += ["", ""]
            f.write("| %d | %dx%d | %.2f | %s | %s |\n" % (k[0], k[1], k[2], k[1] * k[2] / 1e6,
                                                         " | ".join(cells), rel))
    # plot.dat: block 0 = the triangle sweep, block 1 = the pixel sweep
    cols = ["x"] + ["%s_%s" % (e, m) for e in engines for m in ("ms", "mb")]
    with open(os.path.join(outdir, "plot.dat"), "w") as f:
        for block, (xs, fixed) in enumerate(
                (([(n, a.fixed_res) for n in a.triangles], "triangles"),
                 ([(a.fixed_triangles, r) for r in a.res], "pixels"))):
            f.write("# %s sweep: %s\n" % (fixed, " ".join(cols)))
            for n, (w, h) in xs:
                tris = scenes_tris.get(n, -1)
                row = [str(tris if fixed == "triangles" else w * h / 1e6)]
                for e in engines:
                    r = best.get((tris, w, h, e))
                    row += ["%.3f" % r["frame_ms"] if r else "NaN",
                            "%.1f" % r["peak_rss_mb"] if r else "NaN"]
                f.write(" ".join(row) + "\n")
            f.write("\n\n")
    gp = ["D = '%s/plot.dat'" % outdir, "set key outside right", "set grid",
          "set datafile missing 'NaN'", "set logscale xy"]
    plots = [("time_vs_triangles", 0, "triangles",
              "%s frame ms (%s)" % (a.frame_word, a.fixed_res_s),
              "ms"),
             ("memory_vs_triangles", 0, "triangles", "peak resident MB (%s)" % a.fixed_res_s,
              "mb"),
             ("time_vs_megapixels", 1, "megapixels",
              "%s frame ms (%d triangles)" % (a.frame_word, a.fixed_triangles), "ms"),
             ("memory_vs_megapixels", 1, "megapixels",
              "peak resident MB (%d triangles)" % a.fixed_triangles, "mb")]
    for name, block, xl, yl, what in plots:
        for term, ext in (("svg", "svg"), ("pngcairo", "png")):
            gp += ["set terminal %s noenhanced size 800,500" % term,
                   "set output '%s/%s.%s'" % (outdir, name, ext),
                   "set title '%s'" % name.replace("_", " "), "set xlabel '%s'" % xl,
                   "set ylabel '%s'" % yl,
                   "plot " + ", ".join("D index %d u 1:%d w lp t '%s'" % (
                       block, 2 + 2 * i + (0 if what == "ms" else 1), e)
                       for i, e in enumerate(engines)),
                   "set output"]
    with open(os.path.join(outdir, "plots.gp"), "w") as f:
        f.write("\n".join(gp) + "\n")
    r = subprocess.run(["gnuplot", os.path.join(outdir, "plots.gp")], capture_output=True,
                       text=True)
    if r.returncode != 0:
        print("bench-scale: gnuplot failed: %s" % r.stderr.strip()[-300:], file=sys.stderr)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out")
    ap.add_argument("--render", default="build/src/app/dirt-render")
    ap.add_argument("--triangles", default="1e4,1e5,1e6,1e7")
    ap.add_argument("--fixed-res", default="320x240")
    ap.add_argument("--res", default="368x276,816x612,1632x1224,3264x2448")
    ap.add_argument("--fixed-triangles", default="1e4")
    ap.add_argument("--engines", default=DEFAULT_ENGINES)
    ap.add_argument("--frames", type=int, default=1, choices=(1, 2))
    ap.add_argument("--max-mp", default="mmrt=2",
                    help="ENGINE=MP,...: images past MP megapixels are skipped for ENGINE "
                    "(default mmrt=2: MMRT takes 3 minutes at 2 MP on llvmpipe; '' for none)")
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--timeout", type=int, default=1800, help="seconds a run may take")
    ap.add_argument("--max-rel-mse", type=float, default=1e-2,
                    help="DIRT's last frame against Embree's (default 1e-2)")
    ap.add_argument("--scenes")
    ap.add_argument("--quick", action="store_true")
    a = ap.parse_args()
    a.frame_word = "steady (2nd)" if a.frames == 2 else "first"
    if a.quick:
        a.triangles, a.fixed_res, a.res, a.fixed_triangles, a.repeat = \
            "1e4,3e4", "160x120", "160x120,320x240", "1e4", 1
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    try:
        a.triangles = [parse_count(x) for x in a.triangles.split(",")]
        a.fixed_triangles = parse_count(a.fixed_triangles)
        a.fixed_res_s = a.fixed_res
        a.fixed_res = tuple(int(v) for v in a.fixed_res.split("x"))
        a.res = [tuple(int(v) for v in r.split("x")) for r in a.res.split(",")]
        a.engines = [e for e in a.engines.split(",") if e]
        a.max_mp = {kv.split("=")[0]: float(kv.split("=")[1])
                    for kv in a.max_mp.split(",") if kv}
    except (ValueError, IndexError) as e:
        print("bench-scale: bad list: %s" % e, file=sys.stderr)
        return 2
    bad = [e for e in a.engines if e not in ENGINES]
    if bad or not os.access(a.render, os.X_OK):
        print("bench-scale: unknown engine %s (known: %s)" % (bad, ",".join(ENGINES)) if bad else
              "bench-scale: %s is not a program (build first, or --render)" % a.render,
              file=sys.stderr)
        return 2
    os.makedirs(a.out, exist_ok=True)
    scenes = make_scenes(sorted(set(a.triangles + [a.fixed_triangles])),
                         a.scenes or os.path.join(a.out, "scenes"), root)
    if scenes is None:
        print("bench-scale: cannot make the scenes (see above)", file=sys.stderr)
        return 1
    cfgs = configs(a)
    # Embree first: its image is the others' reference
    order = (["embree"] if "embree" in a.engines else []) + \
        [e for e in ENGINES if e in a.engines and e != "embree"]
    runs, ok = [], True
    tris_of = {}
    with tempfile.TemporaryDirectory() as tmp:
        for rnd in range(a.repeat):
            for sweep, n, (w, h) in cfgs:
                ref = None
                for e in order:
                    if w * h / 1e6 > a.max_mp.get(e, float("inf")) * 1.001:
                        if n not in tris_of:
                            tris_of[n] = scene_triangles(a.render, scenes[n])
                        runs.append({"engine": e, "width": w, "height": h, "round": rnd,
                                     "sweep": sweep, "triangles": tris_of[n],
                                     "status": "skipped", "reason": "past --max-mp %s=%g" % (
                                         e, a.max_mp[e])})
                        print("round %d: %8d triangles %9s %-6s skipped (--max-mp)" % (
                            rnd + 1, tris_of[n], "%dx%d" % (w, h), e), flush=True)
                        continue
                    r = run_one(a.render, scenes[n], w, h, e,
                                None if e in ("embree", "raster") else ref, a.timeout, tmp,
                                a.frames)
                    r["round"] = rnd
                    r["sweep"] = sweep
                    # the actual triangle count: from the generator's file name
                    # and make-scale-scene's count (read once per scene)
                    if n not in tris_of:
                        tris_of[n] = scene_triangles(a.render, scenes[n])
                    r["triangles"] = tris_of[n]
                    if e == "embree" and r["status"] == "ok":
                        base = os.path.basename(scenes[n]).split(".")[0]
                        ref = os.path.join(tmp, "%s_%dx%d_embree_#.exr" % (base, w, h))
                    if e.startswith("dirt") and r["status"] == "ok" and "rel_mse" in r and \
                            not r["rel_mse"] <= a.max_rel_mse:
                        r["status"] = "disagrees"
                        r["reason"] = "relative MSE %.3g against Embree" % r["rel_mse"]
                    if r["status"] not in ("ok", "skipped"):
                        ok = False
                    runs.append(r)
                    print("round %d: %8d triangles %9s %-6s %s" % (
                        rnd + 1, r["triangles"], "%dx%d" % (w, h), e,
                        "%8.0f ms %6.0f MB" % (r["frame_ms"], r["peak_rss_mb"])
                        if r["status"] == "ok" else r["status"] + ": " + r.get("reason", "")),
                        flush=True)
    meta = {"machine": platform.node(), "cpus": os.cpu_count(), "render": a.render,
            "command": " ".join(sys.argv), "device": next((r["device"] for r in runs
                                                           if r.get("device") and
                                                           r["engine"] != "embree"), ""),
            "date": time.strftime("%Y-%m-%dT%H:%M:%S"), "runs": runs}
    with open(os.path.join(a.out, "results.json"), "w") as f:
        json.dump(meta, f, indent=1)
    write_outputs(a.out, runs, a, tris_of)
    print("bench-scale: %d runs, %s; see %s/table.md" % (
        len(runs), "all succeeded" if ok else "some failed", a.out))
    return 0 if ok else 1


def scene_triangles(render, scene):
    r = subprocess.run([render, "--info", scene, "--max-scene-memory", "16G"],
                       capture_output=True, text=True)
    for line in r.stdout.splitlines():
        if line.startswith("triangles"):
            return int(line.split()[1])
    return -1


if __name__ == "__main__":
    sys.exit(main())
