//! Decals on a real rasterizer: every way of drawing them, on the same scenes, in the same run.
//! Each scene is a base plane, a grid of coplanar decals, and an occluder parallel to the plane
//! a small gap in front of it. For each method: the median time per frame, the decal pixels lost
//! to the base, and the decal pixels that bleed through the occluder.

use std::time::Instant;

use zshift::recommend::{
    recommend, DepthFormat as RecFormat, RasterizerProfile, Recommendation, Scene as RecScene,
    Snapping,
};
use zshift::Frustum;
use zshift_harness::{rgba8, DepthFormat, DrawState, Gl, Image, Quad};

/// Pixels of the square render target.
pub const SIZE: u32 = 256;
/// `tan` of half the field of view, both axes (a 28° frustum).
const TAN_HALF_FOV: f64 = 0.25;
/// Decals per side of the grid.
const GRID: usize = 6;
/// The occluder sits this fraction of the plane's distance in front of it.
pub const GAP_FRACTION: f64 = 0.005;
/// Timed frames per method and scene (after two warm-up frames), interleaved across methods.
pub const ROUNDS: usize = 41;

const BACKGROUND: [f32; 4] = [0.0, 0.0, 0.0, 1.0];
const BASE: [f32; 4] = [0.0, 0.0, 1.0, 1.0];
const DECAL: [f32; 4] = [1.0, 0.0, 0.0, 1.0];
const OCCLUDER: [f32; 4] = [0.0, 1.0, 0.0, 1.0];

/// One configuration: planes, the base plane's distance and tilt, and the depth format.
#[derive(Clone, Debug)]
pub struct Scene {
    pub name: String,
    pub n: f64,
    pub f: f64,
    /// Distance of the plane along the view axis.
    pub distance: f64,
    /// Eye-space slope dz/dy of the plane (0: facing the camera).
    pub slope: f64,
    pub format: DepthFormat,
}

impl Scene {
    fn new(n: f64, f: f64, distance: f64, slope: f64, format: DepthFormat) -> Scene {
        let facing = if slope == 0.0 {
            "facing".to_string()
        } else {
            format!("slope {slope}")
        };
        Scene {
            name: format!(
                "{facing}, d = {distance}, f/n = {:.0e}, {}",
                f / n,
                format.name()
            ),
            n,
            f,
            distance,
            slope,
            format,
        }
    }

    fn frustum(&self) -> Frustum {
        let e = self.n * TAN_HALF_FOV;
        Frustum::new(-e, e, -e, e, self.n, self.f).expect("valid scene frustum")
    }

    /// Eye-space z of the plane at (x, y): it recedes as y grows.
    fn plane_z(&self, y: f64) -> f64 {
        -self.distance - self.slope * y
    }

    /// The y range of the plane inside the view: where y / −z(y) = ±tan.
    fn visible_y(&self) -> (f64, f64) {
        let t = TAN_HALF_FOV;
        let bottom = -t * self.distance / (1.0 + self.slope * t);
        let top = t * self.distance / (1.0 - self.slope * t);
        (bottom, top)
    }

    /// A quad on the plane (or `lift` in front of it), corners in f64, rounded once to f32;
    /// `toward` moves each vertex toward the eye along its own ray by that eye-space z shift.
    fn quad(&self, x: (f64, f64), y: (f64, f64), lift: f64, toward: f64) -> Quad {
        let corner = |cx: f64, cy: f64| {
            let z = self.plane_z(cy) + lift;
            let s = (z + toward) / z;
            [(cx * s) as f32, (cy * s) as f32, (z * s) as f32]
        };
        Quad {
            corners: [
                corner(x.0, y.0),
                corner(x.1, y.0),
                corner(x.1, y.1),
                corner(x.0, y.1),
            ],
        }
    }

    fn base(&self) -> Quad {
        let (bottom, top) = self.visible_y();
        let half_width = 1.2 * TAN_HALF_FOV * -self.plane_z(top);
        self.quad(
            (-half_width, half_width),
            (1.2 * bottom, 1.1 * top),
            0.0,
            0.0,
        )
    }

