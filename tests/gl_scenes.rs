//! The recommendation on the scenes engines draw, checked on a real rasterizer (headless EGL;
//! Mesa llvmpipe in CI): ground planes running behind the camera (base corners ≥ 100× the
//! decal's distance, clipped by the rasterizer, and the same base cut to the frustum in f64 by
//! `recommend::clip_to_frustum`), screen-fitted bases, slopes 0 to 10 and grazing planes whose
//! horizon is on screen, odd viewports (97×211, 320×180, 64×48), off-centre frusta (one whose
//! view axis is off screen), f/n from 10 to 1e7 and infinite, D16/D24/D32F under `[−1, 1]`,
//! `[0, 1]` and reversed Z, `GL_LESS`/`GL_LEQUAL` (`GL_GREATER`/`GL_GEQUAL` reversed), decals
//! whose corners are not the base's. Every scene is checked with the worst-case profile (the
//! default) and with the profile `zshift::probe::probe` measures in this test's own context: 0
//! decal pixels lost at the recommendation, 0 pixels bled through an occluder at the documented
//! gap. Then it prints, per class, the
//! recommended ÷ smallest working offset (bisection over f32 steps of the offset element).
//!
//! References are GL readbacks and this file's own f64 geometry, never zshift's numbers.
//! Fails (never skips) without GL.
//!
//! CI runs a deterministic sample of the grid (`ZSHIFT_SCENES` unset: one scene in 12, about 1000
//! scenes in 5 s on two cores; the full grid 40 s); `ZSHIFT_SCENES=full` runs every scene of the grid, `ZSHIFT_SCENES=N`
//! one in N. `cargo test --release --test gl_scenes -- --nocapture` prints the table;
//! `ZSHIFT_SCENES_SEED=N` draws another grid of the same classes (other slopes, decals and depths),
//! `ZSHIFT_SCENES_VERBOSE=1` also names every refused scene and the survey's worst planes,
//! `ZSHIFT_SCENES_TERMS=1` every scene's error terms.
//! `ZSHIFT_SCENES_ONLY=<text>` only the scenes whose label contains `<text>`.

mod gl_common;

use zshift::projection::{projection, ClipDepth, Frustum};
use zshift::recommend::{
    clip_to_frustum, decal_shape, recommend_clip, Base, ClipRecommendation, DepthTest,
    RasterizerProfile, Scene,
};
use zshift_harness::coplanar::{
    bisect_smallest_passing, coverage, stepped_toward_camera, steps_between, Count, BASE, CLEAR,
    DECAL, OCCLUDER,
};
use zshift_harness::{ClipDepth as GlClip, DepthFormat, DrawState, Gl, Profile, Quad};

/// The profile `zshift::probe::probe` measures in this test's own context (what an engine
/// does once at start-up): on llvmpipe unsnapped, `r` = 2 quanta on UNORM, `error_ulps` ≈ 1.4,
/// near-plane clipping in f32. `the_probed_error_bound_holds` checks its per-pixel bound
/// against planes the probe never drew.
fn probed(gl: &Gl) -> RasterizerProfile {
    let profile = gl_common::probed(gl);
    assert!(
        profile.measured && profile.error_ulps.is_finite(),
        "{profile:?}"
    );
    profile
}

// ---------------------------------------------------------------------------------------------
// Geometry, in f64, independent of zshift.
// ---------------------------------------------------------------------------------------------

/// `glFrustum(l, r, b, t, n, f)`, `f` may be infinite.
#[derive(Debug, Clone, Copy)]
struct Cam {
    l: f64,
    r: f64,
    b: f64,
    t: f64,
    n: f64,
    f: f64,
}

impl Cam {
    /// The sweep's frustum of `kind` ("centred", "off-centre", or "axis-off": the view axis
    /// left of and below the screen) for a viewport `aspect`, with n = 0.1 and f = n·`ratio`
    /// (infinite for an infinite ratio).
    fn of_kind(kind: &str, aspect: f64, ratio: f64) -> Self {
        let n = 0.1;
        let t = n * 0.5774;
        let (l, r, b, tt) = match kind {
            "centred" => (-t * aspect, t * aspect, -t, t),
            "off-centre" => (-0.4 * t * aspect, 1.3 * t * aspect, -1.2 * t, 0.6 * t),
            _ => (0.15 * t * aspect, 1.6 * t * aspect, 0.1 * t, 1.1 * t),
        };
        let f = if ratio.is_finite() {
            n * ratio
        } else {
            f64::INFINITY
        };
        Cam {
            l,
            r,
            b,
            t: tt,
            n,
            f,
        }
    }

    /// The eye ray `(kₓ, k_y)` (eye x/d, y/d) through NDC `(x, y)`.
    fn ray(&self, x: f64, y: f64) -> (f64, f64) {
        let kx = (self.l + 0.5 * (x + 1.0) * (self.r - self.l)) / self.n;
        let ky = (self.b + 0.5 * (y + 1.0) * (self.t - self.b)) / self.n;
        (kx, ky)
    }

    /// Window depth of eye depth `d` under `clip` (`glDepthRange(0, 1)`).
    fn window(&self, d: f64, clip: ClipDepth) -> f64 {
        let (n, f) = (self.n, self.f);
        let inf = f.is_infinite();
        match clip {
            ClipDepth::NegOneToOne if inf => 1.0 - n / d,
            ClipDepth::NegOneToOne => 0.5 * ((f + n) / (f - n) - 2.0 * f * n / ((f - n) * d)) + 0.5,
            ClipDepth::ZeroToOne if inf => 1.0 - n / d,
            ClipDepth::ZeroToOne => f / (f - n) * (1.0 - n / d),
            ClipDepth::ReversedZeroToOne if inf => n / d,
            ClipDepth::ReversedZeroToOne => n * (f - d) / ((f - n) * d),
        }
    }

    fn frustum(&self) -> Frustum {
        Frustum::new(self.l, self.r, self.b, self.t, self.n, self.f).expect("valid frustum")
    }
}

/// The eye-space plane `z = −d_a + sₓ·x + s_y·y`.
#[derive(Debug, Clone, Copy)]
struct Plane {
    sx: f64,
    sy: f64,
    da: f64,
}

impl Plane {
    fn z(&self, x: f64, y: f64) -> f64 {
        -self.da + self.sx * x + self.sy * y
    }

    /// Eye depth (−z) where the ray `(kₓ, k_y)` meets the plane, if in front of the eye.
    fn depth_on_ray(&self, (kx, ky): (f64, f64)) -> Option<f64> {
        let d = self.da / (1.0 + self.sx * kx + self.sy * ky);
        (d.is_finite() && d > 0.0).then_some(d)
    }

    fn point(&self, (kx, ky): (f64, f64), d: f64) -> [f64; 3] {
        [kx * d, ky * d, -d]
    }
}

/// How the base is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
enum BaseKind {
    /// Screen-fitted: the plane under NDC `[−0.9, 0.9]²` (cut at 0.9·f / 200·d₂ toward the
    /// horizon), inside the frustum.
    Fitted,
    /// A quad `±R` around the decal (R = 100× the decal's far distance): the rasterizer clips it
    /// (it runs behind the camera unless the plane faces it).
    Ground,
    /// The same quad cut to the frustum in f64 by `recommend::clip_to_frustum`.
    Split,
}

/// One scene.
#[derive(Debug, Clone)]
struct Case {
    cam: Cam,
    size: (u32, u32),
    clip: ClipDepth,
    format: DepthFormat,
    test: DepthTest,
    plane: Plane,
    base_kind: BaseKind,
    /// The decal's corners (f64, on the plane), and the base's polygon.
    decal: [[f64; 3]; 4],
    base: Vec<[f64; 3]>,
    frustum_kind: &'static str,
}

impl Case {
    fn slope(&self) -> f64 {
        self.plane.sx.abs() + self.plane.sy.abs()
    }

    /// The decal's eye depths as drawn: its corners' f32 z (what an engine passes).
    fn depth_range(&self) -> (f64, f64) {
        let d = self.decal.map(|p| -f64::from(p[2] as f32));
        (
            d.iter().copied().fold(f64::INFINITY, f64::min),
            d.iter().copied().fold(0.0, f64::max),
        )
    }

