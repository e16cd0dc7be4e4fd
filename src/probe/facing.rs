//! The facing figures (`facing_quanta`, `facing_quanta_zero_to_one`, `facing_reversed`) and the
//! depth chain (`facing_chain`): the offset a facing decal over a shared-z base needs under a
//! strict test, and the one candidate f32 arithmetic that reproduces every stored depth.

use super::*;

/// A stored depth the facing measurements read, with the f32 inputs that made it.
pub(super) struct ChainObservation {
    pub(super) clip: ClipDepth,
    pub(super) bits: u32,
    pub(super) m10: f32,
    pub(super) m14: f32,
    pub(super) z: f32,
    pub(super) stored: f64,
}

/// The one candidate chain that reproduces every observation bit for bit, if any (several may
/// agree where their differences never show; the first in [`DepthChain::candidates`]' order is
/// kept, and any of them predicts every observation).
pub(super) fn identify_chain(seen: &[ChainObservation]) -> Option<DepthChain> {
    // D16 alone (its base depths only, each hundreds of steps from the next value) cannot tell
    // the candidates' arithmetic apart: the offset steps on D24 or D32F must be among them.
    if seen.iter().all(|o| o.bits == 16) {
        return None;
    }
    DepthChain::candidates().find(|chain| {
        seen.iter().all(|o| {
            chain.stored(o.bits, chain.window_depth(o.clip, o.m10, o.m14, o.z)) == o.stored
        })
    })
}

// ---------------------------------------------------------------------------------------------
// What a facing decal needs: the element-10 offset that always wins a strict depth test
// ---------------------------------------------------------------------------------------------

/// The depth conventions [`facing_quanta`] measures.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Facing {
    NegOneToOne,
    ZeroToOne,
    Reversed,
}

/// The view's matrix (`glFrustum`'s, or its reversed form), or under [`Facing::ZeroToOne`] its
/// `[0, 1]` form (`glClipControl`
/// `GL_ZERO_TO_ONE`, standard depth): `m10 = −f/(f − n)`, `m14 = −fn/(f − n)`.
pub(super) fn facing_matrix(view: &View, mode: Facing) -> [f32; 16] {
    let mut m = view.matrix();
    if mode == Facing::ZeroToOne {
        let (n, f) = (view.n, view.f);
        m[10] = (-f / (f - n)) as f32;
        m[14] = (-f * n / (f - n)) as f32;
    }
    m
}

/// The most f32 steps of element 10 the search tries (a D24 quantum is one or two).
pub(super) const FACING_MAX_STEPS: u32 = 16;

