//! Lines over their faces: where a line fragment takes its depth (`line_reach`) and the
//! polygon-offset slope rule (`offset_slope`).

use super::*;

/// The window-depth gradient per pixel (along the steeper axis) of the planes the line
/// measurement draws in: steep enough that D32F's spacing (≈ 6·10⁻⁸ at 0.5) is 1.5·10⁻⁵ pixel.
pub(super) const LINE_GRADIENT: f64 = 1.0 / 256.0;

/// Tiles per line kind (`GL_LINES`, polygon-mode lines), each with its own plane.
pub(super) const LINE_TILES: usize = 16;

/// What [`line_reach`] measured.
pub(super) struct LineFigures {
    /// The largest `|stored − plane at the pixel centre| / max(|gₓ|, |g_y|)` per kind
    /// (`GL_LINES` width 1, polygon-mode lines width 1), pixels.
    pub(super) reach: [f64; 2],
    /// Fragments compared per kind.
    pub(super) pixels: [usize; 2],
    /// How far a polygon-mode outline takes its depth off its side's line, onto the
    /// neighbouring face: the largest `|stored − side's depth| / max(|gₓ|, |g_y|)` over outline
    /// fragments beyond a side of constant depth, outside its triangle (the neighbour's side),
    /// `gₓ`, `g_y` the triangle's gradients, pixels. Near 0 (f32 noise) where the outline's
    /// depth follows its line, as Mesa's draw module does; up to the fragment's distance from
    /// the side (in `max` units) where the rasterizer evaluates the triangle's plane. NaN where
    /// no outline fragment landed beyond a side.
    pub(super) neighbour: f64,
    /// Fragments compared for `neighbour`.
    pub(super) neighbour_pixels: usize,
    /// `glPolygonOffset(1, 0)`'s offset on a plane with `|gₓ| = |g_y| = g`, over `g`
    /// (1: `max(|gₓ|, |g_y|)`; `√2`: their root sum of squares), and the same on a plane with
    /// `g_y = 0` (1 under either rule: the factor's scale).
    pub(super) slope: [f64; 2],
}

/// Tile `k`'s plane of `tiles` (one per gradient direction), window depth
/// `0.5 + gₓ·(x − 32) + g_y·(y − 32)` in tile pixels.
pub(super) fn tile_plane(k: usize, tiles: usize) -> (f64, f64) {
    // Gradient directions spread over the circle, the larger component always LINE_GRADIENT.
    let theta = std::f64::consts::PI * (2 * k + 1) as f64 / (tiles as f64);
    let (c, s) = (theta.cos(), theta.sin());
    let big = c.abs().max(s.abs());
    (LINE_GRADIENT * c / big, LINE_GRADIENT * s / big)
}

/// What [`reach_in_tiles`] measured, per kind (`GL_LINES`, polygon-mode).
pub(super) struct TileReach {
    /// The largest `|stored − plane at the sample| / max(|gₓ|, |g_y|)`, pixels.
    pub(super) reach: [f64; 2],
    /// The largest `|stored − plane at the sample| / |∇z|` (the plane's whole gradient),
    /// pixels: how far from its sample a fragment's depth is taken, in any direction.
    pub(super) whole: [f64; 2],
    /// Fragments (samples) compared.
    pub(super) samples: [usize; 2],
}

impl TileReach {
    /// Nothing measured: NaN figures (the model keeps the worst case), no samples.
    pub(super) fn unmeasured() -> Self {
        Self {
            reach: [f64::NAN; 2],
            whole: [f64::NAN; 2],
            samples: [0; 2],
        }
    }

    /// The larger figures of `self` and `other` (NaN until measured: `f64::max` keeps the
    /// number), and the samples of both.
    pub(super) fn merge(&mut self, other: &TileReach) {
        for kind in 0..2 {
            self.reach[kind] = self.reach[kind].max(other.reach[kind]);
            self.whole[kind] = self.whole[kind].max(other.whole[kind]);
            self.samples[kind] += other.samples[kind];
        }
    }
}

