//! The plane error `error_ulps` (the model's `T + I`, [`crate::model::measured`]): every pixel
//! of about 300 planes against the exact plane through its f32 vertices, per format and under
//! reversed Z.

use super::*;
use crate::projection::ClipDepth;

/// Triangle corners in NDC: one on screen, one reaching four viewports past it.
pub(super) const CORNERS: [[[f64; 2]; 3]; 2] = [
    [[-0.93, -0.871], [0.947, -0.613], [-0.207, 0.969]],
    [[-4.1, -3.3], [3.7, -2.9], [0.31, 5.2]],
];

/// Eye-space slopes `(∂z/∂x, ∂z/∂y)` of the plane-error scenes: facing, gentle, steep, grazing.
pub(super) const SLOPES: [(f64, f64); 4] = [(0.0, 0.0), (0.37, 1.0), (-3.0, 1.9), (10.0, -0.3)];

/// The plane-error scenes of one depth mapping: for each view, axis depth and slope, each
/// corner set shrunk toward the view axis (halved, up to 4 times) until every corner lies
/// between the near and far planes.
pub(super) fn plane_scenes(clip: ClipDepth) -> Vec<Scene> {
    let reversed = clip == ClipDepth::ReversedZeroToOne;
    let views: [(View, [f64; 2]); 3] = if reversed {
        [
            (
                View {
                    e: 0.5,
                    n: 0.1,
                    f: 1e4,
                    reversed,
                    squash: 1.0,
                },
                [0.002, 0.3],
            ),
            (
                View {
                    e: 0.7,
                    n: 1.0,
                    f: 1e6,
                    reversed,
                    squash: 1.0,
                },
                [2e-5, 0.05],
            ),
            (
                View {
                    e: 0.4,
                    n: 0.5,
                    f: 100.0,
                    reversed,
                    squash: 1.0,
                },
                [0.02, 0.7],
            ),
        ]
    } else {
        [
            (
                View {
                    e: 0.5,
                    n: 1.0,
                    f: 10.0,
                    reversed,
                    squash: 1.0,
                },
                [0.02, 0.6],
            ),
            (
                View {
                    e: 0.7,
                    n: 0.1,
                    f: 100.0,
                    reversed,
                    squash: 1.0,
                },
                [0.3, 0.95],
            ),
            (
                View {
                    e: 0.4,
                    n: 1.0,
                    f: 1e5,
                    reversed,
                    squash: 1.0,
                },
                [0.5, 0.998],
            ),
        ]
    };
    let mut out = Vec::new();
    for (view, depths) in views {
        for w in depths {
            let d = view.distance_at_depth(w);
            for (sx, sy) in SLOPES {
                for corners in CORNERS {
                    let fits = (0..5).find_map(|halvings| {
                        let k = 0.5f64.powi(halvings);
                        let t: Option<Vec<[f64; 3]>> = corners
                            .iter()
                            .map(|&[xn, yn]| view.on_plane(k * xn, k * yn, d, sx, sy))
                            .collect();
                        t
                    });
                    if let Some(t) = fits {
                        out.push(Scene {
                            matrix: view.matrix_for(clip != ClipDepth::NegOneToOne),
                            triangles: vec![View::triangle([t[0], t[1], t[2]])],
                        });
                    }
                }
            }
        }
    }
    out
}

/// Sloped planes in every direction, as engines draw them: the fixed scenes of
/// [`plane_scenes`] cover a few slopes and views; these add 256 more (under reversed Z too), deterministic
/// pseudo-random (f/n from 10² to 10⁹, aspect 1/1.6 to 1.6, slope 0.3 to 10 in any direction,
/// axis depths log-spread over the range, triangles on screen or reaching up to half a viewport
/// past it), and 128 through off-centre frusta (the view axis up to 1.3 half-extents off the
/// screen's centre, so off the screen: split screens, tiled and jittered projections), where
/// `glFrustum`'s `m8`, `m9` add their own roundings to the window position. A rounding maximum
/// grows with the number of planes it is taken over, and the figure must hold for planes the
/// probe does not draw: on llvmpipe the fixed scenes alone found 1.40, the 256 centred planes
/// 1.54, and a survey of 804 other planes reaches 1.74 (`tests/gl_scenes.rs`).
pub(super) fn varied_plane_scenes(clip: ClipDepth) -> Vec<Scene> {
    let mut out = varied_planes(clip, 0x5EED_2026_1123, 0.0, 4 * TILES * TILES);
    out.extend(varied_planes(
        clip,
        0x5EED_2026_1126,
        1.3,
        2 * TILES * TILES,
    ));
    out
}

