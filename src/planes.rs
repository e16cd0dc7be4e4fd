//! A decal over several planes: a mesh decal that follows a terrain (or any base of more than
//! one plane), drawn in one pass with one matrix.
//!
//! An engine's decal system clips the base's own triangles to the decal's box and draws the
//! pieces; each piece lies on its own triangle's plane, so the model's terms differ per piece
//! (slope, footprint, the base triangle's reach and box). Every piece is asked for on its own
//! ([`crate::matrix_in::recommend`]), and the decal is drawn with the **largest** offset: the
//! offset moves every depth toward the camera monotonically, so the largest keeps every
//! piece's pixels. What it costs is each piece's bleed gap at that offset, not at its own: an
//! occluder must be in front of a piece by the offset at its depths plus that piece's own
//! errors (`G_w = Δw + 2(E + S) + C_d (+ q)`, (R2) of [`crate::recommend`]), the largest of
//! them over the pieces.
//!
//! Verified by `tests/gl_engine_scene.rs` (hills: a terrain of one-unit cells, the decal built
//! from its triangles in f32, one plane asked per triangle under it).

use crate::domain::domain;
use crate::error::Result;
use crate::matrix_in::{recognize, Decal, Shape};
use crate::projection::ClipDepth;
use crate::recommend::ClipRecommendation;

/// The recommendation for one decal drawn with the engine's matrix `m` under `clip` over
/// several planes, one [`Decal`] per plane (the same viewport, format, depth test, profile and
/// pipeline; each its own corners or depths and slope, its own `base` and `world_box`). Give
/// each plane the corners of the base triangle its piece was cut from, not the piece's (a
/// sliver's f32 corners do not pin its plane down), cut to the frustum with
/// [`crate::recommend::clip_to_frustum`] where the triangle reaches behind the near plane or off
/// the screen (corners must lie in the frustum); a triangle wholly outside needs no plane
/// (leave it out: [`crate::matrix_in::decal_shape`] refuses it with an error whose
/// [`crate::Error::draws_nothing`] is true; the C entry points `zshift_decal_matrix_planes`
/// and `zshift_recommend_for_planes` leave such a plane out themselves).
///
/// Returns the recommendation of the plane whose offset is largest (its `matrix`,
/// `epsilon`, `ndc_offset`, `relative_epsilon`, `window_offset`, `delta_at_far`, `terms`),
/// with `bleed_gap` the largest of every plane's gap at that offset and `polygon_offset` the
/// largest factor and the largest units of the planes' (a `glPolygonOffset` with both keeps
/// every plane: each triangle's own slope enters the factor).
///
/// Convention: as [`crate::matrix_in::recommend`], which each plane goes through.
///
/// # Errors
/// [`crate::ErrorKind::Domain`] for no plane; any error of
/// [`crate::matrix_in::recommend`] for a plane, said of that plane ("plane 2: …", from 0);
/// [`crate::ErrorKind::Unresolvable`] naming `largest_plane` where the largest offset moves a
/// plane nearer the camera past the near plane though its own offset fits (one plane's errors
/// dwarf the others': often a terrain triangle seen nearly edge-on, whose window gradient
/// multiplies every term): draw each piece with its own plane's matrix, or leave out the
/// piece of plane `largest_plane`. Verified by `tests/gl_engine_scene.rs`, which draws such a
/// decal piece by piece.
pub fn recommend_planes(
    m: &[f32; 16],
    clip: ClipDepth,
    decals: &[Decal],
) -> Result<ClipRecommendation> {
    if decals.is_empty() {
        return Err(
            domain("a decal over several planes needs at least one plane")
                .with_integer("planes", 0),
        );
    }
    let mut asked = Vec::with_capacity(decals.len());
    for (i, decal) in decals.iter().enumerate() {
        asked.push(crate::matrix_in::recommend(m, clip, decal).map_err(|e| own_refusal(e, i))?);
    }
    // One of the two is 0 in each convention: the constant NDC offset, or the relative ε.
    let size = |r: &ClipRecommendation| r.ndc_offset.abs() + r.relative_epsilon;
    let (largest, &chosen) = asked
        .iter()
        .enumerate()
        .max_by(|a, b| size(a.1).total_cmp(&size(b.1)))
        .expect("at least one plane");
    let mut out = chosen;
    // Every plane passed recommend, so m is recognised and (perspective) has a frustum.
    let r = recognize(m, clip)?;
    let frustum = match r.shape {
        Shape::Perspective { handedness, .. } => {
            Some(crate::matrix_in::frustum_of(m, &r, handedness)?)
        }
        Shape::Orthographic => None,
    };
    for (i, (decal, own)) in decals.iter().zip(&asked).enumerate() {
        let gap = gap_at(&r, frustum, clip, decal, own, &chosen)
            .map_err(|e| nearer_than_largest(e, largest))
            .map_err(|e| at_plane(e, i))?;
        out.bleed_gap = out.bleed_gap.max(gap);
        out.polygon_offset = [0, 1].map(|k| out.polygon_offset[k].max(own.polygon_offset[k]));
    }
    Ok(out)
}