    /// The occluder covers the middle third of the decal rows, `GAP_FRACTION·distance` in front.
    fn occluder(&self) -> Quad {
        let (_, top) = self.visible_y();
        let half_width = 1.2 * TAN_HALF_FOV * -self.plane_z(top);
        let (y0, y1) = self.decal_rows();
        let third = (y1 - y0) / 3.0;
        self.quad(
            (-half_width, half_width),
            (y0 + third, y0 + 2.0 * third),
            GAP_FRACTION * self.distance,
            0.0,
        )
    }

    fn decal_rows(&self) -> (f64, f64) {
        let (bottom, top) = self.visible_y();
        (0.8 * bottom, 0.8 * top)
    }

    /// The decal rectangles in plane coordinates (x range, y range), and each centre's eye z.
    fn decals(&self) -> Vec<DecalRect> {
        let (y0, y1) = self.decal_rows();
        let cell_y = (y1 - y0) / GRID as f64;
        let mut out = Vec::new();
        for row in 0..GRID {
            let (ya, yb) = (y0 + row as f64 * cell_y, y0 + (row as f64 + 0.7) * cell_y);
            let yc = 0.5 * (ya + yb);
            // The row's width on screen follows its depth: keep the decals inside the view.
            let half = 0.8 * TAN_HALF_FOV * -self.plane_z(yc);
            let cell_x = 2.0 * half / GRID as f64;
            for col in 0..GRID {
                let xa = -half + col as f64 * cell_x;
                out.push(((xa, xa + 0.7 * cell_x), (ya, yb), self.plane_z(yc)));
            }
        }
        out
    }
}

/// A decal's x range and y range on the plane, and its centre's eye z.
type DecalRect = ((f64, f64), (f64, f64), f64);
/// A [`DecalRect`] with the minimum δ toward the camera at its centre.
type DecalShift = ((f64, f64), (f64, f64), f64, f64);

/// The scenes of the report: facing and tilted planes, near and far, D24 and D32F (every
/// method needs a stencil buffer in the same target, and GL has no packed D16 + stencil).
pub fn scenes() -> Vec<Scene> {
    use DepthFormat::*;
    vec![
        Scene::new(0.1, 1000.0, 20.0, 0.0, D24),
        Scene::new(0.1, 1000.0, 500.0, 0.0, D24),
        Scene::new(0.001, 1000.0, 200.0, 0.0, D24),
        Scene::new(0.1, 1000.0, 50.0, 1.0, D24),
        Scene::new(0.1, 1000.0, 50.0, 3.0, D24),
        Scene::new(0.1, 1000.0, 500.0, 0.0, D32F),
        Scene::new(0.1, 1000.0, 50.0, 3.0, D32F),
    ]
}

/// A way of drawing decals.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Method {
    /// No offset at all (depth test GL_LESS).
    NoOffset,
    /// zshift's offset matrix, δ = k × `min_delta_toward` at the decal's centre depth.
    ZshiftMatrix { k: f64 },
    /// `glPolygonOffset(factor, units)`.
    PolygonOffset { factor: f32, units: f32 },
    /// `glPolygonOffset(0, units)` with units equal to zshift's window-depth offset at k.
    PolygonOffsetZshiftEquivalent { k: f64 },
    /// Every decal vertex moved toward the eye along its ray by the eye-space δ of zshift at k.
    EyeSpaceMove { k: f64 },
    /// zshift's recommended offset (`zshift::recommend::recommend`, model R1) per decal, through
    /// `epsilon_matrix`.
    ZshiftRecommended,
    /// The same with the profile the probe measured in the report's context and each decal's
    /// corners (`decal_shape`): the tight description.
    ZshiftRecommendedProbed,
    /// `glPolygonOffset(−factor, −units)` from the recommendation's equivalent pair.
    PolygonOffsetRecommended,
    /// Every decal vertex moved toward the eye by the recommendation's δ at the decal's far end.
    EyeSpaceMoveRecommended,
    /// Seed 004's three passes: base without depth writes, decal without depth writes, base
    /// again with depth writes and no colour.
    ThreePassDepthMask,
    /// Base writes stencil 1 where visible; decals drawn where stencil = 1, depth test off.
    Stencil,
}

