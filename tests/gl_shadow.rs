//! Shadow-map acne on a real rasterizer (headless EGL; Mesa llvmpipe in CI): zshift's
//! shadow bias (`zshift::shadow::shadow_bias`) against an exact reference, beside the engines'
//! defaults.
//!
//! Each scene: a 12 × 12 ground (two triangles, world space) with a 1.2 × 2 × 0.8 box standing on
//! it, lit by a directional (orthographic map fitted to the scene) or a spot light (perspective
//! map fitted to it) at 1°–89° elevation, light f/n 10 to 10⁵, maps of 256–2048 texels, D16, D24
//! and D32F under `[−1, 1]`, `[0, 1]` and reversed Z, read by a fragment shader with nearest
//! or 3×3 PCF lookups (manual `texelFetch` comparisons). A camera looks at the ground; for each
//! ground pixel the exact reference (f64: is the point's ray to the light blocked by the box?)
//! says lit or shadowed, and pixels within `a + 1.5` texels (in the map) of a change of that
//! answer are left out (shadow edges). **Acne**: a lit pixel the map darkens (any tap fails).
//! **Leak**: a shadowed pixel the map leaves fully lit (detachment, peter-panning).
//!
//! zshift's bias goes into the map as `glPolygonOffsetClamp(factor, units, clamp)` (its GL
//! output, with the worst-case and the probed profile), the limit angle being the ground's own
//! angle to the light (its axis for a spot); each from `world_reach` alone and with the light's
//! pipeline (its f32 view matrix, the scene's world box, eye-first: both shaders compute
//! `proj * (view * p)`). Every answered scene must show **0 acne pixels**;
//! every refusal must be a scene where bisection finds no acne-free bias below 1 (the map's
//! whole depth range). Bisection over a constant window bias in the lookup (map drawn without
//! bias) gives the smallest acne-free bias; the table prints zshift's bias on the ground ÷ that,
//! and the engines' defaults as `/work/shared/NOTES.md` describes them.
//!
//! Fails (never skips) without GL. `ZSHIFT_SHADOW_SCENES=full` runs every combination (slow);
//! the default a deterministic sample. `--nocapture` prints the table;
//! `ZSHIFT_SHADOW_VERBOSE=1` every scene; `ZSHIFT_SHADOW_SEED=<n>` another draw ([`seed`]);
//! `ZSHIFT_SHADOW_ONLY=<a>&<b>` only the scenes whose label contains every part.
//!
//! `atlas_tiles_are_acne_free`: maps drawn as tiles of a shadow atlas under `glDepthRange`
//! sub-ranges, zshift told the tile's origin and the range. `far_from_the_origin_is_acne_free`:
//! the whole scene 10²–10⁵ units from the world's origin, in f32 world positions.

mod gl_common;
// Receivers other than flat ground (a sphere, a terrain): a test of their own.
#[path = "gl_shadow/receivers.rs"]
mod receivers;

use glow::HasContext;
use zshift::projection::ClipDepth;
use zshift::recommend::RasterizerProfile;
use zshift::shadow::{shadow_bias, shadow_bias_for_receivers};
use zshift::ErrorKind;
// The scene, the rig, the reference and the engines: shared with the demonstration
// (`cargo run --release -p zshift-demo -- --shadows DIR`).
use zshift_harness::draw::Xorshift;
use zshift_harness::shadow_scene::*;
use zshift_harness::{Gl, Profile};

/// The ground's window-depth gradient in the map, per texel (f64, from three ground points).
fn ground_slope(case: &Case, light: &Light) -> f64 {
    let vp = mul(&light.proj, &light.view);
    let n = f64::from(case.resolution);
    let per_ndc = if case.clip == ClipDepth::NegOneToOne {
        0.5
    } else {
        1.0
    };
    let w = |p: [f64; 3]| {
        let c = apply(&vp, p);
        [
            (c[0] / c[3] * 0.5 + 0.5) * n,
            (c[1] / c[3] * 0.5 + 0.5) * n,
            c[2] / c[3] * per_ndc,
        ]
    };
    let (a, b, c) = (w([0.0, 0.0, 0.0]), w([0.5, 0.0, 0.0]), w([0.0, 0.0, 0.5]));
    // Solve z = z0 + gx·x + gy·y through the three.
    let (x1, y1, z1) = (b[0] - a[0], b[1] - a[1], b[2] - a[2]);
    let (x2, y2, z2) = (c[0] - a[0], c[1] - a[1], c[2] - a[2]);
    let det = x1 * y2 - x2 * y1;
    let gx = (z1 * y2 - z2 * y1) / det;
    let gy = (x1 * z2 - x2 * z1) / det;
    gx.abs().max(gy.abs())
}

