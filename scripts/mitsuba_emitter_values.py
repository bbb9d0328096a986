#!/usr/bin/env python3
"""Write mcrt-render/tests/data/mitsuba-emitter-values.txt: Mitsuba 3's own values of the emitters and
the sensor that issue 16 added, for mcrt-render/tests/it/emitter_mitsuba_values.rs to compare ours against.

Each case is a scene fragment (an <emitter> or a <sensor>), loaded by Mitsuba from the same
text our test loads, inside `<scene version="3.0.0"> ... </scene>` with the scene file's
folder mcrt-render/tests/data (for envmap files). Per case:

- spot, directional: for points p, Mitsuba's `sample_direction` from p: the unit direction
  toward the light and the radiance arriving (its weight; intensity times falloff over the
  squared distance for a spot, the irradiance for a directional light);
- envmap: for directions d, the radiance seen looking along d (`eval` with `wi = -d`);
- thinlens: for film samples (x, y) in [0,1]^2 and aperture samples, `sample_ray`'s origin
  (on the near clip plane) and unit direction.

Usage:  python3 scripts/mitsuba_emitter_values.py [OUT]
Needs the packages of scripts/requirements.txt; uses the scalar_rgb variant.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parent.parent
DATA = REPO / "mcrt-render" / "tests" / "data"

CASES = [
    ("spot-default", '<emitter type="spot"/>'),
    ("spot-lookat",
     '<emitter type="spot"><rgb name="intensity" value="2, 3, 4"/>'
     '<float name="cutoff_angle" value="35"/><float name="beam_width" value="12"/>'
     '<transform name="to_world"><lookat origin="1, 2, 3" target="0.5, -1, 0.2" up="0, 0, 1"/>'
     '</transform></emitter>'),
    ("spot-wide-scaled",
     '<emitter type="spot"><rgb name="intensity" value="1.5"/>'
     '<float name="cutoff_angle" value="120"/>'
     '<transform name="to_world"><scale value="2.5"/><rotate x="1" angle="70"/>'
     '<translate x="-1" y="0.5" z="0.25"/></transform></emitter>'),
    ("directional-default", '<emitter type="directional"/>'),
    ("directional-direction",
     '<emitter type="directional"><vector name="direction" x="1" y="-2" z="0.5"/>'
     '<rgb name="irradiance" value="0.5, 1, 2"/></emitter>'),
    ("directional-to-world",
     '<emitter type="directional"><rgb name="irradiance" value="3"/>'
     '<transform name="to_world"><rotate y="1" angle="40"/><rotate x="1" angle="-65"/>'
     '</transform></emitter>'),
    ("envmap-identity", '<emitter type="envmap"><string name="filename" value="sky.exr"/></emitter>'),
    ("envmap-rotated",
     '<emitter type="envmap"><string name="filename" value="sky.exr"/>'
     '<float name="scale" value="0.5"/>'
     '<transform name="to_world"><rotate y="1" angle="75"/><rotate x="1" angle="-20"/>'
     '</transform></emitter>'),
    ("thinlens",
     '<sensor type="thinlens"><float name="fov" value="40"/>'
     '<float name="aperture_radius" value="0.12"/><float name="focus_distance" value="4.2"/>'
     '<float name="near_clip" value="0.05"/>'
     '<transform name="to_world"><lookat origin="0, 0.8, 4" target="0, 0.2, 0" up="0, 1, 0"/>'
     '</transform><film type="hdrfilm"><integer name="width" value="128"/>'
     '<integer name="height" value="96"/></film></sensor>'),
    ("thinlens-fov-y",
     '<sensor type="thinlens"><float name="fov" value="30"/><string name="fov_axis" value="y"/>'
     '<float name="aperture_radius" value="0.5"/>'
     '<transform name="to_world"><translate x="1" y="2" z="3"/><rotate y="1" angle="30"/>'
     '</transform><film type="hdrfilm"><integer name="width" value="64"/>'
     '<integer name="height" value="80"/></film></sensor>'),
]


def fmt(*vals) -> str:
    return " ".join(f"{float(v):.9g}" for v in vals)


def main() -> None:
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else DATA / "mitsuba-emitter-values.txt"
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from contenders import check_variant, import_mitsuba

    mi, _ = import_mitsuba(["scalar_rgb"])
    check_variant(mi, "scalar_rgb")
    import drjit as dr

    rng = np.random.default_rng(1)
    lines = [
        f"# Mitsuba {mi.__version__} (scalar_rgb) emitter and sensor values, written by "
        "scripts/mitsuba_emitter_values.py.",
        "# case NAME | scene fragment",
        "# l p.xyz wi.xyz radiance.rgb      (spot, directional: sample_direction from p)",
        "# e d.xyz radiance.rgb             (envmap: radiance seen looking along d)",
        "# r film.xy aperture.xy o.xyz d.xyz (thinlens: sample_ray)",
    ]
    for name, frag in CASES:
        xml = f'<scene version="3.0.0">{frag}</scene>'
        path = DATA / f".{name}.tmp.xml"
        path.write_text(xml)
        try:
            scene = mi.load_file(str(path))
        finally:
            path.unlink()
        lines.append(f"case {name} | {frag}")
        if name.startswith(("spot", "directional")):
            em = scene.emitters()[0]
            for _ in range(24):
                # Points around the spot lights' cones, and anywhere for directional ones.
                p = rng.normal(size=3) * 1.5
                if name == "spot-default":
                    p = (np.array([0.0, 0.0, 1.0]) + rng.normal(size=3) * 0.3) * rng.uniform(0.5, 2)
                if name == "spot-lookat":
                    axis = np.array([0.5, -1.0, 0.2]) - np.array([1.0, 2.0, 3.0])
                    p = np.array([1.0, 2.0, 3.0]) + axis * rng.uniform(0.3, 1.2) + rng.normal(size=3)
                it = dr.zeros(mi.Interaction3f)
                it.p = mi.Point3f(*p)
                ds, w = em.sample_direction(it, mi.Point2f(0.5, 0.5))
                d = np.array(ds.d)
                d = d / np.linalg.norm(d)
                lines.append("l " + fmt(*p, *d, *w))
        elif name.startswith("envmap"):
            em = scene.emitters()[0]
            for _ in range(40):
                d = rng.normal(size=3)
                d /= np.linalg.norm(d)
                si = dr.zeros(mi.SurfaceInteraction3f)
                si.wi = mi.Vector3f(*(-d))
                lines.append("e " + fmt(*d, *em.eval(si)))
        else:
            sensor = scene.sensors()[0]
            for _ in range(16):
                f = rng.uniform(0.02, 0.98, size=2)
                a = rng.uniform(0.0, 1.0, size=2)
                ray, _ = sensor.sample_ray(0.0, 0.5, mi.Point2f(*f), mi.Point2f(*a))
                lines.append("r " + fmt(*f, *a, *ray.o, *ray.d))
    out.write_text("\n".join(lines) + "\n")
    print(f"wrote {out}: {len(lines)} lines")


if __name__ == "__main__":
    main()