/// `count` planes of [`varied_plane_scenes`] from the stream `seed`, the view axis up to
/// `off_centre` half-extents from the screen's centre in each direction.
fn varied_planes(clip: ClipDepth, seed: u64, off_centre: f64, count: usize) -> Vec<Scene> {
    let reversed = clip == ClipDepth::ReversedZeroToOne;
    let mut next = uniform_stream(seed);
    let ratios = [1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e9];
    let slopes = [0.3, 1.0, 3.0, 10.0];
    let mut out = Vec::new();
    for i in 0..count * 4 {
        if out.len() == count {
            break;
        }
        let ratio = ratios[i % ratios.len()];
        let n = if next() < 0.5 { 0.1 } else { 1.0 };
        let view = View {
            e: 0.35 + 0.4 * next(),
            n,
            f: n * ratio,
            reversed,
            squash: 0.625 + next(),
        };
        let slope = slopes[(i / ratios.len()) % slopes.len()];
        let angle = std::f64::consts::TAU * next();
        let (sx, sy) = (slope * angle.cos(), slope * angle.sin());
        let d = n * ratio.powf(0.9 * next()).max(1.5);
        let corners: [[f64; 2]; 3] =
            std::array::from_fn(|_| [3.0 * next() - 1.5, 3.0 * next() - 1.5]);
        // The axis's offset in NDC units of the centred view: `m8`, `m9` of glFrustum.
        let shift = if off_centre > 0.0 {
            [0, 1].map(|_| off_centre * (2.0 * next() - 1.0))
        } else {
            [0.0, 0.0]
        };
        let t: Option<Vec<[f64; 3]>> = corners
            .iter()
            .map(|&[xn, yn]| view.on_plane(xn + shift[0], yn + shift[1], d, sx, sy))
            .collect();
        if let Some(t) = t {
            let mut matrix = view.matrix_for(clip != ClipDepth::NegOneToOne);
            matrix[8] = shift[0] as f32;
            matrix[9] = shift[1] as f32;
            out.push(Scene {
                matrix,
                triangles: vec![View::triangle([t[0], t[1], t[2]])],
            });
        }
    }
    out
}

/// The figures of [`plane_error`] for one format and mapping.
pub(super) struct PlaneErrors {
    /// The worst error in quanta (D32F: 2⁻²⁴ under `[−1, 1]`, the spacing at the primitive's
    /// largest depth under reversed Z), over every scene.
    pub(super) worst: f64,
    /// Pixels compared.
    pub(super) pixels: usize,
    /// The worst error in units of the spacing at each pixel's own depth.
    pub(super) local: f64,
    /// The worst `(|stored − exact| − conversion)⁺ / (2⁻²⁴·(1 + M))` ([`Plane::magnitude`]).
    pub(super) error_ulps: f64,
}

