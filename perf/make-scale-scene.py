#!/usr/bin/env python3
"""Writes a closed room full of geometry as one glTF file (binary .glb, or
.gltf with the buffer embedded), for the scaling benchmark
(perf/bench-scale.py), the work counters (perf/bench-work.sh) and the
large-scene checks: a 4 x 3 x 5 room (white floor, ceiling, back and front
walls, red and green side walls, an emissive ceiling panel, a camera inside
at eye height looking at the back wall) holding about TRIANGLES triangles
of one of these kinds (--kind):

  objects  OBJECTS objects (default: about sqrt(TRIANGLES) / 3, at least 8):
           bumpy spheres, tori and rounded boxes, each tessellated to its
           share, scattered with a fixed seed through the back of the room
           (random sizes, rotations and diffuse, glossy or metallic
           materials) in front of the camera;
  mirror   the same objects over a mirror floor (metallic, roughness 0):
           a specular floor under dense geometry;
  slats    OBJECTS thin slats (4 mm thick, 12-20 cm wide, 1.2-3.2 m long,
           tessellated along their length to their share): horizontal
           blinds stacked through the height of the room and vertical
           blades along its depth, each turned a few degrees off the
           camera's line of sight, so that most are seen nearly edge-on
           (thin geometry at grazing angles).

Each object is its own mesh (no shared meshes: the loader would expand
instances anyway, but a file of distinct meshes is what a scanned or CAD
scene is). The file holds positions, normals and 32-bit indices, about
16 bytes per triangle, so 10 M triangles make a file of about 160 MB: keep
such files out of the repository (write them under /tmp or build/).
perf/make-room.py writes the same room around one bumpy sphere.

With --normal-map every mesh also gets texture coordinates (no TANGENT:
the loader generates the tangents; the walls repeat the textures once a
metre, the objects twice around, the slats once a metre on each face) and
every material but the light a tangent-space normal map of bumps and a
checker base colour texture, both SIZE x SIZE (--texture-size, default
256) PNGs inside the file: a normal-mapped, textured scene of any kind for
the large-scene checks of the tangents and texels (about 8 more bytes per
triangle in the file; 4 * SIZE^2 bytes of texels per texture on the GPU).

    perf/make-scale-scene.py OUT.glb|OUT.gltf TRIANGLES [--kind KIND] [--objects N] [--seed S]
                             [--normal-map [--texture-size SIZE]]

Prints the file written and its triangle count. Needs python3-numpy.
"""
import argparse
import importlib.util
import copy
import math
import os
import struct
import sys
import zlib

try:
    import numpy as np
except ImportError:
    sys.exit("make-scale-scene.py: needs numpy (Debian: python3-numpy; run it with "
             "/usr/bin/python3)")

# The room, its first materials and the writer are perf/make-room.py's.
_spec = importlib.util.spec_from_file_location(
    "make_room", os.path.join(os.path.dirname(os.path.abspath(__file__)), "make-room.py"))
room_base = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(room_base)
ROOM = room_base.ROOM


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


MATERIALS = room_base.MATERIALS + [
    {"name": "clay", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.55, 0.35, 1],
                                               "metallicFactor": 0, "roughnessFactor": 0.9}},
    {"name": "blue", "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.3, 0.7, 1],
                                               "metallicFactor": 0, "roughnessFactor": 0.4}},
    {"name": "gold", "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.7, 0.3, 1],
                                               "metallicFactor": 1, "roughnessFactor": 0.35}},
    {"name": "plastic", "pbrMetallicRoughness": {"baseColorFactor": [0.85, 0.85, 0.8, 1],
                                                  "metallicFactor": 0, "roughnessFactor": 0.2}},
    {"name": "mirror", "pbrMetallicRoughness": {"baseColorFactor": [0.95, 0.95, 0.95, 1],
                                                 "metallicFactor": 1, "roughnessFactor": 0}},
    {"name": "slat", "pbrMetallicRoughness": {"baseColorFactor": [0.75, 0.7, 0.6, 1],
                                               "metallicFactor": 0, "roughnessFactor": 0.6}},
]
MIRROR, SLAT = 8, 9


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