/// The window-depth offset, in quanta of `format`, that a decal facing the camera needs to pass
/// `GL_LESS` over its base when both share one f32 z and the decal's element 10 moves toward 0
/// by `k` f32 steps (the rest of the matrix unchanged, as `zshift_recommend_matrix` draws it):
/// for each of 256 depths (window depth 0.02 to 0.9995, two frusta, a tile quadrant each), the smallest
/// `k` whose stored depth is below the base's, its exact window offset `k·ulp(m10)/2` over the
/// quantum (D32F: over 2⁻²⁴); the largest over the depths. Each depth has its own phase between two stored
/// values, so the largest is what the worst phase needs. `None` (not measured) on D16, whose
/// quantum is hundreds of steps (its `q + 2T` is within a few percent of `q` anyway), or if some
/// depth needs more than [`FACING_MAX_STEPS`].
/// With [`Facing::ZeroToOne`] the same under `glClipControl(GL_ZERO_TO_ONE)` (set by the caller) with
/// the `[0, 1]` matrix (`m10 = −f/(f − n)`, `m14 = −fn/(f − n)`), where a step of element 10
/// moves window depth by a whole `ulp(m10)`.
///
/// With [`Facing::Reversed`] (D32F only): reversed depth under `GL_ZERO_TO_ONE`, element 14
/// moved away from 0 by `k` steps (the relative offset of `zshift_recommend_clip`), `GL_GREATER`,
/// 256 window depths from 10⁻⁵ to 0.9 spaced by ratio; the figure is the relative ε
/// `k·ulp(m14)/m14` in units of 2⁻²⁴.
pub(super) unsafe fn facing_quanta(
    gl: &Gl,
    o: &Objects,
    format: Format,
    mode: Facing,
    seen: &mut Vec<ChainObservation>,
) -> Result<Option<f64>> {
    let reversed = mode == Facing::Reversed;
    if reversed && format != Format::Float {
        return Ok(None);
    }
    let views = [
        View {
            e: 0.5,
            n: 0.1,
            f: 1e3,
            reversed,
            squash: 1.0,
        },
        View {
            e: 0.6,
            n: 1.0,
            f: 1e6,
            reversed,
            squash: 0.5625,
        },
    ];
    // Four planes per tile, one per quadrant (the tile's matrix is its view's): 128 depths per
    // view for the cost of 32 tiles.
    let per_view = TILES * TILES / 2;
    let planes: Vec<(View, f64)> = views
        .iter()
        .flat_map(|&v| {
            let count = 4 * per_view;
            (0..count).map(move |i| {
                let x = i as f64 / (count - 1) as f64;
                let w = if reversed {
                    1e-5 * (0.9f64 / 1e-5).powf(x)
                } else {
                    0.02 + (0.9995 - 0.02) * x
                };
                (v, w)
            })
        })
        .collect();
    const QUADRANTS: [(f64, f64); 4] = [(-0.5, -0.5), (0.5, -0.5), (-0.5, 0.5), (0.5, 0.5)];
    let scenes = |k: u32| -> Vec<Scene> {
        planes
            .chunks(4)
            .map(|four| {
                let view = four[0].0;
                let ey = view.e * view.squash;
                let mut triangles = Vec::new();
                for (&(_, w), (cx, cy)) in four.iter().zip(QUADRANTS) {
                    let d = view.distance_at_depth(w);
                    let at = |xn: f64, yn: f64| [(cx + xn) * view.e * d, (cy + yn) * ey * d, -d];
                    let (a, b, c, e) = (
                        at(-0.45, -0.45),
                        at(0.45, -0.45),
                        at(0.45, 0.45),
                        at(-0.45, 0.45),
                    );
                    triangles.push(View::triangle([a, b, c]));
                    triangles.push(View::triangle([a, c, e]));
                }
                let mut matrix = facing_matrix(&view, mode);
                if reversed {
                    matrix[14] = f32::from_bits(matrix[14].to_bits() + k); // m14 > 0: away from 0
                } else {
                    matrix[10] = f32::from_bits(matrix[10].to_bits() - k); // m10 < 0: toward 0
                }
                Scene { matrix, triangles }
            })
            .collect()
    };
    // The stored depth at each quadrant's centre, plane by plane: only the two rows of pixels
    // through the centres of each row of tiles are read back (a 32nd of the tiles).
    let centre = |c: f64| ((c + 1.0) * 0.5 * SIZE as f64) as usize;
    let draw_and_read = |k: u32| -> Result<Vec<f64>> {
        let scenes = scenes(k);
        let (width, height) = render_tiles(gl, o, &scenes)?;
        let mut rows = Vec::new();
        for tile_row in 0..height / SIZE {
            let lower = read_depth(gl, format, tile_row * SIZE + centre(-0.5), width, 1)?;
            let upper = read_depth(gl, format, tile_row * SIZE + centre(0.5), width, 1)?;
            rows.push((lower, upper));
        }
        Ok((0..scenes.len())
            .flat_map(|i| {
                let (lower, upper) = &rows[i / TILES];
                let x = (i % TILES) * SIZE;
                QUADRANTS.map(|(cx, cy)| {
                    let row = if cy < 0.0 { lower } else { upper };
                    row[x + centre(cx)]
                })
            })
            .collect())
    };
    // Every stored value read, with the f32 inputs that made it, for identifying the chain.
    let clip = match mode {
        Facing::NegOneToOne => ClipDepth::NegOneToOne,
        Facing::ZeroToOne => ClipDepth::ZeroToOne,
        Facing::Reversed => ClipDepth::ReversedZeroToOne,
    };
    let mut record = |k: u32, values: &[f64]| {
        for (&(view, w), &value) in planes.iter().zip(values) {
            let m = facing_matrix(&view, mode);
            let Some((m10, m14)) = crate::depth_chain::stepped((m[10], m[14]), reversed, k) else {
                continue;
            };
            seen.push(ChainObservation {
                clip,
                bits: format.bits(),
                m10,
                m14,
                z: -(view.distance_at_depth(w) as f32),
                stored: format.integer(value),
            });
        }
    };
    let base = draw_and_read(0)?;
    record(0, &base);
    if format == Format::Unorm(16) {
        // One D16 quantum is hundreds of steps: only the chain's conversion is checked here.
        return Ok(None);
    }
    let mut needed = vec![None; planes.len()];
    for k in 1..=FACING_MAX_STEPS {
        let decal = draw_and_read(k)?;
        record(k, &decal);
        for (i, d) in decal.iter().enumerate() {
            let wins = if reversed { *d > base[i] } else { *d < base[i] };
            if needed[i].is_none() && wins {
                needed[i] = Some(k);
            }
        }
        if needed.iter().all(Option::is_some) {
            break;
        }
    }
    let mut worst = 0.0f64;
    for (&(view, w), k) in planes.iter().zip(&needed) {
        let Some(k) = k else { return Ok(None) };
        let m = facing_matrix(&view, mode);
        if reversed {
            let m14 = f64::from(m[14]);
            let step = f64::from(f32::from_bits(m[14].to_bits() + 1)) - m14;
            worst = worst.max(f64::from(*k) * step / m14 / F32_UNIT_ROUNDOFF);
            continue;
        }
        let step = f64::from(m[10]).abs() - f64::from(f32::from_bits(m[10].to_bits() - 1)).abs();
        // Window depth moves by the NDC change, halved under [−1, 1].
        let ulp = if mode == Facing::ZeroToOne {
            2.0 * step
        } else {
            step
        };
        // D32F in units of 2⁻²⁴ (the offset is a constant window depth), as `plane_error`.
        let unit = match format {
            Format::Float => F32_UNIT_ROUNDOFF,
            _ => format.quantum(w),
        };
        worst = worst.max(f64::from(*k) * ulp / 2.0 / unit);
    }
    Ok(Some(worst))
}
