//! A first-order dual number with derivatives along `N` directions, x = re + Σ_k eps_k ε_k
//! (ε_j ε_k = 0): the scalar of every forward-mode derivative in the workspace (the
//! tangents dσ/dF, the parameter sensitivities, the derivative pass of an MPM run).
//!
//! It follows `num_dual::DualSVec64` rule for rule (product, quotient and chain rules with
//! the same expressions, so the same numbers to the bit for finite operands) but keeps
//! the derivative part as a plain vector of `N` numbers where `num-dual` keeps an
//! optional one: no branch on every operation, and every whole four of the `N` parts is
//! one 256-bit operation (`zip`). The one difference: where `num-dual` has no derivative
//! part and the other operand is infinite or NaN, this type gives 0 · ∞ = NaN in the
//! derivative part instead of none; the derivative pass stops on a non-finite derivative.
//!
//! Comparisons look at the real part only, so generic code takes the same branches in
//! dual arithmetic as in real arithmetic.

use nalgebra::SVector;
use num_dual::{DualNum, DualStruct, Mappable};
use num_traits::{FromPrimitive, Inv, Num, One, Signed, Zero};
use std::cmp::Ordering;
use std::fmt;
use std::iter::{Product, Sum};
use std::ops::{
    Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Rem, RemAssign, Sub, SubAssign,
};
use wide::f64x4;

/// re + Σ_k eps_k ε_k.
#[derive(Clone, Copy, Debug)]
pub struct Dual<const N: usize> {
    /// The value.
    pub re: f64,
    /// The derivatives along the `N` directions.
    pub eps: SVector<f64, N>,
}

impl<const N: usize> Dual<N> {
    /// `re` with derivatives `eps`.
    #[inline]
    pub fn new(re: f64, eps: SVector<f64, N>) -> Self {
        Dual { re, eps }
    }

    /// The constant `re` (zero derivatives).
    #[inline]
    pub fn from_re(re: f64) -> Self {
        Dual::new(re, SVector::zeros())
    }

    /// `re` with unit derivative along direction `k` (and zero along the others).
    #[inline]
    pub fn seeded(re: f64, k: usize) -> Self {
        let mut eps = SVector::zeros();
        eps[k] = 1.0;
        Dual::new(re, eps)
    }

    /// Add the derivatives of x y to these, the value left as it is: an accumulation
    /// whose values are known elsewhere (the derivative pass's node sums). The same
    /// operations as `self + x * y` on the derivatives.
    #[inline]
    pub fn add_derivatives_of_product(&mut self, x: &Dual<N>, y: &Dual<N>) {
        let product = combined(&x.eps, y.re, &y.eps, x.re);
        self.eps = zip(&self.eps, &product, |s, p| s + p, |s, p| s + p);
    }

    /// Subtract the derivatives of x y from these, the value left as it is (as
    /// `self - x * y` on the derivatives).
    #[inline]
    pub fn sub_derivatives_of_product(&mut self, x: &Dual<N>, y: &Dual<N>) {
        let product = combined(&x.eps, y.re, &y.eps, x.re);
        self.eps = zip(&self.eps, &product, |s, p| s - p, |s, p| s - p);
    }

    /// Add the derivatives of x a, a real, to these, the value left as it is (as
    /// `self + x * a` on the derivatives).
    #[inline]
    pub fn add_derivatives_scaled(&mut self, x: &Dual<N>, a: f64) {
        let product = scaled(&x.eps, a);
        self.eps = zip(&self.eps, &product, |s, p| s + p, |s, p| s + p);
    }

    /// f(x) from f(re) = `f0` and f'(re) = `f1`.
    #[inline]
    fn chain_rule(&self, f0: f64, f1: f64) -> Self {
        Dual::new(f0, scaled(&self.eps, f1))
    }
}

