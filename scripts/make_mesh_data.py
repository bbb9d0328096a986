#!/usr/bin/env python3
"""Writes the mesh files of mcrt-render/tests/data/meshes/ (PLY and Mitsuba `serialized`), checks that
Mitsuba 3 reads each to the geometry written, and with --render renders the references
mcrt-render/tests/data/meshes.exr and mcrt-render/tests/data/tent-crop.exr with Mitsuba 3 (llvm_ad_rgb, path
integrator, the mean of many independent passes).

    python3 scripts/make_mesh_data.py            # write and check the mesh files
    python3 scripts/make_mesh_data.py --render   # and render the references (minutes)

The serialized file is written from the format's description in Mitsuba 3's
documentation (Mitsuba 3 cannot write it); the PLY files by this script too, in the three
encodings.
"""

from __future__ import annotations

import argparse
import math
import struct
import sys
import time
import zlib
from pathlib import Path

import numpy as np

from contenders import import_mitsuba

REPO = Path(__file__).resolve().parent.parent
DATA = REPO / "mcrt-render" / "tests" / "data"
MESHES = DATA / "meshes"


def icosphere(subdivisions: int):
    """Unit sphere: positions, outward unit normals, triangles (counter-clockwise outside)."""
    t = (1 + 5 ** 0.5) / 2
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
         (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    v = [np.array(p, float) / np.linalg.norm(p) for p in v]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
         (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
         (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(subdivisions):
        cache, nf = {}, []

        def mid(a, b):
            k = (min(a, b), max(a, b))
            if k not in cache:
                m = v[a] + v[b]
                v.append(m / np.linalg.norm(m))
                cache[k] = len(v) - 1
            return cache[k]

        for a, b, c in f:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            nf += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        f = nf
    p = np.array(v, np.float32)
    return p, p.copy(), np.array(f, np.uint32)


def torus(major: float, minor: float, nu: int, nv: int):
    """A torus about the z axis: positions and triangles (outward winding), no normals."""
    p = []
    for i in range(nu):
        for j in range(nv):
            u, w = 2 * math.pi * i / nu, 2 * math.pi * j / nv
            r = major + minor * math.cos(w)
            p.append((r * math.cos(u), r * math.sin(u), minor * math.sin(w)))
    f = []
    for i in range(nu):
        for j in range(nv):
            a, b = i * nv + j, ((i + 1) % nu) * nv + j
            c, d = ((i + 1) % nu) * nv + (j + 1) % nv, i * nv + (j + 1) % nv
            f += [(a, b, c), (a, c, d)]
    return np.array(p, np.float32), np.array(f, np.uint32)


def write_ply(path: Path, p, f, n=None, uv=None, fmt="binary_little_endian", quads=None):
    """A PLY file: float positions (and normals, uvs), faces as uchar-counted int lists."""
    props = ["x", "y", "z"] + (["nx", "ny", "nz"] if n is not None else []) + \
        (["u", "v"] if uv is not None else [])
    cols = [p] + ([n] if n is not None else []) + ([uv] if uv is not None else [])
    rows = np.hstack(cols).astype(np.float32)
    faces = [list(t) for t in f] + [list(q) for q in (quads or [])]
    head = ["ply", f"format {fmt} 1.0", f"element vertex {len(p)}"]
    head += [f"property float {k}" for k in props]
    head += [f"element face {len(faces)}", "property list uchar int vertex_indices", "end_header"]
    out = ("\n".join(head) + "\n").encode()
    if fmt == "ascii":
        out += "".join(" ".join(f"{x:.7g}" for x in r) + "\n" for r in rows).encode()
        out += "".join(f"{len(t)} " + " ".join(str(i) for i in t) + "\n" for t in faces).encode()
    else:
        e = "<" if fmt == "binary_little_endian" else ">"
        out += rows.astype(e + "f4").tobytes()
        out += b"".join(struct.pack(f"{e}B{len(t)}i", len(t), *t) for t in faces)
    path.write_bytes(out)


def write_serialized(path: Path, meshes):
    """Version 4, single precision; `meshes` is a list of (name, positions, triangles)."""
    out, offsets = b"", []
    for name, p, f in meshes:
        offsets.append(len(out))
        body = struct.pack("<I", 0x1000) + name.encode() + b"\0"
        body += struct.pack("<QQ", len(p), len(f))
        body += p.astype("<f4").tobytes() + f.astype("<u4").tobytes()
        out += struct.pack("<HH", 0x041C, 4) + zlib.compress(body)
    out += b"".join(struct.pack("<Q", o) for o in offsets) + struct.pack("<I", len(offsets))
    path.write_bytes(out)


def check(mi, name, params, p, f, n=None):
    """Mitsuba reads the file to these positions, triangles (and normals)."""
    m = mi.load_dict({"type": params.pop("type"), "filename": str(MESHES / name), **params})
    got = mi.traverse(m)
    pos = np.array(got["vertex_positions"]).reshape(-1, 3)
    tri = np.array(got["faces"]).reshape(-1, 3)
    ok = np.allclose(pos, p, atol=1e-6) and (tri == f).all()
    if n is not None:
        ok = ok and np.allclose(np.array(got["vertex_normals"]).reshape(-1, 3), n, atol=1e-6)
    print(f"{name}: Mitsuba reads {len(pos)} vertices, {len(tri)} triangles: "
          f"{'same' if ok else 'DIFFERENT'}")
    if not ok:
        sys.exit(1)


def render(mi, scene: str, reference: str, spp: int, passes: int) -> None:
    s = mi.load_file(str(DATA / scene))
    t0, acc = time.time(), None
    for i in range(passes):
        img = np.array(mi.render(s, spp=spp, seed=1000 + i))
        acc = img if acc is None else acc + img
    acc /= passes
    mi.Bitmap(acc.astype(np.float32)).write(str(DATA / reference))
    print(f"{reference}: {spp * passes} spp in {time.time() - t0:.1f} s, "
          f"mean {acc.reshape(-1, acc.shape[-1])[:, :3].mean(0)}")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--render", action="store_true", help="also render the references")
    ap.add_argument("--spp", type=int, default=256, help="samples per pass")
    ap.add_argument("--passes", type=int, default=16, help="passes per reference")
    args = ap.parse_args()
    MESHES.mkdir(parents=True, exist_ok=True)
    sp, sn, sf = icosphere(2)
    write_ply(MESHES / "icosphere.ply", sp, sf, n=sn)
    tp, tf = torus(1.0, 0.35, 24, 12)
    bp = np.array([(x, y, z) for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], np.float32)
    bf = np.array([(0, 2, 3), (0, 3, 1)], np.uint32)
    write_serialized(MESHES / "shapes.serialized", [("card", bp, bf), ("torus", tp, tf)])
    # Tetrahedra in the other two encodings (triangles only: Mitsuba 3 refuses polygons).
    qp = np.array([(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)], np.float32)
    qf = np.array([(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)], np.uint32)
    write_ply(MESHES / "tetra-be.ply", qp, qf, fmt="binary_big_endian")
    write_ply(MESHES / "tetra-ascii.ply", qp, qf, uv=qp[:, :2].copy(), fmt="ascii")
    mi, _ = import_mitsuba(["llvm_ad_rgb" if args.render else "scalar_rgb"])
    mi.set_variant("llvm_ad_rgb" if args.render else "scalar_rgb")
    check(mi, "icosphere.ply", {"type": "ply"}, sp, sf, sn)
    check(mi, "shapes.serialized", {"type": "serialized", "shape_index": 1}, tp, tf)
    check(mi, "shapes.serialized", {"type": "serialized"}, bp, bf)
    check(mi, "tetra-be.ply", {"type": "ply"}, qp, qf)
    check(mi, "tetra-ascii.ply", {"type": "ply"}, qp, qf)
    if args.render:
        render(mi, "meshes.xml", "meshes.exr", args.spp, args.passes)
        render(mi, "tent-crop.xml", "tent-crop.exr", args.spp, args.passes)
    return 0


if __name__ == "__main__":
    sys.exit(main())