impl Method {
    pub fn label(&self) -> String {
        match *self {
            Method::NoOffset => "no offset".into(),
            Method::ZshiftMatrix { k } => format!("zshift matrix, δ = {k}×min"),
            Method::PolygonOffset { factor, units } => {
                format!("glPolygonOffset({factor}, {units})")
            }
            Method::PolygonOffsetZshiftEquivalent { k } => {
                format!("glPolygonOffset(0, zshift-equiv. {k}×min)")
            }
            Method::EyeSpaceMove { k } => format!("eye-space move, δ = {k}×min"),
            Method::ZshiftRecommended => "zshift matrix, recommended (R1)".into(),
            Method::ZshiftRecommendedProbed => {
                "zshift matrix, recommended, probed profile + corners".into()
            }
            Method::PolygonOffsetRecommended => "glPolygonOffset at zshift's recommendation".into(),
            Method::EyeSpaceMoveRecommended => "eye-space move, recommended δ".into(),
            Method::ThreePassDepthMask => "three-pass depth mask (004)".into(),
            Method::Stencil => "stencil".into(),
        }
    }
}

/// The methods of the report, with zshift at the stated multiples `ks` of the minimum δ.
pub fn methods(ks: &[f64]) -> Vec<Method> {
    let mut m = vec![
        Method::NoOffset,
        Method::ZshiftRecommended,
        Method::ZshiftRecommendedProbed,
    ];
    for &k in ks {
        m.push(Method::ZshiftMatrix { k });
    }
    m.extend([
        Method::PolygonOffset {
            factor: -1.0,
            units: -1.0,
        },
        Method::PolygonOffset {
            factor: -2.0,
            units: -2.0,
        },
        Method::PolygonOffset {
            factor: 0.0,
            units: -1.0,
        },
    ]);
    m.push(Method::PolygonOffsetRecommended);
    for &k in ks {
        m.push(Method::PolygonOffsetZshiftEquivalent { k });
    }
    m.push(Method::EyeSpaceMoveRecommended);
    for &k in ks {
        m.push(Method::EyeSpaceMove { k });
    }
    m.extend([Method::ThreePassDepthMask, Method::Stencil]);
    m
}

/// What one method did on one scene.
#[derive(Clone, Debug)]
pub struct Outcome {
    pub scene: String,
    pub method: String,
    /// Median time per frame (clear, occluder, base, decals, glFinish), milliseconds.
    pub frame_ms: f64,
    /// Decal pixels that should be visible (interior, away from the occluder).
    pub visible: usize,
    /// Of those, how many show something else.
    pub lost: usize,
    /// Decal pixels behind the occluder (interior of both).
    pub hidden: usize,
    /// Of those, how many show the decal.
    pub bleed: usize,
}

/// Renders every method on `scene`: the reference masks, then interleaved timed frames, then
/// one frame read back per method.
pub fn run_scene(
    gl: &mut Gl,
    scene: &Scene,
    methods: &[Method],
    probed: &RasterizerProfile,
    tick: &dyn Fn(),
) -> Result<Vec<Outcome>, String> {
    gl.set_target_with_stencil(SIZE, SIZE, scene.format)?;
    let plan = Plan::new(scene, probed)?;
    let (visible_mask, hidden_mask) = reference_masks(gl, scene, &plan)?;
    let mut times: Vec<Vec<f64>> = vec![Vec::new(); methods.len()];
    for round in 0..ROUNDS + 2 {
        for (i, m) in methods.iter().enumerate() {
            let start = Instant::now();
            draw_frame(gl, scene, &plan, m)?;
            unsafe { glow::HasContext::finish(gl.glow()) };
            if round >= 2 {
                times[i].push(start.elapsed().as_secs_f64() * 1e3);
            }
        }
        tick();
    }
    let mut out = Vec::new();
    for (i, m) in methods.iter().enumerate() {
        draw_frame(gl, scene, &plan, m)?;
        let image = gl.read_color()?;
        let decal = rgba8(DECAL);
        let lost = count(&image, &visible_mask, |p| p[..3] != decal[..3]);
        let bleed = count(&image, &hidden_mask, |p| p[..3] == decal[..3]);
        out.push(Outcome {
            scene: scene.name.clone(),
            method: m.label(),
            frame_ms: median(&mut times[i]),
            visible: visible_mask.iter().filter(|&&b| b).count(),
            lost,
            hidden: hidden_mask.iter().filter(|&&b| b).count(),
            bleed,
        });
    }
    gl.check("run_scene")?;
    Ok(out)
}