    fn class(&self) -> String {
        let conv = match self.clip {
            ClipDepth::NegOneToOne => "[-1,1]",
            ClipDepth::ZeroToOne => "[0,1]",
            ClipDepth::ReversedZeroToOne => "rev-Z",
        };
        let shape = if self.slope() == 0.0 {
            "facing"
        } else {
            "sloped"
        };
        let test = if self.test.is_strict() { "<" } else { "<=" };
        let base = match self.base_kind {
            BaseKind::Fitted => "fitted",
            BaseKind::Ground => "clipped",
            BaseKind::Split => "split",
        };
        format!(
            "{conv:<6} {:<4} {test:<2} {shape:<6} {base:<7}",
            self.format.name()
        )
    }

    fn label(&self) -> String {
        let (d1, d2) = self.depth_range();
        let far = if self.cam.f.is_infinite() {
            "inf".to_string()
        } else {
            format!("{:.0e}", self.cam.f / self.cam.n)
        };
        format!(
            "{} {:?} {}x{} {} f/n={far} s=({:.2},{:.2}) d=[{d1:.4e},{d2:.4e}]",
            self.class(),
            self.test,
            self.size.0,
            self.size.1,
            self.frustum_kind,
            self.plane.sx,
            self.plane.sy,
        )
    }

    fn reach(&self) -> f64 {
        self.base
            .iter()
            .flat_map(|p| p.iter().map(|c| c.abs()))
            .fold(0.0, f64::max)
    }

    /// What the engine knows, as zshift's `Scene` takes it.
    fn scene(&self, profile: RasterizerProfile) -> Scene {
        let (d1, d2) = self.depth_range();
        let format = zshift::recommend::DepthFormat::from_gl_internal_format(self.format.gl_enum())
            .expect("a GL depth format");
        Scene {
            pipeline: Default::default(),
            footprint: None,
            frustum: self.cam.frustum(),
            viewport: [self.size.0, self.size.1],
            format,
            depth_range: [d1, d2],
            slope: self.slope(),
            // A facing plane's corners all have z = −d_a, and `clip_to_frustum` keeps that z
            // exactly (a + t·(b − a) with a = b): fitted and cut bases share the decal's f32 z.
            exact_depth: self.slope() == 0.0 && self.base_kind != BaseKind::Ground,
            depth_test: self.test,
            base: match self.base_kind {
                BaseKind::Ground => Base::Clipped {
                    reach: self.reach(),
                },
                _ => Base::InsideFrustum,
            },
            profile,
        }
    }

    fn reversed(&self) -> bool {
        self.clip == ClipDepth::ReversedZeroToOne
    }

    /// The scene as an engine that passes the decal's corners describes it: depth range,
    /// slope and footprint from `decal_shape` on the f32 corners it draws.
    fn scene_with_corners(&self, profile: RasterizerProfile) -> Scene {
        let corners = self
            .decal
            .map(|p| glam::Vec3::new(p[0] as f32, p[1] as f32, p[2] as f32));
        let shape = decal_shape(
            &self.cam.frustum(),
            self.clip,
            [self.size.0, self.size.1],
            &corners,
        )
        .unwrap_or_else(|e| panic!("decal_shape on {}: {e}", self.label()));
        Scene {
            depth_range: shape.depth_range,
            slope: shape.slope,
            footprint: Some(shape.footprint),
            ..self.scene(profile)
        }
    }
}

/// Cuts `poly` to the region `keep(p) ≥ 0` (Sutherland–Hodgman, f64): this test's own clipper.
fn cut(poly: &[[f64; 3]], keep: impl Fn(&[f64; 3]) -> f64) -> Vec<[f64; 3]> {
    let mut out = Vec::new();
    for (i, a) in poly.iter().enumerate() {
        let b = &poly[(i + 1) % poly.len()];
        let (da, db) = (keep(a), keep(b));
        if da >= 0.0 {
            out.push(*a);
        }
        if (da >= 0.0) != (db >= 0.0) {
            let t = da / (da - db);
            out.push([0, 1, 2].map(|k| a[k] + t * (b[k] - a[k])));
        }
    }
    out
}

/// The plane under the screen rectangle NDC `[−0.9, 0.9]²`, cut at depth `far` and at 1.01·n.
fn fitted_base(cam: &Cam, plane: &Plane, far: f64) -> Vec<[f64; 3]> {
    // A big quad on the plane, cut to the shrunk frustum by this file's own clipper.
    let big = 1e3 * far;
    let mut poly: Vec<[f64; 3]> = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .iter()
        .map(|&(x, y)| [x * big, y * big, plane.z(x * big, y * big)])
        .collect();
    let (xl, yb) = cam.ray(-0.9, -0.9);
    let (xr, yt) = cam.ray(0.9, 0.9);
    let n = cam.n;
    poly = cut(&poly, |p| -p[2] - 1.01 * n);
    poly = cut(&poly, |p| far + p[2]);
    poly = cut(&poly, |p| p[0] - xl * -p[2]);
    poly = cut(&poly, |p| xr * -p[2] - p[0]);
    poly = cut(&poly, |p| p[1] - yb * -p[2]);
    poly = cut(&poly, |p| yt * -p[2] - p[1]);
    poly
}

/// The f32 quads that draw a convex polygon as a fan (one triangle each, the fourth corner
/// repeating the third: a zero-area second triangle).
fn fan(poly: &[[f64; 3]]) -> Vec<Quad> {
    let v = |p: &[f64; 3]| p.map(|c| c as f32);
    (1..poly.len().saturating_sub(1))
        .map(|i| Quad {
            corners: [v(&poly[0]), v(&poly[i]), v(&poly[i + 1]), v(&poly[i + 1])],
        })
        .collect()
}

fn quad_of(c: &[[f64; 3]; 4]) -> Quad {
    Quad {
        corners: c.map(|p| p.map(|x| x as f32)),
    }
}

/// A deterministic generator for sampling the grid.
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Builds a scene: the decal is the plane under the NDC rectangle centred at `(cx, cy)` with
/// half-size `hs`, whose centre lies at eye depth `dc`. `None` when the decal leaves `[n, f]`
/// or crosses the horizon.
#[allow(clippy::too_many_arguments)]
fn build(
    cam: Cam,
    frustum_kind: &'static str,
    size: (u32, u32),
    (clip, format): (ClipDepth, DepthFormat),
    test: DepthTest,
    (sx, sy): (f64, f64),
    (cx, cy, hs, dc): (f64, f64, f64, f64),
    base_kind: BaseKind,
) -> Option<Case> {
    let kc = cam.ray(cx, cy);
    let centre = [kc.0 * dc, kc.1 * dc, -dc];
    let plane = Plane {
        sx,
        sy,
        da: dc + sx * centre[0] + sy * centre[1],
    };
    let mut decal = [[0.0; 3]; 4];
    for (i, (x, y)) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .into_iter()
        .enumerate()
    {
        // A slightly irregular quad: corners not on a grid the base shares.
        let k = cam.ray(cx + hs * x * (1.0 + 0.07 * i as f64), cy + hs * y * 0.83);
        let d = plane.depth_on_ray(k)?;
        let far_limit = if cam.f.is_finite() {
            0.95 * cam.f
        } else {
            1e12
        };
        if d < 1.05 * cam.n || d > far_limit {
            return None;
        }
        decal[i] = plane.point(k, d);
    }
    let d2 = decal.iter().map(|p| -p[2]).fold(0.0, f64::max);
    let base = match base_kind {
        BaseKind::Fitted => {
            let far = if cam.f.is_finite() {
                (0.9 * cam.f).min(200.0 * d2)
            } else {
                200.0 * d2
            };
            fitted_base(&cam, &plane, far)
        }
        BaseKind::Ground | BaseKind::Split => {
            let r = 100.0 * d2;
            let ground: Vec<[f64; 3]> = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
                .iter()
                .map(|&(x, y)| {
                    let (px, py) = (centre[0] + x * r, centre[1] + y * r);
                    [px, py, plane.z(px, py)]
                })
                .collect();
            if base_kind == BaseKind::Split {
                clip_to_frustum(&cam.frustum(), &ground).expect("clip_to_frustum")
            } else {
                ground
            }
        }
    };
    if base.len() < 3 {
        return None;
    }
    Some(Case {
        cam,
        size,
        clip,
        format,
        test,
        plane,
        base_kind,
        decal,
        base,
        frustum_kind,
    })
}