/// `wide(x, y)` entry by entry, four derivatives at a time in one 256-bit operation
/// (`wide::f64x4`), and `narrow(x_k, y_k)` for the last N mod 4: the same IEEE operations
/// in the same order either way (nothing is fused), so the same numbers as a loop, at
/// about half the instructions of what the compiler makes of the loop on a `Dual` (it
/// packs the value into the vector with shuffles).
#[inline(always)]
fn zip<const N: usize>(
    x: &SVector<f64, N>,
    y: &SVector<f64, N>,
    wide: impl Fn(f64x4, f64x4) -> f64x4,
    narrow: impl Fn(f64, f64) -> f64,
) -> SVector<f64, N> {
    let (x, y) = (x.as_slice(), y.as_slice());
    let mut out = SVector::<f64, N>::zeros();
    let four = |v: &[f64]| f64x4::new([v[0], v[1], v[2], v[3]]);
    let whole = N - N % 4;
    for k in (0..whole).step_by(4) {
        let result = wide(four(&x[k..]), four(&y[k..]));
        out.as_mut_slice()[k..k + 4].copy_from_slice(&result.to_array());
    }
    for k in whole..N {
        out[k] = narrow(x[k], y[k]);
    }
    out
}

/// x a + y b.
#[inline(always)]
fn combined<const N: usize>(
    x: &SVector<f64, N>,
    a: f64,
    y: &SVector<f64, N>,
    b: f64,
) -> SVector<f64, N> {
    let (a4, b4) = (f64x4::splat(a), f64x4::splat(b));
    zip(x, y, |x, y| x * a4 + y * b4, |x, y| x * a + y * b)
}

/// x a.
#[inline(always)]
fn scaled<const N: usize>(x: &SVector<f64, N>, a: f64) -> SVector<f64, N> {
    let a4 = f64x4::splat(a);
    zip(x, x, |x, _| x * a4, |x, _| x * a)
}

impl<const N: usize> Add<&Dual<N>> for &Dual<N> {
    type Output = Dual<N>;
    #[inline]
    fn add(self, other: &Dual<N>) -> Dual<N> {
        Dual::new(
            self.re + other.re,
            zip(&self.eps, &other.eps, |x, y| x + y, |x, y| x + y),
        )
    }
}

impl<const N: usize> Sub<&Dual<N>> for &Dual<N> {
    type Output = Dual<N>;
    #[inline]
    fn sub(self, other: &Dual<N>) -> Dual<N> {
        Dual::new(
            self.re - other.re,
            zip(&self.eps, &other.eps, |x, y| x - y, |x, y| x - y),
        )
    }
}

/// The product rule.
impl<const N: usize> Mul<&Dual<N>> for &Dual<N> {
    type Output = Dual<N>;
    #[inline]
    fn mul(self, other: &Dual<N>) -> Dual<N> {
        Dual::new(
            self.re * other.re,
            combined(&self.eps, other.re, &other.eps, self.re),
        )
    }
}

/// The quotient rule.
impl<const N: usize> Div<&Dual<N>> for &Dual<N> {
    type Output = Dual<N>;
    #[inline]
    fn div(self, other: &Dual<N>) -> Dual<N> {
        let inv = other.re.recip();
        let (r, s, inv4) = (
            f64x4::splat(other.re),
            f64x4::splat(self.re),
            f64x4::splat(inv),
        );
        let eps = zip(
            &self.eps,
            &other.eps,
            |x, y| (x * r - y * s) * inv4 * inv4,
            |x, y| (x * other.re - y * self.re) * inv * inv,
        );
        Dual::new(self.re * inv, eps)
    }
}

impl<const N: usize> Rem<&Dual<N>> for &Dual<N> {
    type Output = Dual<N>;
    fn rem(self, _: &Dual<N>) -> Dual<N> {
        unimplemented!("the remainder of dual numbers")
    }
}

/// `a op b`, `a op &b` and `&a op b` from `&a op &b`, and `a op= b` from `a op b`.
macro_rules! by_value {
    ($op:ident, $method:ident, $assign:ident, $assign_method:ident) => {
        impl<const N: usize> $op<Dual<N>> for Dual<N> {
            type Output = Dual<N>;
            #[inline]
            fn $method(self, other: Dual<N>) -> Dual<N> {
                (&self).$method(&other)
            }
        }
        impl<const N: usize> $op<&Dual<N>> for Dual<N> {
            type Output = Dual<N>;
            #[inline]
            fn $method(self, other: &Dual<N>) -> Dual<N> {
                (&self).$method(other)
            }
        }
        impl<const N: usize> $op<Dual<N>> for &Dual<N> {
            type Output = Dual<N>;
            #[inline]
            fn $method(self, other: Dual<N>) -> Dual<N> {
                self.$method(&other)
            }
        }
        impl<const N: usize> $assign for Dual<N> {
            #[inline]
            fn $assign_method(&mut self, other: Dual<N>) {
                *self = (&*self).$method(&other);
            }
        }
    };
}

