//! The coplanar-quads experiment: a base quad and a smaller decal quad with different vertices
//! in the same eye-space plane, drawn with `GL_LESS`; the decal pixels the base hides are the
//! z-fighting, and decal pixels drawn over an occluder in front are the bleed-through.
//!
//! The scene (eye space, right-handed, looking down −z): a symmetric frustum of vertical and
//! horizontal half-angle `atan(tan_half)`, a square viewport, and the plane
//! `z = −d0 + slope·y`, which meets the view axis at distance `d0` and tilts about the x axis
//! (`slope` is the eye-space `dz/dy`; 0 faces the camera, 3 is about 72°). The base covers most
//! of the visible plane without crossing any clip plane (so no clipper-made vertices); the
//! decal is an off-centre rectangle inside it whose diagonals differ from the base's.
//!
//! Matrices come from the caller (`[f32; 16]`, column-major): this crate knows nothing of
//! zshift, so the tests compare zshift's matrices against the rasterizer, not against itself.

use crate::{DepthFormat, DrawState, Gl, Image, Quad};

/// Base colour: blue.
pub const BASE: [f32; 4] = [0.0, 0.0, 1.0, 1.0];
/// Decal colour: red.
pub const DECAL: [f32; 4] = [1.0, 0.0, 0.0, 1.0];
/// Occluder colour: green.
pub const OCCLUDER: [f32; 4] = [0.0, 1.0, 0.0, 1.0];
/// Clear colour: black.
pub const CLEAR: [f32; 4] = [0.0, 0.0, 0.0, 1.0];

/// One configuration of the experiment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Setup {
    /// Near plane distance.
    pub n: f64,
    /// Far plane distance.
    pub f: f64,
    /// `tan` of the half field of view (both axes).
    pub tan_half: f64,
    /// Viewport width and height in pixels.
    pub size: u32,
    /// Depth attachment format.
    pub format: DepthFormat,
    /// Where the plane meets the view axis, as a fraction of `[n, f]`: `d0 = n + p·(f − n)`.
    pub depth_fraction: f64,
    /// Eye-space slope `dz/dy` of the plane (≥ 0).
    pub slope: f64,
}

/// An axis-aligned rectangle in the plane's (x, y) eye coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Extent {
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
}

impl Setup {
    /// The `glFrustum` parameters `(l, r, b, t, n, f)`.
    pub fn frustum(&self) -> (f64, f64, f64, f64, f64, f64) {
        let e = self.n * self.tan_half;
        (-e, e, -e, e, self.n, self.f)
    }

    /// Distance at which the plane meets the view axis.
    pub fn axis_depth(&self) -> f64 {
        self.n + self.depth_fraction * (self.f - self.n)
    }

    /// Eye distance of the plane at eye-space height `y`.
    pub fn distance_at(&self, y: f64) -> f64 {
        self.axis_depth() - self.slope * y
    }

    fn base_extent(&self) -> Extent {
        let (d0, s, t) = (self.axis_depth(), self.slope, self.tan_half);
        // Upward the plane approaches the eye: stay inside the top plane and 2% beyond near.
        let mut y1 = 0.85 * d0 * t / (1.0 + s * t);
        let mut y0 = -0.85 * d0 * t;
        if s > 0.0 {
            y1 = y1.min((d0 - 1.02 * self.n) / s);
            y0 = y0.max(-(0.98 * self.f - d0) / s);
        }
        let x = 0.85 * self.distance_at(y1) * t;
        Extent {
            x0: -x,
            x1: x,
            y0,
            y1,
        }
    }

    fn decal_extent(&self) -> Extent {
        let b = self.base_extent();
        Extent {
            x0: 0.55 * b.x0,
            x1: 0.6 * b.x1,
            y0: 0.6 * b.y0,
            y1: 0.5 * b.y1,
        }
    }

    fn quad(&self, e: Extent, toward: f64) -> Quad {
        let (d0, s) = (self.axis_depth(), self.slope);
        Quad::on_plane(e.x0, e.x1, e.y0, e.y1, |_, y| -d0 + s * y + toward)
    }

    /// The base quad.
    pub fn base(&self) -> Quad {
        self.quad(self.base_extent(), 0.0)
    }

    /// The decal quad: same plane, different vertices.
    pub fn decal(&self) -> Quad {
        self.quad(self.decal_extent(), 0.0)
    }

    /// An occluder: the decal's rectangle moved `gap` eye-space units toward the camera along z.
    pub fn occluder(&self, gap: f64) -> Quad {
        self.quad(self.decal_extent(), gap)
    }

    /// An occluder over the decal whose eye distance at every pixel is at least `gap` less than
    /// the base's there. Moving a plane of slope `s` by `G` along z changes the distance along
    /// a line of sight `y = k·d` by `G/(1 + s·k)`, so the shift is `gap·(1 + s·max k)`.
    pub fn occluder_with_depth_gap(&self, gap: f64) -> Quad {
        let e = self.decal_extent();
        let k_max = [e.y0, e.y1]
            .map(|y| y / self.distance_at(y))
            .into_iter()
            .fold(0.0, f64::max);
        self.occluder(gap * (1.0 + self.slope * k_max))
    }