fn count(image: &Image, mask: &[bool], bad: impl Fn(&[u8; 4]) -> bool) -> usize {
    image
        .pixels
        .iter()
        .zip(mask)
        .filter(|(p, &m)| m && bad(p))
        .count()
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(|a, b| a.total_cmp(b));
    v[v.len() / 2]
}

/// The per-scene geometry and per-decal offsets, computed once.
struct Plan {
    plain: [f32; 16],
    base: Quad,
    occluder: Quad,
    /// Per decal: rectangle, centre eye z, and the minimum δ toward the camera there.
    decals: Vec<DecalShift>,
    /// Per decal: zshift's recommendation for it.
    recommended: Vec<Recommendation>,
    /// Per decal: the recommendation with the probed profile and the decal's corners.
    probed: Vec<Recommendation>,
    frustum: Frustum,
    bits: u32,
}

impl Plan {
    fn new(scene: &Scene, probed: &RasterizerProfile) -> Result<Plan, String> {
        let frustum = scene.frustum();
        // D32F under the standard mapping resolves like D24 near window depth 1 (NOTES.md).
        let bits = scene.format.bits().min(24);
        let decals = scene
            .decals()
            .into_iter()
            .map(|(x, y, pz)| {
                let min = zshift::min_delta_toward(scene.n, scene.f, bits, pz)
                    .map_err(|e| format!("min_delta_toward at {pz}: {e}"))?;
                Ok((x, y, pz, min))
            })
            .collect::<Result<_, String>>()?;
        let recommended = scene
            .decals()
            .into_iter()
            .map(|(x, y, _)| recommendation(scene, &frustum, x, y, None))
            .collect::<Result<_, String>>()?;
        let probed = scene
            .decals()
            .into_iter()
            .map(|(x, y, _)| recommendation(scene, &frustum, x, y, Some(probed)))
            .collect::<Result<_, String>>()?;
        Ok(Plan {
            recommended,
            probed,
            plain: frustum.to_cols_array().map_err(|e| e.to_string())?,
            base: scene.base(),
            occluder: scene.occluder(),
            decals,
            frustum,
            bits,
        })
    }

    /// `glPolygonOffset` units equal to zshift's window-depth offset for δ at pz: the NDC offset
    /// `m10·ε` halved (window = NDC/2 + 1/2), in units of r = 1/(2^m − 1).
    fn equivalent_units(&self, n: f64, f: f64, delta: f64, pz: f64) -> f32 {
        let eps = zshift::epsilon(n, f, delta, pz).expect("valid shift");
        let m10 = -(f + n) / (f - n);
        let window = (m10 * eps).abs() / 2.0;
        -(window * ((1u64 << self.bits) - 1) as f64) as f32
    }
}

/// The largest of zshift's `bleed_gap` over the scene's decals: occluders nearer than the base
/// by at least this are never overdrawn at the recommendation (model R1).
pub fn recommended_bleed_gap(scene: &Scene) -> Result<f64, String> {
    let plan = Plan::new(scene, &RasterizerProfile::worst_case())?;
    Ok(plan
        .recommended
        .iter()
        .map(|r| r.bleed_gap)
        .fold(0.0, f64::max))
}

/// zshift's recommendation for one decal: its corners' eye distances, the plane's slope, the
/// viewport and format, and llvmpipe's unsnapped depth setup (measured by the gl helper; a GPU
/// run would use `Snapping::SubpixelBits(GL_SUBPIXEL_BITS)`); with `probed`, that profile and the
/// decal's corners (`decal_shape`: depths, slope and footprint) instead.
fn recommendation(
    scene: &Scene,
    frustum: &Frustum,
    x: (f64, f64),
    y: (f64, f64),
    probed: Option<&RasterizerProfile>,
) -> Result<Recommendation, String> {
    let quad = scene.quad(x, y, 0.0, 0.0);
    let distances = quad.corners.map(|c| -(c[2] as f64));
    let d1 = distances.iter().copied().fold(f64::MAX, f64::min);
    let d2 = distances.iter().copied().fold(0.0, f64::max);
    let format =
        RecFormat::from_gl_internal_format(scene.format.gl_enum()).expect("a GL depth format");
    let mut model = RecScene {
        pipeline: Default::default(),
        footprint: None,
        frustum: *frustum,
        viewport: [SIZE, SIZE],
        format,
        depth_range: [d1, d2],
        slope: scene.slope,
        exact_depth: scene.slope == 0.0,
        depth_test: zshift::recommend::DepthTest::Less,
        base: zshift::recommend::Base::InsideFrustum,
        profile: RasterizerProfile {
            snapping: Snapping::Unsnapped,
            ..Default::default()
        },
    };
    if let Some(profile) = probed {
        let corners = quad
            .corners
            .map(|[x, y, z]| zshift::glam::Vec3::new(x, y, z));
        let shape = zshift::recommend::decal_shape(
            frustum,
            zshift::projection::ClipDepth::NegOneToOne,
            [SIZE, SIZE],
            &corners,
        )
        .map_err(|e| format!("decal_shape for decal at {y:?}: {e}"))?;
        model.depth_range = shape.depth_range;
        model.slope = shape.slope;
        model.footprint = Some(shape.footprint);
        model.profile = *profile;
    }
    recommend(&model).map_err(|e| format!("recommend for decal at {y:?}: {e}"))
}

