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
/// 1..=12).
pub(super) unsafe fn snapping(
    gl: &Gl,
    o: &Objects,
    reported_bits: i32,
) -> Result<(Snapping, (f64, u32, f64))> {
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
        _ if residual[best] > SNAP_FIT => (Snapping::SubpixelBits(conservative), figures),
        0 => (Snapping::Unsnapped, figures),
        h => (Snapping::SubpixelBits(((h - 1) / 2) as u32), figures),
    })
}

/// `t` (with w = 1) with its window positions snapped per hypothesis `h`: 0 none; `1 + 2b` to
/// the nearest `2^-b` pixel; `2 + 2b` down to it.
pub(super) fn snap(t: &Triangle, h: usize) -> ClipTriangle {
    let (b, down) = (h.saturating_sub(1) / 2, h > 0 && (h - 1) % 2 == 1);
    let grid = 2f64.powi(b as i32);
    let s = SIZE as f64;
    t.map(|v| {
        let [x, y, z, w] = v.map(f64::from);
        let snap_ndc = |c: f64| {
            if h == 0 {
                return c;
            }
            let window = (c + 1.0) * s / 2.0 * grid;
            let window = if down { window.floor() } else { window.round() } / grid;
            window * 2.0 / s - 1.0
        };
        [snap_ndc(x), snap_ndc(y), z, w]
    })
}
