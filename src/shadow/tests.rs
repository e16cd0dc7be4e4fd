//! Unit tests of the shadow-map bias: the storage term, the footprint and slope factor per
//! kernel, reversed Z, the refusal, spot lights, the light's pipeline, atlas tiles, and listed
//! receivers and meshes.

use super::*;

fn ground_map(lookup: Lookup, angle: f64) -> ShadowMap {
    ShadowMap {
        light: LightProjection::Orthographic(Ortho::new(-8.0, 8.0, -8.0, 8.0, 2.0, 30.0).unwrap()),
        clip: ClipDepth::NegOneToOne,
        resolution: [1024, 1024],
        format: DepthFormat::Unorm24,
        lookup,
        limit_angle_deg: angle,
        receiver_depths: [2.0, 30.0],
        world_reach: 0.0,
        elevation_deg: 90.0 - angle,
        profile: RasterizerProfile::worst_case(),
        pipeline: crate::model::Pipeline::default(),
    }
}

/// A measured profile whose conversion the probe identified stores D16 within half a
/// quantum (plus the f32 product's rounding): the storage term halves; without the chain, or
/// with the worst case, it stays a whole quantum; D32F has no conversion to halve.
#[test]
fn an_identified_conversion_halves_the_storage_term() {
    let q16 = 1.0 / 65_535.0;
    let chain = crate::depth_chain::DepthChain {
        fused_clip: false,
        reciprocal: true,
        fused_viewport: false,
        conversion: crate::depth_chain::Conversion::F32NearestEven,
    };
    let measured = RasterizerProfile {
        measured: true,
        facing_chain: Some(chain),
        ..RasterizerProfile::worst_case()
    };
    let d16 = ShadowMap {
        format: DepthFormat::Unorm16,
        ..ground_map(Lookup::Nearest, 60.0)
    };
    let worst = shadow_bias(&d16).unwrap().terms.quantum;
    assert!((worst - q16).abs() < 1e-12 * q16, "{worst}");
    let probed = shadow_bias(&ShadowMap {
        profile: measured,
        ..d16
    })
    .unwrap()
    .terms
    .quantum;
    assert!(probed >= 0.5 * q16 && probed <= 0.5 * q16 + U, "{probed}");
    let unidentified = RasterizerProfile {
        facing_chain: None,
        ..measured
    };
    let kept = shadow_bias(&ShadowMap {
        profile: unidentified,
        ..d16
    })
    .unwrap()
    .terms
    .quantum;
    assert_eq!(kept, worst);
    // Receivers off the near plane, where D32F's polygon-offset unit does not vanish.
    let d32f = ShadowMap {
        format: DepthFormat::Float32,
        receiver_depths: [3.0, 30.0],
        ..d16
    };
    let float = shadow_bias(&d32f).unwrap().terms.quantum;
    let measured_float = shadow_bias(&ShadowMap {
        profile: measured,
        ..d32f
    })
    .unwrap()
    .terms
    .quantum;
    assert_eq!(measured_float, float);
}

