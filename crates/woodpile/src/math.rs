//! The transcendental functions of the library (powers, exponentials, logarithms, circular and
//! hyperbolic functions), computed by the `libm` crate on every platform rather than by the
//! platform's C library.
//!
//! `f64::sqrt` and the arithmetic operators are correctly rounded by IEEE 754, so they give
//! the same bits everywhere; `powf`, `exp`, `sin` and the rest are not: the standard library
//! hands them to the platform (glibc on Linux, the `libm` port in a browser), whose results
//! differ in the last bit now and then. A nonlinear chain carries such a bit through thousands
//! of steps (and through step-size choices) to about 1e-12 of a peak force. With one
//! implementation everywhere, a run gives the same numbers bit for bit on Linux, macOS, Windows
//! and in the browser (the docs' playground checks it against `woodpile simulate`).

/// f64's transcendental functions, by `libm` ([module docs](self)).
pub(crate) trait Libm: Sized {
    fn libm_powf(self, y: Self) -> Self;
    fn libm_exp(self) -> Self;
    fn libm_ln(self) -> Self;
    fn libm_log2(self) -> Self;
    fn libm_log10(self) -> Self;
    fn libm_sin(self) -> Self;
    fn libm_cos(self) -> Self;
    fn libm_sin_cos(self) -> (Self, Self);
    fn libm_asin(self) -> Self;
    fn libm_atan2(self, x: Self) -> Self;
    fn libm_sinh(self) -> Self;
    fn libm_cosh(self) -> Self;
    fn libm_tanh(self) -> Self;
    fn libm_cbrt(self) -> Self;
    fn libm_hypot(self, y: Self) -> Self;
}

impl Libm for f64 {
    #[inline]
    fn libm_powf(self, y: f64) -> f64 {
        libm::pow(self, y)
    }
    #[inline]
    fn libm_exp(self) -> f64 {
        libm::exp(self)
    }
    #[inline]
    fn libm_ln(self) -> f64 {
        libm::log(self)
    }
    #[inline]
    fn libm_log2(self) -> f64 {
        libm::log2(self)
    }
    #[inline]
    fn libm_log10(self) -> f64 {
        libm::log10(self)
    }
    #[inline]
    fn libm_sin(self) -> f64 {
        libm::sin(self)
    }
    #[inline]
    fn libm_cos(self) -> f64 {
        libm::cos(self)
    }
    #[inline]
    fn libm_sin_cos(self) -> (f64, f64) {
        libm::sincos(self)
    }
    #[inline]
    fn libm_asin(self) -> f64 {
        libm::asin(self)
    }
    #[inline]
    fn libm_atan2(self, x: f64) -> f64 {
        libm::atan2(self, x)
    }
    #[inline]
    fn libm_sinh(self) -> f64 {
        libm::sinh(self)
    }
    #[inline]
    fn libm_cosh(self) -> f64 {
        libm::cosh(self)
    }
    #[inline]
    fn libm_tanh(self) -> f64 {
        libm::tanh(self)
    }
    #[inline]
    fn libm_cbrt(self) -> f64 {
        libm::cbrt(self)
    }
    #[inline]
    fn libm_hypot(self, y: f64) -> f64 {
        libm::hypot(self, y)
    }
}

/// |z| of a complex number, by `libm` (`Complex::norm` is the platform's `hypot`).
pub(crate) fn modulus(z: nalgebra::Complex<f64>) -> f64 {
    z.re.libm_hypot(z.im)
}
