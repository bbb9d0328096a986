//! Adaptive Gauss–Legendre quadrature in `f64` over intervals and rectangles.
//!
//! A region is integrated with a 4-point rule (4×4 in 2D) and again as two halves (four
//! quarters in 2D); when the two estimates agree to `max(abs_tol, rel_tol·|I|)` and the
//! integrand is either zero at every node or nonzero at every node, the finer one is kept.
//! Otherwise each part recurses, down to [`MAX_DEPTH`] levels: a region that holds an edge
//! of the support (a disk's rim, a cone's edge, a sliver triangle) is never accepted on a
//! chance agreement of the two rules, and the edge is resolved to `2^-MAX_DEPTH` of a cell's
//! width. A support narrower than the node spacing of a cell (1/8 of its width) can still
//! be missed; the harness re-integrates such cells finely when samples land in them.

/// Deepest subdivision level.
pub(crate) const MAX_DEPTH: u32 = 6;

/// Deepest subdivision level in 1D.
pub(crate) const MAX_DEPTH_1D: u32 = 16;

/// Relative tolerance of each cell's integral.
pub(crate) const REL_TOL: f64 = 1e-5;

const NODES: [f64; 4] = [
    -0.861_136_311_594_052_6,
    -0.339_981_043_584_856_3,
    0.339_981_043_584_856_3,
    0.861_136_311_594_052_6,
];
const WEIGHTS: [f64; 4] = [
    0.347_854_845_137_453_8,
    0.652_145_154_862_546_2,
    0.652_145_154_862_546_2,
    0.347_854_845_137_453_8,
];

/// A rule's estimate and which kinds of node values it saw.
#[derive(Clone, Copy, Default)]
struct Est {
    value: f64,
    zero: bool,
    nonzero: bool,
}

impl Est {
    fn add(self, o: Est) -> Est {
        Est {
            value: self.value + o.value,
            zero: self.zero || o.zero,
            nonzero: self.nonzero || o.nonzero,
        }
    }

    /// Whether `self` (the finer estimate) may be accepted against `coarse`.
    fn accepts(self, coarse: Est, tol: f64) -> bool {
        let mixed = (self.zero || coarse.zero) && (self.nonzero || coarse.nonzero);
        !mixed && (self.value - coarse.value).abs() <= tol.max(REL_TOL * self.value.abs())
    }
}

fn node(acc: &mut Est, w: f64, v: f64) {
    acc.value += w * v;
    if v == 0.0 {
        acc.zero = true;
    } else {
        acc.nonzero = true;
    }
}

fn rule_1d(f: &dyn Fn(f64) -> f64, a: f64, b: f64) -> Est {
    let (c, h) = (0.5 * (a + b), 0.5 * (b - a));
    let mut s = Est::default();
    for (x, w) in NODES.iter().zip(WEIGHTS) {
        node(&mut s, w * h, f(c + h * x));
    }
    s
}

/// Subdivision levels forced when a cell holds samples but its integral came out 0 (a
/// support narrower than the quadrature nodes' spacing).
pub(crate) const REFINED_MIN_DEPTH: u32 = 6;

/// ∫ₐᵇ f, adaptively, to about `abs_tol` absolute error, subdividing at least `min_depth`
/// levels.
pub(crate) fn integrate_1d(
    f: &dyn Fn(f64) -> f64,
    a: f64,
    b: f64,
    abs_tol: f64,
    min_depth: u32,
) -> f64 {
    struct Ctx<'a> {
        f: &'a dyn Fn(f64) -> f64,
        min_depth: u32,
    }
    fn rec(c: &Ctx<'_>, a: f64, b: f64, coarse: Est, tol: f64, depth: u32) -> f64 {
        let m = 0.5 * (a + b);
        let (l, r) = (rule_1d(c.f, a, m), rule_1d(c.f, m, b));
        let fine = l.add(r);
        let converged = fine.accepts(coarse, tol);
        if depth >= MAX_DEPTH_1D.max(c.min_depth + 2) || (depth >= c.min_depth && converged) {
            return fine.value;
        }
        rec(c, a, m, l, 0.5 * tol, depth + 1) + rec(c, m, b, r, 0.5 * tol, depth + 1)
    }
    let c = Ctx { f, min_depth };
    rec(&c, a, b, rule_1d(f, a, b), abs_tol, 0)
}

