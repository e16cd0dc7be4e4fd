//! Shadow maps placed as engines place them: tiles of a shadow atlas under `glDepthRange`
//! sub-ranges, and whole scenes far from the world's origin in f32 world positions. zshift is
//! told the placement (`ShadowMap::pipeline`, `world_reach`); every answer must show 0 acne
//! pixels, with both profiles, for the bound over the limit angle and for the ground listed.
//! Without bias the same maps show acne (the checks can fail).

use super::*;
use zshift::shadow::{ShadowBias, ShadowMap};

/// zshift's bias for `map`: the bound over the limit angle, or with the ground listed.
fn ask(
    map: &ShadowMap,
    receivers: bool,
    ground: &[zshift::glam::Vec3],
) -> zshift::Result<ShadowBias> {
    if receivers {
        shadow_bias_for_receivers(map, &[ground])
    } else {
        shadow_bias(map)
    }
}

/// One drawn case: what its lookups need.
struct Looker<'a> {
    gl: &'a mut Gl,
    rig: &'a Rig,
    eye: [f64; 3],
    camera: &'a M4,
    light: &'a Light,
    truth: &'a [Option<bool>],
    /// The map drawn without bias (what `Rig::look_biased` needs beside the biased one).
    unbiased: glow::Texture,
}

impl Looker<'_> {
    /// The camera's count with `case`'s map drawn under `bias`'s `glPolygonOffsetClamp`.
    fn look(&mut self, case: &Case, bias: &ShadowBias) -> Count {
        self.look_with(case, CasterBias::of(bias), ReceiverBias::default())
    }

    /// [`Looker::look_judged`] against the case's own reference.
    fn look_with(&mut self, case: &Case, caster: CasterBias, receiver: ReceiverBias) -> Count {
        let truth = self.truth;
        self.look_judged(case, caster, receiver, truth)
    }

    /// The camera's count with `case`'s map drawn under `caster` and looked up with `receiver`,
    /// judged against `truth`.
    fn look_judged(
        &mut self,
        case: &Case,
        caster: CasterBias,
        receiver: ReceiverBias,
        truth: &[Option<bool>],
    ) -> Count {
        count(&self.look_pixels(case, caster, receiver), truth)
    }

    /// The camera's pixels with `case`'s map drawn under `caster` and looked up with
    /// `receiver`, for [`count`] against one reference or several.
    fn look_pixels(
        &mut self,
        case: &Case,
        caster: CasterBias,
        receiver: ReceiverBias,
    ) -> Vec<[u8; 2]> {
        unsafe {
            self.rig.look_biased(
                self.gl,
                case,
                self.light,
                self.camera,
                self.unbiased,
                caster,
                receiver,
            )
        }
        .unwrap_or_else(|e| panic!("{e}"))
    }
}

/// One answer, for a sweep's own figures: the case, the profile's name, the map asked, whether
/// the ground (`ground`, in the light's view) was listed, the bias and its count.
struct Answer<'a> {
    case: &'a Case,
    profile: &'a str,
    map: &'a ShadowMap,
    receivers: bool,
    ground: &'a [zshift::glam::Vec3],
    bias: &'a ShadowBias,
    got: Count,
}

