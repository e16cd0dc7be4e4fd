//! Drawing for the measurements: triangles on eye-space planes, projected with `glFrustum` in
//! f64 and rounded to f32, drawn into the probe's tiles and read back, and the exact window-depth
//! plane each pixel is checked against.

use super::*;
pub(super) use crate::footprint::cross;

/// A triangle's vertices as the vertex buffer holds them (eye space, `w = 1`; or clip
/// coordinates when drawn with [`IDENTITY`]).
pub(super) type Triangle = [[f32; 4]; 3];

/// A triangle's exact clip coordinates: its f32 vertices times the f32 matrix, in f64.
pub(super) type ClipTriangle = [[f64; 4]; 3];

/// The identity matrix: vertices are clip coordinates.
pub(super) const IDENTITY: [f32; 16] = [
    1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0,
];

/// Triangles drawn with one projection matrix (column-major, as `glUniformMatrix4fv` takes it).
pub(super) struct Scene {
    pub(super) matrix: [f32; 16],
    pub(super) triangles: Vec<Triangle>,
}

impl Scene {
    /// Triangles whose vertices are clip coordinates.
    pub(super) fn clip(triangles: Vec<Triangle>) -> Scene {
        Scene {
            matrix: IDENTITY,
            triangles,
        }
    }

    /// Each triangle's exact clip coordinates: the products of f32 values are exact in f64 and
    /// the sums of four of them err by ~10⁻¹⁶ relative, far below the GPU's f32 arithmetic.
    pub(super) fn exact(&self) -> Vec<ClipTriangle> {
        let m = self.matrix.map(f64::from);
        self.triangles
            .iter()
            .map(|t| {
                t.map(|v| {
                    let v = v.map(f64::from);
                    std::array::from_fn(|row| (0..4).map(|k| m[4 * k + row] * v[k]).sum())
                })
            })
            .collect()
    }
}

/// Clears depth to 1, draws `scene` into the first tile (depth test `GL_ALWAYS`), and reads the
/// stored window depth back exactly (rows bottom-up).
pub(super) unsafe fn draw(gl: &Gl, o: &Objects, format: Format, scene: &Scene) -> Result<Vec<f64>> {
    let mut tiles = draw_tiles(gl, o, format, std::slice::from_ref(scene))?;
    Ok(tiles.swap_remove(0))
}