    /// The decal's nearest and farthest eye distance (of its exact corners).
    pub fn decal_depth_range(&self) -> (f64, f64) {
        let e = self.decal_extent();
        let (a, b) = (self.distance_at(e.y0), self.distance_at(e.y1));
        (a.min(b), a.max(b))
    }

    /// A one-line label for tables.
    pub fn label(&self) -> String {
        format!(
            "{:<4} f/n={:<7.0e} d0={:>3.0}% slope={:<3}",
            self.format.name(),
            self.f / self.n,
            self.depth_fraction * 100.0,
            self.slope
        )
    }
}

/// A configured experiment on one context: the target is made and the decal's coverage known.
pub struct Bench<'a> {
    gl: &'a mut Gl,
    setup: Setup,
    plain: [f32; 16],
    mask: Vec<bool>,
}

/// Counts from one render: `hit` of `of` pixels (lost decal pixels, or bled ones).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Count {
    /// Pixels counted (lost, or bled).
    pub hit: usize,
    /// Pixels they were counted among (the decal's coverage, or decal ∩ occluder).
    pub of: usize,
}

impl Count {
    /// The pixels of `mask` (the decal's coverage) where `image` does not show the decal: lost.
    pub fn decal_missing(image: &Image, mask: &[bool]) -> Self {
        Self {
            hit: image.count_not_in_mask(mask, crate::rgba8(DECAL)),
            of: mask.iter().filter(|&&m| m).count(),
        }
    }

    /// The pixels of `mask` (decal ∩ occluder) where `image` shows the decal: bled.
    pub fn decal_shown(image: &Image, mask: &[bool]) -> Self {
        let red = crate::rgba8(DECAL);
        Self {
            hit: image
                .pixels
                .iter()
                .zip(mask)
                .filter(|(p, &m)| m && p[..3] == red[..3])
                .count(),
            of: mask.iter().filter(|&&m| m).count(),
        }
    }

    /// `hit / of` (0 when `of` is 0).
    pub fn fraction(&self) -> f64 {
        if self.of == 0 {
            0.0
        } else {
            self.hit as f64 / self.of as f64
        }
    }
}

impl<'a> Bench<'a> {
    /// Makes the target for `setup` and records which pixels the decal covers (drawn alone
    /// with `plain`; the offset changes only depth, never coverage).
    ///
    /// # Errors
    /// GL failures, or a decal that covers no pixel.
    pub fn new(gl: &'a mut Gl, setup: Setup, plain: [f32; 16]) -> Result<Self, String> {
        gl.set_target(setup.size, setup.size, setup.format)?;
        let mut bench = Bench {
            gl,
            setup,
            plain,
            mask: Vec::new(),
        };
        bench.mask = bench.coverage(&setup.decal())?;
        if !bench.mask.contains(&true) {
            return Err(format!("{}: the decal covers no pixel", setup.label()));
        }
        Ok(bench)
    }

    /// The setup this bench renders.
    pub fn setup(&self) -> Setup {
        self.setup
    }

    /// Decal pixels lost to the base when the decal is drawn with `decal_proj` (z-fighting).
    ///
    /// # Errors
    /// GL failures.
    pub fn lost(&mut self, decal_proj: &[f32; 16]) -> Result<Count, String> {
        self.lost_with(decal_proj, &DrawState::default())
    }

    /// As [`Bench::lost`], with the decal drawn under `state` (e.g. a polygon offset).
    ///
    /// # Errors
    /// GL failures.
    pub fn lost_with(
        &mut self,
        decal_proj: &[f32; 16],
        state: &DrawState,
    ) -> Result<Count, String> {
        let s = self.setup;
        self.gl.clear(CLEAR, 1.0)?;
        self.gl
            .draw_quad(&s.base(), &self.plain, BASE, &DrawState::default())?;
        self.gl.draw_quad(&s.decal(), decal_proj, DECAL, state)?;
        Ok(Count::decal_missing(&self.gl.read_color()?, &self.mask))
    }

    /// Decal pixels drawn over an occluder at least `gap` eye-space units nearer than the base at
    /// every pixel ([`Setup::occluder_with_depth_gap`]), among the pixels both cover
    /// (bleed-through).
    ///
    /// # Errors
    /// GL failures.
    pub fn bleed(&mut self, decal_proj: &[f32; 16], gap: f64) -> Result<Count, String> {
        let s = self.setup;
        let occluder = s.occluder_with_depth_gap(gap);
        let occ_mask = self.coverage(&occluder)?;
        let both: Vec<bool> = occ_mask
            .iter()
            .zip(&self.mask)
            .map(|(a, b)| *a && *b)
            .collect();
        self.gl.clear(CLEAR, 1.0)?;
        self.gl
            .draw_quad(&s.base(), &self.plain, BASE, &DrawState::default())?;
        self.gl
            .draw_quad(&occluder, &self.plain, OCCLUDER, &DrawState::default())?;
        self.gl
            .draw_quad(&s.decal(), decal_proj, DECAL, &DrawState::default())?;
        Ok(Count::decal_shown(&self.gl.read_color()?, &both))
    }

