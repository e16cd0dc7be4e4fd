//! Depth-buffer precision: window depth as a function of eye distance, and the exact size of one
//! depth step at a distance (Walker, seed 001).
//!
//! Conventions: OpenGL's standard mapping, NDC depth `[−1, 1]`, `glDepthRange(0, 1)`, an m-bit
//! unsigned normalized depth buffer whose steps are `1/(2^m − 1)` of window depth.

use crate::domain::{depth_steps, representable, Planes};
use crate::double_double::{unit_scale, DoubleDouble};
use crate::error::Result;

/// Window depth (what the depth buffer stores, in `[0, 1]`) at eye distance `d`: Walker's
///
/// `f(d) = (f+n)/(2(f−n)) − f·n/(d(f−n)) + 1/2`,
///
/// evaluated in the equivalent form `f·(d−n) / (d·(f−n))` in double-double arithmetic, so the
/// result is the correctly rounded f64 but for near-ties (≤ 0.5 ulp + 2⁻¹⁰⁰ relative), with no
/// cancellation at either plane. `f(n) = 0`, `f(f) = 1`; with `f = +∞`, `1 − n/d`.
///
/// # Errors
/// As [`Planes::new`] and [`Planes::check_distance`] (`d` in `[n, f]`).
pub fn window_depth(n: f64, f: f64, d: f64) -> Result<f64> {
    let planes = Planes::new(n, f)?;
    planes.check_distance(d)?;
    let s = unit_scale(n);
    let (n, d) = (n * s, d * s);
    let depth_past_near = DoubleDouble::sum(d, -n);
    if planes.is_infinite() {
        return Ok(depth_past_near.div(DoubleDouble::from_f64(d)).to_f64());
    }
    let f = planes.far() * s;
    let numerator = depth_past_near.mul_f64(f);
    Ok(numerator.div(DoubleDouble::sum(f, -n).mul_f64(d)).to_f64())
}

/// The exact size of one depth step at eye distance `d`: the `Δd > 0` with
/// `f(d) − f(d − Δd) = 1/(2^m − 1)` — Walker's eq. (3) generalised from `d = f` to any `d`:
///
/// `Δd = q·d² / (b + q·d)`, with `q = 1/(2^m − 1)` and `b = f·n/(f − n)`.
///
/// Geometry nearer the camera than `d − Δd` is guaranteed to store a smaller value; closer
/// pairs may tie. This is also the corrected eq. 4.1.9 ([`crate::offset::min_delta_toward`]).
///
/// # Errors
/// As [`Planes::new`], [`Planes::check_distance`] and [`depth_steps`].
pub fn depth_resolution(n: f64, f: f64, bits: u32, d: f64) -> Result<f64> {
    let planes = Planes::new(n, f)?;
    planes.check_distance(d)?;
    depth_step_toward(&planes, depth_steps(bits)?, d)
}

/// The two terms of Walker's step at distance `d`, exact to double-double precision:
/// `reach = d·(f − n)` and `base = n·f·(2^m − 1)`, so that `k·d = reach / base`. Every
/// depth-step formula is a ratio of these (times `d`); `(d, n, f)` are first scaled by a power of
/// two that keeps the products in range, and [`StepTerms::unscale`] undoes it.
pub(crate) struct StepTerms {
    reach: DoubleDouble,
    base: DoubleDouble,
    d: f64,
    scale: f64,
}

impl StepTerms {
    pub(crate) fn new(planes: &Planes, steps: f64, d: f64) -> Self {
        let scale = unit_scale(planes.near());
        let (n, d) = (planes.near() * scale, d * scale);
        // With f = +∞ both terms are divided by f: reach = d, base = n·(2^m − 1).
        let (reach, base) = if planes.is_infinite() {
            (DoubleDouble::from_f64(d), DoubleDouble::product(n, steps))
        } else {
            let f = planes.far() * scale;
            let reach = DoubleDouble::sum(f, -n).mul_f64(d);
            (reach, DoubleDouble::product(n, f).mul_f64(steps))
        };
        Self {
            reach,
            base,
            d,
            scale,
        }
    }

    /// Whether `k·d ≥ 1`: the step at `d` is larger than everything behind it.
    pub(crate) fn unresolvable_away(&self) -> bool {
        self.base.sub(self.reach).hi <= 0.0
    }

    /// `d·reach / (base ± reach)` in unscaled units: `+` for the step toward the camera
    /// (eq. 4.1.9, Walker's eq. 3), `−` for the step away (eq. 4.1.10, before its sign).
    pub(crate) fn step(&self, toward: bool) -> Result<f64> {
        let denominator = if toward {
            self.base.add(self.reach)
        } else {
            self.base.sub(self.reach)
        };
        let step = self.reach.mul_f64(self.d).div(denominator).to_f64() / self.scale;
        representable(step, "the depth step overflows f64")
    }
}

/// `Δd = q·d² / (b + q·d)`, the step toward the camera at `d`.
pub(crate) fn depth_step_toward(planes: &Planes, steps: f64, d: f64) -> Result<f64> {
    StepTerms::new(planes, steps, d).step(true)
}
