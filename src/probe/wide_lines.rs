//! Wide lines over their faces: where a 3-pixel line fragment takes its depth
//! (`line_reach_wide`).
//!
//! A rasterizer draws a wide line with a set-up of its own (Mesa's draw module: a quad moved
//! `w/2 + 1/8` across and half a pixel along, [`crate::lines`]), not the 1-pixel one
//! [`super::lines`] measures. The probe draws the dense geometry ([`dense_tiles`]) at
//! `glLineWidth(3)` into its D32F renderbuffer and compares every fragment with its tile's plane
//! at the pixel centre. A context that refuses the width (a forward-compatible core profile
//! allows only 1) or draws narrower lines leaves it unmeasured.

use super::*;
use crate::profile::WIDE_LINE_WIDTH as WIDE;

/// Primitives drawn per tile: a wide line's reach is set by its quad, not by how a sample
/// pattern lines up, and levels off sooner than the multisampled one, at a tenth of the time.
/// On llvmpipe the figure is 1.5005–1.5016 at 4, 8, 16 and 64 per tile.
pub(super) const WIDE_PER_TILE: usize = 16;

/// Measures the reach of [`WIDE`]-pixel lines per kind (module docs): the largest
/// `|stored − plane at the pixel centre| / max(|gₓ|, |g_y|)` per kind (`GL_LINES`, polygon-mode
/// lines), pixels, and the fragments compared; [`TileReach::unmeasured`] where the context does
/// not draw the width. Needs D32F attached.
pub(super) unsafe fn wide_line_reach(gl: &Gl, o: &Objects) -> Result<TileReach> {
    let figures = TileReach::unmeasured();
    if !set_wide(gl)? {
        return Ok(figures);
    }
    let side = (SIZE * TILES) as Sizei;
    let drawn = draw_dense(gl, o, side, DENSE_ROWS as Sizei, WIDE_PER_TILE);
    (gl.LineWidth)(1.0);
    drawn?;
    let depth = read_depth(gl, Format::Float, 0, side as usize, DENSE_ROWS)?;
    let measured = reach_in_tiles(
        &depth,
        &[[0.5, 0.5]],
        (side as usize, DENSE_ROWS),
        DENSE_TILES,
    );
    Ok(if measured.samples.iter().all(|&n| n > 0) {
        measured
    } else {
        figures
    })
}

/// Sets `glLineWidth(`[`WIDE`]`)`; `false` (and the width left at 1) where the context draws no
/// line that wide or refuses the width (a forward-compatible core context allows only 1: not
/// measured).
pub(super) unsafe fn set_wide(gl: &Gl) -> Result<bool> {
    let mut range = [0.0f32; 2];
    (gl.GetFloatv)(ALIASED_LINE_WIDTH_RANGE, range.as_mut_ptr());
    gl.check("glGetFloatv(GL_ALIASED_LINE_WIDTH_RANGE) raised a GL error")?;
    if range[1] < WIDE {
        return Ok(false);
    }
    (gl.LineWidth)(WIDE);
    Ok(!gl.failed())
}
