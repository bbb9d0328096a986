#!/usr/bin/env python3
"""Write the scenes of issue 28 into mcrt-render/tests/data/issue28/ (deterministic: a fixed
seed, so running it again writes the same files).

- many-lights.xml: a room (open at the front, like the Cornell box) lit by 420 small
  rectangle lights on the ceiling and the three walls, of radiances spread over three
  decades and of many hues; a tall box in front of the back wall, a free-standing screen in
  front of the left wall and a panel under the ceiling hide some of them; and a sphere
  mesh emitter of 10 000 triangles (many-lights-sphere.ply) on the floor.
- indirect.xml: a closed room whose only light faces the ceiling from inside an opaque
  shade (a box open at the top): everything but the ceiling is lit after one bounce off
  the bright patch above the lamp. The walls and floor are dark (0.2) under a white
  ceiling, so that nearly all light arrives after that one bounce (90% of the image's mean
  within paths of at most three segments, against 56% with white walls).
- door.xml: Veach's door scene: two rooms; the camera's room is lit only through the narrow
  gap of a door left ajar, from a lamp on the ceiling of the next room.

Usage: python3 scripts/make_issue28_scenes.py [--out DIR] [--shade-height H]
"""

from __future__ import annotations

import argparse
import colorsys
import math
import random
import struct
from pathlib import Path

HEADER = """<scene version="3.0.0">
    <!-- {comment} -->
    <default name="spp" value="64"/>
    <default name="res" value="128"/>
    <default name="max_depth" value="-1"/>

    <integrator type="path">
        <integer name="max_depth" value="$max_depth"/>
    </integrator>
    <sensor type="perspective">
        <string name="fov_axis" value="smaller"/>
        <float name="fov" value="{fov}"/>
        <transform name="to_world">
            <lookat origin="{origin}" target="{target}" up="0, 1, 0"/>
        </transform>
        <sampler type="independent">
            <integer name="sample_count" value="$spp"/>
        </sampler>
        <film type="hdrfilm">
            <integer name="width" value="$res"/>
            <integer name="height" value="$res"/>
            <rfilter type="box"/>
        </film>
    </sensor>

{bsdfs}"""

def bsdfs(**reflectances: str) -> str:
    """Diffuse BSDFs named by the keywords, each with its reflectance ("r, g, b")."""
    return "".join(
        f'    <bsdf type="diffuse" id="{name}">\n'
        f'        <rgb name="reflectance" value="{value}"/>\n'
        "    </bsdf>\n"
        for name, value in reflectances.items()
    )


# The materials of the many-lights room and the door scene: a Cornell-box room.
ROOM_BSDFS = bsdfs(white="0.8, 0.8, 0.8", red="0.6, 0.1, 0.1", green="0.15, 0.5, 0.15",
                   dark="0.1, 0.1, 0.1")

# The indirect room's: a white ceiling over walls and a floor a quarter as bright as the
# Cornell box's (grey 0.2, red and green scaled by 1/4), so that the light that comes after
# two or more bounces is a tenth of the image (with the Cornell box's walls it was 44%).
INDIRECT_BSDFS = bsdfs(white="0.8, 0.8, 0.8", grey="0.2, 0.2, 0.2", red="0.15, 0.025, 0.025",
                       green="0.0375, 0.125, 0.0375", dark="0.1, 0.1, 0.1")


def fmt(v: float) -> str:
    return f"{v:.6g}"


def rect(c, ex, ey, bsdf: str, radiance=None, ident: str | None = None) -> str:
    """A rectangle centred at c with half-edges ex, ey: Mitsuba's [-1, 1]² with normal
    ex × ey (the emitting side)."""
    n = cross(ex, ey)
    ln = math.sqrt(dot(n, n))
    n = [x / ln for x in n]
    rows = [
        [ex[0], ey[0], n[0], c[0]],
        [ex[1], ey[1], n[1], c[1]],
        [ex[2], ey[2], n[2], c[2]],
        [0, 0, 0, 1],
    ]
    m = "  ".join(" ".join(fmt(x) for x in r) for r in rows)
    idattr = f' id="{ident}"' if ident else ""
    s = f'    <shape type="rectangle"{idattr}>\n'
    s += f'        <transform name="to_world"><matrix value="{m}"/></transform>\n'
    s += f'        <ref id="{bsdf}"/>\n'
    if radiance is not None:
        r = ", ".join(fmt(x) for x in radiance)
        s += f'        <emitter type="area"><rgb name="radiance" value="{r}"/></emitter>\n'
    s += "    </shape>\n"
    return s


