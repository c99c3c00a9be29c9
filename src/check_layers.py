#!/usr/bin/env python3
"""Fails when a source file includes a header of a layer it may not use.

usage: check_layers.py SRC_DIR STAMP

Each folder of src/ is one layer; LAYERS lists what each may use (the
layers below it; the techniques dirt, mmrt and raster are siblings and do
not see each other). The consumer API, the headers installed under
include/dirt/ (src/include/dirt/X.h), belongs to the layers that implement
it (PUBLIC); every other header is internal and sits beside its code
(src/LAYER/x.h, included as "LAYER/x.h"; those of src/dirt/ as
"dirt/x.h", so no internal header of src/dirt/ may share a consumer
header's name). The programs (app) include consumer headers, their own
headers and, for the viewer, which links the static layers (the window and
its panels are not consumer API), the internal headers in VIEWER. Headers
of glsl/common/ (shared C/GLSL layouts) are open to every layer but not to
the consumer headers, which are self-contained: they include consumer
headers and the C library only. On success the stamp file is written; on a
violation every offending line is printed and the exit status is 1.
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
# Consumer header -> the layer that implements it.
PUBLIC = {
    "api.h": "core", "clock.h": "core", "log.h": "core", "stats.h": "core",
    "types.h": "core", "version.h": "core", "input.h": "core",
    "file.h": "io", "image.h": "io",
    "scene.h": "scene",
    "gpu.h": "gl",
    "env.h": "integrator",
    "session.h": "session",
}
# Internal headers the viewer (dirt-view) may include besides the consumer API.
VIEWER = {"gl/window.h", "gl/ui.h", "core/vec.h"}
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
            consumer = os.path.relpath(root, src).startswith("include")
            if here == "dirt" and not consumer and name in PUBLIC:
                errors.append("%s: an internal header of src/dirt/ named like the consumer "
                              "header dirt/%s" % (os.path.relpath(path, src), name))
            with open(path, encoding="utf-8") as f:
                for no, line in enumerate(f, 1):
                    m = INCLUDE.match(line)
                    if not m:
                        continue
                    o = owner(m.group(1), here)
                    inc = m.group(1)
                    if consumer and not (inc.startswith("dirt/") and inc[5:] in PUBLIC):
                        errors.append("%s:%d: a consumer header includes consumer headers "
                                      "only, not \"%s\"" % (os.path.relpath(path, src), no, inc))
                    elif here == "app" and o not in (None, "app") and not (
                            inc.startswith("dirt/") and inc[5:] in PUBLIC) and inc not in VIEWER:
                        errors.append("%s:%d: the programs use the consumer API only (and the "
                                      "viewer %s), not \"%s\""
                                      % (os.path.relpath(path, src), no, ", ".join(sorted(VIEWER)),
                                         inc))
                    elif here == "app" and o is None and inc.startswith("common/"):
                        errors.append("%s:%d: the programs use the consumer API only, not \"%s\""
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
