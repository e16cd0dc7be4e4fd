//! One scene asked for and judged: the recommendation asked through the front door as an
//! engine asks ([`ask`], [`piece_by_piece`] where one matrix cannot serve every plane), then
//! drawn and counted ([`run_case`]) into an [`Outcome`].

use super::*;

/// What one scene gave.
#[derive(Debug, Default)]
pub(crate) struct Outcome {
    pub(crate) lost: usize,
    /// Decal pixels lost with the plain matrix and the recommendation's `glPolygonOffset`
    /// equivalent instead (not under reversed Z, where it has none).
    pub(crate) lost_polygon_offset: usize,
    /// Decal pixels lost over the quad cut to the frustum (`clip_to_frustum`, stored back in
    /// world space) at the recommendation for the cut ground.
    pub(crate) lost_cut: usize,
    /// Whether the cut quad was drawn.
    pub(crate) cut_drawn: bool,
    pub(crate) bled: usize,
    pub(crate) refused: Option<String>,
    pub(crate) drawable: bool,
    pub(crate) ratio: Option<f64>,
    pub(crate) gap_over_distance: f64,
    pub(crate) terms: Option<zshift::recommend::ErrorTerms>,
    /// The offset (f32 steps of the offset element) over the one for the ground cut to the frustum.
    pub(crate) over_cut: Option<f64>,
    /// The offset in f32 steps of the offset element.
    pub(crate) steps: f64,
    /// Drawn piece by piece, each piece with its own plane's matrix (the remedy of a
    /// `largest_plane` refusal, [`piece_by_piece`]).
    pub(crate) by_pieces: bool,
}

/// What the engine gets: the recommendation (over hills, for every plane under the decal at
/// once: `zshift::planes::recommend_planes`), the decal's nearest eye depth, and for the quad the
/// recommendation over the ground cut to the frustum.
pub(crate) struct Asked {
    rec: zshift::recommend::ClipRecommendation,
    d1: f64,
    cut: Option<zshift::recommend::ClipRecommendation>,
    /// Over hills, where one matrix cannot serve every plane (the largest plane's offset moves
    /// a nearer one past the near plane) and the refusal says to draw each piece with its own
    /// plane's matrix: the pieces so drawn (`rec` is then the largest plane's, its bleed gap
    /// the largest of the planes' own), with each piece's own bleed gap.
    pieces: Option<(Vec<Piece>, Vec<f64>)>,
}

/// The remedy of a refusal that names `largest_plane`: each plane asked alone, its piece drawn
/// with its own matrix (`rec` the named plane's, the bleed gap the largest of the planes').
pub(crate) fn piece_by_piece(
    plain: &[f32; 16],
    clip: ClipDepth,
    decals: &[Decal],
    largest: usize,
    pieces: Vec<Vec<[f32; 3]>>,
    d1: f64,
) -> Result<Asked, String> {
    let own: Vec<_> = decals
        .iter()
        .map(|d| recommend(plain, clip, d).map_err(|e| e.to_string()))
        .collect::<Result<_, _>>()?;
    let mut rec = own[largest];
    rec.bleed_gap = own.iter().map(|r| r.bleed_gap).fold(0.0, f64::max);
    let gaps = own.iter().map(|r| r.bleed_gap).collect();
    let pieces = pieces
        .into_iter()
        .zip(&own)
        .map(|(p, r)| (p, r.matrix))
        .collect();
    Ok(Asked {
        rec,
        d1,
        cut: None,
        pieces: Some((pieces, gaps)),
    })
}

