#!/usr/bin/env python3
"""Writes a closed room full of objects as one binary glTF (.glb), for the
scaling benchmark (perf/bench-scale.py) and the large-scene checks: the
4 x 3 x 5 room of perf/make-room.py (white floor, ceiling, back and front
walls, red and green side walls, an emissive ceiling panel, a camera inside
looking at the back wall) holding OBJECTS objects (default: about
sqrt(TRIANGLES) / 3, at least 8) of about TRIANGLES triangles in all: bumpy
spheres, tori and rounded boxes, each tessellated to its share, scattered
with a fixed seed through the back of the room (random sizes, rotations and diffuse,
glossy or metallic materials) in front of the camera.

Each object is its own mesh (no shared meshes: the loader would expand
instances anyway, but a file of distinct meshes is what a scanned or CAD
scene is). The file holds positions, normals and 32-bit indices, about
16 bytes per triangle, so 10 M triangles make a file of about 160 MB: keep
such files out of the repository (write them under /tmp or build/).

With --normal-map every mesh also gets texture coordinates (no TANGENT:
the loader generates the tangents) and every material but the light a
tangent-space normal map of bumps and a checker base colour texture, both
SIZE x SIZE (--texture-size, default 256) PNGs inside the file: a
normal-mapped, textured scene for the large-scene checks of the tangents
and texels (about 8 more bytes per triangle in the file; 4 * SIZE^2 bytes
of texels per texture on the GPU).

    perf/make-scale-scene.py OUT.glb TRIANGLES [--objects N] [--seed S]
                             [--normal-map [--texture-size SIZE]]

Prints the file written and its triangle count. Needs python3-numpy.
"""
import argparse
import json
import math
import struct
import sys
import zlib

try:
    import numpy as np
except ImportError:
    sys.exit("make-scale-scene.py: needs numpy (Debian: python3-numpy; run it with "
             "/usr/bin/python3)")

ROOM = (-2.0, 2.0, 0.0, 3.0, -5.0, 0.0)  # x0, x1, y0, y1, z0, z1


def grid(n_u, n_v, closed_u, closed_v):
    """Triangle indices of an n_u x n_v grid of vertices (row-major, u
    fastest); closed directions wrap around."""
    cu = n_u if closed_u else n_u - 1
    cv = n_v if closed_v else n_v - 1
    i, j = np.meshgrid(np.arange(cv), np.arange(cu), indexing="ij")
    a = i * n_u + j
    b = i * n_u + (j + 1) % n_u
    c = ((i + 1) % n_v) * n_u + j
    d = ((i + 1) % n_v) * n_u + (j + 1) % n_u
    tri = np.stack([np.stack([a, b, d], -1), np.stack([a, d, c], -1)], -2)
    return tri.reshape(-1, 3).astype(np.uint32)


def sphere_grid(tris):
    """Rows and columns of a latitude-longitude grid of about `tris`
    triangles: (n_u columns, n_v rows strictly between the poles)."""
    n_v = max(3, int(round(math.sqrt(tris / 4.0))))
    n_u = max(6, int(round(tris / (2.0 * n_v))))
    return n_u, n_v


def close_poles(pos, n_u, n_v, north, south):
    """Appends the two pole vertices to an n_u x n_v closed-in-u grid and
    the fans that join them to its first and last rows."""
    idx = [grid(n_u, n_v, True, False)]
    pn, ps = len(pos), len(pos) + 1
    j = np.arange(n_u, dtype=np.uint32)
    idx.append(np.stack([np.full(n_u, pn, np.uint32), (j + 1) % n_u, j], -1))
    last = (n_v - 1) * n_u
    idx.append(np.stack([np.full(n_u, ps, np.uint32), last + j, last + (j + 1) % n_u], -1))
    return np.vstack([pos, north, south]), np.vstack(idx).astype(np.uint32)


def blob(tris, rng):
    """A bumpy sphere of about `tris` triangles."""
    n_u, n_v = sphere_grid(tris)
    th = (np.arange(n_v)[:, None] + 1) * math.pi / (n_v + 1)
    ph = np.linspace(0, 2 * math.pi, n_u, endpoint=False)[None, :]
    k1, k2 = rng.integers(3, 8), rng.integers(5, 12)
    r = 1 + 0.08 * np.sin(k1 * th) * np.cos(k2 * ph) + 0.04 * np.sin(11 * ph + 3 * th)
    d = np.stack([np.sin(th) * np.cos(ph), np.cos(th) * np.ones_like(ph),
                  np.sin(th) * np.sin(ph)], -1)
    pos, idx = close_poles((r[..., None] * d).reshape(-1, 3), n_u, n_v, [0, 1, 0], [0, -1, 0])
    return pos, None, idx


