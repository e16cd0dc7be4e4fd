//! Sub-pixel snapping (the model's `S`, [`crate::model::snap`]): whether the rasterizer sets
//! depth up from snapped window positions, and at how many bits.

use super::*;

/// The finest snapping the probe tells from none: `2^-(12+1)` pixel moves the test triangle's
/// depth by 1.7·10⁻⁶, 17× the f32 noise of its depth (≈ 10⁻⁷); finer grids move it by less
/// than the noise, and their term in the model is as small (they read as unsnapped).
pub(super) const MAX_SNAP_BITS: u32 = 12;

/// The largest residual (window depth) a snapping hypothesis may leave and still be believed:
/// 10× the f32 noise of the test triangles' depth, below the shift of any `b ≤ 12`.
pub(super) const SNAP_FIT: f64 = 1e-6;

/// Which snapping hypothesis the stored depth of steep triangles fits best (module docs). When
/// none fits to [`SNAP_FIT`] the rasterizer does something the hypotheses do not describe, and
/// the answer is the conservative `GL_SUBPIXEL_BITS` it reports (8 if it reports none in
/// 1..=12). Also the hypothesis believed ([`snap`]'s `h`; 0, none, when none fits), for the
/// plane-error reference.
pub(super) unsafe fn snapping(
    gl: &Gl,
    o: &Objects,
    reported_bits: i32,
) -> Result<(Snapping, (f64, u32, f64), usize)> {
    // Window positions with assorted sub-pixel parts; depth grows with x only.
    let sets: [[[f64; 2]; 3]; 2] = [
        [[6.3071, 5.1187], [58.6523, 9.4402], [11.8816, 59.7311]],
        [[4.5939, 7.8023], [60.1252, 3.2765], [33.3388, 61.0909]],
    ];
    let s = SIZE as f64;
    let mut residual = [0.0f64; 2 * (MAX_SNAP_BITS as usize + 1) + 1]; // none, (nearest, down) × b
    for set in sets {
        let t: Triangle = set.map(|[x, y]| {
            let z = 0.9 * (2.0 * x / s - 1.0);
            [
                (2.0 * x / s - 1.0) as f32,
                (2.0 * y / s - 1.0) as f32,
                z as f32,
                1.0,
            ]
        });
        let scene = Scene::clip(vec![t]);
        let stored = draw(gl, o, Format::Float, &scene)?;
        let plane = Plane::new(&scene.exact()[0]);
        let inside: Vec<(usize, usize)> = (0..SIZE * SIZE)
            .map(|i| (i % SIZE, i / SIZE))
            .filter(|&(px, py)| plane.depth_inside(px, py).is_some())
            .collect();
        let t = t.map(|v| v.map(f64::from));
        for (h, slot) in residual.iter_mut().enumerate() {
            let snapped = Plane::new(&snap(&t, h));
            for &(px, py) in &inside {
                let Some(predicted) = snapped.depth_at(px as f64 + 0.5, py as f64 + 0.5) else {
                    continue;
                };
                *slot = slot.max((stored[py * SIZE + px] - predicted).abs());
            }
        }
    }
    let best = (0..residual.len())
        .min_by(|&a, &b| residual[a].total_cmp(&residual[b]))
        .unwrap_or(0);
    let snapped = (1..residual.len())
        .min_by(|&a, &b| residual[a].total_cmp(&residual[b]))
        .unwrap_or(1);
    let figures = (residual[0], ((snapped - 1) / 2) as u32, residual[snapped]);
    let conservative = match reported_bits {
        b @ 1..=12 => b as u32,
        _ => 8,
    };
    Ok(match best {
        _ if residual[best] > SNAP_FIT => (Snapping::SubpixelBits(conservative), figures, 0),
        0 => (Snapping::Unsnapped, figures, 0),
        h => (Snapping::SubpixelBits(((h - 1) / 2) as u32), figures, h),
    })
}

/// `t`'s clip coordinates with each vertex's window position in a tile snapped per hypothesis
/// `h`: 0 none; `1 + 2b` to the nearest `2^-b` pixel; `2 + 2b` down to it. Tiles start at whole
/// pixels, so a tile's grid is the framebuffer's. Every vertex must lie in front of the camera
/// (`w > 0`): the plane a snapping rasterizer sets its depth up from.
pub(super) fn snap(t: &ClipTriangle, h: usize) -> ClipTriangle {
    if h == 0 {
        return *t;
    }
    let (b, down) = ((h - 1) / 2, (h - 1) % 2 == 1);
    let grid = 2f64.powi(b as i32);
    let half = SIZE as f64 / 2.0;
    t.map(|[x, y, z, w]| {
        let snap_clip = |c: f64| {
            let window = (c / w + 1.0) * half * grid;
            let window = if down { window.floor() } else { window.round() } / grid;
            (window / half - 1.0) * w
        };
        [snap_clip(x), snap_clip(y), z, w]
    })
}