/// The slope factor is `2a`; the footprint at the limit is `a·tan θ·σ/(f − n)` (computed
/// here from the texel geometry, not from the code); the constant holds the quantum.
#[test]
fn footprint_and_factor_follow_the_kernel() {
    for (lookup, a) in [
        (Lookup::Nearest, 0.5),
        (Lookup::Hardware2x2, 1.0),
        (Lookup::Pcf(3), 1.5),
        (Lookup::Radius(2.0), 2.5),
    ] {
        let map = ground_map(lookup, 60.0);
        let bias = shadow_bias(&map).unwrap();
        let texel = 16.0 / 1024.0;
        let want = a * 3f64.sqrt() * texel * 2f64.sqrt() / 28.0;
        assert!(
            (bias.terms.footprint - want).abs() < 1e-12 * want,
            "{lookup:?}"
        );
        let factor = 2.0 * a + 1.0 / 256.0; // 8 sub-pixel bits in the worst case
        assert!(f64::from(bias.d3d.slope_scaled) >= factor);
        assert!(f64::from(bias.d3d.slope_scaled) < factor * (1.0 + 1e-6));
        assert!(bias.terms.constant > 1.0 / 16_777_215.0);
        // A few tens of quanta: the caster's interpolation term counts the plane's run
        // from the map's origin (1.4 units of window depth at 60° here).
        assert!(
            bias.terms.constant < 30.0 / 16_777_215.0,
            "{:?}",
            bias.terms
        );
        // The clamp is the constant plus the footprint at the limit.
        let clamp = f64::from(bias.d3d.clamp);
        assert!(clamp >= bias.terms.constant + bias.terms.snap + bias.terms.footprint);
        // Receiver side: along the light, the window bias times f − n.
        let along = (bias.terms.constant + bias.terms.snap + bias.terms.footprint) * 28.0;
        assert!((bias.along_light - along).abs() < 1e-9 * along);
        assert!(bias.along_normal <= bias.along_light && bias.along_normal > 0.0);
        // D3D's integer covers the constant in units of 1/(2^24 − 1).
        assert!(f64::from(bias.d3d.depth_bias) / 16_777_215.0 >= bias.terms.constant);
        assert!(bias.webgpu_depth_bias >= bias.d3d.depth_bias);
    }
}

#[test]
fn reversed_z_flips_the_signs() {
    let mut map = ground_map(Lookup::Nearest, 45.0);
    map.clip = ClipDepth::ReversedZeroToOne;
    map.format = DepthFormat::Float32;
    // Receivers at the far plane have window depth 0, where float's unit vanishes.
    let err = shadow_bias(&map).unwrap_err();
    assert_eq!(
        (err.kind(), err.input().unwrap().0),
        (ErrorKind::Unresolvable, "receiver_near")
    );
    map.receiver_depths = [2.0, 28.0];
    let bias = shadow_bias(&map).unwrap();
    assert!(bias.gl_polygon_offset[0] < 0.0 && bias.gl_polygon_offset[1] < 0.0);
    assert!(bias.d3d.depth_bias < 0 && bias.vulkan[2] < 0.0);
    assert!(bias.along_light > 0.0);
}

/// A grazing limit under a wide kernel at a low resolution: the clamp would span the map's
/// whole depth range, so none is set (as for a spot whose rays graze), the slope factor still
/// covers the footprint, and no receiver-side offset reaches; only rounding terms that span
/// the range are refused.
#[test]
fn a_clamp_spanning_the_depth_range_is_none() {
    let mut map = ground_map(Lookup::Pcf(5), 89.9);
    map.resolution = [64, 64];
    let bias = shadow_bias(&map).unwrap();
    assert!(bias.terms.footprint >= 1.0, "{bias:?}");
    assert_eq!(bias.gl_polygon_offset[2], 0.0);
    assert!(bias.gl_polygon_offset[0] >= 5.0, "{bias:?}");
    assert!(bias.gl_polygon_offset[1] >= 1.0, "{bias:?}");
    assert_eq!((bias.d3d.clamp, bias.vulkan[2]), (0.0, 0.0));
    assert!(bias.along_light.is_infinite() && bias.along_normal.is_infinite());
    assert!(bias.peter_panning.is_infinite());
    // A spot light whose rounding terms span the depth range (D16, f/n 10⁹, receivers at the
    // far end, world coordinates up to 10¹³): refused, naming near/far and the format.
    let mut deep = ground_map(Lookup::Nearest, 30.0);
    deep.light =
        LightProjection::Perspective(Frustum::new(-1e-3, 1e-3, -1e-3, 1e-3, 1e-3, 1e6).unwrap());
    deep.format = DepthFormat::Unorm16;
    deep.receiver_depths = [5e5, 1e6];
    deep.world_reach = 1e13;
    let err = shadow_bias(&deep).unwrap_err();
    assert_eq!(err.kind(), ErrorKind::Unresolvable, "{err}");
    assert!(err.detail().contains("near/far"), "{err}");
    map.limit_angle_deg = 90.0;
    assert_eq!(shadow_bias(&map).unwrap_err().kind(), ErrorKind::Domain);
    map.limit_angle_deg = 30.0;
    map.receiver_depths = [1.0, 30.0];
    let err = shadow_bias(&map).unwrap_err();
    assert_eq!(err.input().unwrap().0, "receiver_near");
    map.receiver_depths = [2.0, 30.0];
    map.lookup = Lookup::Pcf(0);
    assert_eq!(shadow_bias(&map).unwrap_err().input().unwrap().0, "pcf");
}

