//! The number type the solver is written over: `f64` for one run, [`Lane`] for several runs
//! advanced together in SIMD lanes (`crate::lanes`).
//!
//! The equations of motion (`crate::ode::Equations`), the contact laws
//! ([`crate::model::ContactLaw`]), the stage loop, the error terms and the crossing prediction
//! (`crate::integrate`) are written once over [`Real`]. Every operation of [`Lane`] is the IEEE
//! operation of `f64` lane by lane (no fused multiply–add, square roots correctly rounded), so a
//! lane computes bit for bit what the `f64` instance computes for the same run.

// Lane loops index several arrays by the lane number l: the plain form that LLVM vectorizes.
#![allow(clippy::needless_range_loop)]

use std::ops::{Add, Div, Mul, Neg, Sub};

/// The most lanes a [`Real`] has (fixed-size per-lane arrays are this long).
pub(crate) const MAX_LANES: usize = 8;

/// Per-lane booleans (the first [`Real::LANES`] are used).
pub(crate) type Mask = [bool; MAX_LANES];

/// Arithmetic over one value (`f64`) or one value per lane ([`Lane`]).
pub(crate) trait Real:
    Copy
    + std::fmt::Debug
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// How many runs one value carries.
    const LANES: usize;
    /// Zero in every lane.
    const ZERO: Self;
    /// `x` in every lane.
    fn splat(x: f64) -> Self;
    /// Lane `l`'s value.
    fn lane(self, l: usize) -> f64;
    /// Sets lane `l`'s value.
    fn set_lane(&mut self, l: usize, x: f64);
    /// Square root, lane by lane.
    fn sqrt(self) -> Self;
    /// Absolute value, lane by lane.
    fn abs(self) -> Self;
    /// `f64::max`, lane by lane (NaN gives the other operand).
    fn max(self, o: Self) -> Self;
    /// `yes` where the value is > 0, `no` elsewhere (NaN: `no`).
    fn if_positive(self, yes: Self, no: Self) -> Self;
    /// `yes` where the value is < 0, `no` elsewhere (NaN: `no`).
    fn if_negative(self, yes: Self, no: Self) -> Self;
    /// `yes` where the value is exactly 0, `no` elsewhere.
    fn if_zero(self, yes: Self, no: Self) -> Self;
    /// `yes` where `mask` is set, `no` elsewhere.
    fn select(mask: Mask, yes: Self, no: Self) -> Self;
}

impl Real for f64 {
    const LANES: usize = 1;
    const ZERO: Self = 0.0;
    #[inline(always)]
    fn splat(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn lane(self, _l: usize) -> f64 {
        self
    }
    #[inline(always)]
    fn set_lane(&mut self, _l: usize, x: f64) {
        *self = x;
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
    #[inline(always)]
    fn abs(self) -> Self {
        f64::abs(self)
    }
    #[inline(always)]
    fn max(self, o: Self) -> Self {
        f64::max(self, o)
    }
    #[inline(always)]
    fn if_positive(self, yes: Self, no: Self) -> Self {
        if self > 0.0 {
            yes
        } else {
            no
        }
    }
    #[inline(always)]
    fn if_negative(self, yes: Self, no: Self) -> Self {
        if self < 0.0 {
            yes
        } else {
            no
        }
    }
    #[inline(always)]
    fn if_zero(self, yes: Self, no: Self) -> Self {
        if self == 0.0 {
            yes
        } else {
            no
        }
    }
    #[inline(always)]
    fn select(mask: Mask, yes: Self, no: Self) -> Self {
        if mask[0] {
            yes
        } else {
            no
        }
    }
}

/// One value per lane, with IEEE arithmetic lane by lane. Operations take and return values, so
/// that each reads its operands whole before it writes: the form LLVM turns into one vector
/// instruction per operation (indexing arrays in place left it scalar: stores may alias loads).
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(transparent)]
pub(crate) struct Lane<const L: usize>(pub(crate) [f64; L]);

impl Lane<4> {
    /// The sum of the four lanes, the halves first: (l₀ + l₂) + (l₁ + l₃) (one vector add of
    /// the two halves, then one of the pair). Passes over groups of four modes end with it.
    #[inline(always)]
    pub(crate) fn sum(self) -> f64 {
        (self.0[0] + self.0[2]) + (self.0[1] + self.0[3])
    }
}

impl<const L: usize> Default for Lane<L> {
    fn default() -> Self {
        Lane([0.0; L])
    }
}

impl<const L: usize> Lane<L> {
    #[inline(always)]
    fn map(self, f: impl Fn(f64) -> f64) -> Self {
        let mut r = [0.0; L];
        for l in 0..L {
            r[l] = f(self.0[l]);
        }
        Lane(r)
    }