/// A rectangle `[a0, a1] × [b0, b1]` of parameter space.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Rect {
    pub a0: f64,
    pub a1: f64,
    pub b0: f64,
    pub b1: f64,
}

impl Rect {
    fn quarters(self) -> [Rect; 4] {
        let (am, bm) = (0.5 * (self.a0 + self.a1), 0.5 * (self.b0 + self.b1));
        [
            Rect {
                a1: am,
                b1: bm,
                ..self
            },
            Rect {
                a0: am,
                b1: bm,
                ..self
            },
            Rect {
                a1: am,
                b0: bm,
                ..self
            },
            Rect {
                a0: am,
                b0: bm,
                ..self
            },
        ]
    }
}

fn rule_2d(f: &dyn Fn(f64, f64) -> f64, r: Rect) -> Est {
    let (ca, ha) = (0.5 * (r.a0 + r.a1), 0.5 * (r.a1 - r.a0));
    let (cb, hb) = (0.5 * (r.b0 + r.b1), 0.5 * (r.b1 - r.b0));
    let mut s = Est::default();
    for (y, wy) in NODES.iter().zip(WEIGHTS) {
        let b = cb + hb * y;
        for (x, wx) in NODES.iter().zip(WEIGHTS) {
            node(&mut s, wx * wy * ha * hb, f(ca + ha * x, b));
        }
    }
    s
}

/// ∬ f over `r`, adaptively, to about `abs_tol` absolute error, subdividing at least
/// `min_depth` levels.
pub(crate) fn integrate_2d(
    f: &dyn Fn(f64, f64) -> f64,
    r: Rect,
    abs_tol: f64,
    min_depth: u32,
) -> f64 {
    fn rec(
        f: &dyn Fn(f64, f64) -> f64,
        r: Rect,
        coarse: Est,
        tol: f64,
        depth: u32,
        min: u32,
    ) -> f64 {
        let q = r.quarters();
        let parts = q.map(|s| rule_2d(f, s));
        let fine = parts.iter().fold(Est::default(), |a, &p| a.add(p));
        if depth >= MAX_DEPTH.max(min + 2) || (depth >= min && fine.accepts(coarse, tol)) {
            return fine.value;
        }
        let mut s = 0.0;
        for (sub, c) in q.into_iter().zip(parts) {
            s += rec(f, sub, c, 0.25 * tol, depth + 1, min);
        }
        s
    }
    rec(f, r, rule_2d(f, r), abs_tol, 0, min_depth)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polynomials_are_exact() {
        let v = integrate_1d(&|x| x * x * x + 1.0, 0.0, 2.0, 1e-12, 0);
        assert!(v.is_finite() && (v - 6.0).abs() < 1e-12, "{v}");
        let r = Rect {
            a0: 0.0,
            a1: 1.0,
            b0: 0.0,
            b1: 2.0,
        };
        let v = integrate_2d(&|a, b| a * b, r, 1e-12, 0);
        assert!(v.is_finite() && (v - 1.0).abs() < 1e-12, "{v}");
    }

    #[test]
    fn discontinuity_is_resolved() {
        // Indicator of the unit disk over [-1,1]²: π.
        let r = Rect {
            a0: -1.0,
            a1: 1.0,
            b0: -1.0,
            b1: 1.0,
        };
        let disk = |a: f64, b: f64| if a * a + b * b < 1.0 { 1.0 } else { 0.0 };
        let v = integrate_2d(&disk, r, 1e-9, 0);
        assert!(
            v.is_finite() && (v - std::f64::consts::PI).abs() < 1e-3,
            "{v}"
        );
        let step = integrate_1d(&|x| if x < 0.3 { 1.0 } else { 0.0 }, 0.0, 1.0, 1e-12, 0);
        assert!(step.is_finite() && (step - 0.3).abs() < 1e-5, "{step}");
        // A sliver the nodes miss is found with a forced minimum depth.
        let sliver = |a: f64, _b: f64| if (0.5..0.51).contains(&a) { 1.0 } else { 0.0 };
        let unit = Rect {
            a0: 0.0,
            a1: 1.0,
            b0: 0.0,
            b1: 1.0,
        };
        assert_eq!(integrate_2d(&sliver, unit, 1e-12, 0), 0.0);
        let v = integrate_2d(&sliver, unit, 1e-12, REFINED_MIN_DEPTH);
        assert!(v.is_finite() && (v - 0.01).abs() < 5e-4, "{v}");
    }
}
