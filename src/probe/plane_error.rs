//! The plane error `error_ulps` (the model's `T + I`, [`crate::model::measured`]): every pixel
//! of about 300 planes against the exact plane through its f32 vertices, per format and under
//! reversed Z.

use super::*;

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
pub(super) fn plane_scenes(reversed: bool) -> Vec<Scene> {
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
                            matrix: view.matrix(),
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
/// past it). A rounding maximum grows with the number of planes it is taken over, and the
/// figure must hold for planes the probe does not draw: on llvmpipe the fixed scenes alone found
/// 1.40, these 256 more 1.54, and a survey of 804 other planes reaches 1.74 (`tests/gl_scenes.rs`).
pub(super) fn varied_plane_scenes(reversed: bool) -> Vec<Scene> {
    let mut next = uniform_stream(0x5EED_2026_1123);
    let ratios = [1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e9];
    let slopes = [0.3, 1.0, 3.0, 10.0];
    let mut out = Vec::new();
    for i in 0..TILES * TILES * 16 {
        if out.len() == 4 * TILES * TILES {
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
        let t: Option<Vec<[f64; 3]>> = corners
            .iter()
            .map(|&[xn, yn]| view.on_plane(xn, yn, d, sx, sy))
            .collect();
        if let Some(t) = t {
            out.push(Scene {
                matrix: view.matrix(),
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
    reversed: bool,
) -> Result<PlaneErrors> {
    let mut e = PlaneErrors {
        worst: 0.0,
        pixels: 0,
        local: 0.0,
        error_ulps: 0.0,
    };
    let mut scenes = plane_scenes(reversed);
    let fixed = scenes.len();
    if format == Format::Float {
        // D32F stores the computed depth as is: error_ulps comes from it (the UNORM formats'
        // conversion hides a quantum), so the varied planes are drawn there only.
        scenes.extend(varied_plane_scenes(reversed));
    }
    let mut stored_tiles = Vec::new();
    for batch in scenes.chunks(TILES * TILES) {
        stored_tiles.extend(draw_tiles(gl, o, format, batch)?);
    }
    for (i, (scene, stored)) in scenes.iter().zip(stored_tiles).enumerate() {
        let plane = Plane::with_mapping(&scene.exact()[0], reversed);
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
                let conversion = match format {
                    Format::Float => 0.0,
                    Format::Unorm(_) => format.quantum(exact),
                };
                // Under [−1, 1] the 1 stands for the transform's own roundings; under reversed Z
                // they are relative to |m10| (the product m10·z) and to the depth itself (in M).
                let constant = if reversed { m10 } else { 1.0 };
                let scale = F32_UNIT_ROUNDOFF * (constant + magnitude(px, py));
                e.error_ulps = e.error_ulps.max((error - conversion).max(0.0) / scale);
            }
        }
    }
    Ok(e)
}

/// The unit roundoff of f32, `2⁻²⁴` (one home: [`crate::model`]).
pub(super) use crate::model::F32_UNIT_ROUNDOFF;

/// [`plane_error`] of D32F under reversed Z (`glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE)`,
/// reversed projection), where float depth keeps its relative precision; `None` without
/// `glClipControl`.
pub(super) unsafe fn reversed_plane_error(gl: &Gl, o: &Objects) -> Result<Option<PlaneErrors>> {
    let Some(clip_control) = gl.ClipControl else {
        return Ok(None);
    };
    clip_control(LOWER_LEFT, ZERO_TO_ONE);
    let result = plane_error(gl, o, Format::Float, true);
    clip_control(LOWER_LEFT, NEGATIVE_ONE_TO_ONE);
    result.map(Some)
}
