//! `recommend::recommend_clip` checked on a real rasterizer (headless EGL; Mesa llvmpipe in CI):
//! the coplanar-quads experiment of `zshift-harness` under `[0, 1]` clip depth (D24 and D32F,
//! `GL_LESS`) and reversed Z (D32F, `GL_GREATER`, clear depth 0), both through
//! `glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE)`, with finite and infinite far planes, facing
//! and sloped planes. References are GL readbacks, never zshift's own numbers. Fails (never
//! skips) without GL.
//!
//! The table: `cargo test --release --test gl_recommend_clip -- --nocapture`; the wider sweep
//! (256², f/n ∈ {10, 1e3, 1e6, ∞}, planes at 20/50/90 %, slopes 0, 0.3, 1, 3; 184 rows, a few
//! seconds): the same with `ZSHIFT_CLIP_SWEEP=1`.

mod gl_common;

use zshift::projection::{projection, ClipDepth};
use zshift::recommend::{recommend_clip, ClipRecommendation, Scene};
use zshift::Frustum;
use zshift_harness::coplanar::{
    bisect_smallest_passing, coverage, stepped_toward_camera, steps_between, Count, Setup, BASE,
    CLEAR, DECAL, OCCLUDER,
};
use zshift_harness::{ClipDepth as GlClip, DepthFormat, DrawState, Gl, Profile, Quad};

/// Viewport size of the CI grid (small: llvmpipe on two shared cores); the sweep uses 256².
const SIZE: u32 = 96;
const SWEEP_SIZE: u32 = 256;

/// The stated factor: the recommended offset is at most this many times the smallest offset
/// that works (bisection over f32 steps of the offset element), with the worst-case profile.
/// Measured at most 179 on this grid: reversed Z on slope-3 planes, where one or two f32 steps
/// of element 14 work and the interpolation term's extrapolation across the viewport (llvmpipe
/// sets its depth plane up relative to the framebuffer origin), bounded through the plane's
/// unknown axis crossing, dominates; `[0, 1]` at most 60.
const FACTOR: f64 = 200.0;
/// The factor stated for the wider sweep: measured at most 350 (reversed Z, f/n = 10, slope 3,
/// 256²), for the same reason.
const FACTOR_SWEEP: f64 = 400.0;

fn sweep() -> bool {
    std::env::var_os("ZSHIFT_CLIP_SWEEP").is_some_and(|v| v != "0")
}

/// One configuration: the coplanar setup (its geometry uses `setup.f`), the far plane of the
/// projection (`setup.f` or `+∞`) and the convention.
#[derive(Debug, Clone, Copy)]
struct Case {
    setup: Setup,
    far: f64,
    clip: ClipDepth,
}

impl Case {
    fn label(&self) -> String {
        let clip = match self.clip {
            ClipDepth::NegOneToOne => "[-1,1]",
            ClipDepth::ZeroToOne => "[0,1] ",
            ClipDepth::ReversedZeroToOne => "rev-Z ",
        };
        let far = if self.far.is_infinite() {
            "inf  ".to_string()
        } else {
            format!("{:<5.0e}", self.far / self.setup.n)
        };
        format!(
            "{clip} {:<4} f/n={far} d0={:>8.1} slope={}",
            self.setup.format.name(),
            self.setup.axis_depth(),
            self.setup.slope
        )
    }

    fn frustum(&self) -> Frustum {
        let (l, r, b, t, n, _) = self.setup.frustum();
        Frustum::new(l, r, b, t, n, self.far).expect("valid frustum")
    }

    fn reversed(&self) -> bool {
        self.clip == ClipDepth::ReversedZeroToOne
    }

    fn scene(&self, gl: &Gl) -> Scene {
        let s = self.setup;
        let (d1, d2) = s.decal_depth_range();
        Scene {
            frustum: self.frustum(),
            depth_range: [d1, d2],
            depth_test: if self.reversed() {
                zshift::recommend::DepthTest::Greater
            } else {
                zshift::recommend::DepthTest::Less
            },
            ..gl_common::scene_of(&s, gl_common::snapping_of(gl))
        }
    }

    fn recommendation(&self, gl: &Gl) -> ClipRecommendation {
        recommend_clip(&self.scene(gl), self.clip)
            .unwrap_or_else(|e| panic!("{}: {e}", self.label()))
    }
}

