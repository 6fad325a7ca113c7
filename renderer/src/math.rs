//! The renderer's transcendental functions, the same bits on every platform.
//!
//! The standard library's `sin`, `exp`, `powf` and the like call the
//! platform's C math library, whose last bits differ between glibc
//! versions, macOS and Windows; the golden images are compared exactly, so
//! a pixel must not depend on them. Every such call in the renderer (its
//! unit tests too) is one of these functions instead, and each calls the
//! `libm` crate (musl's math library in pure Rust), which computes the same
//! result wherever it runs. `sqrt` is exact (IEEE 754 rounds it correctly)
//! and stays the standard one; integer powers are explicit multiplications
//! ([`powi`]). A function needed that is not here is added here, calling
//! `libm`.

/// Sine of `x` (radians).
pub(crate) fn sin(x: f64) -> f64 {
    libm::sin(x)
}

/// Cosine of `x` (radians).
pub(crate) fn cos(x: f64) -> f64 {
    libm::cos(x)
}

/// Tangent of `x` (radians).
pub(crate) fn tan(x: f64) -> f64 {
    libm::tan(x)
}

/// e^x.
pub(crate) fn exp(x: f64) -> f64 {
    libm::exp(x)
}

/// The natural logarithm.
#[cfg_attr(not(test), allow(dead_code))]
pub(crate) fn ln(x: f64) -> f64 {
    libm::log(x)
}

/// e^x - 1, accurate near 0.
pub(crate) fn exp_m1(x: f64) -> f64 {
    libm::expm1(x)
}

/// x^y for a real exponent.
pub(crate) fn powf(x: f64, y: f64) -> f64 {
    libm::pow(x, y)
}

/// x^n by squaring and multiplying, in the order of compiler-builtins'
/// `__powidf2` (which the standard `powi` may or may not call, depending on
/// how the optimiser expands it): x^5 = x (x^2)^2, rounded the same everywhere.
pub(crate) fn powi(x: f64, n: u32) -> f64 {
    let (mut base, mut n, mut product) = (x, n, 1.0);
    loop {
        if n & 1 != 0 {
            product *= base;
        }
        n >>= 1;
        if n == 0 {
            return product;
        }
        base *= base;
    }
}

/// Hyperbolic sine.
pub(crate) fn sinh(x: f64) -> f64 {
    libm::sinh(x)
}

/// Hyperbolic cosine.
pub(crate) fn cosh(x: f64) -> f64 {
    libm::cosh(x)
}

/// Inverse hyperbolic sine.
pub(crate) fn asinh(x: f64) -> f64 {
    libm::asinh(x)
}

/// Inverse hyperbolic tangent.
pub(crate) fn atanh(x: f64) -> f64 {
    libm::atanh(x)
}

/// The angle of the point (x, y) from the +x axis, in (-pi, pi].
pub(crate) fn atan2(y: f64, x: f64) -> f64 {
    libm::atan2(y, x)
}

/// The angle in [0, pi] whose cosine is `x`.
pub(crate) fn acos(x: f64) -> f64 {
    libm::acos(x)
}

/// sqrt(x^2 + y^2) without undue overflow or underflow.
pub(crate) fn hypot(x: f64, y: f64) -> f64 {
    libm::hypot(x, y)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Known results, to the bit, recorded from `libm` 0.2.16: a change of
    /// implementation (a new `libm` release, or a call that slipped back to
    /// the platform's library) shows here before it shows in a golden image.
    /// Some of these differ from glibc's in the last bit (e^1 is one unit
    /// above `f64::consts::E`, 0.7^20 one above glibc's).
    #[test]
    fn known_values_to_the_bit() {
        let cases: [(&str, f64, u64); 12] = [
            ("sin(1)", sin(1.0), 0x3fea_ed54_8f09_0cee),
            ("cos(1)", cos(1.0), 0x3fe1_4a28_0fb5_068c),
            ("tan(0.5)", tan(0.5), 0x3fe1_7b4f_5bf3_474a),
            ("exp(1)", exp(1.0), 0x4005_bf0a_8b14_576a),
            ("exp(-0.5)", exp(-0.5), 0x3fe3_68b2_fc6f_960a),
            ("exp_m1(1e-3)", exp_m1(1e-3), 0x3f50_6466_dfb8_cf3a),
            ("powf(0.7, 20)", powf(0.7, 20.0), 0x3f4a_2575_df01_0dca),
            ("sinh(0.5)", sinh(0.5), 0x3fe0_acd0_0fe6_3b97),
            ("cosh(0.5)", cosh(0.5), 0x3ff2_0ac1_862a_e8d0),
            ("atanh(0.9)", atanh(0.9), 0x3ff7_8e36_0604_b32d),
            ("asinh(2)", asinh(2.0), 0x3ff7_1921_8313_d087),
            ("hypot(3, 4.5)", hypot(3.0, 4.5), 0x4015_a220_7349_0377),
        ];
        for (name, got, bits) in cases {
            assert_eq!(got.to_bits(), bits, "{name} = {got:e}");
        }
    }

    #[test]
    fn integer_powers_multiply_in_a_fixed_order() {
        let x = 1.1;
        assert_eq!(powi(x, 0), 1.0);
        assert_eq!(powi(x, 1), x);
        assert_eq!(powi(x, 2), x * x);
        assert_eq!(powi(x, 3), x * (x * x));
        assert_eq!(powi(x, 4), (x * x) * (x * x));
        assert_eq!(powi(x, 5), x * ((x * x) * (x * x)));
        assert_eq!(powi(-2.0, 3), -8.0);
    }
}
