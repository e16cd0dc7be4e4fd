//! Projection matrix builders (f64 inside, f32 out).
//!
//! Conventions, as OpenGL's fixed-function pipeline: right-handed eye space looking down −z,
//! clip-space depth in `[−w, w]` (NDC depth `[−1, 1]`), matrices column-major (element `i` of
//! the 16-float array is column `i / 4`, row `i % 4`, exactly what `glLoadMatrixf` and
//! `glUniformMatrix4fv(.., GL_FALSE, ..)` take).

use glam::{DMat4, Mat4};

use crate::domain::{domain, finite, representable, Planes};
use crate::error::{Error, ErrorKind, Result};

/// The six parameters of `glFrustum`, validated.
///
/// `l`, `r`, `b`, `t` are the extents of the view window on the near plane; `n` and `f` the
/// near and far plane distances (`f` may be `+∞`, the infinite-far limit).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frustum {
    left: f64,
    right: f64,
    bottom: f64,
    top: f64,
    planes: Planes,
}

impl Frustum {
    /// Checks the parameters as `glFrustum` would, and more strictly.
    ///
    /// # Errors
    /// [`ErrorKind::NotFinite`] for NaN or an infinity (other than `f = +∞`);
    /// [`ErrorKind::Domain`] if `l = r`, `b = t`, `n ≤ 0` or `f ≤ n`
    /// (`glFrustum` raises `GL_INVALID_VALUE` for the same cases).
    pub fn new(l: f64, r: f64, b: f64, t: f64, n: f64, f: f64) -> Result<Self> {
        finite(l, "the left extent l is NaN or infinite")?;
        finite(r, "the right extent r is NaN or infinite")?;
        finite(b, "the bottom extent b is NaN or infinite")?;
        finite(t, "the top extent t is NaN or infinite")?;
        let planes = Planes::new(n, f)?;
        if l == r {
            return Err(domain("the frustum has zero width: l = r"));
        }
        if b == t {
            return Err(domain("the frustum has zero height: b = t"));
        }
        Ok(Self {
            left: l,
            right: r,
            bottom: b,
            top: t,
            planes,
        })
    }

    /// The validated near and far planes.
    pub fn planes(&self) -> Planes {
        self.planes
    }

    /// The 16 elements, column-major, each within a few f64 ulp of the exact value.
    ///
    /// ```text
    /// | 2n/(r−l)   0        (r+l)/(r−l)    0           |
    /// | 0          2n/(t−b) (t+b)/(t−b)    0           |
    /// | 0          0        −(f+n)/(f−n)   −2fn/(f−n)  |
    /// | 0          0        −1             0           |
    /// ```
    /// With `f = +∞`: element 10 is `−1` and element 14 is `−2n` (Kooima, seed 003).
    ///
    /// # Errors
    /// [`ErrorKind::Overflow`] if an element is not a finite f64 (extents near `f64::MAX`).
    pub fn to_cols_array_f64(&self) -> Result<[f64; 16]> {
        let n = self.planes.near();
        let width = self.right - self.left;
        let height = self.top - self.bottom;
        let mut m = [0.0; 16];
        m[0] = 2.0 * n / width;
        m[5] = 2.0 * n / height;
        m[8] = (self.right + self.left) / width;
        m[9] = (self.top + self.bottom) / height;
        m[10] = -self.planes.sum_over_span();
        m[11] = -1.0;
        m[14] = -2.0 * n * self.planes.far_over_span();
        for x in m {
            representable(x, "a projection matrix element overflows f64")?;
        }
        Ok(m)
    }

    /// The matrix in f64, as a glam [`DMat4`].
    ///
    /// # Errors
    /// As [`Self::to_cols_array_f64`].
    pub fn to_dmat4(&self) -> Result<DMat4> {
        Ok(DMat4::from_cols_array(&self.to_cols_array_f64()?))
    }

    /// The matrix rounded to f32, each element the nearest f32 to the f64 value (so within
    /// one f32 ulp of the exact element). This is what `glFrustum` followed by
    /// `glGetFloatv(GL_PROJECTION_MATRIX)` gives.
    ///
    /// # Errors
    /// [`ErrorKind::Overflow`] if an element does not fit in f32.
    pub fn to_cols_array(&self) -> Result<[f32; 16]> {
        to_f32(&self.to_cols_array_f64()?)
    }

    /// The matrix rounded to f32, as a glam [`Mat4`].
    ///
    /// # Errors
    /// As [`Self::to_cols_array`].
    pub fn to_mat4(&self) -> Result<Mat4> {
        Ok(Mat4::from_cols_array(&self.to_cols_array()?))
    }
}

/// The `glFrustum` matrix in f32, column-major: the Rust twin of `zshift_frustum`.
///
/// Right-handed, NDC depth `[−1, 1]`; `f` may be `+∞`. See [`Frustum::to_cols_array_f64`]
/// for the elements.
///
/// # Errors
/// As [`Frustum::new`] and [`Frustum::to_cols_array`].
pub fn frustum(l: f64, r: f64, b: f64, t: f64, n: f64, f: f64) -> Result<Mat4> {
    Frustum::new(l, r, b, t, n, f)?.to_mat4()
}

/// Rounds each element to the nearest f32, refusing elements that overflow f32.
pub(crate) fn to_f32(m: &[f64; 16]) -> Result<[f32; 16]> {
    let mut out = [0.0f32; 16];
    for (o, &x) in out.iter_mut().zip(m) {
        *o = x as f32;
        if !o.is_finite() {
            return Err(Error::new(
                ErrorKind::Overflow,
                "a projection matrix element overflows f32",
            ));
        }
    }
    Ok(out)
}