/// Viewport size, (f/n, infinite far) pairs, plane positions in [n, f], slopes.
type Grid = (u32, &'static [(f64, bool)], &'static [f64], &'static [f64]);

/// The grid: `[0, 1]` with D24 and D32F, reversed Z with D32F; f/n = 10 and 1e6 and an
/// infinite far plane (geometry laid out for f/n = 1e4); the plane at 20 % and 90 % of the
/// range; facing and slope 3; and `[0, 1]` at f/n = 10 with the plane at 3 % (window depth
/// below ½).
fn grid() -> Vec<Case> {
    let mut v = Vec::new();
    let (size, ratios, fractions, slopes): Grid = if sweep() {
        (
            SWEEP_SIZE,
            &[
                (10.0, false),
                (1e3, false),
                (1e6, false),
                (1e4, true),
                (10.0, true),
            ],
            &[0.2, 0.5, 0.9],
            &[0.0, 0.3, 1.0, 3.0],
        )
    } else {
        (
            SIZE,
            &[(10.0, false), (1e6, false), (1e4, true)],
            &[0.2, 0.9],
            &[0.0, 3.0],
        )
    };
    let kinds = [
        (ClipDepth::ZeroToOne, DepthFormat::D24),
        (ClipDepth::ZeroToOne, DepthFormat::D32F),
        (ClipDepth::ReversedZeroToOne, DepthFormat::D32F),
    ];
    for (clip, format) in kinds {
        for &(ratio, infinite) in ratios {
            for &p in fractions {
                for &slope in slopes {
                    let setup = gl_common::setup(format, ratio, p, slope, size);
                    let far = if infinite { f64::INFINITY } else { ratio };
                    v.push(Case { setup, far, clip });
                }
            }
        }
    }
    // Near the near plane (w < ½), where [0, 1] float depth is finer than 24-bit fixed point.
    for format in [DepthFormat::D24, DepthFormat::D32F] {
        for slope in [0.0, 3.0] {
            let setup = gl_common::setup(format, 10.0, 0.03, slope, size);
            v.push(Case {
                setup,
                far: 10.0,
                clip: ClipDepth::ZeroToOne,
            });
        }
    }
    v
}

fn context() -> Gl {
    Gl::new(Profile::Core).unwrap_or_else(|e| panic!("no OpenGL context (EGL surfaceless): {e}"))
}

/// A render target and depth convention set up for one case.
struct Bench<'a> {
    gl: &'a mut Gl,
    case: Case,
    plain: [f32; 16],
    mask: Vec<bool>,
}

impl<'a> Bench<'a> {
    fn new(gl: &'a mut Gl, case: Case) -> Self {
        let s = case.setup;
        gl.set_target(s.size, s.size, s.format).expect("target");
        gl.clip_control(GlClip::ZeroToOne).expect("glClipControl");
        let plain = projection(&case.frustum(), case.clip).expect("plain matrix");
        let mut b = Bench {
            gl,
            case,
            plain,
            mask: Vec::new(),
        };
        b.mask = b.coverage(&s.decal());
        assert!(
            b.mask.iter().any(|&m| m),
            "{}: no decal pixel",
            case.label()
        );
        b
    }

    fn state(&self) -> DrawState {
        DrawState {
            depth_func: if self.case.reversed() {
                glow::GREATER
            } else {
                glow::LESS
            },
            ..DrawState::default()
        }
    }

    fn clear(&mut self) {
        let depth = if self.case.reversed() { 0.0 } else { 1.0 };
        self.gl.clear(CLEAR, depth).expect("clear");
    }

    fn coverage(&mut self, quad: &Quad) -> Vec<bool> {
        coverage(self.gl, quad, &self.plain).expect("draw the decal alone")
    }

    /// Decal pixels lost to the base with the decal drawn through `decal`.
    fn lost(&mut self, decal: &[f32; 16]) -> Count {
        let s = self.case.setup;
        let state = self.state();
        self.clear();
        let plain = self.plain;
        self.gl.draw_quad(&s.base(), &plain, BASE, &state).unwrap();
        self.gl.draw_quad(&s.decal(), decal, DECAL, &state).unwrap();
        Count::decal_missing(&self.gl.read_color().unwrap(), &self.mask)
    }

    /// Decal pixels drawn over an occluder `gap` nearer than the base at every pixel.
    fn bleed(&mut self, decal: &[f32; 16], gap: f64) -> Count {
        let s = self.case.setup;
        let occluder = s.occluder_with_depth_gap(gap);
        let both: Vec<bool> = self
            .coverage(&occluder)
            .iter()
            .zip(&self.mask)
            .map(|(a, b)| *a && *b)
            .collect();
        let state = self.state();
        let plain = self.plain;
        self.clear();
        self.gl.draw_quad(&s.base(), &plain, BASE, &state).unwrap();
        self.gl
            .draw_quad(&occluder, &plain, OCCLUDER, &state)
            .unwrap();
        self.gl.draw_quad(&s.decal(), decal, DECAL, &state).unwrap();
        Count::decal_shown(&self.gl.read_color().unwrap(), &both)
    }

    /// The plain matrix with the offset element moved `k` f32 steps toward the camera.
    fn stepped(&self, k: u32) -> [f32; 16] {
        stepped_toward_camera(&self.plain, self.case.reversed(), k)
    }

    /// f32 steps between the plain element and the recommended matrix's.
    fn steps_of(&self, m: &[f32; 16]) -> u32 {
        steps_between(&self.plain, m, self.case.reversed())
    }