/// The plane errors of every scene of `format` under one mapping (module docs).
pub(super) unsafe fn plane_error(
    gl: &Gl,
    o: &Objects,
    format: Format,
    clip: ClipDepth,
    snapped_by: usize,
) -> Result<PlaneErrors> {
    let reversed = clip == ClipDepth::ReversedZeroToOne;
    let zero_to_one = clip != ClipDepth::NegOneToOne;
    let mut e = PlaneErrors {
        worst: 0.0,
        pixels: 0,
        local: 0.0,
        error_ulps: 0.0,
    };
    let mut scenes = plane_scenes(clip);
    let fixed = scenes.len();
    if format == Format::Float {
        // D32F stores the computed depth as is: error_ulps comes from it (the UNORM formats'
        // conversion hides a quantum), so the varied planes are drawn there only.
        scenes.extend(varied_plane_scenes(clip));
    }
    let mut stored_tiles = Vec::new();
    for batch in scenes.chunks(TILES * TILES) {
        stored_tiles.extend(draw_tiles(gl, o, format, batch)?);
    }
    for (i, (scene, stored)) in scenes.iter().zip(stored_tiles).enumerate() {
        let plane = Plane::with_mapping(&snap(&scene.exact()[0], snapped_by), zero_to_one);
        // D32F under [−1, 1] errs mostly in absolute terms (u·|m10| from the transform), so its
        // unit is 2⁻²⁴, the spacing at w ≥ ½; under reversed Z the error is relative to the
        // primitive's largest depth, and so is its unit.
        let unit = |exact: f64| match (format, reversed) {
            (Format::Float, false) => F32_UNIT_ROUNDOFF,
            (Format::Float, true) => f32_spacing(plane.largest),
            _ => format.quantum(exact),
        };
        let (x, y) = tile_origin(i % (TILES * TILES));
        let corner = (x as f64, y as f64);
        let magnitude = plane.magnitude(corner);
        let m10 = f64::from(scene.matrix[10]).abs();
        // The varied planes are read on every other row and column: their figure is a maximum
        // over planes more than over neighbouring pixels, and a quarter of the pixels keeps the
        // probe's run time down.
        let stride = if i < fixed { 1 } else { 2 };
        for py in (0..SIZE).step_by(stride) {
            for px in (0..SIZE).step_by(stride) {
                let Some(exact) = plane.depth_inside(px, py) else {
                    continue;
                };
                let error = (stored[py * SIZE + px] - exact).abs();
                e.worst = e.worst.max(error / unit(exact));
                e.local = e.local.max(error / format.quantum(exact));
                e.pixels += 1;
                e.error_ulps = e.error_ulps.max(pixel_ulps(
                    format,
                    clip,
                    m10,
                    error,
                    exact,
                    magnitude(px, py),
                ));
            }
        }
    }
    Ok(e)
}

/// One pixel's `error_ulps`: its error `|stored − exact|` less one quantum of conversion on
/// UNORM, over `u·(c + M)` with `M` the plane's magnitude at the pixel and `c` the transform's
/// constant: 1 under `[−1, 1]`, 2 under `[0, 1]` (nothing halves the transform's roundings:
/// [`crate::model::measured`]), `|m10|` under reversed Z (they are relative to the product
/// `m10·z`, and to the depth itself, in `M`).
fn pixel_ulps(
    format: Format,
    clip: ClipDepth,
    m10: f64,
    error: f64,
    exact: f64,
    magnitude: f64,
) -> f64 {
    let conversion = match format {
        Format::Float => 0.0,
        Format::Unorm(_) => format.quantum(exact),
    };
    let constant = match clip {
        ClipDepth::NegOneToOne => 1.0,
        ClipDepth::ZeroToOne => 2.0,
        ClipDepth::ReversedZeroToOne => m10,
    };
    (error - conversion).max(0.0) / (F32_UNIT_ROUNDOFF * (constant + magnitude))
}

/// The unit roundoff of f32, `2⁻²⁴` (one home: [`crate::model`]).
pub(super) use crate::model::F32_UNIT_ROUNDOFF;

/// [`plane_error`] of D32F under `glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE)` with `clip`'s
/// projection (`[0, 1]`, or reversed Z, where float depth keeps its relative precision);
/// `None` without `glClipControl`.
pub(super) unsafe fn zero_to_one_plane_error(
    gl: &Gl,
    o: &Objects,
    clip: ClipDepth,
    snapped_by: usize,
) -> Result<Option<PlaneErrors>> {
    let Some(clip_control) = gl.ClipControl else {
        return Ok(None);
    };
    clip_control(LOWER_LEFT, ZERO_TO_ONE);
    let result = plane_error(gl, o, Format::Float, clip, snapped_by);
    clip_control(LOWER_LEFT, NEGATIVE_ONE_TO_ONE);
    result.map(Some)
}
