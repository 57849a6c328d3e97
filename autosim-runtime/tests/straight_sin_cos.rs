//! The branch-free sines and cosines generated code calls against libm's
//! and the platform's `sin`/`cos`: `Float::sin_cos_inline` (the pair)
//! within one unit in the last place of the reference value up to 10 rad,
//! two up to 1e6 rad; `Float::sin_inline` and `Float::cos_inline` (one of
//! them alone) within two up to 1e6 rad; libm's own values beyond, exact
//! special values, and `f32` through `f64`.

use autosim_runtime::Float;
use autosim_test_support::worst_of;

/// The distance of `a` from `reference` in units in the last place of
/// `reference`.
fn ulps(a: f64, reference: f64) -> f64 {
    if a == reference {
        return 0.0;
    }
    let exponent = (reference.abs().max(f64::MIN_POSITIVE)).log2().floor();
    (a - reference).abs() / 2f64.powf(exponent - 52.0)
}

/// SplitMix64, uniform in `[-1, 1)`.
fn uniform(state: &mut u64) -> f64 {
    *state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^= z >> 31;
    (z >> 11) as f64 / (1u64 << 52) as f64 - 1.0
}

/// The worst distance of `sin_cos(x)` from libm's and the platform's
/// values over 200 000 random angles at each scale.
fn worst_over(scales: &[f64], seed: u64, sin_cos: impl Fn(f64) -> (f64, f64)) -> f64 {
    let mut state = seed;
    let mut worst: f64 = 0.0;
    for scale in scales {
        for _ in 0..200_000 {
            let x = uniform(&mut state) * scale;
            let (s, c) = sin_cos(x);
            let (ls, lc) = libm::sincos(x);
            for (value, reference) in [(s, ls), (c, lc), (s, x.sin()), (c, x.cos())] {
                worst = worst_of(worst, ulps(value, reference));
            }
        }
    }
    worst
}

#[test]
fn within_one_ulp_of_libm_and_the_platform_up_to_ten_radians() {
    let worst = worst_over(&[1e-8, 1e-3, 0.5, 1.0, 3.2, 10.0], 1, f64::sin_cos_inline);
    assert!(worst <= 1.0, "{worst} ulp");
}

#[test]
fn within_two_ulps_up_to_a_million_radians() {
    let worst = worst_over(&[1e3, 1e5, 1e6, 1e7], 2, f64::sin_cos_inline);
    assert!(worst <= 2.0, "{worst} ulp");
}

/// `sin_cos(x)` within two units in the last place of libm's at every
/// multiple of π/2 up to 40 000 quarter turns and its two neighbours:
/// where a reduced angle is smallest its error counts most (multiples of
/// π for a sine, odd multiples of π/2 for a cosine), and the others put
/// a polynomial at the ends of its interval.
fn within_two_ulps_near_quarter_turns(sin_cos: impl Fn(f64) -> (f64, f64)) {
    for k in -40_000i32..40_000 {
        let x = f64::from(k) * std::f64::consts::FRAC_PI_2;
        for x in [x, x.next_up(), x.next_down()] {
            let (s, c) = sin_cos(x);
            let (ls, lc) = libm::sincos(x);
            assert!(ulps(s, ls) <= 2.0, "sin {x:e}: {s:e} against {ls:e}");
            assert!(ulps(c, lc) <= 2.0, "cos {x:e}: {c:e} against {lc:e}");
        }
    }
}

#[test]
fn near_multiples_of_a_quarter_turn() {
    within_two_ulps_near_quarter_turns(f64::sin_cos_inline);
}

#[test]
fn special_values() {
    let (s, c) = (-0.0f64).sin_cos_inline();
    assert!(s == 0.0 && s.is_sign_negative() && c == 1.0);
    assert_eq!(0.0f64.sin_cos_inline(), (0.0, 1.0));
    for x in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let (s, c) = x.sin_cos_inline();
        assert!(s.is_nan() && c.is_nan());
    }
    let (s, c) = 1e300f64.sin_cos_inline();
    assert_eq!((s, c), libm::sincos(1e300));
}

#[test]
fn f32_rounds_the_f64_result() {
    let mut state = 7;
    for _ in 0..100_000 {
        let x = (uniform(&mut state) * 4.0) as f32;
        let (s, c) = f64::from(x).sin_cos_inline();
        assert_eq!(x.sin_cos_inline(), (s as f32, c as f32));
    }
}

#[test]
fn lanes_equal_one_call_per_angle_bit_for_bit() {
    let mut state = 7;
    let specials = [0.0, -0.0, 1e-12, 2e6, f64::NAN, f64::INFINITY, 0.7, -3.0];
    for round in 0..20_000 {
        let mut pair = [uniform(&mut state) * 10.0, uniform(&mut state) * 1e3];
        if round % 100 == 0 {
            pair[round / 100 % 2] = specials[round / 200 % specials.len()];
        }
        let (s, c) = f64::sin_cos_inline_lanes(pair);
        for lane in 0..2 {
            let (ls, lc) = pair[lane].sin_cos_inline();
            assert_eq!(s[lane].to_bits(), ls.to_bits(), "sin {}", pair[lane]);
            assert_eq!(c[lane].to_bits(), lc.to_bits(), "cos {}", pair[lane]);
        }
    }
    let (s, c) = f32::sin_cos_inline_lanes([0.5f32, -2.0, 3.0, 100.0]);
    assert_eq!(
        (s[1], c[3]),
        ((-2.0f32).sin_cos_inline().0, 100f32.sin_cos_inline().1)
    );
}

#[test]
fn alone_within_two_ulps_up_to_a_million_radians() {
    let scales = [1e-8, 1e-3, 0.5, 1.0, 1.6, 3.2, 10.0, 1e3, 1e5, 1e6, 1e7];
    let worst = worst_over(&scales, 3, |x| (x.sin_inline(), x.cos_inline()));
    assert!(worst <= 2.0, "{worst} ulp");
}

#[test]
fn alone_near_multiples_of_a_quarter_turn() {
    within_two_ulps_near_quarter_turns(|x| (x.sin_inline(), x.cos_inline()));
}

#[test]
fn alone_special_values() {
    let s = (-0.0f64).sin_inline();
    assert!(s == 0.0 && s.is_sign_negative());
    assert_eq!((-0.0f64).cos_inline(), 1.0);
    assert_eq!((0.0f64.sin_inline(), 0.0f64.cos_inline()), (0.0, 1.0));
    for x in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        assert!(x.sin_inline().is_nan() && x.cos_inline().is_nan());
    }
    for x in [1e300, -3e7, 1e-12] {
        assert_eq!((x.sin_inline(), x.cos_inline()), libm::sincos(x));
    }
}

#[test]
fn alone_f32_rounds_the_f64_result() {
    let mut state = 9;
    for _ in 0..100_000 {
        let x = (uniform(&mut state) * 4.0) as f32;
        let (s, c) = (f64::from(x).sin_inline(), f64::from(x).cos_inline());
        assert_eq!((x.sin_inline(), x.cos_inline()), (s as f32, c as f32));
    }
}