/// A spot light: the footprint shrinks with the nearest receiver's distance, and a wide
/// cone at a steep limit gets no clamp.
#[test]
fn spot_lights_take_the_ray_angle() {
    let frustum = Frustum::new(-0.5, 0.5, -0.5, 0.5, 1.0, 100.0).unwrap();
    let mut map = ShadowMap {
        light: LightProjection::Perspective(frustum),
        receiver_depths: [10.0, 50.0],
        ..ground_map(Lookup::Nearest, 30.0)
    };
    let near = shadow_bias(&map).unwrap();
    map.receiver_depths = [20.0, 50.0];
    let far = shadow_bias(&map).unwrap();
    assert!((near.terms.footprint / far.terms.footprint - 2.0).abs() < 1e-9);
    map.limit_angle_deg = 60.0; // 60° + atan(0.707) = 95°
    let open = shadow_bias(&map).unwrap();
    assert!(open.terms.footprint.is_infinite());
    assert_eq!(open.d3d.clamp, 0.0);
    assert!(open.along_normal.is_finite() && open.along_light.is_infinite());
}

/// The light's pipeline: with its view matrix and the world box, the f32 view term is the
/// exact per-coordinate one, no larger than the bound from `world_reach` (here far smaller);
/// a zeroed pipeline is the scalar bound; a view without its box is refused by name.
/// A directional light's box and a spot light's frustum over the same receivers.
fn both_lights() -> [LightProjection; 2] {
    let frustum = Frustum::new(-0.5, 0.5, -0.5, 0.5, 1.0, 100.0).unwrap();
    [
        LightProjection::Orthographic(Ortho::new(-8.0, 8.0, -8.0, 8.0, 2.0, 30.0).unwrap()),
        LightProjection::Perspective(frustum),
    ]
}

#[test]
fn the_lights_view_tightens_the_vertex_term() {
    for light in both_lights() {
        let scalar = ShadowMap {
            light,
            world_reach: 25.0,
            receiver_depths: [10.0, 30.0],
            ..ground_map(Lookup::Nearest, 30.0)
        };
        let base = shadow_bias(&scalar).unwrap();
        let mut viewed = scalar;
        viewed.pipeline.view = Some([
            1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, -25.0, 1.0,
        ]);
        viewed.pipeline.world_box = Some([[-8.0, -8.0, -5.0], [8.0, 8.0, 15.0]]);
        viewed.pipeline.eye_first = true;
        let tight = shadow_bias(&viewed).unwrap();
        assert!(tight.terms.lookup < 0.5 * base.terms.lookup, "{light:?}");
        assert!(tight.terms.constant < base.terms.constant);
        let mut boxless = viewed;
        boxless.pipeline.world_box = None;
        assert!(shadow_bias(&boxless)
            .unwrap_err()
            .to_string()
            .contains("world_box"));
    }
}

