//! Writes docs/report.md and the PNG plots under docs/: zshift against every alternative, on the
//! CPU (time per matrix, as ratios), in numbers (error against exact arithmetic over stiff
//! cases), and on a real rasterizer (time per frame and wrong decal pixels, per method).
//!
//! Run it through `scripts/report`, which first runs the criterion benches (`cargo bench --bench
//! cpu`) and builds the C++ GLM harness (benches/cpp/); run alone, it reports whatever timings
//! those left under target/. Not part of CI. Fails, with the reason, if no GL context exists.

mod cpu;
mod gpu;
mod numeric;
mod plots;
mod profile;
mod steps;

use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use indicatif::{ProgressBar, ProgressStyle};
use zshift_harness::{Gl, Profile};

/// Besides zshift's recommendation, δ as multiples of the minimum δ toward the camera (eq. 4.1.9
/// with 002's k): 1× is the corrected textbook bound.
const KS: [f64; 1] = [1.0];

fn main() {
    if let Err(e) = run() {
        eprintln!("report: {e}");
        std::process::exit(1);
    }
}

fn run() -> Result<(), String> {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| root.join("target"));
    let docs = root.join("docs");
    std::fs::create_dir_all(&docs).map_err(|e| format!("creating docs/: {e}"))?;

    let mut timings = cpu::criterion_timings(&target.join("criterion"));
    let rust_json = std::fs::read_to_string(target.join("bench-rust/interleaved.json")).ok();
    if let Some(json) = &rust_json {
        timings.extend(cpu::interleaved_timings(json));
    }
    let glm_bench = target.join("bench-cpp/glm_bench");
    let cpp_json = run_tool(&glm_bench, &["time"], "")?;
    if let Some(json) = &cpp_json {
        timings.extend(cpu::cpp_timings(json));
    }

    let cases = numeric::stiff_cases();
    let glm_m10 = match run_tool(&glm_bench, &["m10"], &numeric::glm_input(&cases))? {
        Some(text) => Some(parse_glm_m10(&text, cases.len())?),
        None => None,
    };
    let mut mesa =
        Gl::new(Profile::Compatibility).map_err(|e| format!("no compatibility GL context: {e}"))?;
    mesa.set_target(8, 8, zshift_harness::DepthFormat::D24)?;
    let bar = progress(cases.len() as u64, "stiff cases (exact arithmetic)");
    let numeric = numeric::evaluate(&cases, &mut mesa, glm_m10.as_deref(), &|| bar.inc(1))?;
    bar.finish();
    let gl_info = format!("{} — {}", mesa.renderer(), mesa.version());
    drop(mesa);

    let mut gl = Gl::new(Profile::Core).map_err(|e| format!("no core GL context: {e}"))?;
    let (probed, figures) = profile::measure(&gl)?;
    let scenes = gpu::scenes();
    let methods = gpu::methods(&KS);
    let bar = progress(
        (scenes.len() * (gpu::ROUNDS + 2)) as u64,
        "GPU scenes × methods (frames)",
    );
    let mut outcomes = Vec::new();
    for scene in &scenes {
        outcomes.extend(gpu::run_scene(&mut gl, scene, &methods, &probed, &|| {
            bar.inc(1)
        })?);
    }
    bar.finish();

    let summary = summarize(&methods, &outcomes);
    let error_png = docs.join("error_vs_time.png");
    plots::error_vs_time(
        &error_png,
        &summary,
        &format!(
            "Decals: error against time per frame ({} scenes, llvmpipe)",
            scenes.len()
        ),
    )?;
    let (n, f) = (0.1, 1e4);
    let curves = steps::curves(n, f, 240);
    let steps_png = docs.join("depth_step.png");
    plots::depth_steps(
        &steps_png,
        &curves,
        &format!("Depth step against distance, n = {n}, f = {f:.0e}"),
    )?;

    let md = markdown(&Report {
        machine: machine(&gl_info),
        timings: &timings,
        cpp_ran: cpp_json.is_some(),
        round_ratios: [
            (cpp_json.as_deref(), "ratio_frustum_to_glm"),
            (cpp_json.as_deref(), "ratio_offset_to_glm_tweak"),
            (rust_json.as_deref(), "ratio_frustum_to_glam"),
            (rust_json.as_deref(), "ratio_offset_to_glam_tweak"),
            (rust_json.as_deref(), "ratio_frustum_to_glm_formula"),
            (rust_json.as_deref(), "ratio_offset_to_glm_formula_tweak"),
        ]
        .map(|(json, key)| json.and_then(|j| cpu::round_ratio(j, key))),
        cases: &cases,
        numeric: &numeric,
        scenes: &scenes,
        outcomes: &outcomes,
        summary: &summary,
        curves: &curves,
        probed: (&probed, &figures),
    });
    std::fs::write(docs.join("report.md"), md).map_err(|e| format!("writing report.md: {e}"))?;
    println!(
        "wrote {}, {}, {}",
        docs.join("report.md").display(),
        error_png.display(),
        steps_png.display()
    );
    Ok(())
}