    #[inline(always)]
    fn zip(self, o: Self, f: impl Fn(f64, f64) -> f64) -> Self {
        let mut r = [0.0; L];
        for l in 0..L {
            r[l] = f(self.0[l], o.0[l]);
        }
        Lane(r)
    }

    /// Lane by lane: `yes` where `test` holds for this value, `no` elsewhere (a compare and a
    /// blend).
    #[inline(always)]
    fn choose(self, test: impl Fn(f64) -> bool, yes: Self, no: Self) -> Self {
        let mut r = [0.0; L];
        for l in 0..L {
            r[l] = if test(self.0[l]) { yes.0[l] } else { no.0[l] };
        }
        Lane(r)
    }
}

impl<const L: usize> Real for Lane<L> {
    const LANES: usize = L;
    const ZERO: Self = Lane([0.0; L]);
    #[inline(always)]
    fn splat(x: f64) -> Self {
        Lane([x; L])
    }
    #[inline(always)]
    fn lane(self, l: usize) -> f64 {
        self.0[l]
    }
    #[inline(always)]
    fn set_lane(&mut self, l: usize, x: f64) {
        self.0[l] = x;
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        self.map(f64::sqrt)
    }
    #[inline(always)]
    fn abs(self) -> Self {
        self.map(f64::abs)
    }
    #[inline(always)]
    fn max(self, o: Self) -> Self {
        self.zip(o, f64::max)
    }
    #[inline(always)]
    fn if_positive(self, yes: Self, no: Self) -> Self {
        self.choose(|x| x > 0.0, yes, no)
    }
    #[inline(always)]
    fn if_negative(self, yes: Self, no: Self) -> Self {
        self.choose(|x| x < 0.0, yes, no)
    }
    #[inline(always)]
    fn if_zero(self, yes: Self, no: Self) -> Self {
        self.choose(|x| x == 0.0, yes, no)
    }
    #[inline(always)]
    fn select(mask: Mask, yes: Self, no: Self) -> Self {
        let mut r = [0.0; L];
        for l in 0..L {
            r[l] = if mask[l] { yes.0[l] } else { no.0[l] };
        }
        Lane(r)
    }
}

macro_rules! lane_op {
    ($trait:ident, $method:ident, $op:tt) => {
        impl<const L: usize> $trait for Lane<L> {
            type Output = Self;
            #[inline(always)]
            fn $method(self, o: Self) -> Self {
                self.zip(o, |a, b| a $op b)
            }
        }
    };
}
lane_op!(Add, add, +);
lane_op!(Sub, sub, -);
lane_op!(Mul, mul, *);
lane_op!(Div, div, /);

impl<const L: usize> Neg for Lane<L> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        self.map(|a| -a)
    }
}

/// Whether the sign (> 0 or not) of `a` differs from that of `b` in any lane: one compare over
/// the lanes, so that lane-by-lane work runs only where a contact may cross.
#[inline(always)]
pub(crate) fn sign_changed<R: Real>(a: R, b: R) -> bool {
    let mut changed = false;
    for l in 0..R::LANES {
        changed |= (a.lane(l) > 0.0) != (b.lane(l) > 0.0);
    }
    changed
}
