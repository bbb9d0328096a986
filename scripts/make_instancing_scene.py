#!/usr/bin/env python3
"""Writes the instancing scene of issue 25's measurement: a binary PLY mesh of about
TRIANGLES triangles (a bumpy torus with vertex normals) and a Mitsuba 3 scene that instances
it INSTANCES times (one `shapegroup`, INSTANCES `instance`s on a grid, each rotated and scaled
non-uniformly), lit by a `constant` emitter, 64 x 64 pixels at 1 spp. Nothing large is
committed: run this to make the files.

    python3 scripts/make_instancing_scene.py --instances 10000 --triangles 100000 --out target/instancing
    /usr/bin/time -v target/release/render target/instancing/scene-10000.xml -o /tmp/i.exr
    /usr/bin/time -v python3 scripts/make_instancing_scene.py --mitsuba-load target/instancing/scene-10000.xml

`--mitsuba-load FILE` loads FILE with Mitsuba 3 (`mi.load_file`, variant scalar_rgb unless
`--variant` says otherwise) and prints the load time, for `/usr/bin/time -v` to add the
peak memory. Needs only the standard library to write the files.
"""

from __future__ import annotations

import argparse
import math
import struct
import sys
import time
from pathlib import Path


def torus(triangles: int) -> tuple[list[tuple[float, ...]], list[tuple[int, int, int]]]:
    """A bumpy torus of at least `triangles` triangles: vertices (x, y, z, nx, ny, nz)."""
    # 2 · n · m triangles with m = 2n.
    n = max(3, math.ceil(math.sqrt(triangles / 4)))
    m = 2 * n
    R, r = 1.0, 0.35
    verts = []
    for i in range(m):
        u = 2 * math.pi * i / m
        for j in range(n):
            v = 2 * math.pi * j / n
            rr = r * (1 + 0.08 * math.sin(7 * u) * math.cos(5 * v))
            c = (math.cos(u) * R, math.sin(u) * R, 0.0)
            d = (math.cos(u) * math.cos(v), math.sin(u) * math.cos(v), math.sin(v))
            verts.append((c[0] + rr * d[0], c[1] + rr * d[1], rr * d[2], *d))
    faces = []
    for i in range(m):
        for j in range(n):
            a = i * n + j
            b = ((i + 1) % m) * n + j
            c = ((i + 1) % m) * n + (j + 1) % n
            d = i * n + (j + 1) % n
            faces.append((a, b, c))
            faces.append((a, c, d))
    return verts, faces


def write_ply(path: Path, verts, faces) -> None:
    head = (
        "ply\nformat binary_little_endian 1.0\n"
        f"element vertex {len(verts)}\n"
        "property float x\nproperty float y\nproperty float z\n"
        "property float nx\nproperty float ny\nproperty float nz\n"
        f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n"
    )
    with open(path, "wb") as f:
        f.write(head.encode())
        f.write(b"".join(struct.pack("<6f", *v) for v in verts))
        f.write(b"".join(struct.pack("<B3i", 3, *t) for t in faces))


def write_scene(path: Path, mesh: str, instances: int) -> None:
    side = math.ceil(math.sqrt(instances))
    out = [
        '<scene version="3.0.0">',
        '    <integrator type="path"><integer name="max_depth" value="3"/></integrator>',
        '    <sensor type="perspective">',
        '        <float name="fov" value="50"/>',
        '        <transform name="to_world">',
        f'            <lookat origin="0, {-1.2 * side}, {1.6 * side}" target="0, 0, 0" up="0, 0, 1"/>',
        "        </transform>",
        '        <sampler type="independent"><integer name="sample_count" value="1"/></sampler>',
        '        <film type="hdrfilm"><integer name="width" value="64"/>'
        '<integer name="height" value="64"/></film>',
        "    </sensor>",
        '    <emitter type="constant"><rgb name="radiance" value="1, 1, 1"/></emitter>',
        '    <shape type="shapegroup" id="torus">',
        f'        <shape type="ply"><string name="filename" value="{mesh}"/>',
        '            <bsdf type="diffuse"><rgb name="reflectance" value="0.6, 0.5, 0.4"/></bsdf>',
        "        </shape>",
        "    </shape>",
    ]
    for k in range(instances):
        x, y = (k % side - side / 2) * 2.5, (k // side - side / 2) * 2.5
        a = (k * 37) % 360
        sx, sy, sz = 0.6 + (k % 5) * 0.1, 0.5 + (k % 3) * 0.2, 0.4 + (k % 7) * 0.1
        out.append(
            f'    <shape type="instance"><ref id="torus"/><transform name="to_world">'
            f'<scale x="{sx:.2f}" y="{sy:.2f}" z="{sz:.2f}"/><rotate z="1" angle="{a}"/>'
            f'<translate x="{x:.2f}" y="{y:.2f}"/></transform></shape>'
        )
    out.append("</scene>")
    path.write_text("\n".join(out) + "\n")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--instances", type=int, nargs="+", default=[100, 10000])
    ap.add_argument("--triangles", type=int, default=100000)
    ap.add_argument("--out", type=Path, default=Path("target/instancing"))
    ap.add_argument("--mitsuba-load", type=Path)
    ap.add_argument("--variant", default="scalar_rgb")
    a = ap.parse_args()
    if a.mitsuba_load:
        import mitsuba as mi

        mi.set_variant(a.variant)
        t = time.perf_counter()
        scene = mi.load_file(str(a.mitsuba_load))
        dt = time.perf_counter() - t
        print(f"mitsuba {a.variant}: loaded {a.mitsuba_load} in {dt:.3f} s "
              f"({len(scene.shapes())} shapes)")
        return 0
    a.out.mkdir(parents=True, exist_ok=True)
    verts, faces = torus(a.triangles)
    mesh = a.out / "torus.ply"
    write_ply(mesh, verts, faces)
    print(f"{mesh}: {len(verts)} vertices, {len(faces)} triangles")
    for n in a.instances:
        scene = a.out / f"scene-{n}.xml"
        write_scene(scene, "torus.ply", n)
        print(f"{scene}: {n} instances")
    return 0


if __name__ == "__main__":
    sys.exit(main())