fn progress(len: u64, what: &str) -> ProgressBar {
    let bar = ProgressBar::new(len);
    bar.set_style(
        ProgressStyle::with_template("{msg:40} [{bar:40}] {pos}/{len} {elapsed}")
            .expect("valid template")
            .progress_chars("=> "),
    );
    bar.set_message(what.to_string());
    bar
}

/// Runs the C++ harness if it was built; `None` if it was not.
fn run_tool(path: &Path, args: &[&str], stdin: &str) -> Result<Option<String>, String> {
    if !path.exists() {
        eprintln!(
            "note: {} not built (scripts/report builds it): no GLM figures",
            path.display()
        );
        return Ok(None);
    }
    let mut child = Command::new(path)
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .map_err(|e| format!("running {}: {e}", path.display()))?;
    child
        .stdin
        .take()
        .expect("piped")
        .write_all(stdin.as_bytes())
        .map_err(|e| e.to_string())?;
    let out = child.wait_with_output().map_err(|e| e.to_string())?;
    if !out.status.success() {
        return Err(format!(
            "{} {args:?} failed: {}",
            path.display(),
            out.status
        ));
    }
    Ok(Some(String::from_utf8_lossy(&out.stdout).into_owned()))
}

/// GLM's float element 10, one C99 hex float per line (first column).
fn parse_glm_m10(text: &str, expected: usize) -> Result<Vec<f32>, String> {
    let values: Vec<f32> = text
        .lines()
        .map(|line| parse_hex_float(line.split_whitespace().next().unwrap_or("")) as f32)
        .collect();
    if values.len() != expected {
        return Err(format!(
            "GLM harness gave {} values, expected {expected}",
            values.len()
        ));
    }
    Ok(values)
}

/// Parses C's `%a` output, e.g. `-0x1.000d1ap+0`.
fn parse_hex_float(s: &str) -> f64 {
    let (sign, s) = match s.strip_prefix('-') {
        Some(rest) => (-1.0, rest),
        None => (1.0, s),
    };
    let s = s.trim_start_matches("0x");
    let (mantissa, exp) = s.split_once('p').unwrap_or((s, "0"));
    let (int, frac) = mantissa.split_once('.').unwrap_or((mantissa, ""));
    let mut value = u64::from_str_radix(int, 16).unwrap_or(0) as f64;
    for (i, c) in frac.chars().enumerate() {
        value += c.to_digit(16).unwrap_or(0) as f64 * 16f64.powi(-(i as i32 + 1));
    }
    sign * value * 2f64.powi(exp.parse().unwrap_or(0))
}

fn machine(gl_info: &str) -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|m| m.trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".into());
    let cores = std::thread::available_parallelism().map_or(0, |n| n.get());
    let kernel = std::fs::read_to_string("/proc/sys/kernel/osrelease").unwrap_or_default();
    let date = command_line("date", &["-u", "+%Y-%m-%d %H:%M UTC"]);
    let rustc = command_line("rustc", &["-V"]);
    let gxx = command_line("g++", &["--version"]);
    format!(
        "- date: {date}\n- CPU: {cpu}, {cores} logical cores available (shared with other jobs)\n\
         - kernel: Linux {}\n- GL: {gl_info} (software rasterizer: no GPU was lent to this run)\n\
         - {rustc}; {gxx}\n",
        kernel.trim()
    )
}

fn command_line(cmd: &str, args: &[&str]) -> String {
    Command::new(cmd)
        .args(args)
        .output()
        .ok()
        .and_then(|o| String::from_utf8(o.stdout).ok())
        .and_then(|s| s.lines().next().map(str::to_string))
        .unwrap_or_else(|| format!("{cmd}: unavailable"))
}