/// Asks for the decal through the front door, as an engine does: the engine's own matrix, the
/// decal's eye-space corners, `base_reach`, the view matrix and world box, `eye_first`. Over
/// hills the decal covers several planes: one `Decal` per terrain triangle under it (its
/// corners, its reach, its box), asked for together.
pub(crate) fn ask(
    case: &Case,
    plain: &[f32; 16],
    profile: &RasterizerProfile,
) -> Result<Asked, String> {
    let text = |e: zshift::Error| e.to_string();
    // Per plane: its world corners, the base's reach and its world box, and over hills the
    // decal's piece on it.
    type Plane = (Vec<[f64; 3]>, f64, [[f64; 3]; 2], Vec<[f32; 3]>);
    let planes: Vec<Plane> = if case.ground == Ground::Hills {
        let ground = case.ground();
        clip_to_square(&ground, case.decal_square(1.0))
            .into_iter()
            .map(|(i, piece)| {
                let t: Vec<[f64; 3]> = ground[3 * i..3 * i + 3]
                    .iter()
                    .map(|p| p.map(f64::from))
                    .collect();
                (t.clone(), case.reach_of(&t), bounding_box(&t), piece)
            })
            .collect()
    } else {
        let corners = case.decal_world().map(|p| p.map(f64::from)).to_vec();
        vec![(corners, case.base_reach(), case.world_box(), Vec::new())]
    };
    let mut decals = Vec::new();
    let mut pieces = Vec::new();
    let mut d1 = f64::INFINITY;
    for (world, reach, world_box, piece) in planes {
        let eye: Vec<[f64; 3]> = world.iter().map(|&p| case.eye(p)).collect();
        // A terrain triangle may reach behind the near plane or off the screen: its plane is
        // described by the part the rasterizer draws, cut to the frustum in f64; one wholly
        // outside draws nothing and needs no offset.
        let eye = if case.ground == Ground::Hills {
            zshift::recommend::clip_to_frustum(&case.frustum(), &eye).map_err(text)?
        } else {
            eye
        };
        if eye.len() < 3 {
            continue;
        }
        pieces.push(piece);
        let corners: Vec<glam::Vec3> = eye
            .iter()
            .map(|e| glam::Vec3::new(e[0] as f32, e[1] as f32, e[2] as f32))
            .collect();
        let shape = decal_shape(plain, case.at.clip, viewport(), &corners).map_err(text)?;
        d1 = d1.min(shape.depth_range[0]);
        decals.push(Decal {
            viewport: viewport(),
            format: Format::from_gl_internal_format(if case.at.packed {
                match case.at.format {
                    DepthFormat::D24 => glow::DEPTH24_STENCIL8,
                    _ => glow::DEPTH32F_STENCIL8,
                }
            } else {
                case.at.format.gl_enum()
            })
            .map_err(text)?,
            depth_range: shape.depth_range,
            slope: shape.slope,
            exact_depth: false,
            snapping: Snapping::SubpixelBits(8),
            base: match reach {
                0.0 => Base::InsideFrustum,
                reach => Base::Clipped { reach },
            },
            profile: Some(*profile),
            footprint: Some(shape.footprint),
            depth_test: Some(case.tests().1),
            pipeline: case.pipeline(world_box),
        });
    }
    if case.ground == Ground::Hills {
        return match zshift::planes::recommend_planes(plain, case.at.clip, &decals) {
            Ok(rec) => Ok(Asked {
                rec,
                d1,
                cut: None,
                pieces: None,
            }),
            Err(e) => match e.input() {
                Some(("largest_plane", k)) => {
                    piece_by_piece(plain, case.at.clip, &decals, k as usize, pieces, d1)
                }
                _ => Err(text(e)),
            },
        };
    }
    // The same decal over the ground cut to the frustum in f64 (nothing left to clip): what the
    // honest description of the ground as drawn is compared with.
    let cut = recommend(
        plain,
        case.at.clip,
        &Decal {
            base: Base::InsideFrustum,
            ..decals[0]
        },
    )
    .ok();
    let rec = recommend(plain, case.at.clip, &decals[0]).map_err(text)?;
    Ok(Asked {
        rec,
        d1,
        cut,
        pieces: None,
    })
}

