//! The scene every engine draws, on a real rasterizer (headless EGL; Mesa llvmpipe in CI): a
//! decal on ground that runs to the horizon and behind the camera, seen by a camera 1.7 units
//! above it at pitch 0° (level) to 60°, with vertices in **world space** through an **f32 view
//! matrix** in the vertex shader (`proj * (view * vec4(p, 1))`), the whole scene translated with
//! the camera by 0 to 10⁴ units from the world origin (the camera heading 0° or 33.7° and placed
//! off the translation by a fraction of a unit, so that nothing rounds exactly in f32), the
//! ground drawn **as it is** (one quad of
//! ±1000 units, or a 64×64 grid of triangles; no cutting), in a viewport at the framebuffer's
//! origin or inside a larger one, under `glDepthRange(0, 1)` or a sub-range, on D24, D24S8,
//! D32F and D32F_S8 attachments under `[−1, 1]`, `[0, 1]` and reversed Z, with strict and
//! `…EQUAL` depth tests (every pass drawn with the same test, as engines do), and with the
//! worst-case and the probed profile.
//!
//! The decal is asked for through the front door (`matrix_in::recommend` on the engine's own
//! matrix, the decal's eye-space corners, `base_reach`, the pipeline), exactly as an engine
//! would. Every answered scene must lose 0 decal pixels and bleed 0 pixels over an occluder
//! parallel to the ground whose eye depth is at least the reported gap in front of the ground
//! at every pixel. A refusal must be a scene where bisection finds no working offset. The test
//! prints, per class, the recommended ÷ smallest working offset (bisection over f32 steps of the
//! offset element) and the bleed gap ÷ the decal's distance.
//!
//! References are GL readbacks and this file's own f64 geometry. Fails (never skips) without GL.
//! `ZSHIFT_ENGINE_SCENES=full` runs every variation of the grid (slow); the default samples
//! one variation per base scene. `--nocapture` prints the table; `ZSHIFT_ENGINE_SCENES_VERBOSE=1`
//! every scene; `ZSHIFT_ENGINE_SCENES_ONLY=<text>` only the scenes whose label contains `<text>`
//! (the counts the test asserts then fail: it is for looking at one scene);
//! `ZSHIFT_ENGINE_SCENES_GROUND_ERROR=1` each scene's ground drawn alone against its exact plane,
//! row by row; `ZSHIFT_ENGINE_SCENES_VIEWPORT=1920x1080` (or `3840x2160`) draws at an engine's
//! own size instead of 320×180; `ZSHIFT_ENGINE_SCENES_SEED=<n>` another draw, with values between
//! the grid's, the ground at a world height as far from the origin as the translation and a field
//! of view of 40° to 100°; `ZSHIFT_ENGINE_SCENES_SHARD=<i>/<n>` one `n`th of the grid;
//! `ZSHIFT_ENGINE_SCENES_MSAA=4` every scene on a 4× multisampled target, each sample judged;
//! `ZSHIFT_ENGINE_SCENES_EVERY=<n>` one case in `n` for the tests that draw a variation of the grid
//! (1: all of them).

mod gl_common;
// One scene and its exact geometry: what the engine draws and what it knows.
#[path = "gl_engine_scene/case.rs"]
mod case;
// The scenes the tests draw: the grid, its seeded draws, one case in `n`.
#[path = "gl_engine_scene/grid.rs"]
mod grid;
// One scene drawn on GL as an engine draws it, its pixels counted.
#[path = "gl_engine_scene/render.rs"]
mod render;
// One scene asked for through the front door, drawn and judged.
#[path = "gl_engine_scene/ask.rs"]
mod ask;
// A sweep over scenes: both profiles, the per-class table, the assertions.
#[path = "gl_engine_scene/sweep.rs"]
mod sweep;

use zshift::matrix_in::{decal_shape, recommend, Decal};
use zshift::model::Pipeline;
use zshift::precision::DepthFormat as Format;
use zshift::projection::{projection, ClipDepth, Frustum};
use zshift::recommend::{Base, DepthTest, RasterizerProfile, Snapping};
use zshift_harness::coplanar::{
    bisect_smallest_passing, stepped_toward_camera, steps_between, Count, BASE, CLEAR, DECAL,
    OCCLUDER,
};
use zshift_harness::draw::Xorshift;
use zshift_harness::world::{
    bounding_box, clip_to_square, eye_of, transformed, view_matrix, Window,
};
use zshift_harness::{ClipDepth as GlClip, DepthFormat, DrawState, Gl, Profile};

use ask::*;
use case::*;
use grid::*;
use render::*;
use sweep::*;

#[test]
fn the_scene_every_engine_draws() {
    let (shard, shards) = gl_common::shard("ZSHIFT_ENGINE_SCENES_SHARD");
    let picked = cases()
        .into_iter()
        .enumerate()
        .filter(|(index, _)| index % shards == shard)
        .map(|(_, case)| case);
    sweep(picked.collect(), 100);
}