/// A deterministic stream of numbers in `[0, 1)` from `seed` (a 64-bit LCG, Knuth's MMIX
/// constants, its top 53 bits): the probe's pseudo-random planes, the same on every run.
pub(super) fn uniform_stream(seed: u64) -> impl FnMut() -> f64 {
    let mut state = seed;
    move || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The framebuffer pixel of tile `i`'s lower-left corner (tiles in rows of `TILES`).
pub(super) fn tile_origin(i: usize) -> (usize, usize) {
    ((i % TILES) * SIZE, (i / TILES) * SIZE)
}

/// Clears depth to 1 over all `TILES²` tiles and puts `vertices` in the probe's array buffer.
pub(super) unsafe fn clear_and_upload<T>(gl: &Gl, vertices: &[T]) {
    let side = (SIZE * TILES) as Sizei;
    (gl.Viewport)(0, 0, side, side);
    (gl.ClearDepth)(1.0);
    (gl.Clear)(DEPTH_BUFFER_BIT);
    (gl.BufferData)(
        ARRAY_BUFFER,
        std::mem::size_of_val(vertices) as isize,
        vertices.as_ptr().cast(),
        STREAM_DRAW,
    );
}

/// Draws each scene into a tile of its own (at most `TILES²`) and returns each tile's stored
/// window depth, `SIZE × SIZE` rows bottom-up.
pub(super) unsafe fn draw_tiles(
    gl: &Gl,
    o: &Objects,
    format: Format,
    scenes: &[Scene],
) -> Result<Vec<Vec<f64>>> {
    let (width, height) = render_tiles(gl, o, scenes)?;
    let depth = read_depth(gl, format, 0, width, height)?;
    Ok((0..scenes.len().min(TILES * TILES))
        .map(|i| {
            let (x, y) = tile_origin(i);
            (0..SIZE)
                .flat_map(|row| {
                    let start = (y + row) * width + x;
                    depth[start..start + SIZE].iter().copied()
                })
                .collect()
        })
        .collect())
}

/// Draws each scene into a tile of its own (at most `TILES²`, depth test `GL_ALWAYS` into a
/// cleared buffer) and returns the width and height of the framebuffer region the tiles cover.
pub(super) unsafe fn render_tiles(
    gl: &Gl,
    o: &Objects,
    scenes: &[Scene],
) -> Result<(usize, usize)> {
    let all: Vec<Triangle> = scenes
        .iter()
        .flat_map(|s| s.triangles.iter().copied())
        .collect();
    clear_and_upload(gl, &all);
    let mut first = 0;
    for (i, scene) in scenes.iter().enumerate().take(TILES * TILES) {
        let (x, y) = tile_origin(i);
        (gl.Viewport)(x as Int, y as Int, SIZE as Sizei, SIZE as Sizei);
        (gl.UniformMatrix4fv)(o.projection, 1, 0, scene.matrix.as_ptr());
        (gl.DrawArrays)(TRIANGLES, first, 3 * scene.triangles.len() as Sizei);
        first += 3 * scene.triangles.len() as Int;
    }
    gl.check("drawing the probe's triangles raised a GL error")?;
    let columns = scenes.len().clamp(1, TILES);
    let rows = scenes.len().div_ceil(TILES).clamp(1, TILES);
    Ok((columns * SIZE, rows * SIZE))
}

pub(super) unsafe fn read_depth(
    gl: &Gl,
    format: Format,
    y: usize,
    width: usize,
    height: usize,
) -> Result<Vec<f64>> {
    let mut raw = vec![0u32; width * height];
    let kind = match format {
        Format::Unorm(_) => UNSIGNED_INT,
        Format::Float => FLOAT,
    };
    let (w, h, ptr) = (width as Sizei, height as Sizei, raw.as_mut_ptr().cast());
    (gl.ReadPixels)(0, y as Int, w, h, DEPTH_COMPONENT, kind, ptr);
    gl.check("glReadPixels(GL_DEPTH_COMPONENT) raised a GL error")?;
    Ok(match format {
        Format::Unorm(m) => {
            let steps = 2f64.powi(m as i32) - 1.0;
            let scale = steps / (2f64.powi(32) - 1.0);
            raw.iter()
                .map(|&v| (v as f64 * scale).round() / steps)
                .collect()
        }
        Format::Float => raw.iter().map(|&v| f32::from_bits(v) as f64).collect(),
    })
}

/// A triangle's plane in window space, exactly: the homogeneous weights `a` with `Σ aᵢ·vᵢ` on
/// the ray through NDC point `(x, y)` are the cross product of the rows `Xᵢ − x·Wᵢ` and
/// `Yᵢ − y·Wᵢ`, which is affine in `(x, y)`: `a = X×Y + x·(Y×W) + y·(W×X)`. The point is inside
/// when every `aᵢ` has the sign of `Σ aᵢ·Wᵢ`, and its NDC depth is `Σ aᵢ·Zᵢ / Σ aᵢ·Wᵢ`. Valid
/// for triangles with vertices behind the camera, which a clipper cuts.
pub(super) struct Plane {
    /// `[constant, ∂/∂x, ∂/∂y]` of each `aᵢ`, of `Σ aᵢ·Wᵢ` and of `Σ aᵢ·Zᵢ`.
    pub(super) weights: [[f64; 3]; 3],
    pub(super) w: [f64; 3],
    pub(super) z: [f64; 3],
    /// NDC depth in `[0, 1]` (`glClipControl(GL_ZERO_TO_ONE)`), stored as is; else `[−1, 1]`.
    pub(super) zero_to_one: bool,
    /// The largest window depth of the vertices in front of the camera.
    pub(super) largest: f64,
}

impl Plane {
    pub(super) fn new(t: &ClipTriangle) -> Plane {
        Plane::with_mapping(t, false)
    }

    pub(super) fn with_mapping(t: &ClipTriangle, zero_to_one: bool) -> Plane {
        let column = |k: usize| [t[0][k], t[1][k], t[2][k]];
        let (x, y, z, w) = (column(0), column(1), column(2), column(3));
        let parts = [cross(x, y), cross(y, w), cross(w, x)];
        let weights = std::array::from_fn(|i| parts.map(|p| p[i]));
        let dot = |v: [f64; 3]| parts.map(|p| p[0] * v[0] + p[1] * v[1] + p[2] * v[2]);
        let largest = t
            .iter()
            .filter(|v| v[3] > 0.0)
            .map(|v| {
                let ndc = v[2] / v[3];
                if zero_to_one {
                    ndc
                } else {
                    0.5 * ndc + 0.5
                }
            })
            .fold(0.0, f64::max);
        Plane {
            weights,
            w: dot(w),
            z: dot(z),
            zero_to_one,
            largest,
        }
    }

    /// The exact window depth at window point `(x, y)`, if it lies inside the visible part of
    /// the triangle (in front of the near plane, inside the far one).
    pub(super) fn depth_at(&self, x: f64, y: f64) -> Option<f64> {
        let s = SIZE as f64;
        let (xn, yn) = (2.0 * x / s - 1.0, 2.0 * y / s - 1.0);
        let eval = |c: &[f64; 3]| c[0] + xn * c[1] + yn * c[2];
        let w = eval(&self.w);
        if w == 0.0 || self.weights.iter().any(|c| eval(c) * w <= 0.0) {
            return None;
        }
        let ndc = eval(&self.z) / w;
        let window = if self.zero_to_one {
            ndc
        } else {
            0.5 * ndc + 0.5
        };
        let lowest = if self.zero_to_one { 0.0 } else { -1.0 + 1e-6 };
        (ndc > lowest && ndc < 1.0 - 1e-6).then_some(window)
    }

    /// The window depth of the plane at tile point `(x, y)`, inside the triangle or not.
    pub(super) fn extended(&self, x: f64, y: f64) -> f64 {
        let s = SIZE as f64;
        let (xn, yn) = (2.0 * x / s - 1.0, 2.0 * y / s - 1.0);
        let eval = |c: &[f64; 3]| c[0] + xn * c[1] + yn * c[2];
        let ndc = eval(&self.z) / eval(&self.w);
        if self.zero_to_one {
            ndc
        } else {
            0.5 * ndc + 0.5
        }
    }

    /// `M(px, py) = |w₀| + |∂w/∂x|·x + |∂w/∂y|·y` for the pixels of a tile whose corner is at
    /// window `(tx, ty)`: the magnitude of the terms of the plane evaluated from the window
    /// origin (`w₀` its depth extrapolated to window `(0, 0)`, `x`, `y` window coordinates).
    pub(super) fn magnitude(&self, (tx, ty): (f64, f64)) -> impl Fn(usize, usize) -> f64 {
        let origin = self.extended(-tx, -ty);
        let gx = (self.extended(1.0 - tx, -ty) - origin).abs();
        let gy = (self.extended(-tx, 1.0 - ty) - origin).abs();
        move |px, py| origin.abs() + gx * (tx + px as f64 + 0.5) + gy * (ty + py as f64 + 0.5)
    }

    /// The exact window depth at pixel `(px, py)`'s centre, if the centre and its four
    /// neighbours one pixel away are inside: pixels on an edge, whose coverage is ambiguous, are
    /// left out.
    pub(super) fn depth_inside(&self, px: usize, py: usize) -> Option<f64> {
        let (x, y) = (px as f64 + 0.5, py as f64 + 0.5);
        let window = self.depth_at(x, y)?;
        // Each weight is affine: it keeps its sign a pixel away in x and y when its value
        // exceeds what a one-pixel step in both can change (one NDC pixel is 2/SIZE).
        let (xn, yn) = (2.0 * x / SIZE as f64 - 1.0, 2.0 * y / SIZE as f64 - 1.0);
        let step = 2.0 / SIZE as f64;
        let sign = (self.w[0] + xn * self.w[1] + yn * self.w[2]).signum();
        let margin_ok = self
            .weights
            .iter()
            .all(|c| sign * (c[0] + xn * c[1] + yn * c[2]) > step * (c[1].abs() + c[2].abs()));
        margin_ok.then_some(window)
    }
}

// ---------------------------------------------------------------------------------------------
// Scenes: triangles on eye-space planes, projected with glFrustum in f64 and rounded to f32.
// ---------------------------------------------------------------------------------------------

/// `glFrustum`'s depth row `(m10, m14)` in f64 for near `n`, far `f` under `clip`:
/// `(−(f + n)/(f − n), −2f·n/(f − n))` under `[−1, 1]`, `(−f/(f − n), −f·n/(f − n))` under
/// `[0, 1]`, `(n/(f − n), f·n/(f − n))` reversed.
pub(super) fn depth_row(n: f64, f: f64, clip: ClipDepth) -> (f64, f64) {
    match clip {
        ClipDepth::NegOneToOne => (-(f + n) / (f - n), -2.0 * f * n / (f - n)),
        ClipDepth::ZeroToOne => (-f / (f - n), -f * n / (f - n)),
        ClipDepth::ReversedZeroToOne => (n / (f - n), f * n / (f - n)),
    }
}

/// A symmetric `glFrustum(−e·n, e·n, −e·n, e·n, n, f)`.
#[derive(Clone, Copy)]
pub(super) struct View {
    pub(super) e: f64,
    pub(super) n: f64,
    pub(super) f: f64,
    /// Reversed depth for `glClipControl(GL_ZERO_TO_ONE)`: window depth `n(f − d)/((f − n)d)`.
    pub(super) reversed: bool,
    /// The vertical half-extent tangent over the horizontal one (0.5625 for 16:9).
    pub(super) squash: f64,
}

impl View {
    /// The projection matrix, each element computed in f64 and rounded to f32 as an engine
    /// passes it (`glFrustum`'s, or its reversed `[0, 1]` form).
    pub(super) fn matrix(&self) -> [f32; 16] {
        self.matrix_for(false)
    }

    /// [`View::matrix`] with `glFrustum`'s depth row in its `[0, 1]` form for
    /// `glClipControl(GL_ZERO_TO_ONE)` where `zero_to_one` (and the view is not reversed).
    /// Window depth is the same function of eye depth under both.
    pub(super) fn matrix_for(&self, zero_to_one: bool) -> [f32; 16] {
        let clip = match (self.reversed, zero_to_one) {
            (true, _) => ClipDepth::ReversedZeroToOne,
            (false, true) => ClipDepth::ZeroToOne,
            (false, false) => ClipDepth::NegOneToOne,
        };
        let (m10, m14) = depth_row(self.n, self.f, clip);
        let (sx, sy) = (1.0 / self.e, 1.0 / (self.e * self.squash));
        [
            sx, 0.0, 0.0, 0.0, 0.0, sy, 0.0, 0.0, 0.0, 0.0, m10, -1.0, 0.0, 0.0, m14, 0.0,
        ]
        .map(|m| m as f32)
    }

    /// The triangle `t` (eye space) as a vertex buffer holds it: f32 coordinates, `w = 1`.
    pub(super) fn triangle(t: [[f64; 3]; 3]) -> Triangle {
        t.map(|[x, y, z]| [x as f32, y as f32, z as f32, 1.0])
    }

    /// The eye point on the plane `z = −d − sx·x − sy·y` seen at NDC `(xn, yn)`, if it lies
    /// between the near and far planes.
    pub(super) fn on_plane(&self, xn: f64, yn: f64, d: f64, sx: f64, sy: f64) -> Option<[f64; 3]> {
        let ey = self.e * self.squash;
        let denominator = 1.0 - (self.e * sx * xn + ey * sy * yn);
        if denominator <= 0.0 {
            return None;
        }
        let z = -d / denominator;
        (-z > self.n * 1.001 && -z < self.f * 0.999).then_some([-z * xn * self.e, -z * yn * ey, z])
    }

    /// Window depth at eye distance `d` (for choosing planes by the depth they store).
    pub(super) fn distance_at_depth(&self, w: f64) -> f64 {
        let (n, f) = (self.n, self.f);
        if self.reversed {
            // w = n(f − d)/((f − n)d)  ⇒  d = f·n/(n + w(f − n))
            f * n / (n + w * (f - n))
        } else {
            // w = f(d − n)/(d(f − n))  ⇒  d = f·n/(f − w(f − n))
            f * n / (f - w * (f - n))
        }
    }
}