def torus(tris, rng):
    n_v = max(4, int(round(math.sqrt(tris / 6.0))))
    n_u = max(6, int(round(tris / (2.0 * n_v))))
    rr = rng.uniform(0.25, 0.4)
    u = np.linspace(0, 2 * math.pi, n_u, endpoint=False)[None, :]
    v = np.linspace(0, 2 * math.pi, n_v, endpoint=False)[:, None]
    ring = 1 - rr
    pos = np.stack([(ring + rr * np.cos(v)) * np.cos(u), rr * np.sin(v) * np.ones_like(u),
                    (ring + rr * np.cos(v)) * np.sin(u)], -1).reshape(-1, 3)
    nrm = np.stack([np.cos(v) * np.cos(u), np.sin(v) * np.ones_like(u),
                    np.cos(v) * np.sin(u)], -1).reshape(-1, 3)
    return pos, nrm, grid(n_u, n_v, True, True)


def rounded_box(tris, rng):
    """A superellipsoid (|x|^p + |y|^p + |z|^p = 1, p = 6..10): a box with
    rounded edges, as a latitude-longitude grid."""
    n_u, n_v = sphere_grid(tris)
    e = 2.0 / rng.uniform(6, 10)
    th = (np.arange(n_v)[:, None] + 1) * math.pi / (n_v + 1)
    ph = np.linspace(-math.pi, math.pi, n_u, endpoint=False)[None, :]

    def sp(x):
        return np.sign(x) * np.abs(x) ** e
    pos = np.stack([sp(np.sin(th)) * sp(np.cos(ph)), sp(np.cos(th)) * np.ones_like(ph),
                    sp(np.sin(th)) * sp(np.sin(ph))], -1).reshape(-1, 3)
    pos, idx = close_poles(pos, n_u, n_v, [0, 1, 0], [0, -1, 0])
    scale = np.array([1.0, rng.uniform(0.5, 1.0), rng.uniform(0.6, 1.0)])
    return pos * scale, None, idx


def vertex_normals(pos, idx):
    n = np.zeros_like(pos)
    p = pos[idx]
    f = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    for k in range(3):
        np.add.at(n, idx[:, k], f)
    length = np.linalg.norm(n, axis=1, keepdims=True)
    return n / np.where(length > 0, length, 1)


def rotation(rng):
    q = rng.normal(size=4)
    w, x, y, z = q / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def quad(p0, p1, p2, p3, n):
    pos = np.array([p0, p1, p2, p3], dtype=np.float64)
    uv = np.array([[0, 0], [4, 0], [4, 4], [0, 4]], dtype=np.float64)
    return (pos, np.array([n] * 4, dtype=np.float64), np.array([[0, 1, 2], [0, 2, 3]], np.uint32),
            uv)


def room():
    x0, x1, y0, y1, z0, z1 = ROOM
    return [  # (name, (pos, nrm, idx), material), inward normals
        ("floor", quad((x0, y0, z1), (x1, y0, z1), (x1, y0, z0), (x0, y0, z0), (0, 1, 0)), 0),
        ("ceiling", quad((x0, y1, z0), (x1, y1, z0), (x1, y1, z1), (x0, y1, z1), (0, -1, 0)), 0),
        ("back", quad((x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0), (0, 0, 1)), 0),
        ("front", quad((x1, y0, z1), (x0, y0, z1), (x0, y1, z1), (x1, y1, z1), (0, 0, -1)), 0),
        ("left", quad((x0, y0, z1), (x0, y0, z0), (x0, y1, z0), (x0, y1, z1), (1, 0, 0)), 1),
        ("right", quad((x1, y0, z0), (x1, y0, z1), (x1, y1, z1), (x1, y1, z0), (-1, 0, 0)), 2),
        ("light", quad((-0.5, y1 - 1e-3, -3.0), (0.5, y1 - 1e-3, -3.0), (0.5, y1 - 1e-3, -2.0),
                       (-0.5, y1 - 1e-3, -2.0), (0, -1, 0)), 3),
    ]