/// The reach over every sample a line (tiles `0..tiles`) or outline (tiles `tiles..2·tiles`,
/// each on [`tile_plane`]`(k, tiles)`) wrote (stored below 0.99; cleared to 1): `depth` holds
/// one `width × rows` image per sample position (pixel offsets; `[0.5, 0.5]` for a
/// single-sampled pixel centre).
pub(super) fn reach_in_tiles(
    depth: &[f64],
    positions: &[[f64; 2]],
    (width, rows): (usize, usize),
    tiles: usize,
) -> TileReach {
    let mut out = TileReach {
        reach: [0.0; 2],
        whole: [0.0; 2],
        samples: [0; 2],
    };
    let half = SIZE as f64 / 2.0;
    for (image, [sx, sy]) in depth.chunks_exact(width * rows).zip(positions) {
        for tile in 0..2 * tiles {
            let kind = tile / tiles;
            let (gx, gy) = tile_plane(tile % tiles, tiles);
            let norm = gx.hypot(gy);
            let (ox, oy) = tile_origin(tile);
            for py in 0..SIZE {
                for px in 0..SIZE {
                    let stored = image[(oy + py) * width + ox + px];
                    if stored >= 0.99 {
                        continue;
                    }
                    let (x, y) = (px as f64 + sx - half, py as f64 + sy - half);
                    let off = (stored - (0.5 + gx * x + gy * y)).abs();
                    out.reach[kind] = out.reach[kind].max(off / LINE_GRADIENT);
                    out.whole[kind] = out.whole[kind].max(off / norm);
                    out.samples[kind] += 1;
                }
            }
        }
    }
    out
}

/// The vertex of tile pixel coordinates `(x, y)` on plane `(gₓ, g_y)`: clip coordinates with
/// `w = 1` (drawn with [`IDENTITY`] into a `SIZE`-pixel tile), `[−1, 1]` depth.
pub(super) fn tile_vertex(x: f64, y: f64, (gx, gy): (f64, f64)) -> [f32; 4] {
    let half = SIZE as f64 / 2.0;
    let z = 0.5 + gx * (x - half) + gy * (y - half);
    [
        (x / half - 1.0) as f32,
        (y / half - 1.0) as f32,
        (2.0 * z - 1.0) as f32,
        1.0,
    ]
}

/// Each tile's vertices (clip coordinates, as [`tile_vertex`] makes them), tile by tile.
pub(super) type Tiles = Vec<Vec<[f32; 4]>>;

/// A segment's two vertices on `plane`: centred at `(cx, cy)` (tile pixels), `half` pixels
/// each way in direction `phi`.
pub(super) fn segment(
    (cx, cy): (f64, f64),
    half: f64,
    phi: f64,
    plane: (f64, f64),
) -> [[f32; 4]; 2] {
    let (dx, dy) = (half * phi.cos(), half * phi.sin());
    [
        tile_vertex(cx - dx, cy - dy, plane),
        tile_vertex(cx + dx, cy + dy, plane),
    ]
}