by_value!(Add, add, AddAssign, add_assign);
by_value!(Sub, sub, SubAssign, sub_assign);
by_value!(Mul, mul, MulAssign, mul_assign);
by_value!(Div, div, DivAssign, div_assign);
by_value!(Rem, rem, RemAssign, rem_assign);

impl<const N: usize> Neg for Dual<N> {
    type Output = Dual<N>;
    #[inline]
    fn neg(self) -> Dual<N> {
        let sign = f64x4::splat(-0.0);
        Dual::new(
            -self.re,
            zip(&self.eps, &self.eps, |x, _| x ^ sign, |x, _| -x),
        )
    }
}

impl<const N: usize> Neg for &Dual<N> {
    type Output = Dual<N>;
    #[inline]
    fn neg(self) -> Dual<N> {
        -*self
    }
}

/// Operations with a real number: it scales both parts (·, /) or shifts the real part
/// (+, −).
impl<const N: usize> MulAssign<f64> for Dual<N> {
    #[inline]
    fn mul_assign(&mut self, other: f64) {
        self.re *= other;
        self.eps = scaled(&self.eps, other);
    }
}

impl<const N: usize> DivAssign<f64> for Dual<N> {
    #[inline]
    fn div_assign(&mut self, other: f64) {
        self.re /= other;
        let other4 = f64x4::splat(other);
        self.eps = zip(&self.eps, &self.eps, |x, _| x / other4, |x, _| x / other);
    }
}

impl<const N: usize> AddAssign<f64> for Dual<N> {
    #[inline]
    fn add_assign(&mut self, other: f64) {
        self.re += other;
    }
}

impl<const N: usize> SubAssign<f64> for Dual<N> {
    #[inline]
    fn sub_assign(&mut self, other: f64) {
        self.re -= other;
    }
}

impl<const N: usize> RemAssign<f64> for Dual<N> {
    fn rem_assign(&mut self, _: f64) {
        unimplemented!("the remainder of dual numbers")
    }
}

/// `a op x` from `a op= x` for a real `x`.
macro_rules! with_real {
    ($op:ident, $method:ident, $assign_method:ident) => {
        impl<const N: usize> $op<f64> for Dual<N> {
            type Output = Dual<N>;
            #[inline]
            fn $method(mut self, other: f64) -> Dual<N> {
                self.$assign_method(other);
                self
            }
        }
    };
}

with_real!(Mul, mul, mul_assign);
with_real!(Div, div, div_assign);
with_real!(Add, add, add_assign);
with_real!(Sub, sub, sub_assign);
with_real!(Rem, rem, rem_assign);

impl<const N: usize> From<f64> for Dual<N> {
    #[inline]
    fn from(re: f64) -> Self {
        Dual::from_re(re)
    }
}

impl<const N: usize> Zero for Dual<N> {
    #[inline]
    fn zero() -> Self {
        Dual::from_re(0.0)
    }
    #[inline]
    fn is_zero(&self) -> bool {
        self.re.is_zero()
    }
}

impl<const N: usize> One for Dual<N> {
    #[inline]
    fn one() -> Self {
        Dual::from_re(1.0)
    }
    #[inline]
    fn is_one(&self) -> bool {
        self.re.is_one()
    }
}

impl<const N: usize> Num for Dual<N> {
    type FromStrRadixErr = <f64 as Num>::FromStrRadixErr;
    fn from_str_radix(s: &str, radix: u32) -> Result<Self, Self::FromStrRadixErr> {
        f64::from_str_radix(s, radix).map(Dual::from_re)
    }
}