/// Why a plane whose own offset fits is refused at the largest: what an engine can do.
const NEARER_PLANE: &str = "the offset of plane `largest_plane`, the largest, moves this plane past the near plane though its own offset fits: draw each piece with its own plane's matrix (ask for each plane alone: zshift_decal_matrix with its record in C, zshift.decal_matrix with its corners in Python, matrix_in::recommend in Rust), or leave out the piece of plane `largest_plane` (its errors set the offset: often a triangle seen nearly edge-on, whose piece covers few pixels)";

/// A plane refused at the largest offset, though its own fits ([`NEARER_PLANE`]), naming the
/// plane that set it (`largest_plane`); other errors unchanged.
fn nearer_than_largest(e: crate::Error, largest: usize) -> crate::Error {
    if e.kind() != crate::ErrorKind::Unresolvable {
        return e;
    }
    crate::error::Error::new(crate::ErrorKind::Unresolvable, NEARER_PLANE)
        .with_integer("largest_plane", i64::try_from(largest).unwrap_or(i64::MAX))
}

/// Names the plane an error came from.
fn at_plane(e: crate::Error, i: usize) -> crate::Error {
    e.for_item("plane", u32::try_from(i).unwrap_or(u32::MAX))
}

/// [`at_plane`] for a plane's own recommendation: where its own offset moves it past the near
/// plane, leaving its piece out is a remedy too (often a terrain triangle seen nearly edge-on,
/// whose piece covers few pixels).
fn own_refusal(e: crate::Error, i: usize) -> crate::Error {
    let e = at_plane(e, i);
    if crate::recommend::moves_past_the_near_plane(&e) {
        e.with_note(LEAVE_THE_PIECE_OUT)
    } else {
        e
    }
}

/// [`own_refusal`]'s remedy for a plane whose own offset moves it past the near plane.
const LEAVE_THE_PIECE_OUT: &str = "as one plane of several, its piece may also be left out of the decal pass (often a triangle seen nearly edge-on, whose piece covers few pixels)";