def slat_box(length, width, thick, segs):
    """A box along x (length) by y (thickness) by z (width), centred at the
    origin, its four long faces cut into `segs` quads along x: 8 segs + 4
    triangles, flat normals; texture coordinates in metres along each face
    (u along the length, v across; on the end caps u = y, v = z)."""
    x = np.linspace(-length / 2, length / 2, segs + 1)
    h, w = thick / 2, width / 2
    pos, nrm, idx, uv = [], [], [], []
    # the long faces: (y, z) corners a -> b, outward normal
    for (ya, za), (yb, zb), n in (((h, -w), (h, w), (0, 1, 0)), ((-h, w), (-h, -w), (0, -1, 0)),
                                  ((-h, w), (h, w), (0, 0, 1)), ((h, -w), (-h, -w), (0, 0, -1))):
        base = sum(len(p) for p in pos)
        p = np.zeros((2 * (segs + 1), 3))
        p[0::2, 0], p[0::2, 1], p[0::2, 2] = x, ya, za
        p[1::2, 0], p[1::2, 1], p[1::2, 2] = x, yb, zb
        pos.append(p)
        nrm.append(np.tile(n, (len(p), 1)))
        t = np.zeros((len(p), 2))
        t[:, 0] = p[:, 0] + length / 2
        t[1::2, 1] = math.hypot(yb - ya, zb - za)
        uv.append(t)
        k = np.arange(segs) * 2 + base
        idx.append(np.stack([k, k + 2, k + 1], -1))
        idx.append(np.stack([k + 1, k + 2, k + 3], -1))
    for sx in (-1, 1):  # end caps
        base = sum(len(p) for p in pos)
        xe = sx * length / 2
        c = [(xe, -h, -w), (xe, h, -w), (xe, h, w), (xe, -h, w)]
        pos.append(np.array(c))
        nrm.append(np.tile((sx, 0, 0), (4, 1)))
        uv.append(np.array(c)[:, 1:] + (h, w))
        q = [[0, 1, 2], [0, 2, 3]] if sx > 0 else [[0, 2, 1], [0, 3, 2]]
        idx.append(np.array(q) + base)
    return (np.vstack(pos), np.vstack(nrm).astype(np.float64), np.vstack(idx).astype(np.uint32),
            np.vstack(uv))


