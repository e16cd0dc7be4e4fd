//! The scenes the tests draw: the grid of cases ([`cases`]), seeded draws off its values
//! ([`seed`], [`vary`], [`rescale`]), samples per pixel ([`samples`]), and one case in `n`
//! ([`every`]).

use super::*;

/// `ZSHIFT_ENGINE_SCENES_SEED=<n>`: another draw of the sweep (0, the default, is the one CI
/// runs): the same classes, other picks, and values between the grid's — decal size and
/// distance, pitch, heading, translation — with the ground's world height as far from the origin
/// as the translation (up, down, or 0).
pub(crate) fn seed() -> u64 {
    zshift_harness::draw::seed("ZSHIFT_ENGINE_SCENES_SEED")
}

/// Moves a case off the grid's values (`ZSHIFT_ENGINE_SCENES_SEED`, [`seed`]).
pub(crate) fn vary(mut case: Case, v: &mut Xorshift) -> Case {
    case.size = (case.size * (0.8 + 0.45 * v.unit())).clamp(0.5, 4.0);
    case.distance *= 0.8 + 0.45 * v.unit();
    case.pitch_deg *= 1.0 + 0.08 * v.unit();
    case.yaw_deg = 360.0 * v.unit();
    case.translate *= 1.0 + 0.9 * v.unit();
    let height = [0.0, 1.0, -1.0][v.index(3)] * case.translate + 10.0 * v.unit();
    case.ground_y = f64::from(height as f32);
    case.fovy_deg = 40.0 + 60.0 * v.unit();
    case
}

/// Another scale of the world, another camera height and an off-centre frustum
/// ([`Case::scale`], [`Case::eye_height`], [`Case::skew`]; seeded draws, from a stream of their
/// own so that the other picks stay those of [`vary`]): every length of the case multiplied by
/// the scale.
pub(crate) fn rescale(mut case: Case, v: &mut Xorshift) -> Case {
    let scale = [1.0, 100.0, 0.3048, 39.37][v.index(4)];
    case.eye_height = [EYE_HEIGHT, EYE_HEIGHT, 0.5, 10.0][v.index(4)];
    case.scale = scale;
    for length in [
        &mut case.near,
        &mut case.far,
        &mut case.size,
        &mut case.distance,
        &mut case.translate,
    ] {
        *length *= scale;
    }
    case.jitter = case.jitter.map(|c| c * scale);
    case.ground_y = f64::from((case.ground_y * scale) as f32);
    // Half a pixel of jitter is 1/width of the half width.
    let [w, h] = viewport().map(f64::from);
    let jitter = [v.unit() - 0.5, v.unit() - 0.5];
    case.skew = [
        [0.0, 0.0],
        [0.0, 0.0],
        [jitter[0] / w, jitter[1] / h],
        [0.17 * jitter[0].signum(), 0.04 * jitter[1]],
    ][v.index(4)];
    case
}

