//! Validated inputs shared by every formula: the clip planes, eye depths and depth-buffer bits.
//!
//! Every public function checks its inputs here first, so the rules (and their messages) exist
//! once: NaN and stray infinities are [`ErrorKind::NotFinite`], values outside the domain are
//! [`ErrorKind::Domain`].

use crate::error::{Error, ErrorKind, Result};

/// A valid pair of clip-plane distances: `0 < n < f`, `n` finite, `f` finite or `+∞`.
///
/// Distances are positive, measured along the view direction (OpenGL eye space looks down −z,
/// so the planes lie at `z = −n` and `z = −f`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Planes {
    near: f64,
    far: f64,
}

impl Planes {
    /// Checks `n` and `f`.
    ///
    /// # Errors
    /// [`ErrorKind::NotFinite`] if `n` is NaN or infinite, or `f` is NaN or `−∞`;
    /// [`ErrorKind::Domain`] if `n ≤ 0` or `f ≤ n`.
    pub fn new(near: f64, far: f64) -> Result<Self> {
        finite(near, "the near plane distance n is NaN or infinite")?;
        if far.is_nan() || far == f64::NEG_INFINITY {
            return Err(
                not_finite("the far plane distance f is NaN or -infinity").with_value("f", far)
            );
        }
        if near <= 0.0 {
            return Err(
                domain("the near plane distance n must be greater than 0").with_value("n", near)
            );
        }
        if far <= near {
            return Err(
                domain("the far plane distance f must be greater than n").with_value("f", far)
            );
        }
        Ok(Self { near, far })
    }

    /// Planes already checked as [`Self::new`] does (`0 < n < ∞`, `f > n`).
    #[inline]
    pub(crate) fn unchecked(near: f64, far: f64) -> Self {
        debug_assert!(near > 0.0 && near < f64::INFINITY && far > near);
        Self { near, far }
    }

    /// The near plane distance `n`.
    pub fn near(&self) -> f64 {
        self.near
    }

    /// The far plane distance `f` (may be `+∞`).
    pub fn far(&self) -> f64 {
        self.far
    }

    /// Whether the far plane is at infinity.
    pub fn is_infinite(&self) -> bool {
        self.far == f64::INFINITY
    }

    /// `f / (f − n)`, the factor that maps `(d − n)/d` to window depth; 1 when `f = +∞`.
    ///
    /// `f − n` is exact when `f ≤ 2n` (Sterbenz) and correctly rounded otherwise, so this stays
    /// within 1.5 ulp even when `f/n` is `1 + 1e-12`.
    pub(crate) fn far_over_span(&self) -> f64 {
        if self.is_infinite() {
            1.0
        } else {
            self.far / (self.far - self.near)
        }
    }

    /// `(f + n) / (f − n)`, the magnitude of projection element 10; 1 when `f = +∞`.
    pub(crate) fn sum_over_span(&self) -> f64 {
        if self.is_infinite() {
            return 1.0;
        }
        sum_over_difference(self.far, self.near)
    }

    /// Checks that `pz` is an eye-space z inside the frustum's depth range: `−f ≤ pz ≤ −n`.
    ///
    /// # Errors
    /// [`ErrorKind::NotFinite`] for NaN or ±∞, [`ErrorKind::Domain`] outside `[−f, −n]`.
    pub fn check_eye_z(&self, pz: f64) -> Result<()> {
        finite(pz, "the eye-space depth Pz is NaN or infinite")?;
        if pz > -self.near || pz < -self.far {
            return Err(domain("the eye-space depth Pz must lie in [-f, -n]").with_value("Pz", pz));
        }
        Ok(())
    }

    /// Checks that `d` is an eye distance inside the frustum: `n ≤ d ≤ f`.
    ///
    /// # Errors
    /// [`ErrorKind::NotFinite`] for NaN or ±∞, [`ErrorKind::Domain`] outside `[n, f]`.
    pub fn check_distance(&self, d: f64) -> Result<()> {
        finite(d, "the eye distance d is NaN or infinite")?;
        if d < self.near || d > self.far {
            return Err(domain("the eye distance d must lie in [n, f]").with_value("d", d));
        }
        Ok(())
    }
}

/// `2ᵏ` for `−1022 ≤ k ≤ 1023`, exactly, from its bits (`powi` is a library call).
pub(crate) fn power_of_two(k: i32) -> f64 {
    debug_assert!((-1022..=1023).contains(&k));
    f64::from_bits(((1023 + k) as u64) << 52)
}

/// `(a + b) / (a − b)` for `a > b ≥ 0`, halving both first if `a + b` would overflow.
pub(crate) fn sum_over_difference(a: f64, b: f64) -> f64 {
    let (a, b) = halved_if_huge(a, b);
    (a + b) / (a - b)
}

/// Scales a pair by ½ when the larger is so big that their sum could overflow. Halving is exact
/// for normal numbers, and a value it would round (a subnormal) is negligible beside the other.
fn halved_if_huge(a: f64, b: f64) -> (f64, f64) {
    if a.abs().max(b.abs()) > f64::MAX / 4.0 {
        (a * 0.5, b * 0.5)
    } else {
        (a, b)
    }
}

/// The number of steps of an m-bit unsigned normalized depth buffer: `2^m − 1`, exact in f64.
///
/// # Errors
/// [`ErrorKind::Domain`] unless `1 ≤ bits ≤ 32`.
pub fn depth_steps(bits: u32) -> Result<f64> {
    if !(1..=32).contains(&bits) {
        return Err(
            domain("the depth buffer bits m must lie in 1..=32").with_integer("bits", bits as i64)
        );
    }
    Ok(((1u64 << bits) - 1) as f64)
}

/// Checks the ε of the tweaked infinite projection (Lengyel, GDC 2007): finite, `0 ≤ ε < 1`.
pub(crate) fn check_tweak(tweak: f64) -> Result<f64> {
    finite(
        tweak,
        "the infinite-projection tweak epsilon is NaN or infinite",
    )?;
    if !(0.0..1.0).contains(&tweak) {
        return Err(
            domain("the infinite-projection tweak epsilon must lie in [0, 1)")
                .with_value("tweak", tweak),
        );
    }
    Ok(tweak)
}

pub(crate) fn finite(x: f64, detail: &'static str) -> Result<f64> {
    if x.is_finite() {
        Ok(x)
    } else {
        Err(not_finite(detail).with_value("", x))
    }
}

pub(crate) fn not_finite(detail: &'static str) -> Error {
    Error::new(ErrorKind::NotFinite, detail)
}

pub(crate) fn domain(detail: &'static str) -> Error {
    Error::new(ErrorKind::Domain, detail)
}

/// Turns a computed value into a result, refusing ±∞ and NaN as an overflow.
pub(crate) fn representable(x: f64, detail: &'static str) -> Result<f64> {
    if x.is_finite() {
        Ok(x)
    } else {
        Err(Error::new(ErrorKind::Overflow, detail))
    }
}