impl<const N: usize> Signed for Dual<N> {
    fn abs(&self) -> Self {
        if self.is_positive() {
            *self
        } else {
            -self
        }
    }
    fn abs_sub(&self, other: &Self) -> Self {
        if self.re > other.re {
            self - other
        } else {
            Self::zero()
        }
    }
    fn signum(&self) -> Self {
        if self.is_positive() {
            Self::one()
        } else if self.is_zero() {
            Self::zero()
        } else {
            -Self::one()
        }
    }
    fn is_positive(&self) -> bool {
        Signed::is_positive(&self.re)
    }
    fn is_negative(&self) -> bool {
        Signed::is_negative(&self.re)
    }
}

impl<const N: usize> Inv for Dual<N> {
    type Output = Self;
    fn inv(self) -> Self {
        self.recip()
    }
}

impl<const N: usize> Sum for Dual<N> {
    fn sum<I: Iterator<Item = Self>>(iter: I) -> Self {
        iter.fold(Self::zero(), |sum, x| sum + x)
    }
}

impl<'a, const N: usize> Sum<&'a Dual<N>> for Dual<N> {
    fn sum<I: Iterator<Item = &'a Dual<N>>>(iter: I) -> Self {
        iter.fold(Self::zero(), |sum, x| sum + x)
    }
}

impl<const N: usize> Product for Dual<N> {
    fn product<I: Iterator<Item = Self>>(iter: I) -> Self {
        iter.fold(Self::one(), |product, x| product * x)
    }
}

impl<'a, const N: usize> Product<&'a Dual<N>> for Dual<N> {
    fn product<I: Iterator<Item = &'a Dual<N>>>(iter: I) -> Self {
        iter.fold(Self::one(), |product, x| product * x)
    }
}

impl<const N: usize> FromPrimitive for Dual<N> {
    fn from_i64(n: i64) -> Option<Self> {
        f64::from_i64(n).map(Dual::from_re)
    }
    fn from_u64(n: u64) -> Option<Self> {
        f64::from_u64(n).map(Dual::from_re)
    }
    fn from_f64(n: f64) -> Option<Self> {
        Some(Dual::from_re(n))
    }
}

impl<const N: usize> PartialEq for Dual<N> {
    fn eq(&self, other: &Self) -> bool {
        self.re == other.re
    }
}

impl<const N: usize> PartialEq<f64> for Dual<N> {
    fn eq(&self, other: &f64) -> bool {
        self.re == *other
    }
}

impl<const N: usize> PartialOrd for Dual<N> {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        self.re.partial_cmp(&other.re)
    }
}

impl<const N: usize> PartialOrd<f64> for Dual<N> {
    fn partial_cmp(&self, other: &f64) -> Option<Ordering> {
        self.re.partial_cmp(other)
    }
}

impl<const N: usize> fmt::Display for Dual<N> {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        write!(f, "{}", self.re)?;
        for (k, e) in self.eps.iter().enumerate() {
            write!(f, " + {e}ε{k}")?;
        }
        Ok(())
    }
}

impl<const N: usize> DualStruct for Dual<N> {
    type Real = f64;
    type Inner = f64;
    fn re(&self) -> f64 {
        self.re
    }
    fn from_inner(inner: &f64) -> Self {
        Dual::from_re(*inner)
    }
}

impl<const N: usize> Mappable<Self> for Dual<N> {
    type Output<O> = O;
    fn map_dual<G: Fn(Self) -> O, O>(self, g: G) -> O {
        g(self)
    }
}

/// The elementary functions by the chain rule, f(x) = f(re) + f'(re) Σ eps_k ε_k.
impl<const N: usize> DualNum for Dual<N> {
    type Primitive = f64;
    const NDERIV: usize = 1;
    type InnerDual = f64;

