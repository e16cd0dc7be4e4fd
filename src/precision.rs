//! Depth-buffer precision: window depth as a function of eye distance, and the exact size of one
//! depth step at a distance (Walker, seed 001).
//!
//! Conventions: OpenGL's standard mapping, NDC depth `[−1, 1]`, `glDepthRange(0, 1)`, an m-bit
//! unsigned normalized depth buffer whose steps are `1/(2^m − 1)` of window depth.

use crate::domain::{check_tweak, depth_steps, domain, finite, representable, Planes};
use crate::double_double::{unit_scale, DoubleDouble};
use crate::error::Result;
use crate::error::{Error, ErrorKind};
use crate::projection::ClipDepth;

/// Window depth (what the depth buffer stores, in `[0, 1]`) at eye distance `d`: Walker's
///
/// `f(d) = (f+n)/(2(f−n)) − f·n/(d(f−n)) + 1/2`,
///
/// evaluated in the equivalent form `(d−n)/d · f/(f−n)` in double-double arithmetic, so the
/// result is the correctly rounded f64 but for near-ties (≤ 0.5 ulp + 2⁻¹⁰⁰ relative), with no
/// cancellation at either plane. `f(n) = 0`, `f(f) = 1`; with `f = +∞`, `1 − n/d`.
///
/// # Errors
/// As [`Planes::new`] and [`Planes::check_distance`] (`d` in `[n, f]`).
pub fn window_depth(n: f64, f: f64, d: f64) -> Result<f64> {
    let planes = Planes::new(n, f)?;
    planes.check_distance(d)?;
    // As the product of two ratios, (d − n)/d ≤ 1 and f/(f − n) ≥ 1, each scaled by its own
    // power of two, so that nothing overflows at any magnitude: the products f·(d − n) and
    // d·(f − n) did for f near f64::MAX even after scaling by n (∞/∞ returned NaN with
    // ZSHIFT_OK). Still ≈ 2⁻¹⁰⁴ relative error.
    let s = unit_scale(d);
    let depth_past_near = DoubleDouble::sum(d * s, -n * s).div(DoubleDouble::from_f64(d * s));
    if planes.is_infinite() {
        return Ok(depth_past_near.to_f64());
    }
    let s = unit_scale(f);
    let far_over_span = DoubleDouble::from_f64(f * s).div(DoubleDouble::sum(f * s, -n * s));
    Ok(depth_past_near.mul(far_over_span).to_f64())
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
/// two that keeps the products in range, and [`StepTerms::step`] divides it back out.
pub(crate) struct StepTerms {
    reach: DoubleDouble,
    base: DoubleDouble,
    d: f64,
    scale: f64,
}

impl StepTerms {
    pub(crate) fn new(planes: &Planes, steps: f64, d: f64) -> Self {
        // Scaled by d, the middle of n ≤ d ≤ f: scaling by n overflowed d·scale when d/n > 2^1023
        // (a valid input answered ZSHIFT_ERR_OVERFLOW). If n·scale underflows, k·d > 2^1000 and
        // the step is d to rounding whatever n's low bits are.
        let scale = unit_scale(d);
        let (n, d) = (planes.near() * scale, d * scale);
        // With f = +∞ both terms are divided by f: reach = d, base = n·(2^m − 1).
        // f/d > 2^1022 (f·scale overflows): (f − n)/f is 1 to within 2^-1022, so the f = +∞
        // terms are exact to rounding, where the finite ones would overflow.
        let (reach, base) = if planes.is_infinite() || (planes.far() * scale).is_infinite() {
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

// ---------------------------------------------------------------------------------------------
// Precision per clip-depth convention and depth format. Every projection here stores a window
// depth of the form w(d) = α + σ·b/(d + s) (σ = −1 when depth grows with distance, +1 when
// reversed; s = 0 except for Kooima's median projection), so one step formula serves them all.
// ---------------------------------------------------------------------------------------------

/// A depth-buffer format: how window depth in `[0, 1]` is quantised.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum DepthFormat {
    /// `GL_DEPTH_COMPONENT16`: 16-bit unsigned normalized, steps of `1/(2^16 − 1)`.
    Unorm16,
    /// `GL_DEPTH_COMPONENT24` (and D24S8): steps of `1/(2^24 − 1)`.
    Unorm24,
    /// `GL_DEPTH_COMPONENT32`: steps of `1/(2^32 − 1)` (the f32 pipeline feeding it is coarser).
    Unorm32,
    /// `GL_DEPTH_COMPONENT32F`: IEEE binary32, spacing `r = 2^(e − 23)` at a depth with exponent
    /// `e`, as Direct3D and Vulkan define the minimum resolvable difference of float depth.
    Float32,
}

/// `GL_DEPTH24_STENCIL8`: 24-bit UNORM depth packed with 8 stencil bits.
const GL_DEPTH24_STENCIL8: u32 = 0x88F0;
/// `GL_DEPTH32F_STENCIL8`: f32 depth packed with 8 stencil bits.
const GL_DEPTH32F_STENCIL8: u32 = 0x8CAD;
/// `GL_DEPTH_COMPONENT`: unsized depth, the bits the driver's choice.
const GL_DEPTH_COMPONENT: u32 = 0x1902;
/// `GL_DEPTH_STENCIL`: unsized packed depth and stencil.
const GL_DEPTH_STENCIL: u32 = 0x84F9;

impl DepthFormat {
    /// Bits per depth value.
    pub fn bits(self) -> u32 {
        match self {
            Self::Unorm16 => 16,
            Self::Unorm24 => 24,
            Self::Unorm32 | Self::Float32 => 32,
        }
    }

    /// The OpenGL internal format: `GL_DEPTH_COMPONENT16` (0x81A5), `GL_DEPTH_COMPONENT24`
    /// (0x81A6), `GL_DEPTH_COMPONENT32` (0x81A7) or `GL_DEPTH_COMPONENT32F` (0x8CAC).
    pub fn gl_internal_format(self) -> u32 {
        match self {
            Self::Unorm16 => 0x81A5,
            Self::Unorm24 => 0x81A6,
            Self::Unorm32 => 0x81A7,
            Self::Float32 => 0x8CAC,
        }
    }

    /// The format of an OpenGL depth internal format enum (the inverse of
    /// [`Self::gl_internal_format`]), packed depth-stencil formats included: their depth is
    /// stored as the depth-only format's (`GL_DEPTH24_STENCIL8`, 0x88F0, as
    /// `GL_DEPTH_COMPONENT24`; `GL_DEPTH32F_STENCIL8`, 0x8CAD, as `GL_DEPTH_COMPONENT32F`), and
    /// the stencil bits change nothing of it.
    ///
    /// # Errors
    /// [`ErrorKind::Domain`] for any other value; for the unsized `GL_DEPTH_COMPONENT` (0x1902)
    /// and `GL_DEPTH_STENCIL` (0x84F9) the message says how to read the size the driver chose.
    pub fn from_gl_internal_format(internal_format: u32) -> Result<Self> {
        match internal_format {
            GL_DEPTH24_STENCIL8 => return Ok(Self::Unorm24),
            GL_DEPTH32F_STENCIL8 => return Ok(Self::Float32),
            // Unsized: the driver chose the bits, as it does for a window's default framebuffer.
            GL_DEPTH_COMPONENT | GL_DEPTH_STENCIL => {
                return Err(domain(
                    "the depth format is unsized (GL_DEPTH_COMPONENT or GL_DEPTH_STENCIL): the driver chose its size; read it with glGetFramebufferAttachmentParameteriv(GL_FRAMEBUFFER, attachment, GL_FRAMEBUFFER_ATTACHMENT_DEPTH_SIZE, ..) (16, 24 or 32; GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE is GL_FLOAT for 32F; attachment GL_DEPTH for a window's default framebuffer) and pass the sized format",
                ))
            }
            _ => {}
        }
        [Self::Unorm16, Self::Unorm24, Self::Unorm32, Self::Float32]
            .into_iter()
            .find(|f| f.gl_internal_format() == internal_format)
            .ok_or_else(|| {
                domain(
                    "the depth format must be GL_DEPTH_COMPONENT16 (0x81A5), GL_DEPTH_COMPONENT24 (0x81A6), GL_DEPTH_COMPONENT32 (0x81A7), GL_DEPTH_COMPONENT32F (0x8CAC), GL_DEPTH24_STENCIL8 (0x88F0) or GL_DEPTH32F_STENCIL8 (0x8CAD)",
                )
            })
    }

    /// Whether the format is unsigned normalized (fixed point).
    pub fn is_unorm(self) -> bool {
        self != Self::Float32
    }

    /// The spacing of stored values at window depth `w`: `1/(2^m − 1)` for UNORM formats;
    /// for `Float32`, `r = 2^(e − 23)` with `e` the exponent of `w` rounded to f32
    /// (`2^e ≤ f32(w) < 2^(e+1)`), and `2⁻¹⁴⁹` below the normal range (subnormals and 0).
    ///
    /// A window depth moved by at least this much, in either direction, stores a different value.
    ///
    /// # Errors
    /// [`ErrorKind::NotFinite`] for NaN; [`ErrorKind::Domain`] unless `0 ≤ w ≤ 1`.
    pub fn spacing_at(self, w: f64) -> Result<f64> {
        finite(w, "the window depth w is NaN or infinite")?;
        if !(0.0..=1.0).contains(&w) {
            return Err(domain("the window depth w must lie in [0, 1]"));
        }
        if self.is_unorm() {
            return Ok(1.0 / depth_steps(self.bits())?);
        }
        let stored = w as f32;
        if stored < f32::MIN_POSITIVE {
            return Ok(f64::from(f32::from_bits(1)));
        }
        let exponent = ((stored.to_bits() >> 23) & 0xff) as i32 - 127;
        Ok(2f64.powi(exponent - 23))
    }
}

/// The relative error bound `2⁻⁵⁰` of [`DepthMapping::window_depth_estimate`]: its five
/// roundings (and the correctly rounded value's half ulp) stay below `5.6·2⁻⁵³ < 8·2⁻⁵³`.
pub(crate) const WINDOW_ESTIMATE_ERROR: f64 = 1.0 / 1_125_899_906_842_624.0;

#[derive(Debug, Clone, Copy, PartialEq)]
enum Shape {
    Projection(Planes, ClipDepth),
    Tweaked { near: f64, tweak: f64 },
    Median { median: f64 },
}

/// The window depth a projection stores as a function of eye distance `d`, in a form that
/// every convention shares: `w(d) = α + σ·b/(d + s)`.
///
/// | mapping | window depth | σ | b | s |
/// |---|---|---|---|---|
/// | `glFrustum`, `NegOneToOne` or `ZeroToOne` | `f(d−n)/((f−n)d)` (Walker, seed 001) | −1 | `fn/(f−n)` (`n` if `f = ∞`) | 0 |
/// | `ReversedZeroToOne` | `n(f−d)/((f−n)d)` | +1 | as above | 0 |
/// | tweaked infinite, tweak `ε` | `1 − ε/2 − (1 − ε/2)·n/d` | −1 | `(1 − ε/2)·n` | 0 |
/// | Kooima median `m` (seed 003) | `d/(d + m)` | −1 | `m` | `m` |
///
/// `NegOneToOne` and `ZeroToOne` store the same window depth (with `glDepthRange(0, 1)`); they
/// differ in how NDC maps to it ([`Self::window_per_ndc`]) and so in where an offset goes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DepthMapping {
    shape: Shape,
}

impl DepthMapping {
    /// The mapping of a `glFrustum`-family projection with planes `n`, `f` (`f` may be `+∞`)
    /// under `clip`.
    ///
    /// # Errors
    /// As [`Planes::new`].
    pub fn projection(n: f64, f: f64, clip: ClipDepth) -> Result<Self> {
        Ok(Self::of_planes(Planes::new(n, f)?, clip))
    }

    /// [`Self::projection`] for planes already checked.
    pub(crate) fn of_planes(planes: Planes, clip: ClipDepth) -> Self {
        Self {
            shape: Shape::Projection(planes, clip),
        }
    }

    /// The mapping of the tweaked infinite projection
    /// ([`crate::projection::tweaked_infinite`]) with near plane `n`, NDC depth `[−1, 1]`.
    ///
    /// # Errors
    /// As [`Planes::new`]; [`ErrorKind::Domain`] unless `0 ≤ tweak < 1`.
    pub fn tweaked_infinite(n: f64, tweak: f64) -> Result<Self> {
        Planes::new(n, f64::INFINITY)?;
        check_tweak(tweak)?;
        Ok(Self {
            shape: Shape::Tweaked { near: n, tweak },
        })
    }

    /// The mapping of Kooima's median-distance projection (seed 003, `ftransform_mdp`): NDC
    /// depth `(d − m)/(d + m)`, window depth `d/(d + m)`, half the buffer on each side of `m`.
    ///
    /// # Errors
    /// [`ErrorKind::NotFinite`] for NaN or ±∞; [`ErrorKind::Domain`] unless `m > 0`.
    pub fn median(m: f64) -> Result<Self> {
        finite(m, "the median distance is NaN or infinite")?;
        if m <= 0.0 {
            return Err(domain("the median distance must be greater than 0"));
        }
        Ok(Self {
            shape: Shape::Median { median: m },
        })
    }

    /// Whether window depth grows toward the camera (reversed Z; compare with `GL_GREATER`).
    pub fn is_reversed(&self) -> bool {
        matches!(
            self.shape,
            Shape::Projection(_, ClipDepth::ReversedZeroToOne)
        )
    }

    /// Window depth per unit of NDC depth: ½ for NDC `[−1, 1]` (`glDepthRange(0, 1)` maps it
    /// as `(z + 1)/2`), 1 for the `[0, 1]` conventions.
    pub fn window_per_ndc(&self) -> f64 {
        match self.shape {
            Shape::Projection(_, ClipDepth::ZeroToOne | ClipDepth::ReversedZeroToOne) => 1.0,
            _ => 0.5,
        }
    }

    /// `(b, s)` of `w(d) = α + σ·b/(d + s)`.
    fn scale_and_shift(&self) -> (f64, f64) {
        match self.shape {
            Shape::Projection(planes, _) => (planes.near() * planes.far_over_span(), 0.0),
            Shape::Tweaked { near, tweak } => ((1.0 - 0.5 * tweak) * near, 0.0),
            Shape::Median { median } => (median, median),
        }
    }

    /// The nearest distance the mapping covers (`n`, or 0 for the median projection).
    pub fn near(&self) -> f64 {
        match self.shape {
            Shape::Projection(planes, _) => planes.near(),
            Shape::Tweaked { near, .. } => near,
            Shape::Median { .. } => 0.0,
        }
    }

    /// The farthest distance the mapping covers (`f`, or `+∞`).
    pub fn far(&self) -> f64 {
        match self.shape {
            Shape::Projection(planes, _) => planes.far(),
            _ => f64::INFINITY,
        }
    }

    fn check_distance(&self, d: f64) -> Result<()> {
        finite(d, "the eye distance d is NaN or infinite")?;
        if d < self.near() || d > self.far() {
            return Err(domain(
                "the eye distance d must lie in the projection's [near, far]",
            ));
        }
        Ok(())
    }

    /// The window depth stored at eye distance `d` (see the table on [`DepthMapping`]), in
    /// forms without cancellation near either end, clamped to `[0, 1]`.
    ///
    /// # Errors
    /// [`ErrorKind::NotFinite`] for NaN or ±∞; [`ErrorKind::Domain`] for `d` outside the
    /// mapping's range.
    pub fn window_depth(&self, d: f64) -> Result<f64> {
        self.check_distance(d)?;
        self.depth_with(d, |planes| window_depth(planes.near(), planes.far(), d))
    }

    /// [`Self::window_depth`] in plain f64, for a `d` already checked to lie in the mapping's
    /// range: within [`WINDOW_ESTIMATE_ERROR`] (relative) of it. Walker's `f(d)` is
    /// `((d − n)/d)·(f/(f − n))` in five roundings (`d − n` exact when `d ≤ 2n`) instead of
    /// double-double arithmetic; the other shapes are computed as there. For bounds that are
    /// f64 evaluations anyway, such as the recommendation's error terms.
    pub(crate) fn window_depth_estimate(&self, d: f64) -> f64 {
        let walker = |planes: Planes| Ok(((d - planes.near()) / d) * planes.far_over_span());
        self.depth_with(d, walker).unwrap_or(f64::NAN)
    }

    /// The window depth at `d` of the table on [`DepthMapping`], with Walker's `f(d)` (NDC
    /// `[−1, 1]` and `[0, 1]` store the same window depth) from `walker`, clamped to `[0, 1]`.
    fn depth_with(&self, d: f64, walker: impl FnOnce(Planes) -> Result<f64>) -> Result<f64> {
        let w = match self.shape {
            Shape::Projection(planes, clip) => {
                let n = planes.near();
                match clip {
                    ClipDepth::ReversedZeroToOne if planes.is_infinite() => n / d,
                    ClipDepth::ReversedZeroToOne => {
                        (n / d) * ((planes.far() - d) / (planes.far() - n))
                    }
                    _ => walker(planes)?,
                }
            }
            Shape::Tweaked { near, tweak } => (1.0 - 0.5 * tweak) * ((d - near) / d),
            Shape::Median { median } => d / (d + median),
        };
        Ok(w.clamp(0.0, 1.0))
    }

    /// `format`'s spacing ([`DepthFormat::spacing_at`]) at the window depth of `d` (checked to
    /// lie in the mapping's range), given `w` from [`Self::window_depth_estimate`]: from `w`
    /// when every window depth within its error has the same spacing (the spacing is monotone
    /// in `w`, so both ends of the interval decide), else from the exact [`Self::window_depth`]
    /// (float depth within `2⁻⁵⁰` of an f32 binade's rounding edge).
    ///
    /// # Errors
    /// As [`DepthFormat::spacing_at`] and [`Self::window_depth`].
    pub(crate) fn spacing_at_estimate(&self, format: DepthFormat, d: f64, w: f64) -> Result<f64> {
        if format.is_unorm() {
            return format.spacing_at(w);
        }
        let end = |factor: f64| format.spacing_at((w * factor).clamp(0.0, 1.0));
        let spacing = end(1.0 - WINDOW_ESTIMATE_ERROR)?;
        if end(1.0 + WINDOW_ESTIMATE_ERROR)? == spacing {
            return Ok(spacing);
        }
        format.spacing_at(self.window_depth(d)?)
    }

    /// The exact size of one stored-depth step at eye distance `d`: the shift toward the camera
    /// `Δ > 0` with `|w(d − Δ) − w(d)| = r`, where `r` is `format`'s spacing at `w(d)`
    /// ([`DepthFormat::spacing_at`]):
    ///
    /// `Δ = r·(d + s)² / (b + r·(d + s))`
    ///
    /// — Walker's eq. (3) (seed 001) for every convention and format. It is also the minimum
    /// eye-space δ toward the camera (the corrected eq. 4.1.9, seeds 000/002): a point moved
    /// by at least `Δ` is guaranteed to store a different depth.
    ///
    /// # Errors
    /// As [`Self::window_depth`]; [`ErrorKind::Unresolvable`] if no such shift exists (reversed
    /// depth within one step of 1, where the near plane is closer than one step).
    pub fn depth_step(&self, d: f64, format: DepthFormat) -> Result<f64> {
        let w = self.window_depth(d)?;
        let r = format.spacing_at(w)?;
        if let Shape::Projection(planes, _) = self.shape {
            // Every glFrustum-family mapping has b = n·f/(f − n) and s = 0: Walker's step, in
            // the correctly rounded form the standard convention uses. 1/r is exact (2^m − 1,
            // or a power of two for float depth).
            let steps = if format.is_unorm() {
                depth_steps(format.bits())?
            } else {
                1.0 / r
            };
            return StepTerms::new(&planes, steps, d).step(true);
        }
        let (b, s) = self.scale_and_shift();
        let ds = d + s;
        let u = (ds / b) * r;
        representable(ds * (u / (1.0 + u)), "the depth step overflows f64")
    }

    /// The signed window-depth change when a point at distance `d` moves toward the camera by
    /// `δ`: `w(d − δ) − w(d) = −σ·b·δ / ((d + s)(d + s − δ))` (negative unless reversed).
    ///
    /// # Errors
    /// As [`Self::window_depth`]; [`ErrorKind::Domain`] if `d − δ` leaves the mapping's range.
    pub fn window_change_of_shift(&self, delta: f64, d: f64) -> Result<f64> {
        self.check_distance(d)?;
        finite(delta, "the eye-space shift delta is NaN or infinite")?;
        self.check_distance(d - delta)?;
        let (b, s) = self.scale_and_shift();
        let magnitude = (b / (d + s)) * (delta / (d + s - delta));
        let change = if self.is_reversed() {
            magnitude
        } else {
            -magnitude
        };
        representable(change, "the window-depth change overflows f64")
    }

    /// The inverse of [`Self::window_change_of_shift`]: the shift toward the camera `δ` that
    /// changes the window depth at `d` by `dw` (signed, as there).
    ///
    /// # Errors
    /// As [`Self::window_depth`]; [`ErrorKind::Unresolvable`] if no distance stores
    /// `w(d) + dw` (the change reaches past the eye or past infinity).
    pub fn shift_of_window_change(&self, dw: f64, d: f64) -> Result<f64> {
        self.check_distance(d)?;
        finite(dw, "the window-depth change is NaN or infinite")?;
        let (b, s) = self.scale_and_shift();
        let ds = d + s;
        // 1/(d' + s) = 1/(d + s) + t, with t = −σ·dw/b.
        let t = if self.is_reversed() { dw / b } else { -dw / b };
        let scaled = 1.0 + ds * t; // (d + s)/(d' + s)
        if scaled <= 0.0 {
            return Err(Error::new(
                ErrorKind::Unresolvable,
                "the window-depth change reaches beyond infinity or the eye",
            ));
        }
        representable(
            ds * ((ds * t) / scaled),
            "the eye-space shift overflows f64",
        )
    }

    /// The smallest constant NDC depth offset (a magnitude) that changes the stored depth at
    /// `d`: `r / window_per_ndc` with `r` the spacing at `w(d)`. For UNORM formats under
    /// `NegOneToOne` this is `2/(2^m − 1)` everywhere: the corrected quantum of seed 002.
    ///
    /// # Errors
    /// As [`Self::window_depth`].
    pub fn min_ndc_offset(&self, d: f64, format: DepthFormat) -> Result<f64> {
        let r = format.spacing_at(self.window_depth(d)?)?;
        Ok(r / self.window_per_ndc())
    }

    /// The smallest `|ε|` for Lengyel's element-10 scaling `m10·(1 + ε)` (seed 000, eq. 4.1.3)
    /// that changes the stored depth at `d`: [`Self::min_ndc_offset`]` / |m10|`.
    ///
    /// Under `NegOneToOne` with a UNORM format this is the corrected eq. 4.1.8 (seed 002),
    /// `2/(2^m − 1)·(f − n)/(f + n)`; under `ZeroToOne` it is `1/(2^m − 1)·(f − n)/f` (half the
    /// NDC quantum, a smaller `|m10|`); under reversed Z it is `r·(f − n)/n`, useless for large
    /// `f/n` — and with an infinite far plane `m10 = 0`, so no ε exists.
    ///
    /// # Errors
    /// As [`Self::window_depth`]; [`ErrorKind::Unresolvable`] when `m10 = 0` (reversed Z with
    /// `f = ∞`: scaling element 10 does nothing; use [`Self::min_relative_epsilon`]);
    /// [`ErrorKind::Domain`] for the median projection, which has no matrix.
    pub fn min_epsilon(&self, d: f64, format: DepthFormat) -> Result<f64> {
        let m10 = match self.shape {
            Shape::Projection(planes, clip) => crate::projection::depth_row(&planes, clip).0,
            Shape::Tweaked { tweak, .. } => tweak - 1.0,
            Shape::Median { .. } => {
                return Err(domain("the median projection has no element 10 to scale"))
            }
        };
        let c = self.min_ndc_offset(d, format)?;
        if m10 == 0.0 {
            return Err(Error::new(
                ErrorKind::Unresolvable,
                "element 10 is 0 (reversed Z, infinite far): scaling it offsets nothing",
            ));
        }
        representable(c / m10.abs(), "epsilon overflows f64")
    }

    /// The smallest relative offset `ε` (projection element 14 scaled by `1 + ε`, which moves
    /// every point from `d` to `d/(1 + ε)`) that changes the stored depth at `d`: `r·d/b`.
    /// For `Float32` under reversed Z this is about `2⁻²³` at every distance.
    ///
    /// # Errors
    /// As [`Self::window_depth`]; [`ErrorKind::Domain`] for the median projection, whose depth
    /// is not a function of `m14/d`.
    pub fn min_relative_epsilon(&self, d: f64, format: DepthFormat) -> Result<f64> {
        if let Shape::Median { .. } = self.shape {
            return Err(domain(
                "the median projection has no relative (element 14) offset",
            ));
        }
        let r = format.spacing_at(self.window_depth(d)?)?;
        let (b, _) = self.scale_and_shift();
        representable((d / b) * r, "the relative epsilon overflows f64")
    }

    /// The eye distance at which the window depth is `w` (the inverse of
    /// [`Self::window_depth`]); `+∞` where `w` is only reached at infinity.
    ///
    /// # Errors
    /// [`ErrorKind::Domain`] if no distance in the mapping's range stores `w`.
    pub fn distance_at_window(&self, w: f64) -> Result<f64> {
        finite(w, "the window depth w is NaN or infinite")?;
        let lo = self.window_depth(self.near())?;
        let hi = if self.far().is_finite() {
            self.window_depth(self.far())?
        } else {
            self.window_at_infinity()
        };
        let (lo, hi) = if lo <= hi { (lo, hi) } else { (hi, lo) };
        if w < lo || w > hi {
            return Err(domain(
                "no distance in the projection's range stores this window depth",
            ));
        }
        let alpha = self.window_at_infinity();
        let (b, s) = self.scale_and_shift();
        if w == alpha {
            return Ok(f64::INFINITY);
        }
        let sigma = if self.is_reversed() { 1.0 } else { -1.0 };
        let d = (sigma * b / (w - alpha) - s).clamp(self.near(), self.far());
        Ok(d)
    }

    /// `α`: the window depth the mapping approaches as `d → ∞`.
    fn window_at_infinity(&self) -> f64 {
        match self.shape {
            Shape::Projection(planes, ClipDepth::ReversedZeroToOne) => {
                if planes.is_infinite() {
                    0.0
                } else {
                    -planes.near() / (planes.far() - planes.near())
                }
            }
            Shape::Projection(planes, _) => planes.far_over_span(),
            Shape::Tweaked { tweak, .. } => 1.0 - 0.5 * tweak,
            Shape::Median { .. } => 1.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The f64 estimate stays within its bound of the double-double window depth, and the
    /// spacing taken from it is the exact one, also where float depth crosses a binade.
    #[test]
    fn window_depth_estimates_keep_their_bound_and_the_spacing() {
        let clips = [
            ClipDepth::NegOneToOne,
            ClipDepth::ZeroToOne,
            ClipDepth::ReversedZeroToOne,
        ];
        let mut next = crate::test_uniform(0x2545_f491_4f6c_dd1d);
        let mut edges = 0;
        for i in 0..30_000 {
            let n = 10f64.powf(-4.0 + 6.0 * next());
            let f = if i % 5 == 0 {
                f64::INFINITY
            } else {
                n * 10f64.powf(0.001 + 8.0 * next())
            };
            let mapping = DepthMapping::projection(n, f, clips[i % 3]).unwrap();
            let d = if i % 2 == 0 {
                n * (f.min(n * 1e9) / n).powf(next())
            } else {
                // Near an f32 rounding edge of float depth (w just below a power of two).
                let w = 2f64.powi(-((next() * 20.0) as i32)) * (1.0 - 2f64.powi(-25));
                let w = w * (1.0 + (next() - 0.5) * 2f64.powi(-45));
                match mapping.distance_at_window(w) {
                    Ok(d) if d >= n && d <= f => d,
                    _ => continue,
                }
            };
            let exact = mapping.window_depth(d).unwrap();
            let estimate = mapping.window_depth_estimate(d);
            assert!(
                (estimate - exact).abs() <= WINDOW_ESTIMATE_ERROR * exact,
                "{n} {f} {d}: {estimate} vs {exact}"
            );
            for format in [DepthFormat::Unorm24, DepthFormat::Float32] {
                let spacing = mapping.spacing_at_estimate(format, d, estimate).unwrap();
                assert_eq!(spacing, format.spacing_at(exact).unwrap(), "{n} {f} {d}");
            }
            let f32_edge =
                |w: f64| (w * (1.0 - 2f64.powi(-48))) as f32 != (w * (1.0 + 2f64.powi(-48))) as f32;
            edges += usize::from(f32_edge(exact));
        }
        assert!(
            edges > 100,
            "only {edges} window depths near an f32 rounding edge"
        );
    }
}
