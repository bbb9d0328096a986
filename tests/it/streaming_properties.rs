//! Property tests of the streaming utilities: `WeightedReservoir` (the held item is one that
//! was offered with a positive weight; bad weights are ignored; merge keeps the totals) and
//! `VarianceEstimator` (agrees with a two-pass computation in f64 on data with a large
//! offset; merge equals one pass over the concatenation). Fixed seed.

use crate::props;
use mcrt::sampling::{VarianceEstimator, WeightedReservoir};
use props::config;
use proptest::prelude::*;

fn weight() -> impl Strategy<Value = f32> {
    prop_oneof![
        4 => 0.0f32..10.0,
        1 => Just(0.0f32),
        1 => Just(f32::NAN),
        1 => Just(-1.0f32),
        1 => Just(f32::INFINITY),
        1 => Just(f32::MAX),
        1 => Just(1e-45f32),
    ]
}

fn unit() -> impl Strategy<Value = f32> {
    prop_oneof![
        1 => Just(0.0f32),
        1 => Just(1.0 - 1.0 / 16_777_216.0),
        4 => 0.0f32..1.0,
    ]
}

/// Mean and unbiased variance by two passes in f64.
fn two_pass(xs: &[f64]) -> (f64, f64) {
    let n = xs.len() as f64;
    let mean = xs.iter().sum::<f64>() / n;
    let var = xs.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / (n - 1.0);
    (mean, var)
}

proptest! {
    #![proptest_config(config(512))]

    #[test]
    fn reservoir_holds_an_offered_positive_item(
        items in prop::collection::vec((weight(), unit()), 0..40),
        split in 0usize..40,
        u in unit(),
    ) {
        let split = split.min(items.len());
        let (mut a, mut b) = (WeightedReservoir::new(), WeightedReservoir::new());
        let mut total = 0.0f64;
        for (i, &(w, v)) in items.iter().enumerate() {
            let r = if i < split { &mut a } else { &mut b };
            r.add(i, w, v);
            if w.is_finite() && w >= 0.0 {
                total += f64::from(w);
            }
        }
        a.merge(b, u);
        prop_assert!(a.total_weight().is_finite() && (a.total_weight() - total).abs() <= 1e-9 * total);
        let p = a.probability();
        prop_assert!(p.is_finite() && (0.0..=1.0).contains(&p));
        match a.item() {
            Some(&i) => {
                let w = items[i].0;
                prop_assert!(w.is_finite() && w > 0.0 && a.item_weight() == w);
            }
            None => prop_assert!(items.iter().all(|&(w, _)| !(w.is_finite() && w > 0.0))),
        }
    }

    #[test]
    fn variance_matches_two_pass_and_merges(
        offset in prop_oneof![Just(0.0f64), Just(1e9), Just(-1e12)],
        xs in prop::collection::vec(-1.0f64..1.0, 2..200),
        split in 0usize..200,
    ) {
        let data: Vec<f64> = xs.iter().map(|x| offset + x).collect();
        let (mean, var) = two_pass(&data);
        let mut all = VarianceEstimator::new();
        data.iter().for_each(|&x| all.add(x));
        let scale = offset.abs().max(1.0);
        prop_assert!(all.mean().is_finite() && (all.mean() - mean).abs() <= 1e-14 * scale);
        // Both methods see each deviation x − mean with a rounding of a few ε·offset, which
        // moves the variance by about 2 · spread · that.
        let tol = 1e-9 * var + 8.0 * var.sqrt() * f64::EPSILON * scale + 1e-30;
        prop_assert!(all.variance().is_finite() && (all.variance() - var).abs() <= tol, "{} vs {var}", all.variance());
        let split = split.min(data.len());
        let (mut a, mut b) = (VarianceEstimator::new(), VarianceEstimator::new());
        data[..split].iter().for_each(|&x| a.add(x));
        data[split..].iter().for_each(|&x| b.add(x));
        a.merge(&b);
        prop_assert_eq!(a.count(), all.count());
        prop_assert!(a.variance().is_finite() && (a.variance() - all.variance()).abs() <= tol);
        prop_assert!(all.variance() >= 0.0 && all.variance_of_mean() >= 0.0);
    }
}