/// The decals only, then the occluder only, on a cleared target: the masks of where the decal
/// should be visible (interior pixels, not next to the occluder) and where it should be hidden.
fn reference_masks(
    gl: &mut Gl,
    scene: &Scene,
    plan: &Plan,
) -> Result<(Vec<bool>, Vec<bool>), String> {
    gl.clear(BACKGROUND, 1.0)?;
    let always = DrawState {
        depth_func: glow::ALWAYS,
        ..DrawState::default()
    };
    for &(x, y, _, _) in &plan.decals {
        gl.draw_quad(&scene.quad(x, y, 0.0, 0.0), &plan.plain, DECAL, &always)?;
    }
    let decal = interior(&gl.read_color()?.mask_of(rgba8(DECAL)));
    gl.clear(BACKGROUND, 1.0)?;
    gl.draw_quad(&plan.occluder, &plan.plain, OCCLUDER, &always)?;
    let occluder = gl.read_color()?.mask_of(rgba8(OCCLUDER));
    let occluder_core = interior(&occluder);
    let near_occluder = dilate(&occluder);
    let visible = decal
        .iter()
        .zip(&near_occluder)
        .map(|(&d, &o)| d && !o)
        .collect();
    let hidden = decal
        .iter()
        .zip(&occluder_core)
        .map(|(&d, &o)| d && o)
        .collect();
    Ok((visible, hidden))
}

/// Pixels whose 3×3 neighbourhood is inside the mask: edge pixels, whose coverage differs
/// between methods that move vertices, are not counted.
fn interior(mask: &[bool]) -> Vec<bool> {
    neighbourhood(mask, true)
}

fn dilate(mask: &[bool]) -> Vec<bool> {
    neighbourhood(mask, false)
}

fn neighbourhood(mask: &[bool], all: bool) -> Vec<bool> {
    let s = SIZE as i64;
    (0..s * s)
        .map(|i| {
            let (x, y) = (i % s, i / s);
            let mut hits = (-1..=1).flat_map(|dy| (-1..=1).map(move |dx| (x + dx, y + dy)));
            let inside = |(px, py): (i64, i64)| {
                px >= 0 && py >= 0 && px < s && py < s && mask[(py * s + px) as usize]
            };
            if all {
                hits.all(inside)
            } else {
                hits.any(inside)
            }
        })
        .collect()
}

/// One frame: clear, occluder, then base and decals the method's way.
fn draw_frame(gl: &mut Gl, scene: &Scene, plan: &Plan, method: &Method) -> Result<(), String> {
    gl.clear(BACKGROUND, 1.0)?;
    gl.clear_stencil(0)?;
    let normal = DrawState::default();
    gl.draw_quad(&plan.occluder, &plan.plain, OCCLUDER, &normal)?;
    match *method {
        Method::ThreePassDepthMask => three_pass(gl, scene, plan),
        Method::Stencil => stencil(gl, scene, plan),
        _ => {
            gl.draw_quad(&plan.base, &plan.plain, BASE, &normal)?;
            for (i, &(x, y, pz, min)) in plan.decals.iter().enumerate() {
                let rec = if *method == Method::ZshiftRecommendedProbed {
                    &plan.probed[i]
                } else {
                    &plan.recommended[i]
                };
                draw_offset_decal(gl, scene, plan, method, x, y, pz, min, rec)?;
            }
            Ok(())
        }
    }
}

