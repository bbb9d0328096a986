#!/usr/bin/env python3
"""Write mcrt-render/tests/data/mitsuba-bsdf-values.txt: Mitsuba 3's own values of the BSDFs the
loader reads, for mcrt-render/tests/it/bsdf_mitsuba_values.rs to compare ours against.

For each case (a <bsdf> element, loaded by Mitsuba from the same text our test loads) and
each pair of directions it records Mitsuba's `eval` (BSDF times the cosine of the sampled
side, radiance transport, and importance transport for the transmitting ones) and `pdf`;
and for sample values that pick a Dirac component (smooth reflection or transmission), the
sampled direction, probability, weight and relative index.

Directions use Mitsuba's names turned around to ours: our `wo` (toward the viewer) is
Mitsuba's `si.wi`, our `wi` (toward the light) is Mitsuba's `wo`. The shading frame is the
identity (z up). Directions: a fixed random set over the sphere (seed 1), plus the mirror
and refracted directions of each `wo` and points around them, so that narrow lobes are hit.

Usage:  python3 scripts/mitsuba_bsdf_values.py [OUT]   (default mcrt-render/tests/data/mitsuba-bsdf-values.txt)
Needs the packages of scripts/requirements.txt; uses the scalar_rgb variant.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parent.parent

# name, transmits (directions below the surface matter), <bsdf> element.
CASES = [
    ("roughdielectric-default", True, '<bsdf type="roughdielectric"/>'),
    ("roughdielectric-ggx", True,
     '<bsdf type="roughdielectric"><string name="distribution" value="ggx"/>'
     '<float name="alpha" value="0.3"/><float name="int_ior" value="1.33"/>'
     '<float name="ext_ior" value="1.0"/>'
     '<rgb name="specular_transmittance" value="0.8, 0.6, 0.4"/></bsdf>'),
    ("roughdielectric-beckmann-rough", True,
     '<bsdf type="roughdielectric"><float name="alpha" value="0.5"/>'
     '<string name="int_ior" value="water"/><string name="ext_ior" value="vacuum"/>'
     '<rgb name="specular_reflectance" value="0.9, 0.7, 0.5"/></bsdf>'),
    ("thindielectric-default", True, '<bsdf type="thindielectric"/>'),
    ("thindielectric-tinted", True,
     '<bsdf type="thindielectric"><float name="int_ior" value="1.7"/>'
     '<rgb name="specular_transmittance" value="0.8, 0.6, 0.4"/>'
     '<rgb name="specular_reflectance" value="0.5, 0.5, 1.0"/></bsdf>'),
    ("plastic-default", False, '<bsdf type="plastic"/>'),
    ("plastic-nonlinear", False,
     '<bsdf type="plastic"><rgb name="diffuse_reflectance" value="0.8, 0.3, 0.1"/>'
     '<float name="int_ior" value="1.6"/><boolean name="nonlinear" value="true"/></bsdf>'),
    ("plastic-tinted", False,
     '<bsdf type="plastic"><rgb name="diffuse_reflectance" value="0.1, 0.2, 0.6"/>'
     '<rgb name="specular_reflectance" value="0.5, 0.9, 0.9"/></bsdf>'),
    ("roughplastic-default", False, '<bsdf type="roughplastic"/>'),
    ("roughplastic-ggx-nonlinear", False,
     '<bsdf type="roughplastic"><string name="distribution" value="ggx"/>'
     '<float name="alpha" value="0.3"/><rgb name="diffuse_reflectance" value="0.2, 0.5, 0.8"/>'
     '<boolean name="nonlinear" value="true"/></bsdf>'),
    ("roughplastic-beckmann-rough", False,
     '<bsdf type="roughplastic"><float name="alpha" value="0.5"/>'
     '<float name="int_ior" value="1.33"/><rgb name="diffuse_reflectance" value="0.9, 0.9, 0.9"/></bsdf>'),
    ("roughconductor-au-ggx", False,
     '<bsdf type="roughconductor"><string name="material" value="Au"/>'
     '<string name="distribution" value="ggx"/><float name="alpha" value="0.2"/></bsdf>'),
    ("conductor-cu", False, '<bsdf type="conductor"><string name="material" value="Cu"/></bsdf>'),
    ("blendbsdf-diffuse-roughconductor", False,
     '<bsdf type="blendbsdf"><float name="weight" value="0.3"/>'
     '<bsdf type="diffuse"><rgb name="reflectance" value="0.2, 0.5, 0.8"/></bsdf>'
     '<bsdf type="roughconductor"><string name="material" value="Au"/>'
     '<string name="distribution" value="ggx"/><float name="alpha" value="0.3"/></bsdf></bsdf>'),
    ("blendbsdf-plastic-roughdielectric", True,
     '<bsdf type="blendbsdf"><float name="weight" value="0.6"/>'
     '<bsdf type="plastic"/><bsdf type="roughdielectric"><string name="distribution" value="ggx"/>'
     '<float name="alpha" value="0.2"/></bsdf></bsdf>'),
    ("mask-diffuse", True,
     '<bsdf type="mask"><float name="opacity" value="0.3"/>'
     '<bsdf type="diffuse"><rgb name="reflectance" value="0.8, 0.5, 0.2"/></bsdf></bsdf>'),
    ("mask-twosided-roughplastic", True,
     '<bsdf type="mask"><bsdf type="twosided"><bsdf type="roughplastic"/></bsdf></bsdf>'),
    # principled: appended last so the earlier cases' random directions stay as they were.
    ("principled-default", False, '<bsdf type="principled"/>'),
    ("principled-diffuse-retro-sheen", False,
     '<bsdf type="principled"><rgb name="base_color" value="0.8, 0.3, 0.1"/>'
     '<float name="roughness" value="0.9"/><float name="sheen" value="0.8"/>'
     '<float name="sheen_tint" value="0.5"/></bsdf>'),
    ("principled-flatness", False,
     '<bsdf type="principled"><rgb name="base_color" value="0.2, 0.6, 0.4"/>'
     '<float name="roughness" value="0.7"/><float name="flatness" value="0.6"/></bsdf>'),
    ("principled-metal-anisotropic", False,
     '<bsdf type="principled"><rgb name="base_color" value="0.9, 0.6, 0.2"/>'
     '<float name="metallic" value="1"/><float name="roughness" value="0.4"/>'
     '<float name="anisotropic" value="0.8"/></bsdf>'),
    ("principled-half-metal-spec-tint", False,
     '<bsdf type="principled"><rgb name="base_color" value="0.2, 0.5, 0.9"/>'
     '<float name="metallic" value="0.5"/><float name="spec_tint" value="0.7"/>'
     '<float name="roughness" value="0.25"/><float name="specular" value="0.8"/></bsdf>'),
    ("principled-eta-below-one", False,
     '<bsdf type="principled"><float name="eta" value="0.8"/>'
     '<float name="roughness" value="0.3"/><float name="spec_tint" value="0.4"/></bsdf>'),
    ("principled-clearcoat", False,
     '<bsdf type="principled"><rgb name="base_color" value="0.1, 0.1, 0.5"/>'
     '<float name="clearcoat" value="1"/><float name="clearcoat_gloss" value="0.8"/>'
     '<float name="roughness" value="0.6"/></bsdf>'),
    ("principled-sampling-rates", False,
     '<bsdf type="principled"><float name="clearcoat" value="0.5"/>'
     '<float name="metallic" value="0.3"/><float name="anisotropic" value="0.4"/>'
     '<float name="diffuse_reflectance_sampling_rate" value="0.3"/>'
     '<float name="main_specular_sampling_rate" value="2"/>'
     '<float name="clearcoat_sampling_rate" value="0.7"/></bsdf>'),
    ("principled-spec-trans", True,
     '<bsdf type="principled"><float name="spec_trans" value="1"/>'
     '<float name="roughness" value="0.3"/></bsdf>'),
    ("principled-spec-trans-mixed", True,
     '<bsdf type="principled"><rgb name="base_color" value="0.8, 0.3, 0.1"/>'
     '<float name="spec_trans" value="0.6"/><float name="metallic" value="0.2"/>'
     '<float name="clearcoat" value="0.5"/><float name="anisotropic" value="0.5"/>'
     '<float name="eta" value="1.33"/><float name="sheen" value="0.4"/></bsdf>'),
    ("principled-twosided", False,
     '<bsdf type="twosided"><bsdf type="principled"><float name="roughness" value="0.2"/>'
     '<float name="clearcoat" value="0.3"/></bsdf></bsdf>'),
]

WO_DEGREES = [(5.0, 10.0), (30.0, 200.0), (60.0, 45.0), (80.0, 300.0)]


def unit(theta_deg: float, phi_deg: float) -> np.ndarray:
    t, p = math.radians(theta_deg), math.radians(phi_deg)
    return np.array([math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), math.cos(t)])


def refract(wo: np.ndarray, eta: float) -> np.ndarray | None:
    """Smooth refraction of wo about +-z; eta is inside over outside."""
    cos_o = wo[2]
    e = eta if cos_o > 0 else 1.0 / eta
    sin2_t = (1.0 - cos_o * cos_o) / (e * e)
    if sin2_t >= 1.0:
        return None
    cos_t = math.sqrt(1.0 - sin2_t)
    w = np.array([-wo[0] / e, -wo[1] / e, -math.copysign(cos_t, cos_o)])
    return w / np.linalg.norm(w)


def around(w: np.ndarray, rng: np.random.Generator, spread: float, n: int) -> list[np.ndarray]:
    out = []
    for _ in range(n):
        v = w + spread * rng.normal(size=3)
        out.append(v / np.linalg.norm(v))
    return out


def fmt(v) -> str:
    return " ".join(f"{float(x):.9g}" for x in v)


def main() -> None:
    out_path = Path(sys.argv[1]) if len(sys.argv) > 1 else REPO / "mcrt-render/tests/data/mitsuba-bsdf-values.txt"
    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    rng = np.random.default_rng(1)
    lines = [
        "# Mitsuba 3.9.1 (scalar_rgb) BSDF values, written by scripts/mitsuba_bsdf_values.py.",
        "# case NAME | <bsdf> element",
        "# e MODE wo.xyz wi.xyz f.rgb pdf     (MODE r: radiance, i: importance; f includes |cos wi|)",
        "# s wo.xyz u1 wi.xyz pdf weight.rgb eta   (a sample that chose a Dirac component)",
    ]
    sphere = [v / np.linalg.norm(v) for v in rng.normal(size=(16, 3))]
    for name, transmits, xml in CASES:
        bsdf = mi.load_string(xml.replace("<bsdf ", '<bsdf version="3.0.0" ', 1))
        params = mi.traverse(bsdf)
        eta = float(params["eta"]) if "eta" in params.keys() else 1.5
        lines.append(f"case {name} | {xml}")
        wos = [unit(t, p) for t, p in WO_DEGREES]
        if transmits:
            wos += [-w for w in wos[:3]]
        for wo in wos:
            si = mi.SurfaceInteraction3f()
            si.p = mi.Point3f(0, 0, 0)
            si.n = mi.Normal3f(0, 0, 1)
            si.sh_frame = mi.Frame3f(si.n)
            si.wi = mi.Vector3f(*wo)
            mirror = np.array([-wo[0], -wo[1], wo[2]])
            wis = list(sphere) + [mirror] + around(mirror, rng, 0.15, 4)
            t = refract(wo, eta) if transmits else None
            if t is not None:
                wis += [t] + around(t, rng, 0.15, 4)
            modes = [("r", mi.TransportMode.Radiance)]
            if transmits:
                modes.append(("i", mi.TransportMode.Importance))
            for wi in wis:
                for tag, mode in modes:
                    ctx = mi.BSDFContext(mode)
                    f = bsdf.eval(ctx, si, mi.Vector3f(*wi))
                    pdf = bsdf.pdf(ctx, si, mi.Vector3f(*wi))
                    lines.append(f"e {tag} {fmt(wo)} {fmt(wi)} {fmt(f)} {float(pdf):.9g}")
            for u1 in (0.001, 0.5, 0.999):
                ctx = mi.BSDFContext()
                bs, weight = bsdf.sample(ctx, si, u1, mi.Point2f(0.5, 0.5))
                if mi.has_flag(bs.sampled_type, mi.BSDFFlags.Delta) and bs.pdf > 0:
                    lines.append(
                        f"s {fmt(wo)} {u1} {fmt(bs.wo)} {float(bs.pdf):.9g} {fmt(weight)} {float(bs.eta):.9g}"
                    )
    out_path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    print(f"wrote {len(lines)} lines to {out_path}", file=sys.stderr)


if __name__ == "__main__":
    main()