/// The grid's own seed (slopes, decals, depths): the scenes the docs' figures come from.
const GRID_SEED: u64 = 0x2026_1123;

/// [`grid_with`] the grid's seed, or `ZSHIFT_SCENES_SEED`'s: another grid of the same classes.
fn grid(every: usize) -> Vec<Case> {
    let seed = std::env::var("ZSHIFT_SCENES_SEED")
        .ok()
        .and_then(|v| v.parse::<u64>().ok())
        .unwrap_or(GRID_SEED);
    grid_with(every, seed)
}

/// The grid, sampled one in `every` (deterministically), its scenes drawn from `seed`.
fn grid_with(every: usize, seed: u64) -> Vec<Case> {
    let mut rng = Lcg(seed);
    let mut sample = Lcg(0x005A_3D1E);
    let mut cases = Vec::new();
    let kinds = [
        (ClipDepth::NegOneToOne, DepthFormat::D16),
        (ClipDepth::NegOneToOne, DepthFormat::D24),
        (ClipDepth::NegOneToOne, DepthFormat::D32F),
        (ClipDepth::ZeroToOne, DepthFormat::D16),
        (ClipDepth::ZeroToOne, DepthFormat::D24),
        (ClipDepth::ZeroToOne, DepthFormat::D32F),
        (ClipDepth::ReversedZeroToOne, DepthFormat::D16),
        (ClipDepth::ReversedZeroToOne, DepthFormat::D24),
        (ClipDepth::ReversedZeroToOne, DepthFormat::D32F),
    ];
    for size in [(97u32, 211u32), (320, 180), (64, 48)] {
        let aspect = f64::from(size.0) / f64::from(size.1);
        for frustum_kind in ["centred", "off-centre", "axis-off"] {
            for ratio in [10.0, 1e3, 1e5, 1e7, f64::INFINITY] {
                let cam = Cam::of_kind(frustum_kind, aspect, ratio);
                for kind in kinds {
                    for slope in [0.0, 0.3, 1.0, 3.0, 10.0] {
                        for base_kind in [BaseKind::Fitted, BaseKind::Ground, BaseKind::Split] {
                            for test in [false, true] {
                                if sample.next() * every as f64 >= 1.0 {
                                    continue;
                                }
                                let test = match (kind.0 == ClipDepth::ReversedZeroToOne, test) {
                                    (false, false) => DepthTest::Less,
                                    (false, true) => DepthTest::LessEqual,
                                    (true, false) => DepthTest::Greater,
                                    (true, true) => DepthTest::GreaterEqual,
                                };
                                // Tilt direction: mostly "ground" (about x), sometimes a wall.
                                let a = rng.next() * std::f64::consts::TAU;
                                let (sx, sy) = if rng.next() < 0.6 {
                                    (0.2 * slope * a.cos(), slope * (0.8 + 0.2 * a.sin()))
                                } else {
                                    (slope * a.cos(), slope * a.sin())
                                };
                                let sy = if slope > 0.0 && rng.next() < 0.7 {
                                    -sy.abs()
                                } else {
                                    sy
                                };
                                let span = if ratio.is_finite() { ratio } else { 1e4 };
                                for _attempt in 0..8 {
                                    let p = 0.15 + 0.8 * rng.next();
                                    let dc = cam.n * span.powf(p).max(1.5);
                                    let (cx, cy) = (rng.next() - 0.5, rng.next() - 0.5);
                                    let hs = 0.08 + 0.2 * rng.next();
                                    if let Some(c) = build(
                                        cam,
                                        frustum_kind,
                                        size,
                                        kind,
                                        test,
                                        (sx, sy),
                                        (cx, cy, hs, dc),
                                        base_kind,
                                    ) {
                                        cases.push(c);
                                        break;
                                    }
                                }
                            }
                        }
                    }
                }
            }
        }
    }
    cases
}

// ---------------------------------------------------------------------------------------------
// Rendering.
// ---------------------------------------------------------------------------------------------

struct Bench<'a> {
    gl: &'a mut Gl,
    case: &'a Case,
    plain: [f32; 16],
    mask: Vec<bool>,
    base: Vec<Quad>,
    decal: Quad,
}

impl<'a> Bench<'a> {
    fn new(gl: &'a mut Gl, case: &'a Case) -> Result<Self, String> {
        gl.set_target(case.size.0, case.size.1, case.format)?;
        gl.clip_control(if case.clip == ClipDepth::NegOneToOne {
            GlClip::NegativeOneToOne
        } else {
            GlClip::ZeroToOne
        })?;
        let plain = projection(&case.cam.frustum(), case.clip).map_err(|e| e.to_string())?;
        let base = match case.base_kind {
            BaseKind::Ground => vec![Quad {
                corners: [0, 1, 2, 3].map(|i| case.base[i].map(|c| c as f32)),
            }],
            _ => fan(&case.base),
        };
        let mut b = Bench {
            gl,
            case,
            plain,
            mask: Vec::new(),
            base,
            decal: quad_of(&case.decal),
        };
        b.mask = b.coverage(&b.decal.clone())?;
        Ok(b)
    }

    /// The test the base and occluders are drawn with (the usual opaque pass).
    fn opaque(&self) -> DrawState {
        DrawState {
            depth_func: if self.case.reversed() {
                glow::GREATER
            } else {
                glow::LESS
            },
            ..DrawState::default()
        }
    }

    /// The decal pass's test.
    fn decal_state(&self) -> DrawState {
        DrawState {
            depth_func: self.case.test.gl_enum(),
            ..DrawState::default()
        }
    }

    fn clear(&mut self) -> Result<(), String> {
        let depth = if self.case.reversed() { 0.0 } else { 1.0 };
        self.gl.clear(CLEAR, depth)
    }

    fn coverage(&mut self, quad: &Quad) -> Result<Vec<bool>, String> {
        coverage(self.gl, quad, &self.plain)
    }

    fn draw_base(&mut self) -> Result<(), String> {
        let (plain, state) = (self.plain, self.opaque());
        for q in &self.base {
            self.gl.draw_quad(q, &plain, BASE, &state)?;
        }
        Ok(())
    }

    /// Decal pixels lost to the base with the decal drawn through `decal`.
    fn lost(&mut self, decal: &[f32; 16]) -> Result<Count, String> {
        self.clear()?;
        self.draw_base()?;
        let (q, state) = (self.decal, self.decal_state());
        self.gl.draw_quad(&q, decal, DECAL, &state)?;
        Ok(Count::decal_missing(&self.gl.read_color()?, &self.mask))
    }

    /// Decal pixels drawn over an occluder whose eye depth (−z) at every pixel is at least `gap`
    /// less than the base's: the decal's quad moved along z by `gap·(1 + sₓkₓ + s_y·k_y)`, the
    /// factor of largest magnitude over its corners (a plane shifted by δ along z moves by
    /// `δ/(1 + sₓkₓ + s_y·k_y)` along the ray).
    fn bleed(&mut self, decal: &[f32; 16], gap: f64) -> Result<Count, String> {
        let p = self.case.plane;
        // 1 + sₓkₓ + s_y·k_y has one sign over the visible plane (negative when the plane's
        // axis crossing lies behind the eye: then the occluder moves along −z).
        let widest = self
            .case
            .decal
            .iter()
            .map(|c| 1.0 + (p.sx * c[0] + p.sy * c[1]) / -c[2])
            .fold(0.0, |a: f64, b| if b.abs() > a.abs() { b } else { a });
        let shift = gap * widest;
        let mut corners = self.case.decal;
        for c in &mut corners {
            c[2] += shift;
        }
        if corners.iter().any(|c| -c[2] <= 1.001 * self.case.cam.n) {
            return Ok(Count::default());
        }
        let occluder = quad_of(&corners);
        let both: Vec<bool> = self
            .coverage(&occluder)?
            .iter()
            .zip(&self.mask)
            .map(|(a, b)| *a && *b)
            .collect();
        self.clear()?;
        self.draw_base()?;
        let (plain, opaque, state) = (self.plain, self.opaque(), self.decal_state());
        self.gl.draw_quad(&occluder, &plain, OCCLUDER, &opaque)?;
        let q = self.decal;
        self.gl.draw_quad(&q, decal, DECAL, &state)?;
        Ok(Count::decal_shown(&self.gl.read_color()?, &both))
    }