def cube(c, h, bsdf: str) -> str:
    """An axis-aligned box centred at c with half-extents h (Mitsuba's cube is [-1, 1]³)."""
    return (
        '    <shape type="cube">\n'
        f'        <transform name="to_world"><scale x="{fmt(h[0])}" y="{fmt(h[1])}" z="{fmt(h[2])}"/>'
        f'<translate x="{fmt(c[0])}" y="{fmt(c[1])}" z="{fmt(c[2])}"/></transform>\n'
        f'        <ref id="{bsdf}"/>\n'
        "    </shape>\n"
    )


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def open_room(wall: str = "white") -> str:
    """The Cornell-box room [-1, 1]³, open at z = +1, all walls facing inward; the floor and
    the back wall of the BSDF `wall`, the ceiling white."""
    return (
        rect([0, -1, 0], [1, 0, 0], [0, 0, -1], wall)  # floor, normal +y
        + rect([0, 1, 0], [1, 0, 0], [0, 0, 1], "white")  # ceiling, normal -y
        + rect([0, 0, -1], [1, 0, 0], [0, 1, 0], wall)  # back, normal +z
        + rect([-1, 0, 0], [0, 1, 0], [0, 0, 1], "red")  # left, normal +x
        + rect([1, 0, 0], [0, 0, 1], [0, 1, 0], "green")  # right, normal -x
    )


def sphere_ply(path: Path, rings: int, segments: int) -> int:
    """A UV sphere of radius 1 as binary little-endian PLY; returns its triangle count."""
    verts = [(0.0, 1.0, 0.0)]
    for i in range(1, rings):
        th = math.pi * i / rings
        for j in range(segments):
            ph = 2 * math.pi * j / segments
            verts.append((math.sin(th) * math.cos(ph), math.cos(th), math.sin(th) * math.sin(ph)))
    verts.append((0.0, -1.0, 0.0))
    bottom = len(verts) - 1

    def ring(i, j):
        return 1 + (i - 1) * segments + (j % segments)

    faces = []
    for j in range(segments):  # caps, wound so that the normal points out
        faces.append((0, ring(1, j + 1), ring(1, j)))
        faces.append((bottom, ring(rings - 1, j), ring(rings - 1, j + 1)))
    for i in range(1, rings - 1):
        for j in range(segments):
            a, b = ring(i, j), ring(i, j + 1)
            c, d = ring(i + 1, j), ring(i + 1, j + 1)
            faces.append((a, b, d))
            faces.append((a, d, c))
    for t in faces:  # outward: the normal (b - a) × (c - a) points away from the centre
        a, b, c = (verts[k] for k in t)
        n = cross([b[i] - a[i] for i in range(3)], [c[i] - a[i] for i in range(3)])
        assert dot(n, [a[i] + b[i] + c[i] for i in range(3)]) > 0, t
    head = (
        "ply\nformat binary_little_endian 1.0\n"
        f"element vertex {len(verts)}\nproperty float x\nproperty float y\nproperty float z\n"
        f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n"
    )
    with open(path, "wb") as f:
        f.write(head.encode())
        for v in verts:
            f.write(struct.pack("<3f", *v))
        for t in faces:
            f.write(struct.pack("<B3i", 3, *t))
    return len(faces)