pub(crate) fn run_case(
    gl: &mut Gl,
    case: Case,
    profile: &RasterizerProfile,
) -> Result<Option<Outcome>, String> {
    if !case.decal_in_depth() {
        return Ok(None);
    }
    let mut r = Renderer::new(gl, case)?;
    if std::env::var_os("ZSHIFT_ENGINE_SCENES_GROUND_ERROR").is_some() {
        println!(
            "{}: the ground alone\n{}",
            case.label(),
            r.ground_error()?.join("\n")
        );
    }
    if r.mask.iter().filter(|&&m| m).count() < 4 {
        return Ok(None);
    }
    let plain = r.plain;
    let asked = ask(&case, &plain, profile);
    let mut out = Outcome::default();
    match asked {
        Err(e) => {
            out.refused = Some(e.to_string());
            out.drawable = r.smallest_working()?.is_some();
        }
        Ok(Asked {
            rec,
            d1,
            cut,
            pieces,
        }) => {
            let pass = match &pieces {
                Some((pieces, _)) => DecalPass::Pieces(pieces),
                None => DecalPass::One(&rec.matrix),
            };
            out.by_pieces = pieces.is_some();
            if let (Some(c), Some(tris)) = (&cut, case.cut_ground()) {
                // A mesh decal is built from the triangles the engine draws: over the cut
                // ground, from the cut ground's own (its vertices then share their roundings;
                // cut from the uncut quad's, they would lie on another f32 plane than the base,
                // one corner rounding off it that neither mesh's own vertex term counts).
                let mesh: Option<Vec<Piece>> = case.mesh_decal.then(|| {
                    let pieces = clip_to_square(&tris, case.decal_square(1.0));
                    vec![(pieces.into_iter().flat_map(|(_, p)| p).collect(), c.matrix)]
                });
                let whole = std::mem::replace(&mut r.ground, tris);
                out.lost_cut = match &mesh {
                    Some(pieces) => {
                        // Judged on its own coverage (its edges are not the other decal's).
                        let own = r.coverage_through(&pieces[0].0, None)?;
                        let mask = std::mem::replace(&mut r.mask, own);
                        let lost = r.lost_offset(DecalPass::Pieces(pieces), None);
                        r.mask = mask;
                        lost?.hit
                    }
                    None => r.lost(&c.matrix)?.hit,
                };
                out.cut_drawn = true;
                r.ground = whole;
            }
            let steps = |m: &[f32; 16]| f64::from(steps_between(&plain, m, case.reversed()).max(1));
            out.over_cut = cut.map(|c| steps(&rec.matrix) / steps(&c.matrix));
            out.steps = steps(&rec.matrix);
            out.lost = r.lost_offset(pass, None)?.hit;
            if !case.reversed() && pieces.is_none() {
                let [factor, units] = rec.polygon_offset;
                let pulled = Some((-factor as f32, -units as f32));
                out.lost_polygon_offset = r.lost_offset(DecalPass::One(&plain), pulled)?.hit;
            }
            out.bled = match &pieces {
                // Each piece over an occluder at its own gap (a sliver's is far larger than
                // its neighbours').
                Some((pieces, gaps)) => {
                    let mut bled = 0;
                    for (piece, &gap) in pieces.iter().zip(gaps) {
                        let one = DecalPass::Pieces(std::slice::from_ref(piece));
                        bled += r.bled_scaled(one, gap, d1)?.map_or(0, |c| c.hit);
                    }
                    bled
                }
                None if case.ground == Ground::Hills => {
                    r.bled_scaled(pass, rec.bleed_gap, d1)?.map_or(0, |c| c.hit)
                }
                None => r.bled(pass, rec.bleed_gap, d1)?.map_or(0, |c| c.hit),
            };
            out.gap_over_distance = rec.bleed_gap / d1;
            out.terms = Some(rec.terms);
            let steps = steps_between(&plain, &rec.matrix, case.reversed());
            // Piece by piece there is no one offset to compare with the smallest working one.
            out.ratio = match pieces {
                Some(_) => None,
                None => r
                    .smallest_working()?
                    .map(|k| f64::from(steps) / f64::from(k.max(1))),
            };
        }
    }
    Ok(Some(out))
}