    /// The plain matrix with the offset element moved `k` f32 steps toward the camera.
    fn stepped(&self, k: u32) -> [f32; 16] {
        stepped_toward_camera(&self.plain, self.case.reversed(), k)
    }

    fn steps_of(&self, m: &[f32; 16]) -> u32 {
        steps_between(&self.plain, m, self.case.reversed())
    }

    /// The smallest k in 0..=hi that loses no pixel, by bisection (`hi` must work).
    fn smallest_working(&mut self, hi: u32) -> Result<u32, String> {
        if self.lost(&self.stepped(0))?.hit == 0 {
            return Ok(0);
        }
        bisect_smallest_passing(0, hi, |k| Ok(self.lost(&self.stepped(k))?.hit == 0))
    }
}

/// One profile's result on one scene.
#[derive(Debug, Clone, Copy)]
struct Outcome {
    rec: ClipRecommendation,
    lost: Count,
    bled: Count,
    steps: u32,
}

/// The four ways a scene is described: each profile, without and with the decal's corners.
const DESCRIPTIONS: [&str; 4] = ["default", "measured", "default+corners", "measured+corners"];

struct Row {
    case: Case,
    /// One outcome per [`DESCRIPTIONS`] entry.
    outcomes: [Outcome; 4],
    /// Smallest working offset in f32 steps of the offset element (0: none needed).
    k_min: u32,
    none: Count,
}

fn outcome(bench: &mut Bench, rec: ClipRecommendation) -> Result<Outcome, String> {
    let lost = bench.lost(&rec.matrix)?;
    let bled = bench.bleed(&rec.matrix, rec.bleed_gap)?;
    Ok(Outcome {
        rec,
        lost,
        bled,
        steps: bench.steps_of(&rec.matrix),
    })
}

/// `ZSHIFT_SCENES_ONLY=<text>`: only the scenes whose label contains it (to look at one).
fn left_out(label: &str) -> bool {
    std::env::var("ZSHIFT_SCENES_ONLY").is_ok_and(|only| !label.contains(only.as_str()))
}

fn measure(gl: &mut Gl, case: Case, probed: RasterizerProfile) -> Result<Option<Row>, String> {
    let label = case.label();
    if left_out(&label) {
        return Ok(None);
    }
    let worst = RasterizerProfile::worst_case();
    let scenes = [
        case.scene(worst),
        case.scene(probed),
        case.scene_with_corners(worst),
        case.scene_with_corners(probed),
    ];
    let recs: Vec<_> = scenes
        .iter()
        .map(|s| recommend_clip(s, case.clip))
        .collect();
    if recs.iter().any(|r| r.is_err()) {
        // Refused (the clipping term of a clipped base made the offset useless): say so.
        if std::env::var_os("ZSHIFT_SCENES_VERBOSE").is_some() {
            let errors: Vec<String> = recs
                .iter()
                .filter_map(|r| r.as_ref().err().map(|e| e.to_string()))
                .collect();
            println!("{label}: refused: {errors:?}");
        }
        return Ok(None);
    }
    let mut bench = Bench::new(gl, &case)?;
    if !bench.mask.iter().any(|&m| m) {
        return Ok(None);
    }
    let none = bench.lost(&bench.plain.clone())?;
    let mut outcomes = Vec::new();
    for rec in recs.into_iter().flatten() {
        outcomes.push(outcome(&mut bench, rec)?);
    }
    let outcomes: [Outcome; 4] = outcomes.try_into().expect("four outcomes");
    let hi = outcomes.iter().map(|o| o.steps).max().unwrap_or(0);
    let k_min = if outcomes.iter().any(|o| o.lost.hit == 0) {
        bench.smallest_working(hi)?
    } else {
        u32::MAX
    };
    drop(bench);
    if std::env::var_os("ZSHIFT_SCENES_TERMS").is_some() {
        for (name, o) in DESCRIPTIONS.iter().zip(&outcomes) {
            let t = o.rec.terms;
            println!(
                "terms {label} [{name}]: steps {} min {k_min} | q {:.2e} T {:.2e} V {:.2e} I {:.2e} E {:.2e} S {:.2e} C {:.2e}",
                o.steps, t.quantum, t.transform, t.vertex, t.interpolation, t.plane, t.snap, t.clip
            );
        }
    }
    Ok(Some(Row {
        case,
        outcomes,
        k_min,
        none,
    }))
}

/// What a scene [`measure`] could not measure (refused by some description, or empty) gives
/// with the probed profile alone.
enum ProbedAlone {
    /// The decal covers no pixel (or `ZSHIFT_SCENES_ONLY` leaves the scene out): nothing to judge.
    Empty,
    /// The probed profile refuses it too.
    Refused,
    /// The probed descriptions answer: drawn, with their failures (lost or bled pixels).
    Drawn(Vec<String>),
}

/// Asks for `case` with the probed profile alone (without and with corners) and draws the
/// answers ([`ProbedAlone`]).
fn probed_alone(gl: &mut Gl, case: Case, probed: RasterizerProfile) -> Result<ProbedAlone, String> {
    if left_out(&case.label()) {
        return Ok(ProbedAlone::Empty);
    }
    if std::env::var_os("ZSHIFT_SCENES_TERMS").is_some() {
        let worst = zshift::recommend::clip_error_terms(
            &case.scene(RasterizerProfile::worst_case()),
            case.clip,
        );
        println!("terms {} [default, refused]: {worst:?}", case.label());
    }
    let asks = [case.scene(probed), case.scene_with_corners(probed)];
    let Ok(recs) = asks
        .iter()
        .map(|s| recommend_clip(s, case.clip))
        .collect::<Result<Vec<_>, _>>()
    else {
        return Ok(ProbedAlone::Refused);
    };
    let mut bench = Bench::new(gl, &case)?;
    if !bench.mask.iter().any(|&m| m) {
        return Ok(ProbedAlone::Empty);
    }
    let mut failed = Vec::new();
    for rec in recs {
        let o = outcome(&mut bench, rec)?;
        if o.lost.hit > 0 || o.bled.hit > 0 {
            failed.push(format!(
                "{} [probed, the worst case refused]: {} lost, {} bled",
                case.label(),
                o.lost.hit,
                o.bled.hit
            ));
        }
    }
    Ok(ProbedAlone::Drawn(failed))
}

fn every() -> usize {
    match std::env::var("ZSHIFT_SCENES").ok().as_deref() {
        Some("full") => 1,
        Some(n) => n.parse().unwrap_or(12),
        None => 12,
    }
}

fn ratio(o: &Outcome, k_min: u32) -> f64 {
    o.steps as f64 / f64::from(k_min.max(1))
}

/// Every lost or bled pixel of `rows`, one line per scene and description.
fn failures_of(rows: &[Row]) -> Vec<String> {
    let mut failures = Vec::new();
    for r in rows {
        for (name, o) in DESCRIPTIONS.iter().zip(&r.outcomes) {
            if o.lost.hit > 0 {
                failures.push(format!(
                    "{} [{name} profile]: {} of {} decal pixels lost at the recommendation ({} steps; none needed {} lost without offset)",
                    r.case.label(),
                    o.lost.hit,
                    o.lost.of,
                    o.steps,
                    r.none.hit
                ));
            }
            if o.bled.hit > 0 {
                failures.push(format!(
                    "{} [{name} profile]: {} of {} pixels bled through an occluder at the gap {:.4e}",
                    r.case.label(),
                    o.bled.hit,
                    o.bled.of,
                    o.rec.bleed_gap
                ));
            }
        }
    }
    failures
}