/// The same scenes on a 4× multisampled target, as engines draw them (a sample of the grid:
/// every 32nd case; `ZSHIFT_ENGINE_SCENES_MSAA=4` draws the whole grid so): every sample is
/// tested against its own interpolated depth and judged on its own, lost, bled and refused as
/// above.
#[test]
fn every_sample_holds_under_msaa() {
    let picked = cases()
        .into_iter()
        .step_by(32)
        .map(|case| Case { samples: 4, ..case });
    sweep(picked.collect(), 20);
}

/// Decals under the camera, part of them behind it (a pool of blood under the player, a
/// scorch mark the camera stands on), which the sweep above skips: the grid's scenes looking
/// 10° or more down, each decal moved under the camera (a 4-unit square from 0.8 units behind
/// it to 3.2 ahead, or from 1.6 behind to 2.4 ahead), one in three drawn as they are
/// (`ZSHIFT_ENGINE_SCENES_EVERY=1`, all:
/// 822 scenes, 87 s, 0 lost, 0 bled, none refused). zshift is given all
/// the corners; it cuts the decal to the view in f64 for its footprint and counts the
/// rasterizer's clipping of it.
#[test]
fn decals_reaching_behind_the_camera() {
    let picked = cases()
        .into_iter()
        .filter(|case| case.pitch_deg >= 10.0)
        .enumerate()
        .map(|(i, case)| Case {
            // In the case's units (seeded draws scale every length).
            size: 4.0 * case.scale,
            distance: [1.2, 0.4][i % 2] * case.scale,
            behind: true,
            ..case
        })
        .filter(Case::crosses_near)
        .step_by(every(3));
    sweep(picked.collect(), 100);
}

/// Decals running on beyond the far plane (a road marking, a long skid mark, under the short
/// far plane of a fogged or indoor scene), which the sweep above skips: the grid's scenes with
/// the far plane moved to the eye depth of the decal's centre, so that the rasterizer clips the
/// decal (and the ground) there, one in six drawn (`ZSHIFT_ENGINE_SCENES_EVERY=1`: all). zshift is given all the corners; it cuts
/// the decal to the view in f64 for its footprint and counts the rasterizer's clipping of it
/// (before, such a decal was refused: "the decal's eye distance lies beyond the far plane").
#[test]
fn decals_reaching_beyond_the_far_plane() {
    let picked = cases()
        .into_iter()
        .map(|case| {
            let [x, z] = case.decal_centre();
            let y = case.surface(x, z);
            Case {
                far: -case.eye([x, y, z])[2],
                beyond: true,
                ..case
            }
        })
        .filter(|case| case.far > 10.0 * case.near && case.decal_in_depth())
        .step_by(every(6));
    sweep(picked.collect(), 100);
}

/// Long, narrow decals (a road marking, a skid mark, a painted line): the grid's scenes looking
/// less than 30° down, each decal 12 times as long along world z as it is wide
/// (`size` wide), one in five drawn (`ZSHIFT_ENGINE_SCENES_EVERY=1`: all). Along the view at a
/// heading of 0°, diagonal at 33.7°: its depth runs over a long range, and at 3 units ahead its
/// near end reaches under the camera (drawn; zshift cuts it to the view).
#[test]
fn long_decals() {
    let picked = cases()
        .into_iter()
        .filter(|case| case.pitch_deg < 30.0)
        .map(|case| Case {
            length: 12.0,
            behind: true,
            ..case
        })
        .step_by(every(5));
    sweep(picked.collect(), 100);
}