MATERIALS = [
    {"name": "white", "pbrMetallicRoughness": {"baseColorFactor": [0.73, 0.73, 0.73, 1],
                                                "metallicFactor": 0, "roughnessFactor": 1}},
    {"name": "red", "pbrMetallicRoughness": {"baseColorFactor": [0.63, 0.065, 0.05, 1],
                                              "metallicFactor": 0, "roughnessFactor": 1}},
    {"name": "green", "pbrMetallicRoughness": {"baseColorFactor": [0.14, 0.45, 0.091, 1],
                                                "metallicFactor": 0, "roughnessFactor": 1}},
    {"name": "light", "emissiveFactor": [1, 1, 1],
     "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 15}},
     "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0}},
    {"name": "clay", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.55, 0.35, 1],
                                               "metallicFactor": 0, "roughnessFactor": 0.9}},
    {"name": "blue", "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.3, 0.7, 1],
                                               "metallicFactor": 0, "roughnessFactor": 0.4}},
    {"name": "gold", "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.7, 0.3, 1],
                                               "metallicFactor": 1, "roughnessFactor": 0.35}},
    {"name": "plastic", "pbrMetallicRoughness": {"baseColorFactor": [0.85, 0.85, 0.8, 1],
                                                  "metallicFactor": 0, "roughnessFactor": 0.2}},
]


def objects(total, count, rng):
    """`count` objects of about `total` triangles in all, placed in front of
    the camera (z in [-4.7, -1.8]) without leaving the room."""
    x0, x1, y0, y1, z0, z1 = ROOM
    share = max(total // count, 24)
    makers = (blob, torus, rounded_box)
    # sizes such that the objects' bounding spheres fill about 6 % of
    # the volume they are scattered in
    vol = (x1 - x0 - 0.4) * (y1 - y0 - 0.6) * 2.9
    radius = (0.06 * vol / count / (4.0 / 3.0 * math.pi)) ** (1.0 / 3.0)
    out = []
    for k in range(count):
        pos, nrm, idx = makers[k % 3](share, rng)
        s = radius * rng.uniform(0.6, 1.4)
        rot = rotation(rng)
        centre = np.array([rng.uniform(x0 + 0.2 + s, x1 - 0.2 - s),
                           rng.uniform(y0 + s, y1 - 0.6 - s),
                           rng.uniform(-4.7 + s, -1.8 - s)])
        if nrm is None:
            nrm = vertex_normals(pos, idx)
        uv = object_uv(pos)
        pos = pos @ rot.T * s + centre
        nrm = nrm @ rot.T
        out.append((f"object{k}", (pos, nrm, idx, uv), 4 + int(rng.integers(0, 4))))
    return out


def object_uv(pos):
    """Texture coordinates of an object's vertices (unit-size, centred at
    the origin before placement): longitude and height, twice around."""
    u = (np.arctan2(pos[:, 2], pos[:, 0]) / (2 * math.pi) + 0.5) * 2
    v = pos[:, 1] + 0.5
    return np.stack([u, v], -1)


def png(rgb):
    """An 8-bit RGB PNG of an H x W x 3 uint8 array."""
    h, w, _ = rgb.shape
    raw = b"".join(b"\0" + rgb[y].tobytes() for y in range(h))

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw, 6)) + chunk(b"IEND", b""))


def textures(size):
    """The normal map (bumps: 8 x 8 cells of h = sin(2 pi 8 u) sin(2 pi 8 v))
    and the checker base colour, as PNG bytes."""
    t = (np.arange(size) + 0.5) / size
    u, v = np.meshgrid(t, t)
    k = 2 * math.pi * 8
    amp = 0.05
    du = amp * k * np.cos(k * u) * np.sin(k * v)
    dv = amp * k * np.sin(k * u) * np.cos(k * v)
    n = np.stack([-du, -dv, np.ones_like(u)], -1)
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    normal = np.clip(np.round((n * 0.5 + 0.5) * 255), 0, 255).astype(np.uint8)
    cells = ((np.floor(u * 8) + np.floor(v * 8)) % 2)[..., None]
    checker = np.where(cells > 0, 230, 140) * np.ones(3)
    return png(normal), png(checker.astype(np.uint8))