/// A map in a shadow atlas: a tile far from the atlas's origin extrapolates the caster's
/// plane further (the caster term grows, the quantum does not); `glDepthRange(0.5, 1)`
/// doubles a UNORM quantum in unit window depth, and the clamp, which GL applies to stored
/// depth, is the unit bias times 0.5. Both answered, neither refused.
#[test]
fn an_atlas_tile_and_a_depth_range_are_modelled() {
    for light in both_lights() {
        let map = ShadowMap {
            light,
            receiver_depths: [10.0, 30.0],
            ..ground_map(Lookup::Nearest, 30.0)
        };
        let whole = shadow_bias(&map).unwrap();
        let mut tile = map;
        tile.pipeline.viewport_origin = [3072, 2048];
        let tiled = shadow_bias(&tile).unwrap();
        assert!(tiled.terms.caster > whole.terms.caster, "{light:?}");
        assert_eq!(tiled.terms.quantum, whole.terms.quantum);
        assert_eq!(tiled.terms.footprint, whole.terms.footprint);
        let mut ranged = map;
        ranged.pipeline.depth_range = [0.5, 1.0];
        let half = shadow_bias(&ranged).unwrap();
        assert_eq!(half.terms.quantum, 2.0 * whole.terms.quantum);
        let needed = half.terms.constant + half.terms.snap + half.terms.footprint;
        assert!((half.gl_polygon_offset[2] - 0.5 * needed).abs() <= 1e-6 * needed);
        // Units of the stored r: the unit constant times 0.5, over 2⁻²⁴ (D24).
        let units = half.terms.constant * 0.5 * 16_777_215.0;
        assert!(
            (half.gl_polygon_offset[1] - units.ceil()).abs() <= 1.0,
            "{half:?}"
        );
    }
}

/// A spot light over grazing ground: with the ground listed, the footprint is the ground's
/// own `a·(|gₓ| + |g_y|)` (of its window plane in the map), the clamp is
/// set, and the constant is no larger than the conservative one.
#[test]
fn listed_receivers_take_their_own_plane() {
    let frustum = Frustum::new(-0.5, 0.5, -0.5, 0.5, 1.0, 100.0).unwrap();
    let map = ShadowMap {
        light: LightProjection::Perspective(frustum),
        receiver_depths: [10.0, 50.0],
        ..ground_map(Lookup::Nearest, 80.0)
    };
    let conservative = shadow_bias(&map).unwrap();
    assert!(conservative.terms.footprint.is_infinite());
    // Ground 3 units below the light, tilted 85° from the axis: y = −3 − z·tan 5°, seen
    // from above (+y), counter-clockwise.
    let y = |z: f32| -3.0 - (-z) * 5f32.to_radians().tan();
    let ground: Vec<glam::Vec3> = [(4.0, -12.0), (12.0, -45.0), (-12.0, -45.0), (-4.0, -12.0)]
        .iter()
        .map(|&(x, z)| glam::Vec3::new(x, y(z), z))
        .collect();
    let bias = shadow_bias_for_receivers(&map, &[&ground]).unwrap();
    let shape = crate::footprint::decal_shape(&frustum, map.clip, map.resolution, &ground).unwrap();
    let own = 0.5 * (shape.footprint.gradient[0].abs() + shape.footprint.gradient[1].abs());
    assert!(bias.terms.footprint >= own && bias.terms.footprint < own * 1.0001);
    assert!(bias.gl_polygon_offset[2] > 0.0 && bias.gl_polygon_offset[2] < 1.0);
    assert!(bias.terms.constant <= conservative.terms.constant);
    assert!(bias.along_light.is_finite() && bias.along_normal <= bias.along_light);
    // Facing away everywhere: skipped, and with nothing left, refused.
    let away: Vec<glam::Vec3> = ground.iter().rev().copied().collect();
    let err = shadow_bias_for_receivers(&map, &[&away]).unwrap_err();
    assert_eq!(err.kind(), ErrorKind::Domain);
    let both = shadow_bias_for_receivers(&map, &[&away, &ground]).unwrap();
    assert_eq!(both, bias);
    // A corner outside the frustum is named.
    let mut wide = ground.clone();
    wide[1].x = 40.0;
    let err = shadow_bias_for_receivers(&map, &[&ground, &wide]).unwrap_err();
    assert!(err.to_string().contains("frustum"), "{err}");
}