/// The case of combination `c` in `0..81` of light f/n, map size, format and convention.
fn case_of(kind: Kind, elevation: f64, pcf: u32, c: usize) -> Case {
    use zshift_harness::DepthFormat as F;
    let clips = [
        ClipDepth::NegOneToOne,
        ClipDepth::ZeroToOne,
        ClipDepth::ReversedZeroToOne,
    ];
    Case {
        kind,
        elevation,
        azimuth: AZIMUTH_DEG,
        ratio: [10.0, 1e3, 1e5][c % 3],
        resolution: [256, 1024, 2048][(c / 3) % 3],
        format: [F::D16, F::D24, F::D32F][(c / 9) % 3],
        clip: clips[(c / 27) % 3],
        pcf,
        atlas: None,
        shift: [0.0; 3],
    }
}

/// `ZSHIFT_SHADOW_SEED=<n>`: another draw of the sweep (0, the default, is the grid CI runs):
/// the same classes and picks, each case moved off the grid's values — elevation anywhere
/// between its grid neighbours, any azimuth, light f/n log-uniform in 10–10⁵, maps of 256–4096
/// texels (not only powers of two).
fn seed() -> u64 {
    zshift_harness::draw::seed("ZSHIFT_SHADOW_SEED")
}

/// Moves `case` off the grid's values ([`seed`]).
fn vary(mut case: Case, v: &mut Xorshift) -> Case {
    let (lo, hi) = match case.elevation {
        e if e <= 1.0 => (0.5, 5.0),
        e if e <= 5.0 => (1.0, 20.0),
        e if e <= 20.0 => (5.0, 45.0),
        e if e <= 45.0 => (20.0, 89.0),
        _ => (45.0, 89.5),
    };
    let round = |x: f64, to: f64| (x / to).round() * to;
    case.elevation = round(lo + (hi - lo) * v.unit(), 0.01);
    case.azimuth = round(360.0 * v.unit(), 0.1);
    let ratio = 10f64.powf(1.0 + 4.0 * v.unit());
    let digits = 10f64.powi(ratio.log10().floor() as i32 - 2);
    case.ratio = round(ratio, digits);
    case.resolution = (256.0 * 16f64.powf(v.unit())).round() as u32;
    case
}

/// The grid's `cases`, or with a seed ([`seed`]) another draw of them.
fn drawn(cases: Vec<Case>) -> Vec<Case> {
    let seed = seed();
    let mut draw = Xorshift(0x5EED_5AD0_2026_1126 ^ seed.wrapping_mul(0x9E37_79B9_7F4A_7C15));
    if seed == 0 {
        return cases;
    }
    cases.into_iter().map(|c| vary(c, &mut draw)).collect()
}

/// The grid: every light, elevation and lookup, with a deterministic sample of f/n, map size,
/// format and convention (every combination under `full`); another draw under a seed.
fn cases(full: bool) -> Vec<Case> {
    let mut v = Vec::new();
    let elevations = [1.0, 5.0, 20.0, 45.0, 89.0];
    let mut i = 0usize;
    for kind in [Kind::Directional, Kind::Spot] {
        for &elevation in &elevations {
            for pcf in [1, 0, 3, 5] {
                // The default run: 6 combinations per class for nearest and 3×3 PCF, 3 for the
                // hardware 2×2 comparison and 5×5 PCF.
                let take = if pcf == 1 || pcf == 3 { 6 } else { 3 };
                let combos: Vec<usize> = if full {
                    (0..81).collect()
                } else {
                    (0..take).map(|j| (i * 7 + j * 13) % 81).collect()
                };
                v.extend(combos.into_iter().map(|c| case_of(kind, elevation, pcf, c)));
                i += 1;
            }
        }
    }
    drawn(v)
}

