//! Property tests of the light BVH (fixed seed): no input, however odd (NaN, infinite or
//! huge coordinates, zero or huge powers, degenerate boxes and cones), makes `new` panic;
//! an accepted set never gives a NaN, `sample` returns what `pmf` gives bit for bit, and the
//! pmf sums to 1 wherever something is sampled.

use crate::props;
use mcrt::glam::Vec3;
use mcrt::sampling::light_bvh::{LightBounds, LightBvh};
use props::{config, float_in, unit};
use proptest::prelude::*;

/// A coordinate: moderate, tiny, huge or not finite.
fn coord() -> impl Strategy<Value = f32> {
    prop_oneof![
        12 => float_in(-20.0, 20.0),
        1 => float_in(-1e-30, 1e-30),
        1 => prop_oneof![Just(3e38f32), Just(-3e38f32), Just(1e20f32)],
        1 => prop_oneof![Just(f32::NAN), Just(f32::INFINITY)],
    ]
}

fn vec3() -> impl Strategy<Value = Vec3> {
    (coord(), coord(), coord()).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

/// A cosine: in range, at its ends, or out of it.
fn cosine() -> impl Strategy<Value = f32> {
    prop_oneof![
        8 => float_in(-1.0, 1.0),
        2 => prop_oneof![Just(-1.0f32), Just(1.0f32), Just(0.0f32)],
        1 => prop_oneof![Just(1.5f32), Just(f32::NAN)],
    ]
}

fn power() -> impl Strategy<Value = f32> {
    prop_oneof![
        8 => float_in(0.0, 100.0),
        2 => prop_oneof![Just(0.0f32), Just(1e-40f32), Just(3e38f32)],
        1 => prop_oneof![Just(-1.0f32), Just(f32::NAN), Just(f32::INFINITY)],
    ]
}

fn light() -> impl Strategy<Value = LightBounds> {
    (
        vec3(),
        (float_in(0.0, 5.0), float_in(0.0, 5.0), float_in(0.0, 5.0)),
        vec3(),
        cosine(),
        cosine(),
        any::<bool>(),
        power(),
    )
        .prop_map(
            |(min, (dx, dy, dz), axis, cos_theta_o, cos_theta_e, two_sided, power)| LightBounds {
                min,
                max: min + Vec3::new(dx, dy, dz),
                axis,
                cos_theta_o,
                cos_theta_e,
                two_sided,
                power,
            },
        )
}

proptest! {
    #![proptest_config(config(2048))]

    #[test]
    fn no_input_gives_nan_or_panic(
        lights in prop::collection::vec(light(), 0..40),
        p in vec3(),
        n in vec3(),
        us in prop::collection::vec(unit(), 8),
    ) {
        let Ok(bvh) = LightBvh::new(&lights) else {
            // Refused: some light has a bad field.
            return Ok(());
        };
        prop_assert!(bvh.depth() <= 64);
        let pmf: Vec<f32> = (0..lights.len()).map(|i| bvh.pmf(p, n, i)).collect();
        prop_assert!(pmf.iter().all(|x| x.is_finite() && (0.0..=1.0).contains(x)), "{pmf:?}");
        let total: f64 = pmf.iter().map(|&x| f64::from(x)).sum();
        for &u in &us {
            match bvh.sample(p, n, u) {
                Some((i, prob)) => {
                    prop_assert!(i < lights.len() && lights[i].power > 0.0);
                    prop_assert!(prob.is_finite() && prob > 0.0);
                    prop_assert_eq!(prob.to_bits(), pmf[i].to_bits());
                    prop_assert!((total - 1.0).abs() < 1e-4, "Σ pmf = {}", total);
                }
                None => prop_assert_eq!(total, 0.0),
            }
        }
    }
}