/// Two faces of a mesh under an orthographic light (window depth affine in the map, its
/// gradient computed here from three projected corners, both along x): listed together, the
/// constant gains what the flat face's slope term lacks for a run across the steep one,
/// `a·(m_steep·(1 + 2⁻¹⁶) − 2·m_flat)`, over the larger of the two listed alone, and the clamp
/// covers `a·(|gₓ| + |g_y|)` of the steep face on top of the constant; two faces of one slope,
/// or a steep face beyond the kernel's reach, change nothing.
#[test]
fn faces_of_a_mesh_cover_the_spread_of_their_slopes() {
    let map = ground_map(Lookup::Pcf(5), 80.0);
    let [l, r, b, t, n, f] = [-8.0, 8.0, -8.0, 8.0, 2.0, 30.0];
    let texel = |x: f64, y: f64, z: f64| {
        // glOrtho's window position (texels) and window depth of an eye point.
        [
            (x - l) / (r - l) * 1024.0,
            (y - b) / (t - b) * 1024.0,
            (-z - n) / (f - n),
        ]
    };
    // A face of the plane z = z0 + sx·x + sy·y, counter-clockwise seen from the light.
    let face = |x0: f32, sx: f32, sy: f32, z0: f32| -> (Vec<glam::Vec3>, f64) {
        let z = |x: f32, y: f32| z0 + sx * x + sy * y;
        let corners: Vec<glam::Vec3> = [(x0, -1.0), (x0 + 2.0, -1.0), (x0 + 2.0, 1.0), (x0, 1.0)]
            .iter()
            .map(|&(x, y)| glam::Vec3::new(x, y, z(x, y)))
            .collect();
        let p = |c: glam::Vec3| texel(c.x.into(), c.y.into(), c.z.into());
        let (a, b, c) = (p(corners[0]), p(corners[1]), p(corners[3]));
        let gx = (b[2] - a[2]) / (b[0] - a[0]);
        let gy = (c[2] - a[2]) / (c[1] - a[1]);
        (corners, gx.abs().max(gy.abs()))
    };
    let (flat, m_flat) = face(-2.0, 0.05, 0.0, -10.0);
    let (steep, m_steep) = face(0.0, 1.5, 0.0, -10.0);
    let (level, _) = face(2.0, 0.05, 0.0, -10.0);
    let alone = [&flat, &steep].map(|f| shadow_bias_for_receivers(&map, &[f]).unwrap());
    let both = shadow_bias_for_receivers(&map, &[&flat, &steep]).unwrap();
    let larger = alone[0].terms.constant.max(alone[1].terms.constant);
    let a = both.terms.reach;
    let spread = a * (m_steep * (1.0 + 1.0 / 65_536.0) - 2.0 * m_flat);
    assert!(m_steep > 10.0 * m_flat, "{m_steep} {m_flat}");
    let gained = both.terms.constant - larger;
    assert!(
        (gained - spread).abs() <= 1e-9 * spread,
        "{gained} vs {spread}"
    );
    let run = 2.5 * m_steep;
    assert!(
        both.gl_polygon_offset[2] >= larger + run,
        "{:?}",
        both.gl_polygon_offset
    );
    // A steep face far from the flat one in the map (x from 5 to 7: 320 texels off, beyond
    // the 5×5 kernel's reach): its slope does not enter the constant.
    let (far_steep, _) = face(5.0, 1.5, 0.0, -20.0);
    let apart = shadow_bias_for_receivers(&map, &[&flat, &far_steep]).unwrap();
    let far_alone = shadow_bias_for_receivers(&map, &[&far_steep]).unwrap();
    let k = alone[0].terms.constant.max(far_alone.terms.constant);
    assert!(
        (apart.terms.constant - k).abs() <= 1e-12 * k,
        "{} vs {k}",
        apart.terms.constant
    );
    // One slope (to the f32 rounding of the corners): the larger of the two alone.
    let same = shadow_bias_for_receivers(&map, &[&flat, &level]).unwrap();
    let level_alone = shadow_bias_for_receivers(&map, &[&level]).unwrap();
    let k = alone[0].terms.constant.max(level_alone.terms.constant);
    assert!(
        same.terms.constant >= k && same.terms.constant <= k * 1.01,
        "{} vs {k}",
        same.terms.constant
    );
}

