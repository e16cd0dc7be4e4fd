//! The dense line geometry the multisampled and the wide-line measurements draw: lines and
//! polygon-mode outlines in 32 gradient directions, 64 per tile (read back with
//! [`reach_in_tiles`]).

use super::*;

/// Tiles per line kind, each with its own plane: twice the single-sampled 1-pixel
/// measurement's gradient directions, since a multisampled sample's (and a wide line's) reach
/// depends on how the line, the gradient and the sample pattern line up.
pub(super) const DENSE_TILES: usize = 32;

/// The rows of tiles the dense geometry fills, pixels: both kinds' tiles.
pub(super) const DENSE_ROWS: usize = (2 * DENSE_TILES).div_ceil(TILES) * SIZE;

/// Lines per `GL_LINES` tile and triangles per polygon-mode tile (overlapping: a later one
/// overwrites an earlier one's samples, all on one plane). On llvmpipe the reach grows with the
/// count and levels off: 1.045 at 16 per tile, 1.0556 at 32, 1.0559 at 64 (6 lines per tile in
/// 16 tiles, as the single-sampled measurement draws, found 0.998).
pub(super) const PER_TILE: usize = 64;

/// The dense geometry: per tile [`PER_TILE`] segments 12–20 pixels long
/// in directions spread over the half circle (each tile turned a little further), and as many
/// triangles for polygon-mode outlines, corners at sub-pixel positions.
pub(super) fn dense_tiles() -> (Tiles, Tiles) {
    let mut next = xorshift();
    let mut lines = Vec::new();
    let mut polygons = Vec::new();
    for k in 0..DENSE_TILES {
        let plane = tile_plane(k, DENSE_TILES);
        let mut segments = Vec::new();
        for j in 0..PER_TILE {
            let turn = (j as f64 + k as f64 / DENSE_TILES as f64) / PER_TILE as f64;
            let phi = std::f64::consts::PI * turn;
            let centre = (32.0 + 24.0 * (next() - 0.5), 32.0 + 24.0 * (next() - 0.5));
            segments.extend(segment(centre, 6.0 + 4.0 * next(), phi, plane));
        }
        lines.push(segments);
        let mut triangles = Vec::new();
        for _ in 0..PER_TILE {
            let (cx, cy) = (12.0 + 40.0 * next(), 12.0 + 40.0 * next());
            for _ in 0..3 {
                triangles.push(tile_vertex(
                    cx + 20.0 * (next() - 0.5),
                    cy + 20.0 * (next() - 0.5),
                    plane,
                ));
            }
        }
        polygons.push(triangles);
    }
    (lines, polygons)
}

/// Draws [`dense_tiles`] (the `GL_LINES` tiles, then the polygon-mode ones), depth test
/// `GL_ALWAYS`, into the bound framebuffer cleared to 1, with the line width and multisampling
/// the caller set; only the first `per_tile` primitives of each tile (at most [`PER_TILE`]).
pub(super) unsafe fn draw_dense(
    gl: &Gl,
    o: &Objects,
    side: Sizei,
    rows: Sizei,
    per_tile: usize,
) -> Result<()> {
    let (lines, polygons) = dense_tiles();
    let mut all: Vec<[f32; 4]> = Vec::new();
    let mut draws = Vec::new(); // (tile, first, count)
    for (k, v) in lines.iter().chain(&polygons).enumerate() {
        draws.push((k, all.len(), v.len()));
        all.extend_from_slice(v);
    }
    (gl.Viewport)(0, 0, side, rows);
    (gl.ClearDepth)(1.0);
    (gl.Clear)(DEPTH_BUFFER_BIT);
    (gl.BindBuffer)(ARRAY_BUFFER, o.buffer);
    let bytes = std::mem::size_of_val(all.as_slice()) as isize;
    (gl.BufferData)(ARRAY_BUFFER, bytes, all.as_ptr().cast(), STREAM_DRAW);
    (gl.UseProgram)(o.program);
    (gl.UniformMatrix4fv)(o.projection, 1, 0, IDENTITY.as_ptr());
    for (tile, first, count) in draws {
        let (x, y) = tile_origin(tile);
        (gl.Viewport)(x as Int, y as Int, SIZE as Sizei, SIZE as Sizei);
        let outline = tile >= DENSE_TILES;
        if outline {
            (gl.PolygonMode)(FRONT_AND_BACK, LINE);
        }
        let (mode, vertices) = if outline { (TRIANGLES, 3) } else { (LINES, 2) };
        let count = count.min(vertices * per_tile);
        (gl.DrawArrays)(mode, first as Int, count as Sizei);
        (gl.PolygonMode)(FRONT_AND_BACK, FILL);
    }
    gl.check("drawing the probe's dense lines raised a GL error")
}