/// The full grid's rasterizer-clipped scenes that lose decal pixels when the probe's clipper
/// figure enters the model without its margin (`γ = 0.83u`, about the figure itself): they need
/// up to 2u (four of them more than 1.25u, one more than 1.5u). The probed profile's
/// `γ = 4·clip_ulps·u` must hold on each, so that CI, which samples one scene in 12, replays
/// them every time.
const HARDEST_CLIPPED: [&str; 27] = [
    "[-1,1] D16  <  sloped clipped Less 320x180 off-centre f/n=1e3 s=(-6.56,-7.55) d=[1.8128e1,4.6440e1]",
    "[-1,1] D16  <= sloped clipped LessEqual 320x180 axis-off f/n=1e5 s=(-0.27,-0.96) d=[5.4609e1,7.4817e1]",
    "[-1,1] D16  <= sloped clipped LessEqual 320x180 off-centre f/n=1e3 s=(-0.18,-0.72) d=[3.4603e-1,3.8601e-1]",
    "[-1,1] D24  <  sloped clipped Less 64x48 off-centre f/n=1e5 s=(-0.44,-2.00) d=[8.1558e-1,1.2084e0]",
    "[-1,1] D24  <= sloped clipped LessEqual 320x180 axis-off f/n=1e3 s=(0.24,9.99) d=[1.7154e1,2.0141e1]",
    "[-1,1] D24  <= sloped clipped LessEqual 320x180 axis-off f/n=1e5 s=(-9.53,-3.02) d=[4.5592e0,6.2774e0]",
    "[-1,1] D32F <  sloped clipped Less 320x180 axis-off f/n=1e5 s=(0.60,-2.36) d=[3.3116e1,5.0313e1]",
    "[-1,1] D32F <  sloped clipped Less 320x180 axis-off f/n=1e7 s=(-1.27,-6.46) d=[1.1181e3,1.8317e3]",
    "[-1,1] D32F <  sloped clipped Less 97x211 off-centre f/n=1e5 s=(1.82,7.16) d=[6.9225e2,1.7812e3]",
    "[-1,1] D32F <= sloped clipped LessEqual 97x211 off-centre f/n=1e3 s=(1.33,9.49) d=[6.7787e0,9.4019e0]",
    "[0,1]  D16  <  sloped clipped Less 320x180 axis-off f/n=1e3 s=(0.21,-1.84) d=[4.6566e1,7.5164e1]",
    "[0,1]  D16  <  sloped clipped Less 320x180 axis-off f/n=1e7 s=(-2.06,-9.79) d=[7.5663e4,1.2370e5]",
    "[0,1]  D16  <= sloped clipped LessEqual 64x48 axis-off f/n=1e3 s=(-0.03,3.00) d=[3.5484e0,3.9394e0]",
    "[0,1]  D16  <= sloped clipped LessEqual 64x48 axis-off f/n=1e5 s=(0.99,0.14) d=[2.0078e0,2.3770e0]",
    "[0,1]  D16  <= sloped clipped LessEqual 97x211 centred f/n=1e5 s=(-0.33,-6.03) d=[1.7928e0,3.6457e0]",
    "[0,1]  D24  <  sloped clipped Less 64x48 off-centre f/n=1e3 s=(-0.68,-0.73) d=[5.1319e1,6.9403e1]",
    "[0,1]  D24  <  sloped clipped Less 64x48 off-centre f/n=1e7 s=(-0.64,-0.77) d=[4.5889e2,6.2618e2]",
    "[0,1]  D24  <  sloped clipped Less 97x211 axis-off f/n=1e3 s=(-2.63,-1.43) d=[2.6307e1,9.2696e1]",
    "[0,1]  D24  <= sloped clipped LessEqual 320x180 axis-off f/n=1e1 s=(-0.08,-1.00) d=[4.7931e-1,5.7945e-1]",
    "[0,1]  D24  <= sloped clipped LessEqual 320x180 off-centre f/n=1e5 s=(-9.66,-2.57) d=[3.1063e1,5.0713e2]",
    "[0,1]  D24  <= sloped clipped LessEqual 97x211 off-centre f/n=1e7 s=(0.07,-0.99) d=[1.2088e4,1.2858e4]",
    "[0,1]  D32F <  sloped clipped Less 64x48 axis-off f/n=1e5 s=(-0.39,-2.85) d=[1.0589e1,6.1970e1]",
    "[0,1]  D32F <  sloped clipped Less 97x211 centred f/n=1e1 s=(-0.01,-1.80) d=[4.1830e-1,5.6401e-1]",
    "[0,1]  D32F <= sloped clipped LessEqual 320x180 axis-off f/n=1e3 s=(0.60,2.43) d=[3.4487e0,3.8524e0]",
    "[0,1]  D32F <= sloped clipped LessEqual 320x180 off-centre f/n=1e7 s=(0.38,-9.96) d=[9.5319e2,1.1127e3]",
    "[0,1]  D32F <= sloped clipped LessEqual 97x211 off-centre f/n=1e7 s=(0.17,1.82) d=[2.6350e3,3.5934e3]",
    "rev-Z  D32F <  sloped clipped Greater 64x48 centred f/n=1e1 s=(-0.03,1.00) d=[1.6552e-1,2.0054e-1]",
];

/// The clipper's hardest scenes of the full grid ([`HARDEST_CLIPPED`]) hold with both profiles,
/// with and without corners: 0 lost, 0 bled.
#[test]
fn the_clippers_hardest_scenes_hold() {
    let mut gl = Gl::new(Profile::Core)
        .unwrap_or_else(|e| panic!("no OpenGL context (EGL surfaceless): {e}"));
    let profile = probed(&gl);
    let cases: Vec<Case> = grid_with(1, GRID_SEED)
        .into_iter()
        .filter(|c| HARDEST_CLIPPED.contains(&c.label().as_str()))
        .collect();
    assert_eq!(
        cases.len(),
        HARDEST_CLIPPED.len(),
        "the grid no longer has every listed scene"
    );
    let rows: Vec<Row> = cases
        .into_iter()
        .map(|c| {
            let label = c.label();
            measure(&mut gl, c, profile)
                .unwrap_or_else(|e| panic!("GL: {e}"))
                .unwrap_or_else(|| panic!("{label} was refused or drew nothing"))
        })
        .collect();
    let failures = failures_of(&rows);
    assert!(failures.is_empty(), "{failures:#?}");
}

/// Every scene: 0 lost, 0 bled with both profiles; prints the ratios per class.
#[test]
fn the_recommendation_holds_on_every_scene() {
    let mut gl = Gl::new(Profile::Core)
        .unwrap_or_else(|e| panic!("no OpenGL context (EGL surfaceless): {e}"));
    let profile = probed(&gl);
    println!("probed profile: {profile:?}");
    let cases = grid(every());
    let total = cases.len();
    let mut rows = Vec::new();
    let (mut refused, mut refused_clipped) = (0, 0);
    let mut worst_only = Vec::new();
    let mut probed_failures = Vec::new();
    for c in cases {
        let clipped = c.base_kind == BaseKind::Ground;
        let label = c.label();
        match measure(&mut gl, c.clone(), profile).unwrap_or_else(|e| panic!("GL: {e}")) {
            Some(r) => rows.push(r),
            None if clipped => refused_clipped += 1,
            None => match probed_alone(&mut gl, c, profile).unwrap_or_else(|e| panic!("GL: {e}")) {
                ProbedAlone::Empty => {}
                ProbedAlone::Refused => refused += 1,
                ProbedAlone::Drawn(failed) => {
                    worst_only.push(label);
                    probed_failures.extend(failed);
                }
            },
        }
    }
    let mut failures = failures_of(&rows);
    failures.extend(probed_failures);
    print_classes(&rows);
    println!(
        "{} scenes ({total} sampled; refused or empty: {refused_clipped} with a rasterizer-clipped base, {} others, {refused} of them with the probed profile), {} failures",
        rows.len(),
        refused + worst_only.len(),
        failures.len()
    );
    // The worst-case bound covers a rasterizer that snaps to 8 sub-pixel bits; a steep plane
    // just beyond the near plane can need more offset there than the depth left in front of
    // it, which this (unsnapped) rasterizer does not: printed, its probed answers drawn.
    for label in &worst_only {
        println!("refused by the worst-case bound alone (its probed answers drawn, judged with the others): {label}");
    }
    for f in failures.iter().take(40) {
        println!("FAIL {f}");
    }
    assert!(
        failures.is_empty(),
        "{} failures, first: {}",
        failures.len(),
        failures[0]
    );
    let fought = rows.iter().filter(|r| r.none.hit > 0).count();
    assert!(
        fought * 2 > rows.len(),
        "most scenes must z-fight with no offset ({fought} of {})",
        rows.len()
    );
    // Only a base the rasterizer clips may be refused (its clipping term made the offset
    // useless, and the status says to cut it); every other scene gets an answer.
    assert_eq!(
        refused, 0,
        "scenes without a clipped base were refused with the probed profile"
    );
    assert!(
        refused_clipped * 2 < total / 3,
        "most clipped bases should still get an answer ({refused_clipped} of about {})",
        total / 3
    );
}