/// The sweep: every attachment × pitch × translation × ground, each with one variation of
/// decal, planes, depth test and window picked deterministically (all of them under
/// `ZSHIFT_ENGINE_SCENES=full`).
pub(crate) fn cases() -> Vec<Case> {
    let full = std::env::var("ZSHIFT_ENGINE_SCENES").is_ok_and(|v| v == "full");
    let seed = seed();
    let mut pick = Xorshift(0x2545_F491_4F6C_DD1D ^ seed.wrapping_mul(0x9E37_79B9_7F4A_7C15));
    // The roll from a stream of its own, so the other choices stay those of the unrolled sweep.
    let mut roll_pick = Xorshift(0x0D1E_2026_1126_5EED ^ seed.wrapping_mul(0xBF58_476D_1CE4_E5B9));
    // The hillside from a stream of its own too.
    let mut tilt_pick = Xorshift(0x7117_2026_1126_0A5E ^ seed.wrapping_mul(0x94D0_49BB_1331_11EB));
    // Mesh decals (the decal built from the ground's triangles in f32) from a stream of their own.
    let mut mesh_pick = Xorshift(0x3E5D_2026_1126_DECA ^ seed.wrapping_mul(0xD6E8_FEB8_6659_FD93));
    // Chunked grids from a stream of their own.
    let mut chunk_pick = Xorshift(0xC4C4_2026_1126_0C4C ^ seed.wrapping_mul(0xE703_7ED1_A0B4_28DB));
    // Decals through their own model matrix from a stream of their own.
    let mut model_pick = Xorshift(0x30DE_2026_1126_3A7A ^ seed.wrapping_mul(0xA076_1D64_78BD_642F));
    // One view-projection matrix from a stream of its own.
    let mut combined_pick =
        Xorshift(0x7C0B_2026_1126_0F0A ^ seed.wrapping_mul(0x9FB2_1C65_1E98_DF25));
    let mut values = Xorshift(0x94D0_49BB_1331_11EB ^ seed);
    // Units and camera heights (seeded draws) from a stream of their own.
    let mut units = Xorshift(0x5CA1_2026_1126_0E7E ^ seed.wrapping_mul(0xC2B2_AE3D_27D4_EB4F));
    let mut out = Vec::new();
    for at in ATTACHMENTS {
        for pitch_deg in [0.0, 0.5, 2.0, 10.0, 30.0, 60.0] {
            for translate in [0.0, 100.0, 1e3, 1e4] {
                for ground in [Ground::Quad, Ground::Grid, Ground::Hills] {
                    let variations = if full { 6 } else { 1 };
                    for _ in 0..variations {
                        let distances: &[f64] = if pitch_deg >= 60.0 {
                            &[1.5, 2.0]
                        } else if pitch_deg >= 30.0 {
                            &[3.0, 4.0]
                        } else if ground == Ground::Hills {
                            // Within the terrain's ±60 units.
                            &[3.0, 10.0, 30.0]
                        } else {
                            &[3.0, 10.0, 50.0, 200.0]
                        };
                        let near = [0.1, 0.01][pick.index(2)];
                        let case = Case {
                            at,
                            pitch_deg,
                            translate,
                            yaw_deg: [0.0, 33.7][pick.index(2)],
                            roll_deg: [0.0, 0.0, 90.0, 17.0][roll_pick.index(4)],
                            jitter: [[0.0, 0.0], [0.3719, -0.6143]][pick.index(2)],
                            ground,
                            near,
                            far: [1000.0, f64::INFINITY][pick.index(2)],
                            size: [0.5, 2.0, 4.0][pick.index(3)],
                            distance: distances[pick.index(distances.len())],
                            side: [0.0, 0.4][pick.index(2)],
                            equal_test: pick.index(2) == 1,
                            origin: [[0, 0], [3500, 1900]][pick.index(2)],
                            depth_range: [[0.0, 1.0], [0.0, 0.5], [0.5, 1.0]][pick.index(3)],
                            ground_y: 0.0,
                            tilt: [0.0, 0.0, 0.25, -0.6][tilt_pick.index(4)],
                            fovy_deg: FOVY_DEG,
                            mesh_decal: mesh_pick.index(2) == 1,
                            model_decal: [ModelView::None, ModelView::Double, ModelView::Float]
                                [model_pick.index(3)],
                            ground_chunks: [ModelView::None, ModelView::Double, ModelView::Float]
                                [chunk_pick.index(3)],
                            combined: false,
                            scale: 1.0,
                            eye_height: EYE_HEIGHT,
                            skew: [0.0, 0.0],
                            samples: samples(),
                            behind: false,
                            beyond: false,
                            stretch: 1.0,
                            length: 1.0,
                        };
                        let case = if seed == 0 {
                            case
                        } else {
                            rescale(vary(case, &mut values), &mut units)
                        };
                        out.push(case);
                        // A quarter of the scenes again, drawn through one view-projection.
                        if combined_pick.index(4) == 0 {
                            out.push(Case {
                                combined: true,
                                ..case
                            });
                        }
                    }
                }
            }
        }
    }
    out
}

/// Samples per pixel of the target: 1, or `ZSHIFT_ENGINE_SCENES_MSAA=<n>` (every sample read back
/// and judged on its own: [`zshift_harness::msaa`]).
pub(crate) fn samples() -> u32 {
    static SAMPLES: std::sync::OnceLock<u32> = std::sync::OnceLock::new();
    *SAMPLES.get_or_init(|| {
        std::env::var("ZSHIFT_ENGINE_SCENES_MSAA").map_or(1, |v| {
            v.parse()
                .unwrap_or_else(|_| panic!("ZSHIFT_ENGINE_SCENES_MSAA={v}: expected 2, 4 or 8, at most GL_MAX_SAMPLES (llvmpipe: 4)"))
        })
    })
}

/// One case in `n` for the tests that draw a variation of the grid
/// ([`decals_reaching_behind_the_camera`], [`decals_reaching_beyond_the_far_plane`]), or one in
/// `ZSHIFT_ENGINE_SCENES_EVERY` (1: all of them).
pub(crate) fn every(n: usize) -> usize {
    std::env::var("ZSHIFT_ENGINE_SCENES_EVERY")
        .ok()
        .and_then(|v| v.parse().ok())
        .filter(|&k| k > 0)
        .unwrap_or(n)
}