/// Draws every case, asks zshift with both profiles, by the bound and with the ground listed,
/// for each light pipeline `views` names (`false`: from `world_reach` alone; `true`: the
/// light's view matrix and world box), counts acne and hands each answer to `each`. Asserts
/// 0 acne in every answer, more answers than cases and some acne without bias; returns the
/// answers and refusals.
fn sweep(
    what: &str,
    cases: &[Case],
    views: &[bool],
    mut each: impl FnMut(&mut Looker, &Answer),
) -> (usize, usize) {
    let mut gl = Gl::new(Profile::Core)
        .unwrap_or_else(|e| panic!("no GL context for the shadow sweep ({what}): {e}"));
    let probed = gl_common::probed(&gl);
    let rig = unsafe { Rig::new(&gl) }.unwrap_or_else(|e| panic!("{e}"));
    let verbose = std::env::var("ZSHIFT_SHADOW_VERBOSE").is_ok_and(|v| v == "1");
    let (eye, camera) = camera();
    let (mut failures, mut answered, mut refused, mut unbiased_acne) = (Vec::new(), 0, 0, 0);
    for case in cases {
        let light = light_of(case);
        let truth = reference(case, &light, &camera, eye, case.kernel_reach());
        let unbiased = unsafe { rig.map(&mut gl, case, &light, CasterBias::default()) }
            .unwrap_or_else(|e| panic!("{e}"));
        let plain = unsafe {
            rig.look(
                &mut gl,
                case,
                &light,
                &camera,
                unbiased.0,
                ReceiverBias::default(),
            )
        }
        .unwrap_or_else(|e| panic!("{e}"));
        unbiased_acne += count(&plain, &truth).acne;
        let ground = light.ground_quad();
        let mut looker = Looker {
            gl: &mut gl,
            rig: &rig,
            eye,
            camera: &camera,
            light: &light,
            truth: &truth,
            unbiased: unbiased.0,
        };
        for (pname, profile) in [
            ("worst", RasterizerProfile::worst_case()),
            ("probed", probed),
        ] {
            for receivers in [false, true] {
                for &view in views {
                    let limit = if receivers {
                        RECEIVER_LIMIT_DEG
                    } else {
                        90.0 - case.elevation
                    };
                    let pipeline = if view {
                        light.pipeline()
                    } else {
                        Default::default()
                    };
                    let map = case.shadow_map(&light, limit, profile, pipeline);
                    let name = format!(
                        "{} shift {:?} ({pname}{}{})",
                        case.label(),
                        case.shift,
                        if receivers { ", receivers" } else { "" },
                        if view { ", view" } else { "" }
                    );
                    let bias = match ask(&map, receivers, &ground) {
                        Ok(b) => b,
                        Err(e) if e.kind() == ErrorKind::Unresolvable => {
                            refused += 1;
                            continue;
                        }
                        Err(e) => {
                            failures.push(format!("{name}: {e}"));
                            continue;
                        }
                    };
                    answered += 1;
                    let got = looker.look(case, &bias);
                    if verbose {
                        println!(
                            "{name}: acne {}/{} leak {}/{} bias {:?}",
                            got.acne, got.lit, got.leak, got.shadowed, bias.gl_polygon_offset
                        );
                    }
                    if got.acne > 0 {
                        failures.push(format!(
                            "{name}: {} acne pixels of {} lit at {:?}",
                            got.acne, got.lit, bias.gl_polygon_offset
                        ));
                    }
                    let answer = Answer {
                        case,
                        profile: pname,
                        map: &map,
                        receivers,
                        ground: &ground,
                        bias: &bias,
                        got,
                    };
                    each(&mut looker, &answer);
                }
            }
        }
        unsafe {
            gl.glow().delete_framebuffer(unbiased.1);
            gl.glow().delete_texture(unbiased.0);
        }
    }
    println!(
        "{what}: {} scenes, {answered} answers, {refused} refusals, {unbiased_acne} acne pixels without bias",
        cases.len()
    );
    assert!(
        answered > cases.len(),
        "{what}: too few answers: {answered}"
    );
    assert!(
        unbiased_acne > 0,
        "{what}: no acne without bias: the check cannot fail"
    );
    assert!(
        failures.is_empty(),
        "{what}: {} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
    (answered, refused)
}

/// A deterministic sample of the grid's cases (another draw under a seed): both lights, four
/// elevations, three lookups, picked by `stride`.
fn sample(stride: usize, offset: usize) -> Vec<Case> {
    let mut v = Vec::new();
    for kind in [Kind::Directional, Kind::Spot] {
        for elevation in [5.0, 20.0, 45.0, 89.0] {
            for pcf in [1, 0, 3] {
                v.push(case_of(
                    kind,
                    elevation,
                    pcf,
                    (v.len() * stride + offset) % 81,
                ));
            }
        }
    }
    drawn(v)
}

/// The atlas cases: each map a tile of a 4096² atlas (8192² for tiles over 2048) far from its
/// origin (where the rasterizer's plane set-up extrapolates furthest), under a `glDepthRange`
/// sub-range or the full one; the tile placed after a seed's draw, which may change its size.
fn atlas_cases() -> Vec<Case> {
    let ranges = [[0.0, 1.0], [0.25, 0.75], [0.5, 1.0], [0.0, 0.5]];
    sample(29, 5)
        .into_iter()
        .enumerate()
        .map(|(i, mut case)| {
            let res = case.resolution;
            let size = if res > 2048 { 8192 } else { 4096 };
            let origins = [
                [size - res, size - res],
                [size - res, 0],
                [res / 2, size - res],
            ];
            case.atlas = Some(Atlas {
                size,
                origin: origins[i % 3],
                depth_range: ranges[i % 4],
            });
            case
        })
        .collect()
}

/// A shadow atlas: every map a tile far from the atlas's origin, some under a `glDepthRange`
/// sub-range, the lookup reading the tile and comparing against `near + (far − near)·w`;
/// zshift told the tile's origin and the depth range. Printed: the tile's cost, the units
/// against the same map as a texture of its own (in unit window depth).
#[test]
fn atlas_tiles_are_acne_free() {
    let mut cost = Vec::new();
    sweep("shadow atlas", &atlas_cases(), &[true], |_, a| {
        let own_map = ShadowMap {
            pipeline: zshift::model::Pipeline {
                viewport_origin: [0, 0],
                depth_range: [0.0, 1.0],
                ..a.map.pipeline
            },
            ..*a.map
        };
        if let Ok(own) = ask(&own_map, a.receivers, a.ground) {
            let span = a.map.pipeline.span();
            cost.push(a.bias.gl_polygon_offset[1] / (own.gl_polygon_offset[1] * span));
        }
    });
    cost.sort_by(f64::total_cmp);
    println!(
        "the tile's units ÷ the map's own (unit window depth): median {:.3}, max {:.3}",
        cost.get(cost.len() / 2).copied().unwrap_or(f64::NAN),
        cost.last().copied().unwrap_or(f64::NAN)
    );
}

/// The scene far from the world's origin: the ground, the box, the light and the camera moved by
/// 10², 10³, 10⁴ or 10⁵ units (f32 world positions, the light's and the camera's f32 matrices of
/// the moved scene, as an engine with a large world holds them); zshift told the light's
/// position and the scene's origin (`world_reach`), and with the view variants the light's f32
/// view matrix and the moved world box. Printed: what the distance costs in leaked shadow,
/// beside the same scenes at the origin.
#[test]
fn far_from_the_origin_is_acne_free() {
    let cases: Vec<Case> = sample(31, 11)
        .into_iter()
        .enumerate()
        .map(|(i, mut case)| {
            let t = [1e2, 1e3, 1e4, 1e5][i % 4];
            case.shift =
                [[0.8, 0.0, -0.6], [0.0, 1.0, 0.0], [-0.6, 0.1, 0.79]][i % 3].map(|c| c * t);
            case
        })
        .collect();
    // Per distance, probed profile, the bound path, from world_reach alone and with the light's
    // view: shadowed pixels left lit, the same at the origin, shadowed pixels.
    let mut leaks = std::collections::BTreeMap::<u64, [[usize; 3]; 2]>::new();
    sweep(
        "far from the origin",
        &cases,
        &[false, true],
        |looker, a| {
            if a.receivers || a.profile != "probed" {
                return;
            }
            let home = Case {
                shift: [0.0; 3],
                ..*a.case
            };
            let view = a.map.pipeline.view.is_some();
            let pipeline = if view {
                looker.light.pipeline()
            } else {
                Default::default()
            };
            let home_map =
                home.shadow_map(looker.light, a.map.limit_angle_deg, a.map.profile, pipeline);
            let at_home = shadow_bias(&home_map)
                .ok()
                .map(|b| looker.look(&home, &b).leak);
            let t = a.case.shift.iter().map(|c| c * c).sum::<f64>().sqrt();
            let row = &mut leaks
                .entry(10f64.powf(t.log10().round()) as u64)
                .or_default()[usize::from(view)];
            row[0] += a.got.leak;
            row[1] += at_home.unwrap_or(a.got.leak);
            row[2] += a.got.shadowed;
        },
    );
    println!("shadowed pixels left lit, probed (the same scenes at the origin): world_reach alone | the light's view matrix");
    for (t, [scalar, view]) in &leaks {
        let pct = |r: [usize; 3], k: usize| 100.0 * r[k] as f64 / r[2].max(1) as f64;
        println!(
            "  {t:>7}: {:5.1} % ({:4.1} %) | {:5.1} % ({:4.1} %) of {}",
            pct(*scalar, 0),
            pct(*scalar, 1),
            pct(*view, 0),
            pct(*view, 1),
            scalar[2]
        );
    }
}

/// zshift's receiver-side alternatives, applied in the lookup as an engine applies them (the
/// map drawn without bias): the receiver moved toward the light by `along_light` (world units),
/// or along its normal by `along_normal`, each alone. Every finite one must show 0 acne
/// pixels, from the bound over the limit angle and with the ground listed, both profiles,
/// from `world_reach` alone and with the light's view. Printed: the leak each costs beside the
/// caster-side bias's.
#[test]
fn receiver_side_offsets_are_acne_free() {
    let (mut failures, mut checked, mut infinite) = (Vec::new(), 0, 0);
    // Shadowed pixels left lit: caster-side, along the light; (unused); shadowed.
    let mut leak = [0usize; 4];
    sweep(
        "receiver-side offsets",
        &sample(13, 2),
        &[false, true],
        |looker, a| {
            for (what, light, normal) in [
                ("along the light", a.bias.along_light, 0.0),
                ("along the normal", 0.0, a.bias.along_normal),
            ] {
                if !(light.is_finite() && normal.is_finite()) {
                    infinite += 1;
                    continue;
                }
                let receiver = ReceiverBias {
                    along_light: light as f32,
                    along_normal: normal as f32,
                    ..Default::default()
                };
                // A normal offset moves the lookup off the ground, and with it the shadows
                // (normal-offset shadows shift): judged against the lifted points' own shadow.
                let lifted;
                let truth = if normal > 0.0 {
                    let (case, light) = (a.case, looker.light);
                    let reach = case.kernel_reach();
                    lifted =
                        reference_lifted(case, light, looker.camera, looker.eye, reach, normal);
                    &lifted[..]
                } else {
                    looker.truth
                };
                let px = looker.look_pixels(a.case, CasterBias::default(), receiver);
                let got = count(&px, truth);
                checked += 1;
                // The bound covers receivers up to the limit angle it was asked for; under a
                // spot light, ground points farther than the scene's centre see the light at a
                // lower elevation, beyond `90° − elevation` (a seeded draw,
                // `ZSHIFT_SHADOW_SEED=15`, counted five such pixels, 87.8°–88.1° from the
                // normal under a limit of 87.7°, as acne of a normal offset). Acne is judged
                // within the limit; the leak over every pixel. The listed ground is covered at
                // every angle short of edge-on.
                let acne = if a.receivers {
                    got.acne
                } else {
                    let beyond = beyond_limit(
                        a.case,
                        looker.light,
                        looker.camera,
                        looker.eye,
                        a.map.limit_angle_deg,
                    );
                    let within: Vec<Option<bool>> = truth
                        .iter()
                        .zip(beyond)
                        .map(|(&t, b)| if b { None } else { t })
                        .collect();
                    count(&px, &within).acne
                };
                if light > 0.0 {
                    leak[1] += got.leak;
                }
                if acne > 0 {
                    failures.push(format!(
                        "{} ({}{}) {what} {}: {} acne pixels of {}",
                        a.case.label(),
                        a.profile,
                        if a.receivers { ", receivers" } else { "" },
                        light.max(normal),
                        acne,
                        got.lit
                    ));
                }
            }
            leak[0] += a.got.leak;
            leak[3] += a.got.shadowed;
        },
    );
    let pct = |k: usize| 100.0 * leak[k] as f64 / leak[3].max(1) as f64;
    println!(
        "receiver-side offsets: {checked} looked up, {infinite} infinite (none exists); shadowed pixels left lit: caster-side bias {:.1} %, along the light {:.1} % (a normal offset shifts shadows instead)",
        pct(0),
        pct(1)
    );
    assert!(checked > 0, "no receiver-side offset was finite");
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// A disk kernel (`Lookup::Radius`: Poisson-style lookups, each tap reading the texel its point
/// lies in), radius 1.5, 2.5 or 4 texels: 0 acne at zshift's bias, as for the square kernels.
#[test]
fn disk_kernels_are_acne_free() {
    let cases: Vec<Case> = sample(17, 7)
        .into_iter()
        .enumerate()
        .map(|(i, mut case)| {
            case.radius = [1.5, 2.5, 4.0][i % 3];
            case
        })
        .collect();
    sweep("disk kernels", &cases, &[false, true], |_, _| {});
}