/// Per class (`<` strict test, `<=` the `…EQUAL` one): scenes, those that need no offset at all
/// (no ratio), and over the rest the median and largest recommended ÷ smallest working offset
/// for each description ([`DESCRIPTIONS`]; f32 steps of the offset element), and the scene
/// where the tightest description (measured profile with corners) is loosest.
fn print_classes(rows: &[Row]) {
    let mut classes: Vec<String> = rows.iter().map(|r| r.case.class()).collect();
    classes.sort();
    classes.dedup();
    println!(
        "class                           | scenes  no-offset | rec/min median / max: {} | {} within target, smallest | worst ({})",
        DESCRIPTIONS.join(" | "),
        DESCRIPTIONS[3],
        DESCRIPTIONS[3]
    );
    for class in classes {
        let all = rows.iter().filter(|r| r.case.class() == class).count();
        let of: Vec<&Row> = rows
            .iter()
            .filter(|r| r.case.class() == class && r.k_min > 0)
            .collect();
        if of.is_empty() {
            println!("{class} | {all:>6} {all:>10} |");
            continue;
        }
        let columns: Vec<String> = (0..DESCRIPTIONS.len())
            .map(|i| {
                let mut v: Vec<f64> = of.iter().map(|r| ratio(&r.outcomes[i], r.k_min)).collect();
                v.sort_by(f64::total_cmp);
                format!("{:>7.1} / {:<8.1}", v[v.len() / 2], v[v.len() - 1])
            })
            .collect();
        let tightest = |r: &&Row| ratio(&r.outcomes[3], r.k_min);
        // The tightest description's share of scenes within the issue's target (2× facing, 4×
        // sloped) and its smallest ratio (how close to the edge the safe answer came).
        let target = if class.contains("facing") { 2.0 } else { 4.0 };
        let within = of.iter().filter(|r| tightest(r) <= target).count();
        let closest = of.iter().map(tightest).fold(f64::INFINITY, f64::min);
        let worst = of
            .iter()
            .max_by(|a, b| tightest(a).total_cmp(&tightest(b)))
            .map(|r| r.case.label())
            .unwrap_or_default();
        println!(
            "{class} | {all:>6} {:>10} | {} | {:>5.1}% ≤{target}×, min {closest:.2} | {worst}",
            all - of.len(),
            columns.join(" | "),
            100.0 * within as f64 / of.len() as f64
        );
    }
}

// ---------------------------------------------------------------------------------------------
// The probed per-pixel bound, on planes the probe never drew.
// ---------------------------------------------------------------------------------------------

/// The largest `(|read − exact| − V)⁺ / (2⁻²⁴·(1 + M))` over the pixels of planes drawn into
/// D32F (which stores the computed depth) under `[−1, 1]`: the figure `error_ulps` claims to
/// bound, `M = |w₀| + |∂w/∂x|·x + |∂w/∂y|·y` from this file's own f64 plane, `V` the model's
/// bound on the rounding of the coordinates at the pixel's depth (the probe's exact plane runs
/// through the f32 vertices, this file's through the f64 ones). Planes: f/n 10 to 1e7
/// and ∞, slopes 0 to 10 in random directions (horizons on screen), three viewports, three
/// frusta, decal distances from 1.5·n deep into the range, four times over with other depths.
/// What [`error_growth_survey`] found, each the largest over its planes.
#[derive(Default)]
struct Survey {
    /// `(|read − exact| − V)⁺ / (u·(1 + M))`, comparable with the probe's `error_ulps`.
    growth: f64,
    /// `|read − exact| / E` with `E` from the measured profile.
    measured: f64,
    /// `|read − exact| / E` with `E` the worst-case bound `T + V + I`.
    bound: f64,
    planes: usize,
}

fn error_growth_survey(
    gl: &mut Gl,
    profile: RasterizerProfile,
    clip: ClipDepth,
) -> Result<Survey, String> {
    let mut survey = Survey::default();
    let mut rng = Lcg(0x00DE_C0DE);
    for size in [(97u32, 211u32), (320, 180), (64, 48)].repeat(4) {
        let aspect = f64::from(size.0) / f64::from(size.1);
        for frustum_kind in ["centred", "off-centre", "axis-off"] {
            for ratio in [10.0, 1e3, 1e5, 1e7, f64::INFINITY] {
                for slope in [0.0, 0.3, 1.0, 3.0, 10.0] {
                    let cam = Cam::of_kind(frustum_kind, aspect, ratio);
                    let span = if ratio.is_finite() { ratio } else { 1e4 };
                    let dc = cam.n * span.powf(0.9 * rng.next()).max(1.5);
                    let a = rng.next() * std::f64::consts::TAU;
                    let (sx, sy) = (slope * a.cos(), slope * a.sin());
                    let Some(case) = build(
                        cam,
                        frustum_kind,
                        size,
                        (clip, DepthFormat::D32F),
                        if clip == ClipDepth::ReversedZeroToOne {
                            DepthTest::Greater
                        } else {
                            DepthTest::Less
                        },
                        (sx, sy),
                        (rng.next() - 0.5, rng.next() - 0.5, 0.2, dc),
                        BaseKind::Fitted,
                    ) else {
                        continue;
                    };
                    let (e, measured, bound) = error_growth(gl, &case, profile)?;
                    if measured > survey.measured
                        && std::env::var_os("ZSHIFT_SCENES_VERBOSE").is_some()
                    {
                        println!("survey: {e:.2}, {measured:.3} of E on {}", case.label());
                    }
                    survey.growth = survey.growth.max(e);
                    survey.measured = survey.measured.max(measured);
                    survey.bound = survey.bound.max(bound);
                    survey.planes += 1;
                }
            }
        }
    }
    Ok(survey)
}

/// Draws the case's (fitted) base into D32F and returns its pixels' largest
/// `|read − exact| / (2⁻²⁴·(1 + M))`. The exact window depth is affine in window `(x, y)` (it
/// is affine in `1/d`, and `1/d` is affine on the screen), so `w₀` and the gradients come from
/// the plane extended over the window, in front of the eye or not.
fn error_growth(
    gl: &mut Gl,
    case: &Case,
    profile: RasterizerProfile,
) -> Result<(f64, f64, f64), String> {
    // The plane's own error and, on a rasterizer that snaps window positions before setting
    // depth up, the snapping term: the exact plane here is through the unsnapped vertices.
    let plane_error = |p: RasterizerProfile| {
        zshift::recommend::clip_error_terms(&case.scene(p), case.clip)
            .map(|t| t.plane + t.snap)
            .map_err(|e| e.to_string())
    };
    let measured = plane_error(profile)?;
    let bound = plane_error(RasterizerProfile::worst_case())?;
    let mut against_bound = 0.0f64;
    let (d1, d2) = case.depth_range();
    let mut against_model = 0.0f64;
    let mut bench = Bench::new(gl, case)?;
    bench.clear()?;
    bench.draw_base()?;
    let depth = bench.gl.read_depth()?;
    let (w, h) = (case.size.0 as usize, case.size.1 as usize);
    let (fw, fh) = (w as f64, h as f64);
    let p = case.plane;
    let window_at = |x: f64, y: f64| {
        let (kx, ky) = case.cam.ray(2.0 * x / fw - 1.0, 2.0 * y / fh - 1.0);
        let inv_d = (1.0 + p.sx * kx + p.sy * ky) / p.da;
        case.cam.window(1.0 / inv_d, case.clip)
    };
    let u = 2f64.powi(-24);
    let c = case.cam;
    let b = if c.f.is_finite() {
        c.f * c.n / (c.f - c.n)
    } else {
        c.n
    };
    let e = [c.l, c.r, c.b, c.t]
        .iter()
        .fold(0.0f64, |a, x| a.max(x.abs()))
        / c.n;
    let w0 = window_at(0.0, 0.0);
    let gx = ((window_at(fw, 0.0) - w0) / fw).abs();
    let gy = ((window_at(0.0, fh) - w0) / fh).abs();
    // The transform's constant part in the probe's normalisation: 1 under [−1, 1] (its own
    // roundings), |m10| = n/(f − n) under reversed Z.
    let constant = if case.reversed() {
        if c.f.is_finite() {
            c.n / (c.f - c.n)
        } else {
            0.0
        }
    } else {
        1.0
    };
    let mut worst = 0.0f64;
    for (i, &read) in depth.iter().enumerate() {
        let (x, y) = ((i % w) as f64 + 0.5, (i / w) as f64 + 0.5);
        let cleared = if case.reversed() { 0.0 } else { 1.0 };
        if read == cleared || (2.0 * x / fw - 1.0).abs() > 0.85 || (2.0 * y / fh - 1.0).abs() > 0.85
        {
            continue; // cleared, or near the base's edges (a centre may lie just outside)
        }
        let Some(d) = p.depth_on_ray(case.cam.ray(2.0 * x / fw - 1.0, 2.0 * y / fh - 1.0)) else {
            continue;
        };
        let m = w0.abs() + gx * x + gy * y;
        let err = (f64::from(read) - case.cam.window(d, case.clip)).abs();
        // The probe's "exact" is the plane through the f32 vertices; this file's is the f64
        // plane, so the rounding of the coordinates (the model's V at this depth) is allowed.
        let vertex = u * (b / d) * (1.0 + case.slope() * e);
        worst = worst.max((err - vertex).max(0.0) / (u * (constant + m)));
        if (d1..=d2).contains(&d) {
            against_model = against_model.max(err / measured);
            against_bound = against_bound.max(err / bound);
        }
    }
    Ok((worst, against_model, against_bound))
}