    fn from_re(re: f64) -> Self {
        Dual::from_re(re)
    }
    #[inline]
    fn scale(self, factor: &f64) -> Self {
        self * *factor
    }
    #[inline]
    fn recip(&self) -> Self {
        let f0 = self.re.recip();
        self.chain_rule(f0, -f0 * f0)
    }
    #[inline]
    fn powi(&self, n: i32) -> Self {
        match n {
            0 => Self::one(),
            1 => *self,
            2 => self * self,
            _ => {
                let pow3 = self.re.powi(n - 3);
                let squared = pow3 * self.re * self.re;
                self.chain_rule(squared * self.re, squared * f64::from(n))
            }
        }
    }
    #[inline]
    fn powf(&self, n: f64) -> Self {
        if n == 0.0 {
            Self::one()
        } else if n == 1.0 {
            *self
        } else if (n - 1.0 - 1.0).abs() < f64::EPSILON {
            self * self
        } else {
            let pow3 = self.re.powf(n - 1.0 - 1.0 - 1.0);
            let squared = pow3 * self.re * self.re;
            self.chain_rule(squared * self.re, squared * n)
        }
    }
    #[inline]
    fn sqrt(&self) -> Self {
        let f0 = self.re.sqrt();
        self.chain_rule(f0, f0 * self.re.recip() * 0.5)
    }
    #[inline]
    fn cbrt(&self) -> Self {
        let f0 = self.re.cbrt();
        self.chain_rule(f0, f0 * self.re.recip() * (1.0 / 3.0))
    }
    #[inline]
    fn exp(&self) -> Self {
        let f = self.re.exp();
        self.chain_rule(f, f)
    }
    #[inline]
    fn exp2(&self) -> Self {
        let f0 = self.re.exp2();
        self.chain_rule(f0, f0 * 2f64.ln())
    }
    #[inline]
    fn exp_m1(&self) -> Self {
        self.chain_rule(self.re.exp_m1(), self.re.exp())
    }
    #[inline]
    fn ln(&self) -> Self {
        self.chain_rule(self.re.ln(), self.re.recip())
    }
    #[inline]
    fn log(&self, base: f64) -> Self {
        self.chain_rule(self.re.log(base), self.re.recip() / base.ln())
    }
    #[inline]
    fn log2(&self) -> Self {
        self.chain_rule(self.re.log2(), self.re.recip() / 2f64.ln())
    }
    #[inline]
    fn log10(&self) -> Self {
        self.chain_rule(self.re.log10(), self.re.recip() / std::f64::consts::LN_10)
    }
    #[inline]
    fn ln_1p(&self) -> Self {
        self.chain_rule(self.re.ln_1p(), (self.re + 1.0).recip())
    }
    #[inline]
    fn sin(&self) -> Self {
        let (s, c) = self.re.sin_cos();
        self.chain_rule(s, c)
    }
    #[inline]
    fn cos(&self) -> Self {
        let (s, c) = self.re.sin_cos();
        self.chain_rule(c, -s)
    }
    #[inline]
    fn tan(&self) -> Self {
        let (sin, cos) = self.sin_cos();
        sin / cos
    }
    #[inline]
    fn sin_cos(&self) -> (Self, Self) {
        let (s, c) = self.re.sin_cos();
        (self.chain_rule(s, c), self.chain_rule(c, -s))
    }
    #[inline]
    fn asin(&self) -> Self {
        let rec = (1.0 - self.re * self.re).recip();
        self.chain_rule(self.re.asin(), rec.sqrt())
    }
    #[inline]
    fn acos(&self) -> Self {
        let rec = (1.0 - self.re * self.re).recip();
        self.chain_rule(self.re.acos(), -rec.sqrt())
    }
    #[inline]
    fn atan(&self) -> Self {
        self.chain_rule(self.re.atan(), (1.0 + self.re * self.re).recip())
    }
    #[inline]
    fn atan2(&self, other: Self) -> Self {
        let mut angle = (self / other).atan();
        angle.re = self.re.atan2(other.re);
        angle
    }
    #[inline]
    fn sinh(&self) -> Self {
        self.chain_rule(self.re.sinh(), self.re.cosh())
    }
    #[inline]
    fn cosh(&self) -> Self {
        self.chain_rule(self.re.cosh(), self.re.sinh())
    }
    #[inline]
    fn tanh(&self) -> Self {
        self.sinh() / self.cosh()
    }
    #[inline]
    fn asinh(&self) -> Self {
        let rec = (1.0 + self.re * self.re).recip();
        self.chain_rule(self.re.asinh(), rec.sqrt())
    }
    #[inline]
    fn acosh(&self) -> Self {
        let rec = (self.re * self.re - 1.0).recip();
        self.chain_rule(self.re.acosh(), rec.sqrt())
    }
    #[inline]
    fn atanh(&self) -> Self {
        self.chain_rule(self.re.atanh(), (1.0 - self.re * self.re).recip())
    }
    fn sph_j0(&self) -> Self {
        if self.re.abs() < f64::EPSILON {
            Self::one() - self * self / 6.0
        } else {
            self.sin() / self
        }
    }
    fn sph_j1(&self) -> Self {
        if self.re.abs() < f64::EPSILON {
            *self / 3.0
        } else {
            let (s, c) = self.sin_cos();
            (s - self * c) / (self * self)
        }
    }
    fn sph_j2(&self) -> Self {
        if self.re.abs() < f64::EPSILON {
            self * self / 15.0
        } else {
            let (s, c) = self.sin_cos();
            let s2 = self * self;
            ((s - self * c) * 3.0 - s2 * s) / (s2 * self)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Dual;
    use num_dual::{DualNum, DualSVec64};
    use num_traits::Signed;

    /// x with derivatives (1, −0.5, 0.25, 2, −1.5, 0, 3, −0.125, 0.75)·`scale` (the first
    /// `N`) in both representations.
    fn pair<const N: usize>(x: f64, scale: f64) -> (Dual<N>, DualSVec64<N>) {
        let pattern = [1.0, -0.5, 0.25, 2.0, -1.5, 0.0, 3.0, -0.125, 0.75];
        let eps = nalgebra::SVector::<f64, N>::from_fn(|k, _| pattern[k] * scale);
        (
            Dual::new(x, eps),
            DualSVec64::new(x, num_dual::Derivative::some(eps)),
        )
    }

    /// Value and derivatives equal to the bit.
    fn same<const N: usize>(ours: Dual<N>, reference: DualSVec64<N>, what: &str) {
        let expected = reference.eps.0.unwrap_or_else(nalgebra::SVector::zeros);
        assert_eq!(ours.re.to_bits(), reference.re.to_bits(), "{what}: value");
        for k in 0..N {
            assert_eq!(
                ours.eps[k].to_bits(),
                expected[k].to_bits(),
                "{what}: derivative {k}: {} against {}",
                ours.eps[k],
                expected[k]
            );
        }
    }

    /// Every arithmetic rule and elementary function gives num-dual's numbers to the bit,
    /// on arguments inside each function's domain: with three directions (entry by entry),
    /// four (one 256-bit operation), six (four in one, two by entry; one derivative 0)
    /// and nine (two 256-bit operations and one entry).
    #[test]
    fn every_rule_gives_num_duals_numbers_to_the_bit() {
        every_rule::<3>();
        every_rule::<4>();
        every_rule::<6>();
        every_rule::<9>();
    }

    /// The accumulations of derivatives change the derivatives as the whole operation
    /// would, to the bit, and leave the value.
    #[test]
    fn accumulated_derivatives_are_those_of_the_whole_operation() {
        accumulated::<4>();
        accumulated::<6>();
    }

    fn accumulated<const N: usize>() {
        let (sum, _) = pair::<N>(0.4, 0.9);
        let (x, _) = pair::<N>(-1.7, 1.3);
        let (y, _) = pair::<N>(0.6, -0.7);
        let cases: [(Dual<N>, Dual<N>, &str); 3] = [
            (
                sum + x * y,
                with(sum, |s| s.add_derivatives_of_product(&x, &y)),
                "sum of products",
            ),
            (
                sum - x * y,
                with(sum, |s| s.sub_derivatives_of_product(&x, &y)),
                "difference",
            ),
            (
                sum + x * 2.5,
                with(sum, |s| s.add_derivatives_scaled(&x, 2.5)),
                "scaled",
            ),
        ];
        for (whole, accumulated, what) in cases {
            assert_eq!(accumulated.re, sum.re, "{what}: the value is left");
            for k in 0..N {
                assert_eq!(
                    accumulated.eps[k].to_bits(),
                    whole.eps[k].to_bits(),
                    "{what}: {k}"
                );
            }
        }
    }

    fn with<const N: usize>(mut x: Dual<N>, change: impl Fn(&mut Dual<N>)) -> Dual<N> {
        change(&mut x);
        x
    }

    fn every_rule<const N: usize>() {
        type Reference<const N: usize> = DualSVec64<N>;
        for &(x, y) in &[(0.3, 0.7), (0.9, -2.5), (0.05, 1.0 / 3.0)] {
            let (a, ra) = pair::<N>(x, 1.3);
            let (b, rb) = pair::<N>(y, -0.7);
            same(a + b, ra + rb, "sum");
            same(a - b, ra - rb, "difference");
            same(a * b, ra * rb, "product");
            same(a / b, ra / rb, "quotient");
            same(-a, -ra, "negation");
            same(a * 2.5, ra * 2.5, "real factor");
            same(a / 2.5, ra / 2.5, "real divisor");
            same(a + 2.5, ra + 2.5, "real shift");
            same(a.atan2(b), ra.atan2(rb), "atan2");
            type Unary<const N: usize> = (
                &'static str,
                fn(&Dual<N>) -> Dual<N>,
                fn(&Reference<N>) -> Reference<N>,
            );
            let unary: [Unary<N>; 27] = [
                ("recip", |x| x.recip(), |x| x.recip()),
                ("powi 0", |x| x.powi(0), |x| x.powi(0)),
                ("powi 2", |x| x.powi(2), |x| x.powi(2)),
                ("powi 5", |x| x.powi(5), |x| x.powi(5)),
                ("powi −3", |x| x.powi(-3), |x| x.powi(-3)),
                ("powf 2", |x| x.abs().powf(2.0), |x| x.abs().powf(2.0)),
                ("powf 0.26", |x| x.abs().powf(0.26), |x| x.abs().powf(0.26)),
                ("sqrt", |x| x.abs().sqrt(), |x| x.abs().sqrt()),
                ("cbrt", |x| x.cbrt(), |x| x.cbrt()),
                ("exp", |x| x.exp(), |x| x.exp()),
                ("exp2", |x| x.exp2(), |x| x.exp2()),
                ("exp_m1", |x| x.exp_m1(), |x| x.exp_m1()),
                ("ln", |x| x.abs().ln(), |x| x.abs().ln()),
                ("log 7", |x| x.abs().log(7.0), |x| x.abs().log(7.0)),
                ("log2", |x| x.abs().log2(), |x| x.abs().log2()),
                ("log10", |x| x.abs().log10(), |x| x.abs().log10()),
                ("ln_1p", |x| x.abs().ln_1p(), |x| x.abs().ln_1p()),
                ("sin", |x| x.sin(), |x| x.sin()),
                ("cos", |x| x.cos(), |x| x.cos()),
                ("tan", |x| x.tan(), |x| x.tan()),
                ("asin", |x| (*x * 0.3).asin(), |x| (*x * 0.3).asin()),
                ("acos", |x| (*x * 0.3).acos(), |x| (*x * 0.3).acos()),
                ("atan", |x| x.atan(), |x| x.atan()),
                ("tanh", |x| x.tanh(), |x| x.tanh()),
                ("asinh", |x| x.asinh(), |x| x.asinh()),
                (
                    "acosh",
                    |x| (*x * *x + 1.5).acosh(),
                    |x| (*x * *x + 1.5).acosh(),
                ),
                ("atanh", |x| (*x * 0.3).atanh(), |x| (*x * 0.3).atanh()),
            ];
            for (what, ours, reference) in unary {
                same(ours(&a), reference(&ra), what);
            }
            same(a.sph_j2(), ra.sph_j2(), "sph_j2");
            let (s, c) = a.sin_cos();
            let (rs, rc) = ra.sin_cos();
            same(s, rs, "sin of sin_cos");
            same(c, rc, "cos of sin_cos");
        }
    }

    /// A seeded number carries a unit derivative in its own direction only, and
    /// comparisons see the value alone.
    #[test]
    fn a_seed_is_a_unit_direction_and_comparisons_see_the_value() {
        let x = Dual::<4>::seeded(2.0, 2);
        assert_eq!(x.eps.as_slice(), &[0.0, 0.0, 1.0, 0.0]);
        assert_eq!((x * x).eps[2], 4.0);
        assert!(x == Dual::from_re(2.0));
        assert!(x < 2.5 && x > Dual::from_re(1.0));
    }
}
