//! Orthographic projections (`glOrtho`): builders for every clip convention, the constant depth
//! offset through element 14, and the exact depth step, which is the same at every distance.
//!
//! Depth under `glOrtho(l, r, b, t, n, f)` is linear in the eye distance `d` (`z = −d`):
//! `z_ndc = m10·z + m14`. Window depth (`glDepthRange(0, 1)`) is `(d − n)/(f − n)` under
//! `[−1, 1]` and `[0, 1]`, `(f − d)/(f − n)` reversed. So a constant NDC offset is the same eye
//! shift everywhere, and a UNORM depth step is `q·(f − n)` at every distance (for float depth,
//! `2^(e−23)·(f − n)` with `e` the exponent of the stored depth). Unlike a perspective frustum,
//! `n` may be 0 or negative (the near plane behind the eye); `f > n`.

use crate::domain::{domain, finite};
use crate::double_double::DoubleDouble;
use crate::error::Result;
use crate::offset::rounded_outward;
use crate::precision::DepthFormat;
use crate::projection::{to_f32, ClipDepth};

/// The six parameters of `glOrtho`, validated: finite, `l ≠ r`, `b ≠ t`, `n < f`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ortho {
    left: f64,
    right: f64,
    bottom: f64,
    top: f64,
    near: f64,
    far: f64,
}

impl Ortho {
    /// Checks the parameters as `glOrtho` would (it raises `GL_INVALID_VALUE` for `l = r`,
    /// `b = t`, `n = f`), and more strictly (`n < f`, all finite).
    ///
    /// # Errors
    /// [`crate::ErrorKind::NotFinite`] for NaN or an infinity; [`crate::ErrorKind::Domain`] if
    /// `l = r`, `b = t` or `f ≤ n`.
    pub fn new(l: f64, r: f64, b: f64, t: f64, n: f64, f: f64) -> Result<Self> {
        for (name, x) in [("l", l), ("r", r), ("b", b), ("t", t), ("n", n), ("f", f)] {
            finite(x, "a glOrtho parameter is NaN or infinite")
                .map_err(|e| e.with_value(name, x))?;
        }
        if l == r {
            return Err(domain("the orthographic box has zero width: l = r").with_value("l", l));
        }
        if b == t {
            return Err(domain("the orthographic box has zero height: b = t").with_value("b", b));
        }
        if f <= n {
            return Err(
                domain("the orthographic far plane f must be greater than n").with_value("f", f),
            );
        }
        Ok(Self {
            left: l,
            right: r,
            bottom: b,
            top: t,
            near: n,
            far: f,
        })
    }

    /// The near plane distance `n` (may be 0 or negative).
    pub fn near(&self) -> f64 {
        self.near
    }

    /// The far plane distance `f`.
    pub fn far(&self) -> f64 {
        self.far
    }

    /// The window depth in `[0, 1]` at eye distance `d` under `clip` (`glDepthRange(0, 1)`):
    /// `(d − n)/(f − n)`, or `(f − d)/(f − n)` reversed.
    ///
    /// # Errors
    /// [`crate::ErrorKind::NotFinite`] for NaN or ±∞; [`crate::ErrorKind::Domain`] unless
    /// `n ≤ d ≤ f`.
    pub fn window_depth(&self, clip: ClipDepth, d: f64) -> Result<f64> {
        self.check_distance(d)?;
        let span = self.far - self.near;
        Ok(if clip == ClipDepth::ReversedZeroToOne {
            (self.far - d) / span
        } else {
            (d - self.near) / span
        })
    }

    /// The exact depth step at eye distance `d`: the shift toward the camera that moves the
    /// stored window depth by the format's spacing `r` at `w(d)` (`1/(2^m − 1)` for UNORM,
    /// `2^(e−23)` for FLOAT32): `r·(f − n)`, the same at every distance for UNORM.
    ///
    /// # Errors
    /// As [`Self::window_depth`].
    pub fn depth_step(&self, clip: ClipDepth, format: DepthFormat, d: f64) -> Result<f64> {
        let w = self.window_depth(clip, d)?;
        Ok(format.spacing_at(w)? * (self.far - self.near))
    }

    fn check_distance(&self, d: f64) -> Result<()> {
        finite(d, "the eye distance d is NaN or infinite").map_err(|e| e.with_value("d", d))?;
        if d < self.near || d > self.far {
            return Err(domain("the eye distance d must lie in [n, f]").with_value("d", d));
        }
        Ok(())
    }
}

/// The depth row `(m10, m14)` of `glOrtho` under a convention:
///
/// | convention | m10 | m14 |
/// |---|---|---|
/// | `NegOneToOne` (`glOrtho`) | `−2/(f−n)` | `−(f+n)/(f−n)` |
/// | `ZeroToOne` | `−1/(f−n)` | `−n/(f−n)` |
/// | `ReversedZeroToOne` | `1/(f−n)` | `f/(f−n)` |
pub fn depth_row(ortho: &Ortho, clip: ClipDepth) -> (f64, f64) {
    let (n, f) = (ortho.near, ortho.far);
    let span = f - n;
    match clip {
        ClipDepth::NegOneToOne => (-2.0 / span, -(f + n) / span),
        ClipDepth::ZeroToOne => (-1.0 / span, -n / span),
        ClipDepth::ReversedZeroToOne => (1.0 / span, f / span),
    }
}

/// The `glOrtho` matrix with the depth row of `clip`, in f64, column-major:
/// `m0 = 2/(r−l)`, `m5 = 2/(t−b)`, `m12 = −(r+l)/(r−l)`, `m13 = −(t+b)/(t−b)`, `m15 = 1`.
pub fn ortho_f64(ortho: &Ortho, clip: ClipDepth) -> [f64; 16] {
    let (width, height) = (ortho.right - ortho.left, ortho.top - ortho.bottom);
    let mut m = [0.0; 16];
    m[0] = 2.0 / width;
    m[5] = 2.0 / height;
    m[12] = -(ortho.right + ortho.left) / width;
    m[13] = -(ortho.top + ortho.bottom) / height;
    m[15] = 1.0;
    (m[10], m[14]) = depth_row(ortho, clip);
    m
}

/// [`ortho_f64`] rounded to f32, each element the nearest f32.
///
/// # Errors
/// [`crate::ErrorKind::Overflow`] if an element leaves f32.
pub fn ortho(ortho: &Ortho, clip: ClipDepth) -> Result<[f32; 16]> {
    to_f32(&ortho_f64(ortho, clip))
}

/// The orthographic matrix of `clip` with every point moved toward the camera by `delta` (eye
/// units; negative: away): element 14 moved by the constant NDC offset `m10·δ`, computed from
/// the f32 element 10 and rounded outward, so the eye shift the GPU sees is at least `δ`.
/// Every other element equals [`ortho`]'s.
///
/// # Errors
/// As [`ortho`]; [`crate::ErrorKind::NotFinite`] if `delta` is NaN or infinite.
pub fn offset_ortho(o: &Ortho, clip: ClipDepth, delta: f64) -> Result<[f32; 16]> {
    finite(delta, "the eye-space shift delta is NaN or infinite")
        .map_err(|e| e.with_value("delta", delta))?;
    let mut m = ortho(o, clip)?;
    m[14] = rounded_outward(m[14], DoubleDouble::product(f64::from(m[10]), delta))?;
    Ok(m)
}
