//! Where generated code's math comes from: the `libm` crate without `std`
//! or with the `libm` feature (the same bits as on a device), the standard
//! library otherwise. Checked in both configurations (`.ci/run` also runs
//! this file with `--features libm`); whether sums of products fuse is
//! checked by the runtime's own `add_mul_rounds_once_exactly_where_it_fuses`.

use autosim_runtime::__private::math;

/// `true` where every math function is asked to come from `libm`.
const FROM_LIBM: bool = cfg!(any(not(feature = "std"), feature = "libm"));

#[test]
fn exp_ln_powers_and_roots_come_from_where_the_features_say() {
    let xs = [0.1_f64, 0.7, 1.3, 2.9, 17.25, 123.456, 1e-7, 700.0];
    for x in xs {
        let want = |libm: f64, std: f64| if FROM_LIBM { libm } else { std };
        assert_eq!(
            math::exp(x).to_bits(),
            want(libm::exp(x), x.exp()).to_bits(),
            "exp({x})"
        );
        assert_eq!(
            math::ln(x).to_bits(),
            want(libm::log(x), x.ln()).to_bits(),
            "ln({x})"
        );
        assert_eq!(
            math::powf(x, 1.37).to_bits(),
            want(libm::pow(x, 1.37), x.powf(1.37)).to_bits(),
            "powf({x})"
        );
        assert_eq!(
            math::sqrt(x).to_bits(),
            want(libm::sqrt(x), x.sqrt()).to_bits(),
            "sqrt({x})"
        );
        let x32 = x as f32;
        assert_eq!(
            math::exp(x32).to_bits(),
            (if FROM_LIBM {
                libm::expf(x32)
            } else {
                x32.exp()
            })
            .to_bits(),
            "expf({x32})"
        );
    }
}