/// Per method over all scenes: mean of the per-scene median frame times, and the error rate
/// (lost + bleed-through pixels over visible + hidden decal pixels).
fn summarize(methods: &[gpu::Method], outcomes: &[gpu::Outcome]) -> Vec<plots::MethodPoint> {
    methods
        .iter()
        .map(|m| {
            let label = m.label();
            let mine: Vec<&gpu::Outcome> = outcomes.iter().filter(|o| o.method == label).collect();
            let ms = mine.iter().map(|o| o.frame_ms).sum::<f64>() / mine.len() as f64;
            let wrong: usize = mine.iter().map(|o| o.lost + o.bleed).sum();
            let total: usize = mine.iter().map(|o| o.visible + o.hidden).sum();
            let lost: usize = mine.iter().map(|o| o.lost).sum();
            let visible: usize = mine.iter().map(|o| o.visible).sum();
            let bleed: usize = mine.iter().map(|o| o.bleed).sum();
            let hidden: usize = mine.iter().map(|o| o.hidden).sum();
            plots::MethodPoint {
                label,
                frame_ms: ms,
                error_pct: 100.0 * wrong as f64 / total.max(1) as f64,
                lost_pct: pct(lost, visible),
                bleed_pct: pct(bleed, hidden),
                scenes_clean: mine.iter().filter(|o| o.lost + o.bleed == 0).count(),
            }
        })
        .collect()
}

struct Report<'a> {
    machine: String,
    timings: &'a [cpu::Timing],
    cpp_ran: bool,
    /// zshift_frustum / GLM, zshift_load_offset_matrix / GLM + tweak (C++), zshift::frustum /
    /// glam, zshift::load_offset_matrix / glam + tweak, and the same two over GLM's formula in
    /// Rust (Rust): medians of per-round ratios.
    round_ratios: [Option<f64>; 6],
    cases: &'a [numeric::Case],
    numeric: &'a [numeric::VariantStats],
    scenes: &'a [gpu::Scene],
    outcomes: &'a [gpu::Outcome],
    summary: &'a [plots::MethodPoint],
    curves: &'a [steps::Curve],
    /// The probe's profile of this context, with its figures.
    probed: (
        &'a zshift::recommend::RasterizerProfile,
        &'a zshift::probe::Figures,
    ),
}

fn find<'a>(t: &'a [cpu::Timing], prefix: &str) -> Option<&'a cpu::Timing> {
    t.iter().find(|x| x.name.starts_with(prefix))
}

fn ratio(t: &[cpu::Timing], a: &str, b: &str) -> String {
    match (find(t, a), find(t, b)) {
        (Some(a), Some(b)) => format!("{:.1}×", a.ns / b.ns),
        _ => "n/a".into(),
    }
}

fn markdown(r: &Report) -> String {
    let mut s = String::new();
    let w = &mut s;
    let _ = writeln!(w, "# zshift: error against run time\n");
    let _ = writeln!(
        w,
        "Generated by `scripts/report` (criterion benches, the C++ GLM harness, then `cargo run \
         --release --example report`). Do not edit by hand.\n\n{}",
        r.machine
    );
    headline(w, r);
    cpu_table(w, r);
    numeric_table(w, r);
    numeric_by_planes(w, r);
    gpu_tables(w, r);
    profile::section(w, r.probed.0, r.probed.1);
    depth_step_table(w, r);
    s
}