def write_glb(path, meshes, texture_size=0):
    bin_ = bytearray()
    views, accessors, gl_meshes, nodes = [], [], [], []
    tris = 0

    def add(data, target, comp, typ, minmax=False):
        while len(bin_) % 4:
            bin_.append(0)
        start = len(bin_)
        bin_.extend(data.tobytes())
        views.append({"buffer": 0, "byteOffset": start, "byteLength": len(bin_) - start,
                      "target": target})
        acc = {"bufferView": len(views) - 1, "count": int(data.shape[0]) if typ != "SCALAR"
               else int(data.size), "componentType": comp, "type": typ}
        if minmax:
            acc["min"] = [float(v) for v in data.min(axis=0)]
            acc["max"] = [float(v) for v in data.max(axis=0)]
        accessors.append(acc)
        return len(accessors) - 1

    for name, (pos, nrm, idx, uv), mat in meshes:
        tris += idx.shape[0]
        p = add(np.ascontiguousarray(pos, np.float32), 34962, 5126, "VEC3", True)
        n = add(np.ascontiguousarray(nrm, np.float32), 34962, 5126, "VEC3")
        i = add(np.ascontiguousarray(idx.reshape(-1), np.uint32), 34963, 5125, "SCALAR")
        attributes = {"POSITION": p, "NORMAL": n}
        if texture_size:
            attributes["TEXCOORD_0"] = add(np.ascontiguousarray(uv, np.float32), 34962, 5126,
                                           "VEC2")
        gl_meshes.append({"name": name, "primitives": [
            {"attributes": attributes, "indices": i, "material": mat, "mode": 4}]})
        nodes.append({"name": name, "mesh": len(gl_meshes) - 1})
    nodes.append({"name": "camera", "camera": 0, "translation": [0.0, 1.5, -0.3]})
    materials = MATERIALS
    images = []
    if texture_size:
        for data in textures(texture_size):
            while len(bin_) % 4:
                bin_.append(0)
            views.append({"buffer": 0, "byteOffset": len(bin_), "byteLength": len(data)})
            bin_.extend(data)
            images.append({"bufferView": len(views) - 1, "mimeType": "image/png"})
        materials = json.loads(json.dumps(MATERIALS))
        for m in materials:
            if "emissiveFactor" not in m:
                m["normalTexture"] = {"index": 0}
                m["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 1}
    gltf = {
        "asset": {"version": "2.0", "generator": "DIRT perf/make-scale-scene.py"},
        "extensionsUsed": ["KHR_materials_emissive_strength"],
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "meshes": gl_meshes,
        "materials": materials,
        "cameras": [{"type": "perspective", "perspective": {"yfov": 1.0, "znear": 0.05,
                                                            "aspectRatio": 4.0 / 3.0}}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(bin_)}],
    }
    if images:
        gltf["images"] = images
        gltf["textures"] = [{"source": 0}, {"source": 1}]
    js = json.dumps(gltf, separators=(",", ":")).encode()
    js += b" " * (-len(js) % 4)
    while len(bin_) % 4:
        bin_.append(0)
    with open(path, "wb") as f:
        f.write(struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(js) + 8 + len(bin_)))
        f.write(struct.pack("<II", len(js), 0x4E4F534A) + js)
        f.write(struct.pack("<II", len(bin_), 0x004E4942))
        f.write(bin_)
    return tris


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out", help="the .glb to write")
    ap.add_argument("triangles", type=int, help="about how many triangles in all (>= 1000)")
    ap.add_argument("--objects", type=int, default=0,
                    help="how many objects (default: about sqrt(TRIANGLES) / 3, at least 8)")
    ap.add_argument("--seed", type=int, default=1, help="placement seed (default 1)")
    ap.add_argument("--normal-map", action="store_true",
                    help="texture coordinates, a normal map and a base colour texture")
    ap.add_argument("--texture-size", type=int, default=256,
                    help="the textures' width and height with --normal-map (default 256)")
    a = ap.parse_args()
    if not a.out.lower().endswith(".glb"):
        sys.exit("make-scale-scene.py: the output must end in .glb")
    if a.triangles < 1000:
        sys.exit("make-scale-scene.py: TRIANGLES must be at least 1000")
    count = a.objects or max(8, int(round(math.sqrt(a.triangles) / 3)))
    if count < 1 or count * 24 > a.triangles:
        sys.exit("make-scale-scene.py: --objects must be at least 1 and at most TRIANGLES / 24")
    if a.normal_map and not 1 <= a.texture_size <= 16384:
        sys.exit("make-scale-scene.py: --texture-size must be 1 .. 16384")
    rng = np.random.default_rng(a.seed)
    meshes = room() + objects(a.triangles - 14, count, rng)
    tris = write_glb(a.out, meshes, a.texture_size if a.normal_map else 0)
    extra = f", normal-mapped, {a.texture_size}^2 textures" if a.normal_map else ""
    print(f"{a.out}: {tris} triangles ({count} objects{extra})")


if __name__ == "__main__":
    main()
