//! A plane as the rasterizer sees it: its window-depth plane, and the linear form on clip
//! coordinates that says how far an error of a vertex moves depth off that plane.
//!
//! # Every plane that covers a pixel has a window plane
//! A planar polygon's NDC depth is affine in NDC `x`, `y` (`z_c/w` is affine in `1/w`, and `1/w`
//! is affine on the screen), so it is `z_n = a₀ + aₓ·xₙ + a_y·yₙ` — also for a plane that
//! contains the view direction (level ground under a level camera, a wall seen along its
//! length), whose eye-space slope `|∂z/∂x| + |∂z/∂y|` is infinite. Only a plane through the eye
//! is degenerate: it is a line on screen and covers no pixel. [`PlaneForm::of_footprint`] reads
//! `(a₀, aₓ, a_y)` off a [`Footprint`] (the window plane computed from the decal's corners).
//!
//! # The form
//! In clip coordinates the plane's image is `L(c) = 0` with
//!
//! `L(c) = z_c − aₓ·x_c − a_y·y_c − a₀·w_c`,
//!
//! normalised to `z_c`'s coefficient 1. A vertex computed as `c + e` (exact clip position `c`
//! on the plane, error `e`) has NDC depth off the plane, at its own screen position, by exactly
//! `L(e)/(w + e_w)`. The rasterizer interpolates window depth in screen space, weighing vertex
//! `i` at a pixel of eye depth `d` by `λᵢ = μᵢ·wᵢ/d` (`μᵢ ≥ 0` the clip-space barycentrics,
//! `Σ μᵢ·wᵢ = d`), so the pixel's NDC depth error is `Σ μᵢ·L(eᵢ)/d`: at most `maxᵢ |L(eᵢ)|/d`,
//! and at most `K` wherever `|L(eᵢ)| ≤ K·wᵢ` for every vertex. [`PlaneForm::bound`] gives
//! `|L(e)|` for componentwise error bounds, [`PlaneForm::on_eye`] the form on eye coordinates
//! through a projection (`L(P·p)`, whose gradient weighs an eye-space error).

use crate::footprint::Footprint;
use crate::projection::ClipDepth;

/// The NDC depth plane `z_n = a₀ + aₓ·xₙ + a_y·yₙ` of a primitive (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaneForm {
    /// NDC depth at the centre of the viewport (`xₙ = yₙ = 0`).
    pub a0: f64,
    /// NDC depth per NDC `x`.
    pub ax: f64,
    /// NDC depth per NDC `y`.
    pub ay: f64,
}

impl PlaneForm {
    /// The plane of a [`Footprint`] (unit window depth, pixels from the viewport's lower-left
    /// corner) seen in a `viewport` of `[W, H]` pixels under `clip`: window depth is
    /// `α·z_n + β` (`α = β = ½` under `[−1, 1]`, `α = 1, β = 0` otherwise) and window `x` is
    /// `(xₙ + 1)·W/2`, so `aₓ = gₓ·W/(2α)`, `a_y = g_y·H/(2α)` and
    /// `a₀ = (w₀ + gₓ·W/2 + g_y·H/2 − β)/α`.
    pub fn of_footprint(footprint: &Footprint, viewport: [u32; 2], clip: ClipDepth) -> Self {
        let (alpha, beta) = if clip == ClipDepth::NegOneToOne {
            (0.5, 0.5)
        } else {
            (1.0, 0.0)
        };
        let [w, h] = viewport.map(f64::from);
        let [gx, gy] = footprint.gradient;
        Self {
            a0: (footprint.origin_depth + gx * w / 2.0 + gy * h / 2.0 - beta) / alpha,
            ax: gx * w / (2.0 * alpha),
            ay: gy * h / (2.0 * alpha),
        }
    }