/// The lookup term `T + V` against the lookup itself, emulated in f32 as the sweep's shader
/// computes it (`proj * (view * vec4(p, 1))` in GLSL's order, plain and fused, `c.z / c.w`,
/// `·½ + ½` under `[−1, 1]`): the sweep's rig (a 12 × 12 ground at `y = 0`, a spot light 27.2
/// out at 20° elevation looking at the origin, the frustum fitted to the ground and a 2-unit
/// box), f/n 10, 10³ and 10⁵, every convention, the ground listed, the light's view and box
/// given. For 4000 ground points the computed depth is within the term of the ground's exact
/// depth (f64, on the ray through the map position the lookup computed: a lateral error
/// counts as the plane's run). The worst is printed in D24 quanta (`2⁻²⁴`): at f/n 10⁵ under
/// `[0, 1]` the lookup alone errs by about 2 quanta, so an engine's bias below a quantum that
/// leaves such a scene acne-free rests on how its roundings fell (docs/shadows.md).
#[test]
fn the_lookup_term_covers_an_f32_lookup() {
    let (e, a) = (20f64.to_radians(), 30f64.to_radians());
    let h = 72f64.sqrt() + 2.0;
    let pos = [e.cos() * a.cos(), e.sin(), e.cos() * a.sin()].map(|c| c * (2.5 * h + 1.0));
    let view = look_at_origin(pos);
    let to_eye = |p: [f64; 3]| -> [f64; 3] {
        [0, 1, 2].map(|k| (0..3).map(|j| view[4 * j + k] * p[j]).sum::<f64>() + view[12 + k])
    };
    let ground = [
        [-6.0, 0.0, -6.0],
        [6.0, 0.0, -6.0],
        [6.0, 0.0, 6.0],
        [-6.0, 0.0, 6.0],
    ];
    let mut points = ground.to_vec();
    for i in 0..8 {
        let [x, y, z] = [i & 1, (i >> 1) & 1, (i >> 2) & 1].map(|b| b as f64);
        points.push([0.2 + 1.2 * x, 2.0 * y, -0.9 + 0.8 * z]);
    }
    let eye: Vec<[f64; 3]> = points.iter().map(|&p| to_eye(p)).collect();
    let zmax = eye.iter().map(|p| -p[2]).fold(0.0, f64::max);
    let tx = eye.iter().map(|p| p[0].abs() / -p[2]).fold(0.0, f64::max) * 1.01;
    let ty = eye.iter().map(|p| p[1].abs() / -p[2]).fold(0.0, f64::max) * 1.01;
    // Seen from above (+y) the corners run counter-clockwise: −z is "up" in the light's x/y.
    let ccw: Vec<glam::Vec3> = [ground[0], ground[3], ground[2], ground[1]]
        .iter()
        .map(|&p| to_eye(p))
        .map(|p| glam::Vec3::new(p[0] as f32, p[1] as f32, p[2] as f32))
        .collect();
    let view32 = view.map(|v| v as f32);
    let mut next = crate::test_uniform(20);
    for ratio in [10.0, 1e3, 1e5] {
        let f = zmax * 1.02;
        let n = f / ratio;
        let frustum = Frustum::new(-tx * n, tx * n, -ty * n, ty * n, n, f).unwrap();
        for clip in [
            ClipDepth::NegOneToOne,
            ClipDepth::ZeroToOne,
            ClipDepth::ReversedZeroToOne,
        ] {
            let mut map = ShadowMap {
                light: LightProjection::Perspective(frustum),
                clip,
                receiver_depths: [n, f],
                ..ground_map(Lookup::Nearest, 89.9)
            };
            map.pipeline.view = Some(view32);
            map.pipeline.world_box = Some([[-6.0, 0.0, -6.0], [6.0, 2.0, 6.0]]);
            map.pipeline.eye_first = true;
            let listed = shadow_bias_for_receivers(&map, &[&ccw]).unwrap();
            let proj = crate::projection::projection_f64(&frustum, clip).unwrap();
            let proj32 = proj.map(|v| v as f32);
            let (mut worst, mut signed) = (0.0f64, [0.0f64; 2]);
            for _ in 0..4000 {
                let p = [12.0 * next() - 6.0, 0.0, 12.0 * next() - 6.0].map(|c| c as f32);
                for fused in [false, true] {
                    let ev = crate::test_mat_vec_f32(&view32, [p[0], p[1], p[2], 1.0], fused);
                    let c = crate::test_mat_vec_f32(&proj32, ev, fused);
                    let ndc = [c[0] / c[3], c[1] / c[3], c[2] / c[3]];
                    let z = if clip == ClipDepth::NegOneToOne {
                        ndc[2] * 0.5 + 0.5
                    } else {
                        ndc[2]
                    };
                    // The ground's exact depth on the ray through (ndc x, ndc y).
                    let exact = ground_depth_on_ray(&view, &proj, [ndc[0], ndc[1]].map(f64::from));
                    let exact = if clip == ClipDepth::NegOneToOne {
                        exact * 0.5 + 0.5
                    } else {
                        exact
                    };
                    let signed_err = f64::from(z) - exact;
                    signed = [signed[0].min(signed_err), signed[1].max(signed_err)];
                    let err = signed_err.abs();
                    assert!(
                        err <= listed.terms.lookup,
                        "f/n {ratio} {clip:?}: {err:e} beyond the lookup term {:e} at {p:?}",
                        listed.terms.lookup
                    );
                    worst = worst.max(err);
                }
            }
            println!(
                "f/n {ratio:e} {clip:?}: lookup worst {:.2} quanta of 2⁻²⁴ ({:+.2} to {:+.2}), term {:.2}",
                worst * 2f64.powi(24),
                signed[0] * 2f64.powi(24),
                signed[1] * 2f64.powi(24),
                listed.terms.lookup * 2f64.powi(24)
            );
        }
    }
}