def many_lights(out: Path, keep: int | None = None) -> None:
    """The many-lights room; with `keep`, only that many of its rectangle lights (every
    420/keep-th) and no sphere, as many-lights-KEEP.xml (the study of the BVH's threshold)."""
    rng = random.Random(28)
    tris = 0 if keep else sphere_ply(out / "many-lights-sphere.ply", 51, 100)
    assert keep or tris >= 10_000, tris
    s = HEADER.format(
        comment="Issue 28's many-lights room, written by scripts/make_issue28_scenes.py: "
        f"420 small rectangle lights on the ceiling and walls (radiance over three decades, "
        f"many hues), some hidden by a box, a screen and a ceiling panel, and a sphere mesh "
        f"emitter of {tris} triangles.",
        fov="39.3077",
        origin="0, 0, 3.9",
        target="0, 0, 0",
        bsdfs=ROOM_BSDFS,
    )
    s += open_room()
    lights = []
    half = 0.035

    def emit():
        hue = rng.random()
        sat = rng.uniform(0.2, 0.9)
        rgb = colorsys.hsv_to_rgb(hue, sat, 1.0)
        power = 10 ** rng.uniform(-1.7, 1.3)  # three decades
        return [power * c for c in rgb]

    # Ceiling: 10 × 10, jittered; facing down.
    for i in range(10):
        for j in range(10):
            x = -0.9 + 1.8 * (i + rng.uniform(0.2, 0.8)) / 10
            z = -0.9 + 1.8 * (j + rng.uniform(0.2, 0.8)) / 10
            lights.append(rect([x, 0.995, z], [half, 0, 0], [0, 0, half], "dark", emit()))
    # Back wall: 10 × 10, facing +z.
    for i in range(10):
        for j in range(10):
            x = -0.9 + 1.8 * (i + rng.uniform(0.2, 0.8)) / 10
            y = -0.9 + 1.8 * (j + rng.uniform(0.2, 0.8)) / 10
            lights.append(rect([x, y, -0.995], [half, 0, 0], [0, half, 0], "dark", emit()))
    # Side walls: 11 × 10 each.
    for side in (-1, 1):
        for i in range(11):
            for j in range(10):
                z = -0.9 + 1.8 * (i + rng.uniform(0.2, 0.8)) / 11
                y = -0.9 + 1.8 * (j + rng.uniform(0.2, 0.8)) / 10
                # Facing into the room: +x on the left wall, -x on the right.
                ex, ey = ([0, half, 0], [0, 0, half]) if side < 0 else ([0, 0, half], [0, half, 0])
                lights.append(rect([0.995 * side, y, z], ex, ey, "dark", emit()))
    assert len(lights) == 420
    if keep:
        lights = [lights[(k * 420) // keep] for k in range(keep)]
    s += "".join(lights)
    # Occluders: a tall box before the back wall, a screen before the left wall, a panel
    # under the ceiling (opaque both ways).
    s += cube([0.35, -0.3, -0.75], [0.2, 0.7, 0.12], "white")
    s += cube([-0.85, 0.1, -0.1], [0.03, 0.5, 0.45], "white")
    s += cube([-0.2, 0.85, -0.2], [0.45, 0.02, 0.45], "white")
    s += "" if keep else (
        '    <shape type="ply">\n'
        '        <string name="filename" value="many-lights-sphere.ply"/>\n'
        '        <transform name="to_world"><scale value="0.25"/>'
        '<translate x="-0.35" y="-0.75" z="0.25"/></transform>\n'
        '        <ref id="white"/>\n'
        '        <emitter type="area"><rgb name="radiance" value="5, 4, 2.5"/></emitter>\n'
        "    </shape>\n"
    )
    s += "</scene>\n"
    (out / (f"many-lights-{keep}.xml" if keep else "many-lights.xml")).write_text(s)


def indirect(out: Path, shade: float = 0.2, name: str = "indirect.xml") -> None:
    """The indirect room, its lamp's shade `shade` high (0.2: issue 28's test scene, whose lit
    patch spreads over much of the ceiling; 0.5: a small bright patch, for guiding studies)."""
    s = HEADER.format(
        comment="Issue 28's indirect room, written by scripts/make_issue28_scenes.py: a "
        "closed room whose only light, a small panel facing the ceiling, sits in an "
        "opaque shade open at the top; all but the ceiling is lit after a bounce off the "
        "bright patch above the lamp. Under the white ceiling the walls and floor are dark "
        "(reflectance 0.2), so nine tenths of the light reach the camera after at most one "
        "bounce. The camera sits inside, by the front wall.",
        fov="70",
        origin="0, 0, 0.95",
        target="0, -0.1, 0",
        bsdfs=INDIRECT_BSDFS,
    )
    s += open_room("grey")
    s += rect([0, 0, 1], [1, 0, 0], [0, -1, 0], "grey")  # front wall, normal -z
    # The lamp: a 0.16 × 0.16 panel at y = -0.2 facing up, in a shade of four walls
    # (`shade` high, open at the top) on a stand.
    y = -0.2
    s += rect([0.3, y + 0.005, -0.4], [0.08, 0, 0], [0, 0, -0.08], "dark", [1000, 900, 750])
    s += cube([0.3, y - 0.01, -0.4], [0.1, 0.01, 0.1], "dark")  # base below the panel
    for dx, dz, hx, hz in ((0.1, 0, 0.005, 0.1), (-0.1, 0, 0.005, 0.1), (0, 0.1, 0.1, 0.005), (0, -0.1, 0.1, 0.005)):
        s += cube([0.3 + dx, y - 0.01 + shade / 2, -0.4 + dz], [hx, shade / 2, hz], "dark")
    s += cube([0.3, (y - 0.02 - 1) / 2, -0.4], [0.02, (y - 0.02 + 1) / 2, 0.02], "dark")  # stand
    s += cube([-0.45, -0.7, -0.3], [0.25, 0.3, 0.25], "grey")  # a box on the floor
    s += "</scene>\n"
    (out / name).write_text(s)


def door(out: Path) -> None:
    s = HEADER.format(
        comment="Issue 28's door scene (after Veach's), written by "
        "scripts/make_issue28_scenes.py: the camera's room (x in [-1, 1]) and, beyond the "
        "wall at z = -1 with a doorway, the next room (z in [-3, -1]) with a lamp on its "
        "ceiling. The door stands ajar: light enters through a gap of about 0.05.",
        fov="60",
        origin="0.2, 0, 0.95",
        target="-0.2, -0.3, -1",
        bsdfs=ROOM_BSDFS,
    )
    # The camera's room: floor, ceiling, left, right, front; the back wall has a doorway
    # x in [-0.3, 0.1], y in [-1, 0.5].
    s += rect([0, -1, -1], [1, 0, 0], [0, 0, -2], "white")  # floor of both rooms, normal +y
    s += rect([0, 1, -1], [1, 0, 0], [0, 0, 2], "white")  # ceiling of both rooms, normal -y
    s += rect([-1, 0, -1], [0, 1, 0], [0, 0, 2], "white")  # left, both rooms, normal +x
    s += rect([1, 0, -1], [0, 0, 2], [0, 1, 0], "white")  # right, both rooms, normal -x
    s += rect([0, 0, 1], [1, 0, 0], [0, -1, 0], "white")  # front
    s += rect([0, 0, -3], [1, 0, 0], [0, 1, 0], "white")  # far wall of the next room
    # The dividing wall (a slab 0.04 thick) around the doorway.
    s += cube([-0.65, 0, -1.0], [0.35, 1, 0.02], "white")
    s += cube([0.55, 0, -1.0], [0.45, 1, 0.02], "white")
    s += cube([-0.1, 0.75, -1.0], [0.2, 0.25, 0.02], "white")
    # The door: hinged at x = 0.1, swung into the next room by a small angle, leaving a
    # gap of about 0.05 between its free edge and the jamb at x = -0.3.
    ang = math.degrees(math.asin(0.07 / 0.4))
    s += (
        '    <shape type="cube">\n'
        '        <transform name="to_world"><scale x="0.2" y="0.75" z="0.015"/>'
        '<translate x="-0.2" y="-0.25" z="-0.015"/>'
        f'<rotate y="1" angle="{fmt(-ang)}"/>'
        '<translate x="0.1" y="0" z="-1.0"/></transform>\n'
        '        <ref id="white"/>\n'
        "    </shape>\n"
    )
    s += rect([0, 0.99, -2.4], [0.25, 0, 0], [0, 0, 0.25], "dark", [200, 190, 170])  # lamp, down
    s += "</scene>\n"
    (out / "door.xml").write_text(s)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", type=Path, default=Path("mcrt-render/tests/data/issue28"))
    ap.add_argument("--threshold-study", type=int, nargs="*", metavar="N",
                    help="write only many-lights-N.xml for each N: N of the room's "
                         "rectangle lights, no sphere")
    ap.add_argument("--shade-height", type=float, metavar="H",
                    help="write only indirect-deep.xml: the indirect room with a shade H high "
                         "(0.5 makes the lit patch small; a study scene, no reference)")
    a = ap.parse_args()
    a.out.mkdir(parents=True, exist_ok=True)
    if a.shade_height is not None:
        indirect(a.out, a.shade_height, "indirect-deep.xml")
        print(f"wrote {a.out}/indirect-deep.xml")
        return
    if a.threshold_study:
        for n in a.threshold_study:
            many_lights(a.out, n)
        print(f"wrote many-lights-N.xml for N = {a.threshold_study} into {a.out}")
        return
    many_lights(a.out)
    indirect(a.out)
    door(a.out)
    print(f"wrote {a.out}/many-lights.xml, many-lights-sphere.ply, indirect.xml, door.xml")


if __name__ == "__main__":
    main()