/// llvmpipe's per-pixel error on planes the probe never drew (steeper, nearer the near plane,
/// other frusta and viewports), under `[−1, 1]`, reversed Z and `[0, 1]` (whose `E` takes the
/// `[−1, 1]` figure with the transform's constant doubled), at the pixels of each plane within its
/// decal's depth range:
/// within the worst-case `E = T + V + I` (a bound, derived), and within twice the `E` a measured
/// profile gives (`error_ulps·u·(1 + M) + V`, a sampled maximum: a single plane of the survey
/// may exceed it, as the largest of more roundings is larger, but never the budget `2E` that
/// the offset reserves for base and decal together). The survey can fail: it sees a nonzero
/// error. It prints the growth figure against the probed `error_ulps` (on llvmpipe 1.74
/// against 1.54).
#[test]
fn the_probed_error_bound_holds() {
    let mut gl = Gl::new(Profile::Core)
        .unwrap_or_else(|e| panic!("no OpenGL context (EGL surfaceless): {e}"));
    let profile = probed(&gl);
    for (clip, probed_figure) in [
        (ClipDepth::NegOneToOne, profile.error_ulps),
        (ClipDepth::ReversedZeroToOne, profile.error_ulps_reversed),
        (ClipDepth::ZeroToOne, profile.error_ulps),
    ] {
        let survey =
            error_growth_survey(&mut gl, profile, clip).unwrap_or_else(|e| panic!("GL: {e}"));
        println!(
            "{clip:?} D32F, over {} planes: error growth {:.3} u(c + M) (probed {probed_figure:.3}); largest error over the measured E {:.3}, over the worst-case E {:.3}",
            survey.planes, survey.growth, survey.measured, survey.bound
        );
        check_survey(&survey);
    }
}

fn check_survey(survey: &Survey) {
    assert!(
        survey.planes > 500 && survey.growth > 0.0,
        "the survey saw no error: it cannot fail"
    );
    assert!(
        survey.bound <= 1.0,
        "llvmpipe's per-pixel error reaches {:.3} times the worst-case E",
        survey.bound
    );
    assert!(
        survey.measured <= 2.0,
        "llvmpipe's per-pixel error on one plane reaches {:.3} times the measured E (the budget is 2E)",
        survey.measured
    );
}

/// `clip_to_frustum` keeps a polygon's plane and cuts it inside the frustum: every output
/// vertex is inside (margin included) and on the input plane; a quad wholly inside is returned
/// unchanged; one wholly behind the camera vanishes.
#[test]
fn clip_to_frustum_cuts_inside_and_on_the_plane() {
    let cam = Cam {
        l: -0.1,
        r: 0.1,
        b: -0.05,
        t: 0.05,
        n: 0.1,
        f: 1000.0,
    };
    let plane = Plane {
        sx: 0.2,
        sy: -0.5,
        da: 10.0,
    };
    let big: Vec<[f64; 3]> = [(-1e3, -1e3), (1e3, -1e3), (1e3, 1e3), (-1e3, 1e3)]
        .iter()
        .map(|&(x, y)| [x, y, plane.z(x, y)])
        .collect();
    let cut = clip_to_frustum(&cam.frustum(), &big).unwrap();
    assert!(cut.len() >= 3, "the plane is visible: {cut:?}");
    for p in &cut {
        let d = -p[2];
        assert!(d > cam.n && d < cam.f, "{p:?} outside [n, f]");
        assert!(
            p[0] / d > cam.l / cam.n && p[0] / d < cam.r / cam.n,
            "{p:?} outside x"
        );
        assert!(
            p[1] / d > cam.b / cam.n && p[1] / d < cam.t / cam.n,
            "{p:?} outside y"
        );
        assert!((p[2] - plane.z(p[0], p[1])).abs() <= 1e-9 * p[2].abs().max(1.0));
    }
    let inside: Vec<[f64; 3]> = [(-0.1, -0.1), (0.1, -0.1), (0.1, 0.1), (-0.1, 0.1)]
        .iter()
        .map(|&(x, y)| [x, y, -5.0])
        .collect();
    assert_eq!(clip_to_frustum(&cam.frustum(), &inside).unwrap(), inside);
    let behind: Vec<[f64; 3]> = inside.iter().map(|p| [p[0], p[1], 5.0]).collect();
    assert!(clip_to_frustum(&cam.frustum(), &behind).unwrap().is_empty());
}

/// A scene from explicit geometry: the decal is the plane under the eye-space rectangle
/// `[x0, x1] × [y0, y1]`; the base is the plane under `±reach` (as drawn: raw, or cut by
/// `clip_to_frustum`).
#[allow(clippy::too_many_arguments)]
fn explicit(
    cam: Cam,
    size: (u32, u32),
    (clip, format): (ClipDepth, DepthFormat),
    test: DepthTest,
    plane: Plane,
    [x0, x1, y0, y1]: [f64; 4],
    reach: f64,
    base_kind: BaseKind,
) -> Case {
    let on = |x: f64, y: f64| [x, y, plane.z(x, y)];
    let ground = vec![
        on(-reach, -reach),
        on(reach, -reach),
        on(reach, reach),
        on(-reach, reach),
    ];
    let base = match base_kind {
        BaseKind::Split => clip_to_frustum(&cam.frustum(), &ground).expect("clip_to_frustum"),
        BaseKind::Ground => ground,
        BaseKind::Fitted => fitted_base(&cam, &plane, 0.9 * cam.f),
    };
    Case {
        cam,
        size,
        clip,
        format,
        test,
        plane,
        base_kind,
        decal: [on(x0, y0), on(x1, y0), on(x1, y1), on(x0, y1)],
        base,
        frustum_kind: "explicit",
    }
}