/// One description, several realizations: each sampled scene (every 13th of the grid's quad
/// and grid scenes, one drawn through one view-projection left out; `ZSHIFT_ENGINE_SCENES_EVERY`
/// another step) drawn again with the whole scene moved by `k·0.0371` units and the ground's
/// half extent by `k·0.037 %` (`k` = 0 to 5; `ZSHIFT_ENGINE_SCENES_REALIZATIONS` another
/// count), so that the vertex shader's and the clipper's inputs differ. The eye-space scene
/// under the decal is the same; what zshift is told barely changes (the view matrix's
/// translation, the world box, the base's reach), and so does its offset; the f32 roundings
/// differ, and with them the smallest working offset.
/// A sound offset must hold for every realization, so it is at least the largest of their
/// smallest working offsets: the spread of those says how close to any one realization's a
/// sound answer can be. Probed profile; asserts 0 lost and 0 bled in every realization, and
/// prints per scene the offset and each realization's smallest working offset, then the
/// medians over scenes of largest ÷ median realization and of offset ÷ largest realization.
#[test]
fn one_description_many_realizations() {
    let count: u32 = std::env::var("ZSHIFT_ENGINE_SCENES_REALIZATIONS")
        .ok()
        .and_then(|v| v.parse().ok())
        .filter(|&k| k > 1)
        .unwrap_or(6);
    let mut gl = Gl::new(Profile::Core).unwrap_or_else(|e| panic!("no GL context: {e}"));
    let probed = gl_common::probed(&gl);
    let sampled = cases()
        .into_iter()
        .filter(|case| case.ground != Ground::Hills && !case.combined)
        .step_by(every(13));
    let (mut spreads, mut over_largest, mut failures, mut drawn) =
        (Vec::new(), Vec::new(), Vec::new(), 0);
    // Offset ÷ largest realization per largest term of the offset.
    let mut by_term = std::collections::BTreeMap::<&str, Vec<f64>>::new();
    for case in sampled {
        let mut steps = Vec::new();
        let mut smallest = Vec::new();
        let mut largest_term = "";
        for k in 0..count {
            let moved = Case {
                translate: case.translate + f64::from(k) * 0.0371 * case.scale,
                stretch: 1.0 + f64::from(k) * 3.7e-4,
                ..case
            };
            let Some(out) = run_case(&mut gl, moved, &probed)
                .unwrap_or_else(|e| panic!("{}: {e}", moved.label()))
            else {
                continue;
            };
            drawn += 1;
            if out.lost + out.bled > 0 {
                failures.push(format!(
                    "{}: lost {} bled {}",
                    moved.label(),
                    out.lost,
                    out.bled
                ));
            }
            if let Some(ratio) = out.ratio {
                steps.push(out.steps);
                smallest.push(out.steps / ratio);
            }
            if let Some(t) = out.terms {
                largest_term = largest_of(&t);
            }
        }
        if smallest.len() < 2 {
            continue;
        }
        let largest = smallest.iter().copied().fold(0.0, f64::max);
        let offset = steps.iter().copied().fold(f64::INFINITY, f64::min);
        // (median sorts them, for the line below too.)
        spreads.push(largest / median(&mut smallest));
        over_largest.push(offset / largest);
        by_term
            .entry(largest_term)
            .or_default()
            .push(offset / largest);
        println!(
            "{}: offset {offset:.0}..{:.0} steps; smallest working {smallest:.0?}",
            case.label(),
            steps.iter().copied().fold(0.0, f64::max)
        );
    }
    println!(
        "{} scenes, {drawn} drawn: largest ÷ median realization, median over scenes {:.2} (max {:.1}); offset ÷ largest realization, median {:.1}",
        spreads.len(),
        median(&mut spreads),
        spreads.iter().copied().fold(0.0, f64::max),
        median(&mut over_largest)
    );
    for (term, ratios) in &mut by_term {
        println!(
            "  largest term {term}: {} scenes, offset ÷ largest realization median {:.1}",
            ratios.len(),
            median(ratios)
        );
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert!(
        spreads.len() >= 10,
        "only {} scenes answered",
        spreads.len()
    );
}

/// A mesh decal over hills whose pieces one matrix cannot serve (found by a seeded draw in
/// inches, a crouching camera 6.9·10⁵ units from the origin): one terrain triangle under the
/// decal passes close to the eye, its window gradient a thousand times its neighbours', and its
/// offset would move the nearer pieces past the near plane (before `recommend_planes` checked
/// every plane at the largest offset, 9648 decal pixels were lost). The call refuses naming
/// `largest_plane`; drawn piece by piece as the refusal says, each with its own plane's matrix,
/// no decal pixel is lost and none bleeds over an occluder at its piece's gap.
#[test]
fn a_decal_one_matrix_cannot_serve_is_drawn_piece_by_piece() {
    let mut gl = Gl::new(Profile::Core).unwrap_or_else(|e| panic!("no GL context: {e}"));
    let probed = gl_common::probed(&gl);
    let scale = 39.37;
    let case = Case {
        at: *ATTACHMENTS
            .iter()
            .find(|a| a.label == "reversed D24")
            .expect("reversed D24"),
        pitch_deg: 61.39199523925781,
        translate: 687491.43866539,
        yaw_deg: 354.2929458618164,
        roll_deg: 0.0,
        jitter: [14.641703, -24.184990999999997],
        ground_y: -687123.0625,
        tilt: -0.6,
        fovy_deg: 83.9,
        ground: Ground::Hills,
        near: 0.01 * scale,
        far: 1000.0 * scale,
        size: 69.34943934726715,
        distance: 53.687067114830015,
        side: 0.0,
        equal_test: false,
        origin: [0, 0],
        depth_range: [0.0, 0.5],
        mesh_decal: true,
        model_decal: ModelView::None,
        combined: false,
        ground_chunks: ModelView::None,
        scale,
        eye_height: 0.5,
        skew: [0.0, 0.0],
        samples: 1,
        behind: false,
        beyond: false,
        stretch: 1.0,
        length: 1.0,
    };
    for profile in [RasterizerProfile::worst_case(), probed] {
        let out = run_case(&mut gl, case, &profile)
            .unwrap_or_else(|e| panic!("{e}"))
            .expect("the decal is on screen");
        assert!(out.by_pieces, "{out:?}");
        assert_eq!((out.lost, out.bled), (0, 0), "{out:?}");
    }
}