/// A right-handed view from `eye` toward the origin, `+y` up (column-major).
fn look_at_origin(eye: [f64; 3]) -> [f64; 16] {
    let norm = |v: [f64; 3]| {
        let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        v.map(|c| c / l)
    };
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let fwd = norm(eye.map(|c| -c));
    let s = norm(cross(fwd, [0.0, 1.0, 0.0]));
    let u = cross(s, fwd);
    let rows = [s, u, fwd.map(|c| -c)];
    let mut m = [0.0; 16];
    for k in 0..3 {
        for j in 0..3 {
            m[4 * j + k] = rows[k][j];
        }
        m[12 + k] = -(0..3).map(|j| rows[k][j] * eye[j]).sum::<f64>();
    }
    m[15] = 1.0;
    m
}

/// NDC depth of the world plane `y = 0` on the ray through NDC `(x, y)` of the exact (f64)
/// `view` and perspective `proj`.
fn ground_depth_on_ray(view: &[f64; 16], proj: &[f64; 16], [x, y]: [f64; 2]) -> f64 {
    // The eye-space ray (x/P₀₀, y/P₁₁, −1) for a symmetric frustum (P₂₀ = P₂₁ = 0).
    let dir = [x / proj[0], y / proj[5], -1.0];
    // World ray: the eye's position and the rotation's transpose.
    let r = |k: usize, j: usize| view[4 * j + k];
    let origin: [f64; 3] = [0, 1, 2].map(|j| -(0..3).map(|k| r(k, j) * view[12 + k]).sum::<f64>());
    let world_dir_y: f64 = (0..3).map(|k| r(k, 1) * dir[k]).sum();
    let d = -origin[1] / world_dir_y; // eye depth: the ray's eye z runs −1 per unit of s
    (-proj[10] * d + proj[14]) / d
}