/// The GL_LEQUAL bleed of the issue: D16, 320×180, glFrustum(±0.1, ±0.05625, 0.1, 100), a
/// facing plane at d = 0.5. At the GL_LESS gap an occluder stores the decal's value and
/// GL_LEQUAL lets the decal through; at the GL_LEQUAL gap (one quantum wider) none bleeds. The
/// plane's corners share their f32 z, so under GL_LEQUAL the decal needs no offset at all.
#[test]
fn lequal_needs_one_more_quantum_of_gap() {
    let mut gl = Gl::new(Profile::Core)
        .unwrap_or_else(|e| panic!("no OpenGL context (EGL surfaceless): {e}"));
    let cam = Cam {
        l: -0.1,
        r: 0.1,
        b: -0.05625,
        t: 0.05625,
        n: 0.1,
        f: 100.0,
    };
    let plane = Plane {
        sx: 0.0,
        sy: 0.0,
        da: 0.5,
    };
    let kind = (ClipDepth::NegOneToOne, DepthFormat::D16);
    let rect = [-0.2, 0.2, -0.1, 0.1];
    let case = explicit(
        cam,
        (320, 180),
        kind,
        DepthTest::LessEqual,
        plane,
        rect,
        0.0,
        BaseKind::Fitted,
    );
    let less = Case {
        test: DepthTest::Less,
        ..case.clone()
    };
    let profile = RasterizerProfile::worst_case();
    let rec_lequal = recommend_clip(&case.scene(profile), case.clip).unwrap();
    let rec_less = recommend_clip(&less.scene(profile), less.clip).unwrap();
    // A facing plane with shared f32 z: under GL_LEQUAL no offset at all (the depth chain is
    // monotone in element 10, so the decal is never behind the base), and none is lost.
    assert!(rec_less.window_offset > 0.0);
    assert_eq!(
        rec_lequal.window_offset, 0.0,
        "correlated: no offset under GL_LEQUAL"
    );
    let mut bench = Bench::new(&mut gl, &case).unwrap();
    assert_eq!(bench.lost(&rec_lequal.matrix).unwrap().hit, 0);
    let at_lequal_gap = bench
        .bleed(&rec_lequal.matrix, rec_lequal.bleed_gap)
        .unwrap();
    // The gap GL_LESS needs for the same offset: one quantum narrower in window depth.
    let w = |d: f64| cam.window(d, ClipDepth::NegOneToOne);
    let d = 0.5;
    let target =
        w(d) - (rec_lequal.window_offset + 2.0 * (rec_lequal.terms.plane + rec_lequal.terms.snap));
    let (mut lo, mut hi) = (0.0, d - cam.n);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if w(d - mid) > target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let less_gap = hi;
    let at_less_gap = bench.bleed(&rec_lequal.matrix, less_gap).unwrap();
    println!(
        "LEQUAL: gap {:.4e} bled {}/{}; the GL_LESS gap {less_gap:.4e} bled {}/{}",
        rec_lequal.bleed_gap, at_lequal_gap.hit, at_lequal_gap.of, at_less_gap.hit, at_less_gap.of
    );
    assert!(at_lequal_gap.of > 0);
    assert_eq!(at_lequal_gap.hit, 0, "bled through at the GL_LEQUAL gap");
    assert!(
        at_less_gap.hit > 0,
        "the GL_LESS gap should let the decal through under GL_LEQUAL (the check can fail)"
    );
}

/// The near-clipped ground of the issue: glFrustum(±0.1, ±0.05625, 0.1, 1000), 256×144, base
/// corners at x, y = ±1000 on z = −10 − 0.5y, decals 8–13 units away, `[−1, 1]` D24 and `[0, 1]`
/// D32F. Drawn raw (the rasterizer clips it in f32) with `Base::Clipped`, and cut by
/// `clip_to_frustum` with `Base::InsideFrustum`: no pixel lost either way, and the cut base's
/// offset is far smaller.
#[test]
fn the_issues_near_clipped_ground_holds() {
    let mut gl = Gl::new(Profile::Core)
        .unwrap_or_else(|e| panic!("no OpenGL context (EGL surfaceless): {e}"));
    let profile = probed(&gl);
    let cam = Cam {
        l: -0.1,
        r: 0.1,
        b: -0.05625,
        t: 0.05625,
        n: 0.1,
        f: 1000.0,
    };
    let plane = Plane {
        sx: 0.0,
        sy: -0.5,
        da: 10.0,
    };
    // Decal rows 8 to 13 units away: y from −4 to 6 on z = −10 − 0.5y, below the view axis.
    let rect = [-0.6, 0.5, -4.0, 6.0];
    for kind in [
        (ClipDepth::NegOneToOne, DepthFormat::D24),
        (ClipDepth::ZeroToOne, DepthFormat::D32F),
    ] {
        let mut steps = Vec::new();
        for base_kind in [BaseKind::Ground, BaseKind::Split] {
            let case = explicit(
                cam,
                (256, 144),
                kind,
                DepthTest::Less,
                plane,
                rect,
                1000.0,
                base_kind,
            );
            let row = measure(&mut gl, case.clone(), profile)
                .unwrap()
                .unwrap_or_else(|| panic!("{}: refused or empty", case.label()));
            for (name, o) in DESCRIPTIONS.iter().zip(&row.outcomes) {
                println!(
                    "{} [{name}]: lost {}/{}, bled {}/{}, {} steps, smallest working {}",
                    case.label(),
                    o.lost.hit,
                    o.lost.of,
                    o.bled.hit,
                    o.bled.of,
                    o.steps,
                    row.k_min
                );
                assert_eq!(o.lost.hit, 0, "{} [{name}]: pixels lost", case.label());
                assert_eq!(o.bled.hit, 0, "{} [{name}]: pixels bled", case.label());
            }
            assert!(
                row.none.hit > 0,
                "{}: no z-fighting without offset",
                case.label()
            );
            steps.push(row.outcomes[1].steps);
        }
        assert!(
            steps[1] * 10 < steps[0],
            "cutting the base should shrink the offset ({steps:?})"
        );
    }
}

/// Planes grazing the eye ray at the decal, off the screen's centre: a plane of slope `s` seen
/// on the ray `k` crosses the view axis at `d_a = d·(1 + s·k)`, so where `1 + s·k` is small
/// (here 0.1 and 0.3) its window gradient is several times the tilt `1 + s·e` the slope-only
/// description assumes (`crate::model::gradient`: a first-order tilt, not a bound there). Every
/// such decal, asked by its depths and slope alone and with its corners, with both profiles:
/// 0 lost, 0 bled (1440 scenes, about 9 s).
#[test]
fn planes_grazing_an_off_axis_ray_hold() {
    let mut gl = Gl::new(Profile::Core)
        .unwrap_or_else(|e| panic!("no OpenGL context (EGL surfaceless): {e}"));
    let profile = probed(&gl);
    let kinds = [
        (ClipDepth::NegOneToOne, DepthFormat::D16),
        (ClipDepth::NegOneToOne, DepthFormat::D24),
        (ClipDepth::NegOneToOne, DepthFormat::D32F),
        (ClipDepth::ZeroToOne, DepthFormat::D24),
        (ClipDepth::ReversedZeroToOne, DepthFormat::D32F),
    ];
    let size = (320u32, 180u32);
    let mut rows = Vec::new();
    for frustum_kind in ["centred", "off-centre", "axis-off"] {
        for ratio in [1e3, 1e5, f64::INFINITY] {
            let cam = Cam::of_kind(frustum_kind, 16.0 / 9.0, ratio);
            for kind in kinds {
                for strict in [true, false] {
                    let test = match (kind.0 == ClipDepth::ReversedZeroToOne, strict) {
                        (false, true) => DepthTest::Less,
                        (false, false) => DepthTest::LessEqual,
                        (true, true) => DepthTest::Greater,
                        (true, false) => DepthTest::GreaterEqual,
                    };
                    for graze in [0.1, 0.3] {
                        for (cx, cy) in [(-0.45, 0.0), (0.45, 0.1), (0.0, -0.45), (-0.4, 0.4)] {
                            // The slope along the ray, so that 1 + s·k = graze at the centre.
                            let k = cam.ray(cx, cy);
                            let kk = k.0.hypot(k.1);
                            let s = (1.0 - graze) / kk;
                            let slope = (-s * k.0 / kk, -s * k.1 / kk);
                            for dc in [2.0, 200.0] {
                                let decal = (cx, cy, 0.04, dc);
                                let Some(c) = build(
                                    cam,
                                    frustum_kind,
                                    size,
                                    kind,
                                    test,
                                    slope,
                                    decal,
                                    BaseKind::Fitted,
                                ) else {
                                    continue;
                                };
                                let label = c.label();
                                let row = measure(&mut gl, c, profile)
                                    .unwrap_or_else(|e| panic!("GL: {e}"))
                                    .unwrap_or_else(|| {
                                        panic!("{label} was refused or drew nothing")
                                    });
                                rows.push(row);
                            }
                        }
                    }
                }
            }
        }
    }
    assert!(
        rows.len() > 1000,
        "only {} grazing scenes were built",
        rows.len()
    );
    let failures = failures_of(&rows);
    assert!(failures.is_empty(), "{failures:#?}");
}