#[allow(clippy::too_many_arguments)]
fn draw_offset_decal(
    gl: &mut Gl,
    scene: &Scene,
    plan: &Plan,
    method: &Method,
    x: (f64, f64),
    y: (f64, f64),
    pz: f64,
    min: f64,
    rec: &Recommendation,
) -> Result<(), String> {
    let normal = DrawState::default();
    let flat = scene.quad(x, y, 0.0, 0.0);
    match *method {
        Method::NoOffset => gl.draw_quad(&flat, &plan.plain, DECAL, &normal),
        Method::ZshiftMatrix { k } => {
            let m = zshift::offset_matrix(&plan.frustum, k * min, pz).map_err(|e| e.to_string())?;
            gl.draw_quad(&flat, &m, DECAL, &normal)
        }
        Method::PolygonOffset { factor, units } => {
            let state = DrawState {
                polygon_offset: Some((factor, units)),
                ..normal
            };
            gl.draw_quad(&flat, &plan.plain, DECAL, &state)
        }
        Method::PolygonOffsetZshiftEquivalent { k } => {
            let units = plan.equivalent_units(scene.n, scene.f, k * min, pz);
            let state = DrawState {
                polygon_offset: Some((0.0, units)),
                ..normal
            };
            gl.draw_quad(&flat, &plan.plain, DECAL, &state)
        }
        Method::EyeSpaceMove { k } => {
            let moved = scene.quad(x, y, 0.0, k * min);
            gl.draw_quad(&moved, &plan.plain, DECAL, &normal)
        }
        Method::ZshiftRecommended | Method::ZshiftRecommendedProbed => {
            let m =
                zshift::epsilon_matrix(&plan.frustum, rec.epsilon).map_err(|e| e.to_string())?;
            gl.draw_quad(&flat, &m, DECAL, &normal)
        }
        Method::PolygonOffsetRecommended => {
            let [factor, units] = rec.polygon_offset;
            let state = DrawState {
                polygon_offset: Some((-factor as f32, -units as f32)),
                ..normal
            };
            gl.draw_quad(&flat, &plan.plain, DECAL, &state)
        }
        Method::EyeSpaceMoveRecommended => {
            let moved = scene.quad(x, y, 0.0, rec.delta_at_far);
            gl.draw_quad(&moved, &plan.plain, DECAL, &normal)
        }
        Method::ThreePassDepthMask | Method::Stencil => unreachable!("drawn by their own passes"),
    }
}

fn three_pass(gl: &mut Gl, scene: &Scene, plan: &Plan) -> Result<(), String> {
    let no_depth_write = DrawState {
        depth_write: false,
        ..DrawState::default()
    };
    gl.draw_quad(&plan.base, &plan.plain, BASE, &no_depth_write)?;
    for &(x, y, _, _) in &plan.decals {
        gl.draw_quad(
            &scene.quad(x, y, 0.0, 0.0),
            &plan.plain,
            DECAL,
            &no_depth_write,
        )?;
    }
    let depth_only = DrawState {
        color_write: false,
        ..DrawState::default()
    };
    gl.draw_quad(&plan.base, &plan.plain, BASE, &depth_only)
}

fn stencil(gl: &mut Gl, scene: &Scene, plan: &Plan) -> Result<(), String> {
    let g = gl.glow();
    unsafe {
        use glow::HasContext;
        g.enable(glow::STENCIL_TEST);
        g.stencil_mask(0xFF);
        g.stencil_func(glow::ALWAYS, 1, 0xFF);
        g.stencil_op(glow::KEEP, glow::KEEP, glow::REPLACE);
    }
    gl.draw_quad(&plan.base, &plan.plain, BASE, &DrawState::default())?;
    unsafe {
        use glow::HasContext;
        let g = gl.glow();
        g.stencil_func(glow::EQUAL, 1, 0xFF);
        g.stencil_op(glow::KEEP, glow::KEEP, glow::KEEP);
    }
    let over = DrawState {
        depth_func: glow::ALWAYS,
        depth_write: false,
        ..DrawState::default()
    };
    for &(x, y, _, _) in &plan.decals {
        gl.draw_quad(&scene.quad(x, y, 0.0, 0.0), &plan.plain, DECAL, &over)?;
    }
    unsafe { glow::HasContext::disable(gl.glow(), glow::STENCIL_TEST) };
    Ok(())
}