/// The bleed gap of one plane (`decal`, recommended `own`) drawn with `chosen`'s offset, under
/// the recognised matrix `r` (its `frustum` if perspective).
/// Perspective: the model's (R2) at the plane's nearest and farthest depth with the chosen
/// window offset there. Orthographic: eye depth is linear in window depth, so the gap grows by
/// the difference of the offsets times the depth span.
fn gap_at(
    r: &crate::matrix_in::Recognized,
    frustum: Option<crate::projection::Frustum>,
    clip: ClipDepth,
    decal: &Decal,
    own: &ClipRecommendation,
    chosen: &ClipRecommendation,
) -> Result<f64> {
    match frustum {
        Some(frustum) => {
            let scene = crate::matrix_in::scene(frustum, decal, clip);
            crate::recommend::bleed_gap_with(&scene, clip, &own.terms, chosen)
        }
        None => {
            let span = (r.far - r.near).abs();
            crate::orthographic::check_near(
                r.near,
                r.far,
                decal.depth_range[0],
                chosen.window_offset,
            )?;
            Ok(own.bleed_gap + (chosen.window_offset - own.window_offset).max(0.0) * span)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::matrix_in::{decal_shape, recommend};
    use crate::precision::DepthFormat;
    use crate::recommend::{Base, Snapping};
    use glam::Vec3;

    /// glFrustum's 60° by 16:9 frustum, near 0.1, far 1000 (∞ reversed), under `clip`.
    fn matrix(clip: ClipDepth) -> [f32; 16] {
        let t = 0.1 * (30f64).to_radians().tan();
        let far = if clip == ClipDepth::ReversedZeroToOne {
            f64::INFINITY
        } else {
            1000.0
        };
        let frustum =
            crate::projection::Frustum::new(-t * 16.0 / 9.0, t * 16.0 / 9.0, -t, t, 0.1, far)
                .expect("a frustum");
        crate::projection::projection(&frustum, clip).expect("a matrix")
    }

    /// A triangle of terrain 1.7 below a level camera, `ahead` units away, rising `rise` per
    /// unit of x, as a decal of its own.
    fn plane(m: &[f32; 16], clip: ClipDepth, ahead: f32, rise: f32) -> Decal {
        let at = |x: f32, z: f32| Vec3::new(x, -1.7 + rise * x, -z);
        let corners = [at(-1.0, ahead), at(1.0, ahead), at(0.0, ahead + 1.5)];
        let shape = decal_shape(m, clip, [1920, 1080], &corners).expect("a plane on screen");
        Decal {
            viewport: [1920, 1080],
            format: DepthFormat::Unorm24,
            depth_range: shape.depth_range,
            slope: shape.slope,
            exact_depth: false,
            snapping: Snapping::SubpixelBits(8),
            base: Base::InsideFrustum,
            profile: None,
            footprint: Some(shape.footprint),
            depth_test: None,
            pipeline: crate::model::Pipeline::default(),
        }
    }

    /// A plane whose own offset moves it past the near plane (world-space vertices 10⁶ units
    /// from the origin, 3.5 ahead) is refused with its number, and with leaving its piece out
    /// among the remedies; the same plane asked alone is refused without that note.
    #[test]
    fn a_plane_refused_on_its_own_may_be_left_out() {
        let clip = ClipDepth::NegOneToOne;
        let m = matrix(clip);
        let near = Decal {
            pipeline: crate::model::Pipeline {
                world_reach: 1e6,
                ..crate::model::Pipeline::default()
            },
            ..plane(&m, clip, 3.5, 0.0)
        };
        let alone = recommend(&m, clip, &near).unwrap_err();
        assert_eq!(alone.kind(), crate::ErrorKind::Unresolvable, "{alone}");
        assert!(!alone.to_string().contains("left out"), "{alone}");
        let e = recommend_planes(&m, clip, &[near, near]).unwrap_err();
        let text = e.to_string();
        assert!(text.starts_with("plane 0: "), "{text}");
        assert!(text.ends_with(LEAVE_THE_PIECE_OUT), "{text}");
    }

    #[test]
    fn one_plane_is_the_plane_itself() {
        for clip in [
            ClipDepth::NegOneToOne,
            ClipDepth::ZeroToOne,
            ClipDepth::ReversedZeroToOne,
        ] {
            let m = matrix(clip);
            let d = plane(&m, clip, 10.0, 0.3);
            let one = recommend_planes(&m, clip, &[d]).unwrap();
            let own = recommend(&m, clip, &d).unwrap();
            assert_eq!(one.matrix, own.matrix, "{clip:?}");
            // The gap of the plane at its own offset, through either formula: never smaller.
            assert!(one.bleed_gap >= own.bleed_gap, "{clip:?}: {one:?} {own:?}");
            assert!(
                one.bleed_gap <= 1.01 * own.bleed_gap,
                "{clip:?}: {one:?} {own:?}"
            );
        }
    }

    /// Two planes: the matrix is the one with the larger offset, and every plane's gap at that
    /// offset is covered: the window separation `G_w` it needs (R2) is reached at the reported
    /// gap, checked on the exact window depth of the f64 frustum at the plane's nearest and
    /// farthest depth.
    #[test]
    fn the_largest_offset_and_every_planes_gap_at_it() {
        for clip in [
            ClipDepth::NegOneToOne,
            ClipDepth::ZeroToOne,
            ClipDepth::ReversedZeroToOne,
        ] {
            let m = matrix(clip);
            let (flat, steep) = (plane(&m, clip, 10.0, 0.0), plane(&m, clip, 12.0, 0.7));
            let both = recommend_planes(&m, clip, &[flat, steep]).unwrap();
            let recs = [flat, steep].map(|d| recommend(&m, clip, &d).unwrap());
            let size = |r: &ClipRecommendation| r.ndc_offset.abs() + r.relative_epsilon;
            let largest = if size(&recs[0]) >= size(&recs[1]) {
                &recs[0]
            } else {
                &recs[1]
            };
            assert_eq!(both.matrix, largest.matrix, "{clip:?}");
            assert!(both.bleed_gap >= recs[0].bleed_gap.max(recs[1].bleed_gap));
            assert_eq!(
                both.polygon_offset,
                [0, 1].map(|k| recs[0].polygon_offset[k].max(recs[1].polygon_offset[k]))
            );
            // The unit window depth of the f64 frustum (glm's near and far; aspect and fov do
            // not enter depth).
            let (n, f) = (0.1f64, 1000.0f64);
            let unit = |d: f64| match clip {
                ClipDepth::ReversedZeroToOne => n / d,
                _ => f * (d - n) / (d * (f - n)),
            };
            for (decal, own) in [flat, steep].iter().zip(&recs) {
                for d in decal.depth_range {
                    let offset = if clip == ClipDepth::ReversedZeroToOne {
                        largest.relative_epsilon * n / d
                    } else {
                        largest.window_offset
                    };
                    let needed = own.terms.gap_window(offset);
                    let apart = (unit(d) - unit(d - both.bleed_gap)).abs();
                    // The model's quantum is taken at each depth; the terms' at the far end:
                    // allow that much.
                    assert!(
                        apart >= needed - own.terms.quantum,
                        "{clip:?} d {d}: {apart} < {needed}"
                    );
                }
            }
        }
    }

    /// `glOrtho(−20, 20, −11.25, 11.25, 1, 501)` under `[−1, 1]`: eye depth `n = 1` to 501.
    fn ortho_matrix() -> [f32; 16] {
        let o = crate::orthographic::Ortho::new(-20.0, 20.0, -11.25, 11.25, 1.0, 501.0).unwrap();
        crate::orthographic::ortho(&o, ClipDepth::NegOneToOne).unwrap()
    }

    /// A decal of slope `slope` from eye depth `d` to `d + depth`, by its range (no corners).
    fn ranged(d: f64, depth: f64, slope: f64) -> Decal {
        let clip = ClipDepth::NegOneToOne;
        Decal {
            depth_range: [d, d + depth],
            slope,
            footprint: None,
            ..plane(&matrix(clip), clip, 10.0, 0.0)
        }
    }

    /// Under an orthographic matrix eye depth is linear in window depth: a plane's gap at the
    /// larger offset is its own errors plus that offset, over the depth span.
    #[test]
    fn orthographic_planes_take_the_larger_offset_and_its_gap() {
        let clip = ClipDepth::NegOneToOne;
        let m = ortho_matrix();
        let (flat, steep) = (ranged(100.0, 2.0, 0.0), ranged(300.0, 2.0, 2.0));
        let both = recommend_planes(&m, clip, &[flat, steep]).unwrap();
        let recs = [flat, steep].map(|d| recommend(&m, clip, &d).unwrap());
        let (big, small) = if recs[0].window_offset >= recs[1].window_offset {
            (&recs[0], &recs[1])
        } else {
            (&recs[1], &recs[0])
        };
        assert!(big.window_offset > small.window_offset);
        assert_eq!(both.matrix, big.matrix);
        // (R2) in window depth: the offset, plus the plane's own errors (its gap at its own
        // offset less that offset); eye depth is window depth times the span 500.
        let errors = |r: &ClipRecommendation| r.bleed_gap / 500.0 - r.window_offset;
        let needed = [big, small].map(|r| (big.window_offset + errors(r)) * 500.0);
        assert!(
            both.bleed_gap >= needed[0].max(needed[1]) * (1.0 - 1e-12),
            "{both:?}"
        );
        assert!(
            both.bleed_gap <= needed[0].max(needed[1]) * (1.0 + 1e-12),
            "{both:?}"
        );
    }

    /// The largest offset is checked at every plane's nearest depth, not only at its own plane's:
    /// a plane just beyond the near plane cannot take the offset of a far plane whose clipped
    /// base asks a large one (each fits alone), and the refusal names the plane that set it.
    /// The orthographic path checks its near plane too.
    #[test]
    fn the_largest_offset_is_refused_where_it_moves_a_nearer_plane_past_the_near_plane() {
        for clip in [
            ClipDepth::NegOneToOne,
            ClipDepth::ZeroToOne,
            ClipDepth::ReversedZeroToOne,
        ] {
            let m = matrix(clip);
            let near = Decal {
                depth_range: [0.125, 0.13],
                footprint: None,
                slope: 0.0,
                ..plane(&m, clip, 10.0, 0.0)
            };
            // The window depth of eye depth d, exact (near 0.1, far 1000, ∞ reversed).
            let unit = |d: f64| match clip {
                ClipDepth::ReversedZeroToOne => 0.1 / d,
                _ => 1000.0 * (d - 0.1) / (d * 999.9),
            };
            let mut refused = 0;
            for reach in [1e4, 3e4, 1e5, 3e5, 1e6, 3e6, 1e7] {
                let far = Decal {
                    depth_range: [50.0, 51.0],
                    footprint: None,
                    slope: 0.5,
                    base: Base::Clipped { reach },
                    ..near
                };
                let (Ok(own_near), Ok(own_far)) =
                    (recommend(&m, clip, &near), recommend(&m, clip, &far))
                else {
                    continue;
                };
                assert!(own_near.window_offset <= own_far.window_offset);
                // The far plane's offset at the near plane's nearest depth.
                let at_near = match clip {
                    ClipDepth::ReversedZeroToOne => own_far.relative_epsilon * unit(0.125),
                    _ => own_far.window_offset,
                };
                let past = match clip {
                    ClipDepth::ReversedZeroToOne => unit(0.125) + at_near > 1.0,
                    _ => unit(0.125) - at_near < 0.0,
                };
                let both = recommend_planes(&m, clip, &[near, far]);
                if past {
                    let e = both.expect_err("the far plane's offset clips the near one");
                    assert_eq!(e.kind(), crate::ErrorKind::Unresolvable, "{clip:?}: {e}");
                    assert_eq!(e.input(), Some(("largest_plane", 1.0)), "{clip:?}: {e}");
                    assert!(e.to_string().starts_with("plane 0: "), "{e}");
                    refused += 1;
                } else {
                    both.unwrap_or_else(|e| panic!("{clip:?} reach {reach}: {e}"));
                }
            }
            assert!(
                refused > 0,
                "{clip:?}: no reach made the far plane's offset too large"
            );
        }
        // Orthographic: a decal 0.001 behind the near plane of a box 500 deep takes no offset
        // larger than 0.001/500 of window depth.
        let clip = ClipDepth::NegOneToOne;
        let m = ortho_matrix();
        let (close, steep) = (ranged(1.001, 0.5, 0.0), ranged(400.0, 0.5, 40.0));
        let own = recommend(&m, clip, &steep).unwrap();
        assert!(own.window_offset * 500.0 > 0.001, "{own:?}");
        let e = recommend_planes(&m, clip, &[close, steep]).unwrap_err();
        assert_eq!(e.input(), Some(("largest_plane", 1.0)), "{e}");
        // And one decal alone: the steep plane's own offset at the near plane's distance.
        let e = recommend(
            &m,
            clip,
            &Decal {
                depth_range: [1.001, 1.5],
                ..steep
            },
        )
        .unwrap_err();
        assert_eq!(e.kind(), crate::ErrorKind::Unresolvable, "{e}");
        let needed = e
            .input()
            .filter(|(name, _)| *name == "needed")
            .expect("needed")
            .1;
        assert!(needed > 0.0 && needed < 0.5, "{e}");
    }

    #[test]
    fn refusals_name_the_plane() {
        let clip = ClipDepth::NegOneToOne;
        let m = matrix(clip);
        let e = recommend_planes(&m, clip, &[]).unwrap_err();
        assert_eq!(e.kind(), crate::ErrorKind::Domain);
        let good = plane(&m, clip, 10.0, 0.0);
        let bad = Decal {
            depth_range: [5000.0, 6000.0],
            footprint: None,
            ..good
        };
        let e = recommend_planes(&m, clip, &[good, bad]).unwrap_err();
        assert!(e.to_string().starts_with("plane 1: "), "{e}");
    }
}