def slats(total, count, rng):
    """`count` thin slats of about `total` triangles in all: half
    horizontal blinds across the room (seen edge-on from the camera's
    height, at grazing angles above and below it), half vertical blades
    along its depth (seen edge-on from straight ahead, grazing off it),
    each turned up to 4 degrees off those planes."""
    x0, x1, y0, y1, z0, z1 = ROOM
    segs = max(1, (max(total // count, 12) - 4) // 8)
    out = []
    for k in range(count):
        thick, width = 0.004, rng.uniform(0.12, 0.2)
        tilt = np.radians(rng.uniform(-4, 4))
        if k % 2 == 0:  # a blind: along x, thin in y
            length = rng.uniform(1.2, 3.2)
            pos, nrm, idx, uv = slat_box(length, width, thick, segs)
            c, s_ = np.cos(tilt), np.sin(tilt)  # about x: the width tips up or down
            rot = np.array([[1, 0, 0], [0, c, -s_], [0, s_, c]])
            centre = (rng.uniform(x0 + length / 2 + 0.05, x1 - length / 2 - 0.05)
                      if length < x1 - x0 - 0.2 else 0.0,
                      rng.uniform(y0 + 0.2, y1 - 0.3), rng.uniform(-4.6, -1.9))
        else:  # a blade: along z, thin in x, standing
            length = rng.uniform(1.2, 2.6)
            pos, nrm, idx, uv = slat_box(length, width, thick, segs)
            # x -> -z (length along the depth), y -> x (thin across), z -> y (width up)
            to_blade = np.array([[0, 1, 0], [0, 0, 1], [-1, 0, 0]])
            c, s_ = np.cos(tilt), np.sin(tilt)  # about y: off the line of sight
            rot = np.array([[c, 0, s_], [0, 1, 0], [-s_, 0, c]]) @ to_blade
            centre = (rng.uniform(x0 + 0.3, x1 - 0.3), rng.uniform(y0 + 0.1, y1 - 0.4),
                      rng.uniform(z0 + length / 2 + 0.1, -0.6 - length / 2))
        out.append((f"slat{k}", (pos @ rot.T + np.array(centre), nrm @ rot.T, idx, uv), SLAT))
    return out


def room_uv(walls):
    """The room's quads with texture coordinates: the textures once a
    metre along each side of the room (4 x 4 on every quad)."""
    uv = [(0, 0), (4, 0), (4, 4), (0, 4)]
    return [(n, (pos, nrm, idx, uv), m) for n, (pos, nrm, idx), m in walls]


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
    return [png(normal), png(checker.astype(np.uint8))]


def textured(materials):
    """`materials` with the normal map (texture 0) and the checker base
    colour (texture 1) on every one but the light (the emissive one)."""
    out = copy.deepcopy(materials)
    for m in out:
        if "emissiveFactor" not in m:
            m["normalTexture"] = {"index": 0}
            m["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 1}
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out", help="the .glb or .gltf to write")
    ap.add_argument("triangles", type=int, help="about how many triangles in all (>= 1000)")
    ap.add_argument("--kind", choices=("objects", "mirror", "slats"), default="objects",
                    help="what fills the room (default objects)")
    ap.add_argument("--objects", type=int, default=0,
                    help="how many objects or slats (default: about sqrt(TRIANGLES) / 3, "
                    "at least 8)")
    ap.add_argument("--seed", type=int, default=1, help="placement seed (default 1)")
    ap.add_argument("--normal-map", action="store_true",
                    help="texture coordinates, a normal map and a base colour texture on "
                    "every material but the light")
    ap.add_argument("--texture-size", type=int, default=256,
                    help="the textures' width and height with --normal-map (default 256)")
    a = ap.parse_args()
    if not a.out.lower().endswith((".glb", ".gltf")):
        sys.exit("make-scale-scene.py: the output must end in .glb or .gltf")
    if a.triangles < 1000:
        sys.exit("make-scale-scene.py: TRIANGLES must be at least 1000")
    count = a.objects or max(8, int(round(math.sqrt(a.triangles) / 3)))
    if count < 1 or count * 24 > a.triangles:
        sys.exit("make-scale-scene.py: --objects must be at least 1 and at most TRIANGLES / 24")
    if a.normal_map and not 1 <= a.texture_size <= 16384:
        sys.exit("make-scale-scene.py: --texture-size must be 1 .. 16384")
    rng = np.random.default_rng(a.seed)
    walls = room_base.room()
    if a.kind == "mirror":
        walls = [(n, g, MIRROR if n == "floor" else m) for n, g, m in walls]
    fill = slats if a.kind == "slats" else objects
    meshes = fill(a.triangles - 14, count, rng)
    if a.normal_map:
        meshes = room_uv(walls) + meshes
        materials, images = textured(MATERIALS), textures(a.texture_size)
    else:
        meshes = walls + [(n, g[:3], m) for n, g, m in meshes]
        materials, images = MATERIALS, []
    tris = room_base.write_gltf(a.out, meshes, materials, "DIRT perf/make-scale-scene.py",
                                 4.0 / 3.0, images)
    extra = f", normal-mapped, {a.texture_size}^2 textures" if a.normal_map else ""
    print(f"{a.out}: {tris} triangles ({count} {'slats' if a.kind == 'slats' else 'objects'}"
          f"{', mirror floor' if a.kind == 'mirror' else ''}{extra})")


if __name__ == "__main__":
    main()