#[derive(Default)]
struct Tally {
    scenes: usize,
    acne_scenes: usize,
    worst_acne: f64,
    leak_sum: f64,
    leak_scenes: usize,
    leak_worst: f64,
    ratios: Vec<f64>,
}

impl Tally {
    fn add(&mut self, c: Count) {
        self.scenes += 1;
        if c.shadowed >= 50 {
            self.leak_scenes += 1;
        }
        let acne = c.acne as f64 / c.lit.max(1) as f64;
        if c.acne > 0 {
            self.acne_scenes += 1;
        }
        self.worst_acne = self.worst_acne.max(acne);
        // Leak counted where the box's shadow covers at least 50 counted pixels.
        let leak = if c.shadowed >= 50 {
            c.leak as f64 / c.shadowed as f64
        } else {
            0.0
        };
        self.leak_sum += leak;
        self.leak_worst = self.leak_worst.max(leak);
    }
    fn row(&self, name: &str) -> String {
        let mut r = self.ratios.clone();
        r.sort_by(f64::total_cmp);
        let med = if r.is_empty() {
            f64::NAN
        } else {
            r[r.len() / 2]
        };
        let max = r.last().copied().unwrap_or(f64::NAN);
        format!(
            "| {name} | {} of {} | {:.2} % | {:.2} % | {:.2} % | {} |",
            self.acne_scenes,
            self.scenes,
            100.0 * self.worst_acne,
            100.0 * self.leak_sum / self.leak_scenes.max(1) as f64,
            100.0 * self.leak_worst,
            if r.is_empty() {
                "—".to_string()
            } else {
                format!("{med:.2} (max {max:.2})")
            }
        )
    }
}

fn tally(tallies: &mut Vec<(String, Tally)>, name: &str, class: &str) -> usize {
    let key = format!("{name} [{class}]");
    match tallies.iter().position(|(k, _)| *k == key) {
        Some(i) => i,
        None => {
            tallies.push((key, Tally::default()));
            tallies.len() - 1
        }
    }
}