fn headline(w: &mut String, r: &Report) {
    let t = r.timings;
    let _ = writeln!(w, "## Headline\n");
    let ns = |name: &str| find(t, name).map_or("n/a".into(), |x| format!("{:.0} ns", x.ns));
    let round = |x: Option<f64>| x.map_or("n/a".into(), |x| format!("{x:.2}×"));
    let _ = writeln!(
        w,
        "- CPU, through the C ABI from C++ (interleaved with GLM; medians of round-by-round \
         ratios): \
         `zshift_frustum` costs {} of GLM's `glm::frustum<float>` and \
         `zshift_load_offset_matrix` {} of `glm::frustum<float>` + the seed's f32 tweak, every \
         element correctly rounded (the offset element outward). Rust API (interleaved, the same \
         way): `zshift::frustum` {} of GLM's `frustum<float>` formula compiled beside it ({} of \
         glam's f32 frustum, which divides three times where GLM divides six), \
         `zshift::load_offset_matrix` {} of that formula + the seed's tweak ({} of glam + the \
         tweak). Recommend + matrix: {} (Rust API), {} (`zshift_recommend_matrix`, C ABI), {} \
         (`zshift_decal_matrix`, the engine's matrix in). On Mesa, zshift + `glLoadMatrixf` costs {} of \
         the seed's `glFrustum` + `glGetFloatv` + tweak + `glLoadMatrixf`.",
        round(r.round_ratios[0]),
        round(r.round_ratios[1]),
        round(r.round_ratios[4]),
        round(r.round_ratios[2]),
        round(r.round_ratios[5]),
        round(r.round_ratios[3]),
        ns("interleaved: zshift recommend + epsilon_matrix"),
        ns("zshift_recommend_matrix (C ABI"),
        ns("zshift_decal_matrix, GLM's matrix in"),
        ratio(
            t,
            "zshift_load_offset_matrix + glLoadMatrixf",
            "seed on Mesa"
        ),
    );
    let seed = r.numeric.first();
    let zs = r.numeric.last();
    if let (Some(seed), Some(zs)) = (seed, zs) {
        let _ = writeln!(
            w,
            "- Numbers, {} stiff cases: the seed's f32 code on Mesa loses the offset entirely in \
             {} cases and delivers less than asked in {} more (element 10 off by up to {:.3e} \
             f32 ulps); zshift loses none and is short in {} (up to {:.2} ulp).",
            r.cases.len(),
            seed.lost,
            seed.short,
            seed.m10_max_ulps,
            zs.lost + zs.short,
            zs.m10_max_ulps
        );
    }
    let pick = |p: &str| r.summary.iter().find(|m| m.label.starts_with(p));
    let _ = writeln!(
        w,
        "- Rasterizer (llvmpipe, {} scenes; wrong pixels = lost + bleed-through, time per frame \
         relative to no offset):",
        r.scenes.len()
    );
    for label in [
        "no offset",
        "zshift matrix, recommended",
        "zshift matrix, δ = 1×",
        "glPolygonOffset(-1, -1)",
        "glPolygonOffset at zshift",
        "eye-space move, recommended",
        "three-pass",
        "stencil",
    ] {
        if let (Some(m), Some(none)) = (pick(label), pick("no offset")) {
            let _ = writeln!(
                w,
                "  - {}: {:.1}% wrong (lost {:.1}%, bleed {:.1}%), clean in {} / {} scenes, \
                 {:.2}× the frame time",
                m.label,
                m.error_pct,
                m.lost_pct,
                m.bleed_pct,
                m.scenes_clean,
                r.scenes.len(),
                m.frame_ms / none.frame_ms
            );
        }
    }
    let _ = writeln!(w);
}

fn cpu_table(w: &mut String, r: &Report) {
    let _ = writeln!(w, "## CPU: time to build one offset projection matrix\n");
    let _ = writeln!(
        w,
        "Case: a 60°×45° `glFrustum`, n = 0.1, f = 1000, decal at Pz = −50, δ = 4 × the \
         minimum δ of a 24-bit buffer (perspective rows: 45°, aspect 1.3937). Medians; the ratio \
         is to zshift's Rust API (criterion) or to zshift's C ABI called from C++ (C++ harness), \
         each within its own harness. The C++ harness (g++ -O2) leaves every matrix whole in \
         memory (GLM's in its own `glm::mat4`, zshift's in the buffer it writes) and interleaves \
         its variants' batches, so a shared machine loads them alike. `cargo bench --bench cpu` \
         reproduces the criterion rows, `cargo bench --bench interleaved` the interleaved Rust \
         rows (timed like the C++ harness) and `target/bench-cpp/glm_bench time` the C++ rows. \
         Read ratios within one harness; criterion's, one variant after another, move most \
         when other jobs share the machine.\n"
    );
    if !r.cpp_ran {
        let _ = writeln!(w, "(The C++ harness was not built: no GLM rows.)\n");
    }
    let _ = writeln!(
        w,
        "| harness | variant | median ns | ratio to zshift in this harness |"
    );
    let _ = writeln!(w, "|---|---|---:|---:|");
    for t in r.timings {
        let base = if t.source.starts_with("C++") {
            find(
                r.timings,
                "zshift_load_offset_matrix (C ABI, called from C++)",
            )
        } else if t.source.starts_with("interleaved") {
            find(r.timings, "interleaved: zshift::load_offset_matrix")
        } else {
            find(r.timings, "zshift::load_offset_matrix")
        };
        let ratio = base.map_or("n/a".into(), |b| format!("{:.3}", t.ns / b.ns));
        let _ = writeln!(w, "| {} | {} | {:.1} | {} |", t.source, t.name, t.ns, ratio);
    }
    let _ = writeln!(w);
}