    fn coverage(&mut self, quad: &Quad) -> Result<Vec<bool>, String> {
        coverage(self.gl, quad, &self.plain)
    }
}

/// The pixels `quad` covers when drawn alone through `proj` (depth test `GL_ALWAYS`, so any
/// offset or clear depth gives the same mask). Leaves the target dirty: clear before drawing.
///
/// # Errors
/// GL failures.
pub fn coverage(gl: &mut Gl, quad: &Quad, proj: &[f32; 16]) -> Result<Vec<bool>, String> {
    gl.clear(CLEAR, 1.0)?;
    let state = DrawState {
        depth_func: glow::ALWAYS,
        ..DrawState::default()
    };
    gl.draw_quad(quad, proj, DECAL, &state)?;
    Ok(gl.read_color()?.mask_of(crate::rgba8(DECAL)))
}

/// The projection element that carries the decal's offset: 14 under reversed Z (scaled up, a
/// relative offset), 10 otherwise (moved toward 0, a constant NDC offset).
pub fn offset_element(reversed: bool) -> usize {
    if reversed {
        14
    } else {
        10
    }
}

/// `plain` with its offset element ([`offset_element`]) moved `k` f32 steps toward the camera:
/// element 14 (> 0) up under reversed Z, element 10 (< 0) toward 0 otherwise. The finest
/// offset a projection matrix can carry is one step.
pub fn stepped_toward_camera(plain: &[f32; 16], reversed: bool, k: u32) -> [f32; 16] {
    let mut m = *plain;
    let i = offset_element(reversed);
    let bits = m[i].to_bits();
    m[i] = f32::from_bits(if reversed { bits + k } else { bits - k });
    m
}

/// The f32 steps between the offset elements ([`offset_element`]) of `plain` and `m`.
pub fn steps_between(plain: &[f32; 16], m: &[f32; 16], reversed: bool) -> u32 {
    let i = offset_element(reversed);
    m[i].to_bits().abs_diff(plain[i].to_bits())
}

/// The smallest `k` in `lo + 1..=hi` that passes, by bisection, given that `lo` fails and `hi`
/// passes (assumes passing is monotone in `k`).
///
/// # Errors
/// Whatever `passes` returns.
pub fn bisect_smallest_passing(
    lo: u32,
    hi: u32,
    mut passes: impl FnMut(u32) -> Result<bool, String>,
) -> Result<u32, String> {
    let (mut lo, mut hi) = (lo, hi);
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if passes(mid)? {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    Ok(hi)
}

/// Element 10 moved `k` f32 steps toward zero (the decal toward the camera by `k` ulps of
/// element 10 in NDC): [`stepped_toward_camera`] for the `[−1, 1]` and `[0, 1]` conventions.
pub fn with_ulps_toward_camera(plain: &[f32; 16], k: u32) -> [f32; 16] {
    assert!(
        plain[10] < 0.0 && k < plain[10].to_bits() & 0x7FFF_FFFF,
        "element 10 must be negative and k small"
    );
    stepped_toward_camera(plain, false, k)
}

/// The smallest `k` (see [`with_ulps_toward_camera`]) in `1..=max_k` at which no decal pixel is
/// lost, by bisection (assumes losses only shrink as the offset grows), or `None` if even
/// `max_k` loses pixels.
///
/// # Errors
/// GL failures.
pub fn smallest_working_ulps(bench: &mut Bench, max_k: u32) -> Result<Option<u32>, String> {
    let plain = bench.plain;
    if bench.lost(&with_ulps_toward_camera(&plain, max_k))?.hit > 0 {
        return Ok(None);
    }
    // k = 0 (no offset) is taken to fail; max_k works.
    bisect_smallest_passing(0, max_k, |k| {
        Ok(bench.lost(&with_ulps_toward_camera(&plain, k))?.hit == 0)
    })
    .map(Some)
}

/// The smallest `k` such that every offset from `k` up to `k_hi` steps (see
/// [`with_ulps_toward_camera`]) loses no decal pixel, scanning down from `k_hi`; `None` if `k_hi`
/// itself loses pixels. Losses are not monotone in `k` near the threshold (each element 10
/// rounds the transform differently: measured, 1 step can work where 2 lose 19 %), so this is
/// the robust threshold, never below what [`smallest_working_ulps`]'s bisection may report
/// by luck.
///
/// # Errors
/// GL failures.
pub fn smallest_working_ulps_below(bench: &mut Bench, k_hi: u32) -> Result<Option<u32>, String> {
    let plain = bench.plain;
    let mut k = k_hi;
    if bench.lost(&with_ulps_toward_camera(&plain, k))?.hit > 0 {
        return Ok(None);
    }
    while k > 1 && bench.lost(&with_ulps_toward_camera(&plain, k - 1))?.hit == 0 {
        k -= 1;
    }
    Ok(Some(k))
}

/// The number of f32 steps between the plain element 10 and an offset one (toward the camera).
pub fn ulps_toward_camera(plain: &[f32; 16], offset: &[f32; 16]) -> u32 {
    plain[10].to_bits().saturating_sub(offset[10].to_bits())
}
