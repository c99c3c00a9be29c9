#!/usr/bin/env python3
"""Fails when a source file includes a header of a layer it may not use.

usage: check_layers.py SRC_DIR STAMP

Each folder of src/ is one layer; LAYERS lists what each may use (the
layers below it; the techniques dirt, mmrt and raster are siblings and do
not see each other). A public header (src/include/dirt/X.h) belongs to the
layer that implements it (PUBLIC). The programs (app) include public
headers only. Headers of glsl/common/ (shared C/GLSL
layouts) are open to every layer. On success the stamp file is written; on
a violation every offending line is printed and the exit status is 1.
"""
import os
import re
import sys

BELOW_TECHNIQUES = ["core", "io", "scene", "graph", "gl", "views"]
LAYERS = {
    "core": [],
    "io": ["core"],
    "scene": ["core"],
    "graph": ["core"],
    "gl": ["core", "graph"],
    "views": ["core", "scene", "graph", "gl"],
    "dirt": BELOW_TECHNIQUES,
    "mmrt": BELOW_TECHNIQUES,
    "raster": BELOW_TECHNIQUES,
    "integrator": BELOW_TECHNIQUES,
    "ref": ["core", "io", "scene", "integrator"],
    "session": BELOW_TECHNIQUES + ["dirt", "mmrt", "raster", "integrator", "ref"],
    "app": BELOW_TECHNIQUES + ["dirt", "mmrt", "raster", "integrator", "ref", "session"],
}
# Public header -> the layer that implements it.
PUBLIC = {
    "clock.h": "core", "log.h": "core", "stats.h": "core", "ray.h": "core", "vec.h": "core",
    "version.h": "core", "input.h": "core",
    "file.h": "io", "image.h": "io",
    "scene.h": "scene",
    "gpu.h": "gl", "window.h": "gl", "ui.h": "gl",
    "views.h": "views", "tracer.h": "views",
    "ads.h": "dirt", "mmrt.h": "mmrt", "raster.h": "raster",
    "integrator.h": "integrator", "gpu_tables.h": "integrator", "pathtrace.h": "integrator",
    "ref.h": "ref", "raytypes.h": "ref",
    "session.h": "session",
}
# Folders whose internal headers (FOLDER/x.h) other layers may include.
INTERNAL = set(LAYERS)
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')


def owner(header, here):
    """Layer of an included header, None when any layer may include it."""
    parts = header.split("/")
    if parts[0] == "common":
        return None
    if parts[0] == "dirt" and len(parts) == 2:
        if parts[1] in PUBLIC:
            return PUBLIC[parts[1]]
        return "dirt"  # internal headers of src/dirt/ (ads_internal.h, ...)
    if parts[0] in INTERNAL and len(parts) == 2:
        return parts[0]
    if len(parts) == 1:
        return here  # a header beside the file
    return None


def layer_of(path, src):
    rel = os.path.relpath(path, src).split(os.sep)
    if rel[0] == "include":
        return PUBLIC.get(rel[-1])
    return rel[0] if rel[0] in LAYERS else None


def main():
    src, stamp = sys.argv[1], sys.argv[2]
    errors = []
    missing = []
    for root, _, files in os.walk(src):
        for name in sorted(files):
            if not name.endswith((".c", ".h", ".cpp")):
                continue
            path = os.path.join(root, name)
            here = layer_of(path, src)
            if here is None:
                if os.path.relpath(root, src).startswith("include"):
                    missing.append(path)
                continue
            allowed = set(LAYERS[here]) | {here}
            with open(path, encoding="utf-8") as f:
                for no, line in enumerate(f, 1):
                    m = INCLUDE.match(line)
                    if not m:
                        continue
                    o = owner(m.group(1), here)
                    inc = m.group(1)
                    if here == "app" and o not in (None, "app") and not (
                            inc.startswith("dirt/") and inc[5:] in PUBLIC):
                        errors.append("%s:%d: the programs use public headers only, not \"%s\""
                                      % (os.path.relpath(path, src), no, inc))
                    elif o is not None and o not in allowed:
                        errors.append("%s:%d: layer '%s' includes \"%s\" of layer '%s'"
                                      % (os.path.relpath(path, src), no, here, m.group(1), o))
    for path in missing:
        errors.append("%s: public header not assigned to a layer (PUBLIC in %s)"
                      % (path, sys.argv[0]))
    if errors:
        print("\n".join(errors), file=sys.stderr)
        print("layer check failed: see doc/architecture.md, Layers", file=sys.stderr)
        return 1
    with open(stamp, "w", encoding="utf-8") as f:
        f.write("ok\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