#[test]
fn zshift_shadow_bias_is_acne_free_where_it_answers() {
    let mut gl = Gl::new(Profile::Core)
        .unwrap_or_else(|e| panic!("no GL context for the shadow sweep: {e}"));
    let probed = gl_common::probed(&gl);
    let rig = unsafe { Rig::new(&gl) }.unwrap_or_else(|e| panic!("{e}"));
    let full = std::env::var("ZSHIFT_SHADOW_SCENES").is_ok_and(|v| v == "full");
    let verbose = std::env::var("ZSHIFT_SHADOW_VERBOSE").is_ok_and(|v| v == "1");
    // `ZSHIFT_SHADOW_ONLY=<a>&<b>…`: only the scenes whose label contains every part.
    let only = std::env::var("ZSHIFT_SHADOW_ONLY").unwrap_or_default();
    let all: Vec<Case> = cases(full)
        .into_iter()
        .filter(|c| only.split('&').all(|part| c.label().contains(part)))
        .collect();
    let (eye, camera) = camera();
    let mut failures = Vec::new();
    let mut tallies: Vec<(String, Tally)> = Vec::new();
    let mut refusals = 0;
    let mut dominance: std::collections::BTreeMap<String, (usize, usize, Vec<String>)> =
        std::collections::BTreeMap::new();
    let started = std::time::Instant::now();
    for case in &all {
        let light = light_of(case);
        let truth = reference(case, &light, &camera, eye, case.kernel_reach());
        let class = format!(
            "{} {}",
            if case.kind == Kind::Spot {
                "spot"
            } else {
                "directional"
            },
            match case.pcf {
                1 => "nearest",
                0 => "hardware 2x2",
                3 => "PCF 3x3",
                _ => "PCF 5x5",
            }
        );
        let unbiased = unsafe { rig.map(&mut gl, case, &light, CasterBias::default()) }
            .unwrap_or_else(|e| panic!("{e}"));
        let acne_at = |gl: &mut Gl, beta: f64| -> Count {
            let px = unsafe {
                rig.look(
                    gl,
                    case,
                    &light,
                    &camera,
                    unbiased.0,
                    ReceiverBias {
                        beta: beta as f32,
                        ..Default::default()
                    },
                )
            }
            .unwrap_or_else(|e| panic!("{e}"));
            count(&px, &truth)
        };
        // The smallest acne-free constant bias in the lookup (bisection, geometric, below 1).
        let smallest = if acne_at(&mut gl, 0.0).acne == 0 {
            Some(0.0)
        } else {
            let mut hi = 1e-9;
            while acne_at(&mut gl, hi).acne > 0 && hi < 1.0 {
                hi = (hi * 4.0).min(1.0);
            }
            if acne_at(&mut gl, hi).acne > 0 {
                None
            } else {
                let mut lo = hi / 4.0;
                for _ in 0..10 {
                    let mid = (lo * hi).sqrt();
                    if acne_at(&mut gl, mid).acne > 0 {
                        lo = mid
                    } else {
                        hi = mid
                    }
                }
                Some(hi)
            }
        };
        let slope = ground_slope(case, &light);
        let ground_quad = light.ground_quad();
        let mut leaks: Vec<(String, usize)> = Vec::new();
        let light_pipeline = light.pipeline();
        for (pname, profile, receivers, pipeline) in [
            ("worst", RasterizerProfile::worst_case(), false, None),
            ("probed", probed, false, None),
            (
                "worst, receivers",
                RasterizerProfile::worst_case(),
                true,
                None,
            ),
            ("probed, receivers", probed, true, None),
            (
                "worst, view",
                RasterizerProfile::worst_case(),
                false,
                Some(light_pipeline),
            ),
            ("probed, view", probed, false, Some(light_pipeline)),
            (
                "worst, receivers, view",
                RasterizerProfile::worst_case(),
                true,
                Some(light_pipeline),
            ),
            (
                "probed, receivers, view",
                probed,
                true,
                Some(light_pipeline),
            ),
        ] {
            let limit = if receivers {
                RECEIVER_LIMIT_DEG
            } else {
                90.0 - case.elevation
            };
            let map = case.shadow_map(&light, limit, profile, pipeline.unwrap_or_default());
            let t = tally(&mut tallies, &format!("zshift ({pname})"), &class);
            let answer = if receivers {
                shadow_bias_for_receivers(&map, &[&ground_quad])
            } else {
                shadow_bias(&map)
            };
            match answer {
                Ok(bias) => {
                    let [f, u, c] = bias.gl_polygon_offset;
                    let caster = CasterBias {
                        offset: Some((f as f32, u as f32, c as f32)),
                        ..Default::default()
                    };
                    let px = unsafe {
                        rig.look_biased(
                            &mut gl,
                            case,
                            &light,
                            &camera,
                            unbiased.0,
                            caster,
                            ReceiverBias::default(),
                        )
                    }
                    .unwrap_or_else(|e| panic!("{e}"));
                    let got = count(&px, &truth);
                    tallies[t].1.add(got);
                    leaks.push((pname.to_string(), got.leak));
                    let on_ground = {
                        let k = bias.terms.constant + bias.terms.slope_factor * slope;
                        let clamp = c.abs();
                        if clamp > 0.0 {
                            k.min(clamp)
                        } else {
                            k
                        }
                    };
                    if let Some(s) = smallest.filter(|&s| s > 0.0) {
                        tallies[t].1.ratios.push(on_ground / s);
                    }
                    if verbose {
                        println!("{} {pname}: acne {}/{} leak {}/{} bias {on_ground:.3e} smallest {smallest:?}", case.label(), got.acne, got.lit, got.leak, got.shadowed);
                    }
                    if got.acne > 0 {
                        failures.push(format!(
                            "{} ({pname}): {} acne pixels of {} lit at {:?}",
                            case.label(),
                            got.acne,
                            got.lit,
                            bias.gl_polygon_offset
                        ));
                    }
                }
                Err(e) if e.kind() == ErrorKind::Unresolvable => {
                    refusals += 1;
                    if let Some(s) = smallest.filter(|&s| s < 1.0) {
                        failures.push(format!(
                            "{} ({pname}): refused ({e}) but {s:.3e} is acne-free",
                            case.label()
                        ));
                    }
                }
                Err(e) => failures.push(format!("{} ({pname}): {e}", case.label())),
            }
        }
        for engine in engines() {
            let (cb, rb) = engine.biases(case, &light);
            let px = unsafe { rig.look_biased(&mut gl, case, &light, &camera, unbiased.0, cb, rb) }
                .unwrap_or_else(|e| panic!("{e}"));
            let got = count(&px, &truth);
            let t = tally(&mut tallies, engine.name, &class);
            tallies[t].1.add(got);
            // No peer dominates: where the engine is acne-free, zshift's leak (shadowed pixels
            // left lit) must be no larger.
            if got.acne == 0 {
                for (pname, leak) in &leaks {
                    let d = dominance.entry(pname.clone()).or_insert((0, 0, Vec::new()));
                    d.0 += 1;
                    if *leak > got.leak {
                        d.1 += 1;
                        d.2.push(format!(
                            "{} {}: zshift ({pname}) leaks {leak}, {} {}",
                            case.label(),
                            engine.name,
                            engine.name,
                            got.leak
                        ));
                    }
                }
            }
        }
        unsafe {
            gl.glow().delete_framebuffer(unbiased.1);
            gl.glow().delete_texture(unbiased.0);
        }
    }
    tallies.sort_by(|a, b| a.0.cmp(&b.0));
    println!(
        "shadow sweep: {} scenes, {} refusals, {:.1} s on {}",
        all.len(),
        refusals,
        started.elapsed().as_secs_f64(),
        gl.renderer()
    );
    println!("| bias [class] | scenes with acne | worst acne (% of lit) | mean leak (% of shadowed) | worst leak | bias ÷ smallest acne-free (median) |");
    println!("|---|---|---|---|---|---|");
    for (name, t) in &tallies {
        println!("{}", t.row(name));
    }
    println!("no peer dominates? (scene, engine) pairs where the engine is acne-free, and those where zshift leaks more");
    for (pname, (pairs, worse, examples)) in &dominance {
        println!("  zshift ({pname}): {worse} of {pairs} pairs leak more");
        if verbose {
            for e in examples {
                println!("    {e}");
            }
        }
    }
    // Not asserted: zshift leaks more than an acne-free peer in some pairs (docs/shadows.md
    // says where and why); `ZSHIFT_SHADOW_VERBOSE=1` lists them.
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// The atlas cases: a deterministic sample of the grid (another draw under a seed), each map
/// drawn as a tile of a 4096² atlas (8192² for tiles over 2048) far from its origin (where the
/// rasterizer's plane set-up extrapolates furthest), under a `glDepthRange` sub-range or the
/// full one.
fn atlas_cases() -> Vec<Case> {
    let ranges = [[0.0, 1.0], [0.25, 0.75], [0.5, 1.0], [0.0, 0.5]];
    let mut v = Vec::new();
    for kind in [Kind::Directional, Kind::Spot] {
        for elevation in [5.0, 20.0, 45.0, 89.0] {
            for pcf in [1, 0, 3] {
                v.push(case_of(kind, elevation, pcf, (v.len() * 29 + 5) % 81));
            }
        }
    }
    // The tile placed after the draw, which may change the map's size.
    drawn(v)
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
/// sub-range, the lookup reading the tile and comparing against `near + (far − near)·w`.
/// zshift is told the tile's origin and the depth range (`ShadowMap::pipeline`); every answer
/// must show 0 acne pixels, with both profiles, for the bound over the limit angle and for the
/// ground listed. Without bias the same maps show acne (the check can fail).
#[test]
fn atlas_tiles_are_acne_free() {
    let mut gl = Gl::new(Profile::Core)
        .unwrap_or_else(|e| panic!("no GL context for the shadow atlas: {e}"));
    let probed = gl_common::probed(&gl);
    let rig = unsafe { Rig::new(&gl) }.unwrap_or_else(|e| panic!("{e}"));
    let verbose = std::env::var("ZSHIFT_SHADOW_VERBOSE").is_ok_and(|v| v == "1");
    let (eye, camera) = camera();
    let (mut failures, mut asked, mut unbiased_acne) = (Vec::new(), 0, 0);
    let mut cost = Vec::new();
    let cases = atlas_cases();
    for case in &cases {
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
        let ground_quad = light.ground_quad();
        for (pname, profile) in [
            ("worst", RasterizerProfile::worst_case()),
            ("probed", probed),
        ] {
            for receivers in [false, true] {
                let limit = if receivers {
                    RECEIVER_LIMIT_DEG
                } else {
                    90.0 - case.elevation
                };
                let map = case.shadow_map(&light, limit, profile, light.pipeline());
                let ask = |map: &zshift::shadow::ShadowMap| {
                    if receivers {
                        shadow_bias_for_receivers(map, &[&ground_quad])
                    } else {
                        shadow_bias(map)
                    }
                };
                let bias = match ask(&map) {
                    Ok(b) => b,
                    Err(e) if e.kind() == ErrorKind::Unresolvable => continue,
                    Err(e) => {
                        failures.push(format!("{} ({pname}): {e}", case.label()));
                        continue;
                    }
                };
                asked += 1;
                // What the tile costs: the units against the same map as a texture of its own
                // (in stored depth both).
                let alone = Case {
                    atlas: None,
                    ..*case
                };
                let own = ask(&alone.shadow_map(&light, limit, profile, light.pipeline()));
                if let Ok(own) = own {
                    let span = map.pipeline.span();
                    cost.push(bias.gl_polygon_offset[1] / (own.gl_polygon_offset[1] * span));
                }
                let [f, u, c] = bias.gl_polygon_offset;
                let caster = CasterBias {
                    offset: Some((f as f32, u as f32, c as f32)),
                    ..Default::default()
                };
                let px = unsafe {
                    rig.look_biased(
                        &mut gl,
                        case,
                        &light,
                        &camera,
                        unbiased.0,
                        caster,
                        ReceiverBias::default(),
                    )
                }
                .unwrap_or_else(|e| panic!("{e}"));
                let got = count(&px, &truth);
                if verbose {
                    println!(
                        "{} ({pname}{}): acne {}/{} leak {}/{} bias {:?}",
                        case.label(),
                        if receivers { ", receivers" } else { "" },
                        got.acne,
                        got.lit,
                        got.leak,
                        got.shadowed,
                        bias.gl_polygon_offset
                    );
                }
                if got.acne > 0 {
                    failures.push(format!(
                        "{} ({pname}{}): {} acne pixels of {} lit at {:?}",
                        case.label(),
                        if receivers { ", receivers" } else { "" },
                        got.acne,
                        got.lit,
                        bias.gl_polygon_offset
                    ));
                }
            }
        }
        unsafe {
            gl.glow().delete_framebuffer(unbiased.1);
            gl.glow().delete_texture(unbiased.0);
        }
    }
    cost.sort_by(f64::total_cmp);
    println!(
        "shadow atlas: {} tiles, {asked} answers, {unbiased_acne} acne pixels without bias; units ÷ the map's own (unit window depth): median {:.3}, max {:.3}",
        cases.len(),
        cost.get(cost.len() / 2).copied().unwrap_or(f64::NAN),
        cost.last().copied().unwrap_or(f64::NAN)
    );
    assert!(asked > cases.len(), "too few answers: {asked}");
    assert!(
        unbiased_acne > 0,
        "no acne without bias: the check cannot fail"
    );
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// The scene far from the world's origin: the ground, the box, the light and the camera moved by
/// 10², 10³, 10⁴ or 10⁵ units (f32 world positions, the light's and the camera's f32 matrices of
/// the moved scene, as an engine with a large world holds them); zshift told the light's
/// position and the scene's origin (`world_reach`), and with the view variants the light's f32
/// view matrix and the moved world box. Every answer must show 0 acne pixels.
#[test]
fn far_from_the_origin_is_acne_free() {
    let mut gl = Gl::new(Profile::Core)
        .unwrap_or_else(|e| panic!("no GL context for the shadow sweep: {e}"));
    let probed = gl_common::probed(&gl);
    let rig = unsafe { Rig::new(&gl) }.unwrap_or_else(|e| panic!("{e}"));
    let verbose = std::env::var("ZSHIFT_SHADOW_VERBOSE").is_ok_and(|v| v == "1");
    let (eye, camera) = camera();
    let (mut failures, mut asked, mut refused, mut unbiased_acne) = (Vec::new(), 0, 0, 0);
    // Per distance from the origin, probed profile, from world_reach alone and with the light's
    // view matrix: shadowed pixels left lit (leak), the same at the origin, shadowed pixels.
    let mut leaks = std::collections::BTreeMap::<u64, [[usize; 3]; 2]>::new();
    let mut cases = Vec::new();
    for kind in [Kind::Directional, Kind::Spot] {
        for elevation in [5.0, 20.0, 45.0, 89.0] {
            for pcf in [1, 0, 3] {
                cases.push(case_of(kind, elevation, pcf, (cases.len() * 31 + 11) % 81));
            }
        }
    }
    let cases: Vec<Case> = drawn(cases)
        .into_iter()
        .enumerate()
        .map(|(i, mut case)| {
            let t = [1e2, 1e3, 1e4, 1e5][i % 4];
            case.shift =
                [[0.8, 0.0, -0.6], [0.0, 1.0, 0.0], [-0.6, 0.1, 0.79]][i % 3].map(|c| c * t);
            case
        })
        .collect();
    for case in &cases {
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
        let ground_quad = light.ground_quad();
        for (pname, profile) in [
            ("worst", RasterizerProfile::worst_case()),
            ("probed", probed),
        ] {
            for receivers in [false, true] {
                for view in [false, true] {
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
                    let answer = if receivers {
                        shadow_bias_for_receivers(&map, &[&ground_quad])
                    } else {
                        shadow_bias(&map)
                    };
                    let name = format!(
                        "{} shift {:?} ({pname}{}{})",
                        case.label(),
                        case.shift,
                        if receivers { ", receivers" } else { "" },
                        if view { ", view" } else { "" }
                    );
                    let bias = match answer {
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
                    asked += 1;
                    let [f, u, c] = bias.gl_polygon_offset;
                    let caster = CasterBias {
                        offset: Some((f as f32, u as f32, c as f32)),
                        ..Default::default()
                    };
                    let px = unsafe {
                        rig.look_biased(
                            &mut gl,
                            case,
                            &light,
                            &camera,
                            unbiased.0,
                            caster,
                            ReceiverBias::default(),
                        )
                    }
                    .unwrap_or_else(|e| panic!("{e}"));
                    let got = count(&px, &truth);
                    if pname == "probed" && !receivers {
                        // The same scene at the origin, asked and drawn the same way.
                        let home = Case {
                            shift: [0.0; 3],
                            ..*case
                        };
                        let at_home =
                            shadow_bias(&home.shadow_map(&light, limit, profile, pipeline))
                                .ok()
                                .map(|b| {
                                    let [f, u, c] = b.gl_polygon_offset;
                                    let caster = CasterBias {
                                        offset: Some((f as f32, u as f32, c as f32)),
                                        ..Default::default()
                                    };
                                    let px = unsafe {
                                        rig.look_biased(
                                            &mut gl,
                                            &home,
                                            &light,
                                            &camera,
                                            unbiased.0,
                                            caster,
                                            ReceiverBias::default(),
                                        )
                                    }
                                    .unwrap_or_else(|e| panic!("{e}"));
                                    count(&px, &truth).leak
                                });
                        let t = case.shift.iter().map(|c| c * c).sum::<f64>().sqrt();
                        let key = 10f64.powf(t.log10().round()) as u64;
                        let row = &mut leaks.entry(key).or_default()[usize::from(view)];
                        row[0] += got.leak;
                        row[1] += at_home.unwrap_or(got.leak);
                        row[2] += got.shadowed;
                    }
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
                }
            }
        }
        unsafe {
            gl.glow().delete_framebuffer(unbiased.1);
            gl.glow().delete_texture(unbiased.0);
        }
    }
    println!(
        "far from the origin: {} scenes, {asked} answers, {refused} refusals, {unbiased_acne} acne pixels without bias",
        cases.len()
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
    assert!(asked > cases.len(), "too few answers: {asked}");
    assert!(
        unbiased_acne > 0,
        "no acne without bias: the check cannot fail"
    );
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
}