fn numeric_table(w: &mut String, r: &Report) {
    let _ = writeln!(w, "## Numbers: element 10 against exact arithmetic\n");
    let planes: Vec<&str> = {
        let mut p: Vec<&str> = r.cases.iter().map(|c| c.planes).collect();
        p.dedup();
        p
    };
    let _ = writeln!(
        w,
        "{} cases: planes {}; Pz at the near plane, 1% in, the geometric mean, half way and \
         the far plane; δ = 1× and 4× the minimum of a 24-bit buffer and 1× that of a 16-bit \
         one. Exact reference: `num-rational` from the f64 inputs (T = m10·(1+ε), o = m10·ε). \
         *Lost*: the offset seen by the GPU, x − p (offset element minus the plain element the \
         same code gives the base), is zero or points away from the camera; *short*: \
         |x − p| < |o|. ε error is in ulps of the variant's own ε type (f32 for the seed's \
         code).\n",
        r.cases.len(),
        planes.join(", ")
    );
    let _ = writeln!(
        w,
        "| variant | ε max err (ulp) | element 10 max err (f32 ulp) | median | lost | short | failed |"
    );
    let _ = writeln!(w, "|---|---:|---:|---:|---:|---:|---:|");
    for v in r.numeric {
        let eps = v.eps_max_ulps.map_or("—".into(), sci);
        let _ = writeln!(
            w,
            "| {} | {} | {} | {} | {} / {} | {} / {} | {} |",
            v.name,
            eps,
            sci(v.m10_max_ulps),
            sci(v.m10_median_ulps),
            v.lost,
            v.cases,
            v.short,
            v.cases,
            v.failed
        );
    }
    let _ = writeln!(w);
}

/// Lost + short offsets per plane set, a column per variant.
fn numeric_by_planes(w: &mut String, r: &Report) {
    let _ = writeln!(w, "Offsets lost / short, per plane set:\n");
    let _ = write!(w, "| planes |");
    for v in r.numeric {
        let _ = write!(w, " {} |", v.name);
    }
    let _ = writeln!(w, "\n|---|{}", "---:|".repeat(r.numeric.len()));
    let Some(first) = r.numeric.first() else {
        return;
    };
    for (i, &(planes, _, _, total)) in first.by_planes.iter().enumerate() {
        let _ = write!(w, "| {planes} ({total} cases) |");
        for v in r.numeric {
            let (_, lost, short, _) = v.by_planes[i];
            let _ = write!(w, " {lost} / {short} |");
        }
        let _ = writeln!(w);
    }
    let _ = writeln!(w);
}

fn sci(x: f64) -> String {
    if x.is_finite() && x.abs() < 1e4 {
        format!("{x:.3}")
    } else {
        format!("{x:.3e}")
    }
}