    /// Bounds on the coefficients' magnitudes of the form, under the projection `m`, over every
    /// plane of eye-space slope `slope` whose axis crossing lies at `d₁` or beyond (the plane
    /// `z = −d_a + sₓx + s_y·y`, `|sₓ| + |s_y| = s`, has `aₓ = m14·sₓ/(d_a·m0)`,
    /// `a_y = m14·s_y/(d_a·m5)`, `a₀ = −m10 + (m14/d_a)(1 + sₓ·m8/m0 + s_y·m9/m5)`; a visible
    /// point at depth `d` on the ray `(kₓ, k_y)` (`|k| ≤ e`, the frustum's largest half-extent
    /// tangent) has `d = d_a/(1 + sₓkₓ + s_y·k_y)`; the tilt `1 + s·e` on `1/d₁` is first-order,
    /// see [`crate::model::gradient`]).
    pub(crate) fn of_slope(m: &[f64; 16], slope: f64, d1: f64, e: f64) -> Self {
        let (m0, m5, m8, m9, m10, m14) = (
            m[0].abs(),
            m[5].abs(),
            m[8].abs(),
            m[9].abs(),
            m[10].abs(),
            m[14].abs(),
        );
        let s = slope;
        let inv_da = (1.0 + s * e) / d1;
        Self {
            a0: m10 + m14 * inv_da * (1.0 + s * (m8 / m0).max(m9 / m5)),
            ax: m14 * s * inv_da / m0,
            ay: m14 * s * inv_da / m5,
        }
    }

    /// `L(c) = z_c − aₓ·x_c − a_y·y_c − a₀·w_c` of clip coordinates `c`: 0 on the plane's image,
    /// and for an error `e` how far it moves a vertex off the plane (over `w`, in NDC depth).
    pub fn at(&self, c: [f64; 4]) -> f64 {
        c[2] - self.ax * c[0] - self.ay * c[1] - self.a0 * c[3]
    }

    /// `max |L(e)|` over clip-space errors with `|e_x| ≤ e[0]`, `|e_y| ≤ e[1]`, `|e_z| ≤ e[2]`,
    /// `|e_w| ≤ e[3]`: `e_z + |aₓ|·e_x + |a_y|·e_y + |a₀|·e_w`.
    pub fn bound(&self, e: [f64; 4]) -> f64 {
        e[2] + self.ax.abs() * e[0] + self.ay.abs() * e[1] + self.a0.abs() * e[3]
    }

    /// The form on eye coordinates through the projection `m` (column-major, f64): the
    /// coefficients `(∂/∂x, ∂/∂y, ∂/∂z)` of `L(m·(x, y, z, 1))`, row 2 minus `aₓ`·row 0 minus
    /// `a_y`·row 1 minus `a₀`·row 3 of `m`'s first three columns. An eye-space error `δp` of a
    /// vertex moves it off the plane by `L(m·δp)` (the translation column does not move).
    pub fn on_eye(&self, m: &[f64; 16]) -> [f64; 3] {
        [0, 1, 2].map(|k| self.at([m[4 * k], m[4 * k + 1], m[4 * k + 2], m[4 * k + 3]]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::projection::{projection_f64, Frustum};

    /// A level camera over ground `y = −h`: the form vanishes on the ground's clip image and
    /// only an error in eye `y` moves depth off it (the ground contains every eye x and z).
    #[test]
    fn level_ground_has_a_form_that_vanishes_on_it() {
        let frustum = Frustum::new(-0.1, 0.1, -0.06, 0.06, 0.1, 1000.0).unwrap();
        let m = projection_f64(&frustum, ClipDepth::NegOneToOne).unwrap();
        let h = 1.7;
        let corners = [
            [-2.0, -h, -9.0],
            [2.0, -h, -9.0],
            [2.0, -h, -11.0f32],
            [-2.0, -h, -11.0],
        ]
        .map(|[x, y, z]| glam::Vec3::new(x, y, z));
        let shape =
            crate::footprint::decal_shape(&frustum, ClipDepth::NegOneToOne, [640, 384], &corners)
                .unwrap();
        assert!(shape.slope.is_infinite());
        let form = PlaneForm::of_footprint(&shape.footprint, [640, 384], ClipDepth::NegOneToOne);
        // Exact references: a0 = −m10 (the horizon's depth), aₓ = 0, and L(P·p) = (m14/h)(y + h).
        assert!((form.a0 + m[10]).abs() < 1e-9, "{form:?}");
        assert!(form.ax.abs() < 1e-9);
        let on_eye = form.on_eye(&m);
        let h32 = f64::from(h);
        assert!(
            (on_eye[1] - m[14] / h32).abs() < 1e-6 * (m[14] / h32).abs(),
            "{on_eye:?}"
        );
        assert!(
            on_eye[0].abs() < 1e-9 && on_eye[2].abs() < 1e-6,
            "{on_eye:?}"
        );
        for p in [[5.0, -h32, -30.0], [-40.0, -h32, -300.0]] {
            let c =
                [0, 1, 2, 3].map(|r| m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r]);
            let l = form.at(c);
            assert!(l.abs() < 1e-6 * c[3], "L = {l} at {p:?}");
        }
    }
}