    /// The smallest k in 1..=hi that loses no pixel, by bisection (`hi` must work).
    fn smallest_working(&mut self, hi: u32) -> u32 {
        bisect_smallest_passing(0, hi, |k| Ok(self.lost(&self.stepped(k)).hit == 0))
            .expect("the bisection's test cannot fail")
    }
}

struct Row {
    case: Case,
    rec: ClipRecommendation,
    none: Count,
    at_rec: Count,
    k_rec: u32,
    k_min: u32,
    bleed_gap: Count,
    bleed_tenth: Count,
}

fn measure(gl: &mut Gl, case: Case) -> Row {
    let rec = case.recommendation(gl);
    let mut bench = Bench::new(gl, case);
    let plain = bench.plain;
    let none = bench.lost(&plain);
    let at_rec = bench.lost(&rec.matrix);
    let k_rec = bench.steps_of(&rec.matrix);
    let k_min = if at_rec.hit == 0 {
        bench.smallest_working(k_rec)
    } else {
        0
    };
    let bleed_gap = bench.bleed(&rec.matrix, rec.bleed_gap);
    let bleed_tenth = bench.bleed(&rec.matrix, rec.bleed_gap / 10.0);
    Row {
        case,
        rec,
        none,
        at_rec,
        k_rec,
        k_min,
        bleed_gap,
        bleed_tenth,
    }
}

const HEADER: &str = "conv   fmt  far         d0         slope | lost: none    rec | offset (f32 steps) rec   min  rec/min | offset            | gap/d2  | bleed: G/10   G";

fn format_row(r: &Row) -> String {
    let pct = |c: &Count| {
        if c.of == 0 {
            "   n/a".to_string()
        } else {
            format!("{:5.1}%", 100.0 * c.fraction())
        }
    };
    let offset = if r.case.reversed() {
        format!("eps={:.3e}", r.rec.relative_epsilon)
    } else {
        format!("ndc={:.3e}", r.rec.ndc_offset)
    };
    format!(
        "{} | {} {} | m{:<2} {:>6} {:>6} {:>7.1} | {offset:<17} | {:.1e} | {} {}",
        r.case.label(),
        pct(&r.none),
        pct(&r.at_rec),
        if r.case.reversed() { 14 } else { 10 },
        r.k_rec,
        r.k_min,
        r.k_rec as f64 / r.k_min.max(1) as f64,
        r.rec.bleed_gap / r.case.setup.decal_depth_range().1,
        pct(&r.bleed_tenth),
        pct(&r.bleed_gap),
    )
}

/// Over the grid: no lost decal pixel at the recommendation; facing decals with no offset
/// z-fight (and most configurations do); the recommendation within [`FACTOR`] of the smallest
/// working offset; no bleed-through past an occluder the documented gap in front, while one a
/// tenth of it in front is overdrawn somewhere (so that check can fail).
#[test]
fn clip_conventions_lose_no_pixel_at_the_recommendation() {
    let mut gl = context();
    let rows: Vec<Row> = grid().into_iter().map(|c| measure(&mut gl, c)).collect();
    println!("{HEADER}");
    for r in &rows {
        println!("{}", format_row(r));
    }
    let (mut sensitive, mut measurable) = (0, 0);
    for r in &rows {
        let label = r.case.label();
        assert_eq!(
            r.at_rec.hit, 0,
            "{label}: {} of {} decal pixels lost at the recommendation",
            r.at_rec.hit, r.at_rec.of
        );
        if r.case.setup.slope == 0.0 {
            assert!(
                r.none.hit > 0,
                "{label}: a facing decal with no offset must z-fight"
            );
        }
        sensitive += usize::from(r.none.hit > 0);
        let factor = if sweep() { FACTOR_SWEEP } else { FACTOR };
        assert!(
            r.k_rec as f64 <= factor * r.k_min as f64,
            "{label}: recommended {} steps > {factor} x the smallest working {}",
            r.k_rec,
            r.k_min
        );
        // An occluder a large gap in front may leave the frustum (f/n = 1e6 on D24 has gaps of
        // half the distance): then nothing can bleed, and the row says "n/a".
        measurable += usize::from(r.bleed_gap.of > 0);
        assert_eq!(
            r.bleed_gap.hit, 0,
            "{label}: {} of {} pixels bleed through an occluder {:.3e} in front",
            r.bleed_gap.hit, r.bleed_gap.of, r.rec.bleed_gap
        );
    }
    assert!(
        sensitive * 2 > rows.len(),
        "most configurations must z-fight with no offset ({sensitive} of {})",
        rows.len()
    );
    assert!(
        measurable * 4 > rows.len() * 3,
        "the bleed check must cover most rows ({measurable} of {})",
        rows.len()
    );
    assert!(
        rows.iter().any(|r| r.bleed_tenth.hit > 0),
        "an occluder at a tenth of the gap never bled: the bleed check cannot fail"
    );
}