fn gpu_tables(w: &mut String, r: &Report) {
    let _ = writeln!(w, "## Rasterizer: every decal method on the same scenes\n");
    let _ = writeln!(
        w,
        "Mesa llvmpipe (software; no GPU was lent to this run), {s}×{s} pixels, one FBO with a \
         depth-stencil attachment for every method. Each scene: a base plane, {g}×{g} coplanar \
         decals, and an occluder parallel to the plane {gap}% of its distance in front, over \
         the middle third of the decal rows. *Recommended*: `zshift::recommend::recommend` per \
         decal (its corners' depth range, the plane's slope, the format, 256² viewport, \
         `Snapping::Unsnapped` as measured on llvmpipe; facing planes with `exact_depth`), \
         applied as `epsilon_matrix(ε)`, as its `polygon_offset` pair, or as an eye-space move \
         by its `delta_at_far`. *k×min*: δ = k × `min_delta_toward` at the decal's centre \
         depth; its glPolygonOffset equivalent uses units = |m10·ε|/2 · (2^m − 1) (m = 24, \
         also for D32F). \
         Frame = clear, occluder, base, decals, `glFinish`; median of {rounds} frames, \
         interleaved across methods. *Lost*: interior decal pixels away from the occluder \
         that do not show the decal; *bleed*: interior decal pixels under the occluder that \
         show the decal. On llvmpipe a frame of this size is mostly CPU-side driver work per \
         draw call, so differences of a few percent between single-pass methods are near the \
         noise; an extra full-screen pass (three-pass) shows.\n",
        s = gpu::SIZE,
        g = 6,
        gap = gpu::GAP_FRACTION * 100.0,
        rounds = gpu::ROUNDS
    );
    let _ = writeln!(w, "![error against time](error_vs_time.png)\n");
    let _ = writeln!(w, "### Summary over all scenes\n");
    let _ = writeln!(
        w,
        "| method | mean frame ms | × no offset | wrong pixels % | lost % | bleed % | scenes with no wrong pixel |"
    );
    let _ = writeln!(w, "|---|---:|---:|---:|---:|---:|---:|");
    let none = r.summary.first().map_or(1.0, |m| m.frame_ms);
    for m in r.summary {
        let _ = writeln!(
            w,
            "| {} | {:.3} | {:.2} | {:.2} | {:.2} | {:.2} | {} / {} |",
            m.label,
            m.frame_ms,
            m.frame_ms / none,
            m.error_pct,
            m.lost_pct,
            m.bleed_pct,
            m.scenes_clean,
            r.scenes.len()
        );
    }
    let _ = writeln!(w, "\n### Per scene\n");
    for scene in r.scenes {
        let bits = scene.format.bits().min(24);
        let gap = gpu::GAP_FRACTION * scene.distance;
        let step =
            zshift::depth_resolution(scene.n, scene.f, bits, scene.distance).unwrap_or(f64::NAN);
        let _ = writeln!(
            w,
            "**{}** — occluder gap {gap:.3} = {:.1} depth steps of a {bits}-bit buffer at d = {}{}{}\n",
            scene.name,
            gap / step,
            scene.distance,
            match gpu::recommended_bleed_gap(scene) {
                Ok(g) => format!("; zshift's recommended bleed gap (largest over the decals) {g:.3}"),
                Err(e) => format!("; no recommendation: {e}"),
            },
            if gap < step {
                ": the occluder is within one step of the plane, so any offset that keeps the \
                 decal visible must also bleed through it"
            } else {
                ""
            }
        );
        let _ = writeln!(w, "| method | frame ms | lost | bleed |");
        let _ = writeln!(w, "|---|---:|---:|---:|");
        for o in r.outcomes.iter().filter(|o| o.scene == scene.name) {
            let _ = writeln!(
                w,
                "| {} | {:.3} | {} / {} ({:.1}%) | {} / {} ({:.1}%) |",
                o.method,
                o.frame_ms,
                o.lost,
                o.visible,
                pct(o.lost, o.visible),
                o.bleed,
                o.hidden,
                pct(o.bleed, o.hidden)
            );
        }
        let _ = writeln!(w);
    }
}

fn pct(a: usize, b: usize) -> f64 {
    100.0 * a as f64 / b.max(1) as f64
}

fn depth_step_table(w: &mut String, r: &Report) {
    let _ = writeln!(w, "## Depth step against distance, per convention\n");
    let _ = writeln!(
        w,
        "n = 0.1, f = 1e4. UNORM rows: zshift's exact step (`depth_resolution`, Walker's eq. 3 \
         at any d). Float rows: a first-order model, not a rasterizer measurement: the largest of \
         the f32 spacing of the stored window depth w, half the f32 spacing of the NDC value \
         2w − 1 (standard mapping only), both carried to eye space through |dw/dd|, and the \
         f32 spacing of the eye depth d itself. Near d = n the standard D32F row is limited by \
         the NDC value near −1; at d = f the reversed-Z rows by the eye depth.\n"
    );
    let _ = writeln!(w, "![depth step](depth_step.png)\n");
    let marks: [f64; 6] = [0.1, 1.0, 10.0, 100.0, 1000.0, 1e4];
    let _ = write!(w, "| convention |");
    for d in marks {
        let _ = write!(w, " d = {d:e} |");
    }
    let _ = writeln!(w);
    let _ = writeln!(w, "|---|{}", "---:|".repeat(marks.len()));
    for c in r.curves {
        let _ = write!(w, "| {} |", c.label);
        for d in marks {
            let (_, step) = c
                .points
                .iter()
                .min_by(|a, b| {
                    (a.0.ln() - d.ln())
                        .abs()
                        .total_cmp(&(b.0.ln() - d.ln()).abs())
                })
                .copied()
                .unwrap_or((d, f64::NAN));
            let _ = write!(w, " {step:.2e} |");
        }
        let _ = writeln!(w);
    }
    let _ = writeln!(w);
}