/// The probe's small deterministic generator (xorshift64): sub-pixel endpoints in every
/// direction, the same on every run.
pub(super) fn xorshift() -> impl FnMut() -> f64 {
    let mut seed = 0x9E37_79B9_7F4A_7C15u64;
    move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The line tiles' geometry, tile `k` on plane [`tile_plane`]`(k, LINE_TILES)`: six `GL_LINES` segments
/// in six directions (each tile turned a little further), and three triangles for polygon-mode
/// outlines, all with sub-pixel corners from `next`.
fn line_tiles(next: &mut impl FnMut() -> f64) -> (Tiles, Tiles) {
    let mut lines = Vec::new();
    let mut polygons = Vec::new();
    for k in 0..LINE_TILES {
        let plane = tile_plane(k, LINE_TILES);
        let mut segments = Vec::new();
        for j in 0..6 {
            let phi = std::f64::consts::PI * (j as f64 + k as f64 / LINE_TILES as f64) / 6.0;
            let centre = (32.0 + 16.0 * (next() - 0.5), 32.0 + 16.0 * (next() - 0.5));
            segments.extend(segment(centre, 18.0 + 8.0 * next(), phi, plane));
        }
        lines.push(segments);
        let mut triangles = Vec::new();
        for _ in 0..3 {
            for _ in 0..3 {
                triangles.push(tile_vertex(4.0 + 56.0 * next(), 4.0 + 56.0 * next(), plane));
            }
        }
        polygons.push(triangles);
    }
    (lines, polygons)
}

/// Measures how far from the pixel a line fragment's depth is taken, per line kind, and
/// `glPolygonOffset`'s slope rule (module docs). Needs D32F attached.
pub(super) unsafe fn line_reach(gl: &Gl, o: &Objects) -> Result<LineFigures> {
    // A small deterministic generator: sub-pixel endpoints in every direction.
    let mut next = xorshift();
    let (lines, polygons) = line_tiles(&mut next);
    // Slope rule: a filled tile on a diagonal plane and on an axis plane, plain and offset.
    let diagonal = (LINE_GRADIENT, LINE_GRADIENT);
    let axis = (LINE_GRADIENT, 0.0);
    let quad = |plane| {
        let c = [(1.0, 1.0), (63.0, 1.0), (63.0, 63.0), (1.0, 63.0)]
            .map(|(x, y)| tile_vertex(x, y, plane));
        vec![c[0], c[1], c[2], c[0], c[2], c[3]]
    };
    let slope_tiles = [quad(diagonal), quad(axis)];
    let sides: Vec<OutlineSide> = (0..LINE_TILES)
        .map(|k| outline_side(k, &mut next))
        .collect();

    let mut all: Vec<[f32; 4]> = Vec::new();
    let mut draws: Vec<(usize, Enum, usize, usize, bool)> = Vec::new(); // tile, mode, first, count, offset
    let mut push = |tile: usize, mode: Enum, vertices: &[[f32; 4]], offset: bool| {
        draws.push((tile, mode, all.len(), vertices.len(), offset));
        all.extend_from_slice(vertices);
    };
    for (k, v) in lines.iter().enumerate() {
        push(k, LINES, v, false);
    }
    for (k, v) in polygons.iter().enumerate() {
        push(LINE_TILES + k, TRIANGLES, v, false);
    }
    for (k, v) in slope_tiles.iter().enumerate() {
        push(2 * LINE_TILES + 2 * k, TRIANGLES, v, false);
        push(2 * LINE_TILES + 2 * k + 1, TRIANGLES, v, true);
    }
    for (k, side) in sides.iter().enumerate() {
        push(NEIGHBOUR_TILE + k, TRIANGLES, &side.triangle, false);
    }
    clear_and_upload(gl, &all);
    (gl.UniformMatrix4fv)(o.projection, 1, 0, IDENTITY.as_ptr());
    for &(tile, mode, first, count, offset) in &draws {
        let (x, y) = tile_origin(tile);
        (gl.Viewport)(x as Int, y as Int, SIZE as Sizei, SIZE as Sizei);
        let polygon_lines = (LINE_TILES..2 * LINE_TILES).contains(&tile) || tile >= NEIGHBOUR_TILE;
        if polygon_lines {
            (gl.PolygonMode)(FRONT_AND_BACK, LINE);
        }
        if offset {
            (gl.Enable)(POLYGON_OFFSET_FILL);
            (gl.PolygonOffset)(1.0, 0.0);
        }
        (gl.DrawArrays)(mode, first as Int, count as Sizei);
        (gl.PolygonMode)(FRONT_AND_BACK, FILL);
        (gl.Disable)(POLYGON_OFFSET_FILL);
        (gl.PolygonOffset)(0.0, 0.0);
    }
    gl.check("drawing the probe's lines raised a GL error")?;
    let width = SIZE * TILES;
    let rows = (NEIGHBOUR_TILE + LINE_TILES).div_ceil(TILES);
    let depth = read_depth(gl, Format::Float, 0, width, rows * SIZE)?;
    let at = |tile: usize, px: usize, py: usize| {
        let (x, y) = tile_origin(tile);
        depth[(y + py) * width + x + px]
    };
    let TileReach {
        reach,
        samples: pixels,
        ..
    } = reach_in_tiles(&depth, &[[0.5, 0.5]], (width, rows * SIZE), LINE_TILES);
    let (mut neighbour, mut neighbour_pixels) = (0.0f64, 0usize);
    for (k, side) in sides.iter().enumerate() {
        for py in 0..SIZE {
            for px in 0..SIZE {
                let stored = at(NEIGHBOUR_TILE + k, px, py);
                if stored >= 0.99 {
                    continue;
                }
                if let Some(depth) = side.depth_beyond(px as f64 + 0.5, py as f64 + 0.5) {
                    neighbour = neighbour.max((stored - depth).abs() / LINE_GRADIENT);
                    neighbour_pixels += 1;
                }
            }
        }
    }
    let mut slope = [0.0; 2];
    for (k, s) in slope.iter_mut().enumerate() {
        let (plain, offset) = (2 * LINE_TILES + 2 * k, 2 * LINE_TILES + 2 * k + 1);
        let (mut sum, mut count) = (0.0, 0usize);
        for py in 4..SIZE - 4 {
            for px in 4..SIZE - 4 {
                sum += at(offset, px, py) - at(plain, px, py);
                count += 1;
            }
        }
        *s = sum / count as f64 / LINE_GRADIENT;
    }
    if neighbour_pixels == 0 {
        // No outline fragment beyond a side: nothing measured, the model keeps the worst case.
        neighbour = f64::NAN;
    }
    if pixels.contains(&0) {
        return Err(Error::new(
            ErrorKind::Gl,
            "the probe's lines drew no fragment (GL_LINES or glPolygonMode(GL_LINE))",
        ));
    }
    Ok(LineFigures {
        reach,
        pixels,
        neighbour,
        neighbour_pixels,
        slope,
    })
}

/// The first tile of the outline-neighbour measurement (after the lines', the polygon-mode
/// lines' and the four slope-rule tiles).
const NEIGHBOUR_TILE: usize = 2 * LINE_TILES + 4;

/// Half the length of an [`OutlineSide`]'s long side, tile pixels.
const SIDE_HALF: f64 = 24.0;

/// A triangle for the outline-neighbour measurement: one long side of constant window depth
/// through the tile, the third corner 20 pixels to one side, the plane's gradient across the
/// side with its larger component [`LINE_GRADIENT`].
struct OutlineSide {
    /// The triangle's corners (clip coordinates, as [`tile_vertex`]).
    triangle: [[f32; 4]; 3],
    /// The side's midpoint, tile pixels.
    centre: (f64, f64),
    /// The side's unit direction.
    along: (f64, f64),
    /// The unit normal pointing away from the third corner (the neighbour's side).
    outward: (f64, f64),
    /// The side's window depth.
    depth: f64,
}

/// Tile `k`'s [`OutlineSide`]: directions spread over the half circle, the third corner on
/// alternate sides, the midpoint jittered by `next`.
fn outline_side(k: usize, next: &mut impl FnMut() -> f64) -> OutlineSide {
    let phi = std::f64::consts::PI * (k as f64 + next()) / LINE_TILES as f64;
    let along = (phi.cos(), phi.sin());
    let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
    let inward = (-along.1 * sign, along.0 * sign);
    let centre = (32.0 + 8.0 * (next() - 0.5), 32.0 + 8.0 * (next() - 0.5));
    // Depth rises into the triangle across the side: gradient `s·inward`, max component g.
    let s = LINE_GRADIENT / inward.0.abs().max(inward.1.abs());
    let plane = (s * inward.0, s * inward.1);
    let corners = [
        (
            centre.0 - SIDE_HALF * along.0,
            centre.1 - SIDE_HALF * along.1,
        ),
        (
            centre.0 + SIDE_HALF * along.0,
            centre.1 + SIDE_HALF * along.1,
        ),
        (centre.0 + 20.0 * inward.0, centre.1 + 20.0 * inward.1),
    ];
    let triangle = corners.map(|(x, y)| tile_vertex(x, y, plane));
    let depth = 0.5 + plane.0 * (centre.0 - 32.0) + plane.1 * (centre.1 - 32.0);
    OutlineSide {
        triangle,
        centre,
        along,
        outward: (-inward.0, -inward.1),
        depth,
    }
}

impl OutlineSide {
    /// The side's depth, for a pixel centre `(x, y)` beyond the side (outside the triangle, up to
    /// 4 pixels) along its middle 60 %, where no other side of the triangle reaches; else `None`.
    fn depth_beyond(&self, x: f64, y: f64) -> Option<f64> {
        let (dx, dy) = (x - self.centre.0, y - self.centre.1);
        let t = dx * self.along.0 + dy * self.along.1;
        let out = dx * self.outward.0 + dy * self.outward.1;
        (t.abs() <= 0.6 * SIDE_HALF && out > 0.0 && out < 4.0).then_some(self.depth)
    }
}
