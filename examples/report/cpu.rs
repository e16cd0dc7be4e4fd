//! The CPU timings: criterion's medians (target/criterion, written by `cargo bench --bench cpu`)
//! and the C++ harness's JSON (GLM and zshift's C ABI called from C++).

use std::path::Path;

/// One timed variant: where it ran, what it is, its median ns per call.
#[derive(Clone, Debug)]
pub struct Timing {
    pub source: &'static str,
    pub name: String,
    pub ns: f64,
}

/// The criterion benches of benches/cpu.rs, with the label the report gives each.
const CRITERION: [(&str, &str, &str); 9] = [
    (
        "offset_matrix",
        "zshift_recommend_epsilon_matrix",
        "zshift recommend + epsilon_matrix (Rust API, slope 1, 1920×1080)",
    ),
    (
        "offset_matrix",
        "zshift_rust",
        "zshift::load_offset_matrix (Rust API)",
    ),
    (
        "offset_matrix",
        "zshift_c_abi",
        "zshift_load_offset_matrix (C ABI, called from Rust)",
    ),
    (
        "offset_matrix",
        "zshift_frustum_plain",
        "zshift::frustum, no offset (Rust API)",
    ),
    (
        "offset_matrix",
        "zshift_frustum_c_abi",
        "zshift_frustum, no offset (C ABI, called from Rust)",
    ),
    (
        "offset_matrix",
        "glam_frustum_plain",
        "glam 0.34 opengl::frustum (f32), no offset",
    ),
    (
        "offset_matrix",
        "glam_frustum_seed_tweak",
        "glam frustum + the seed's f32 tweak",
    ),
    (
        "offset_matrix_on_mesa",
        "seed_glFrustum_glGetFloatv_tweak_glLoadMatrixf",
        "seed on Mesa: glFrustum + glGetFloatv + tweak + glLoadMatrixf",
    ),
    (
        "offset_matrix_on_mesa",
        "zshift_c_abi_glLoadMatrixf",
        "zshift_load_offset_matrix + glLoadMatrixf on Mesa",
    ),
];

/// The criterion medians that exist under `dir` (target/criterion).
pub fn criterion_timings(dir: &Path) -> Vec<Timing> {
    CRITERION
        .iter()
        .filter_map(|&(group, bench, label)| {
            let path = dir.join(group).join(bench).join("new/estimates.json");
            let text = std::fs::read_to_string(path).ok()?;
            let median = &text[text.find("\"median\"")?..];
            Some(Timing {
                source: "criterion (Rust)",
                name: label.to_string(),
                ns: number_after(median, "\"point_estimate\":")?,
            })
        })
        .collect()
}

/// The interleaved Rust timings (benches/interleaved.rs), from its one-line JSON. Names start
/// with "interleaved: " so that the headline finds them apart from criterion's.
pub fn interleaved_timings(json: &str) -> Vec<Timing> {
    [
        (
            "glam_frustum",
            "interleaved: glam 0.34 opengl::frustum (f32), no offset",
        ),
        (
            "glam_frustum_seed_tweak",
            "interleaved: glam frustum + the seed's f32 tweak",
        ),
        (
            "glm_formula_frustum",
            "interleaved: GLM's frustum<float> formula in Rust, no offset",
        ),
        (
            "glm_formula_frustum_seed_tweak",
            "interleaved: GLM's frustum<float> formula in Rust + the seed's f32 tweak",
        ),
        (
            "zshift_frustum",
            "interleaved: zshift::frustum, no offset (Rust API)",
        ),
        (
            "zshift_load_offset_matrix",
            "interleaved: zshift::load_offset_matrix (Rust API)",
        ),
        (
            "zshift_frustum_c_abi",
            "interleaved: zshift_frustum, no offset (C ABI, called from Rust)",
        ),
        (
            "zshift_offset_matrix_c_abi",
            "interleaved: zshift_offset_matrix, the engine's matrix in (C ABI, called from Rust)",
        ),
        (
            "zshift_ortho_c_abi",
            "interleaved: zshift_ortho (C ABI, called from Rust)",
        ),
        (
            "zshift_recommend_epsilon_matrix",
            "interleaved: zshift recommend + epsilon_matrix (Rust API, slope 1, 1920×1080)",
        ),
    ]
    .into_iter()
    .filter_map(|(key, label)| {
        Some(Timing {
            source: "interleaved (Rust)",
            name: label.to_string(),
            ns: number_after(json, &format!("\"{key}\":"))?,
        })
    })
    .collect()
}

/// The C++ harness's timings, from its one-line JSON.
pub fn cpp_timings(json: &str) -> Vec<Timing> {
    let version = json
        .split("\"glm_version\": \"")
        .nth(1)
        .and_then(|s| s.split('"').next())
        .unwrap_or("?");
    [
        (
            "glm_frustum_float",
            format!("GLM {version} glm::frustum<float>, no offset"),
        ),
        (
            "glm_frustum_float_seed_tweak",
            format!("GLM {version} glm::frustum<float> + the seed's f32 tweak"),
        ),
        (
            "glm_frustum_double",
            format!("GLM {version} glm::frustum<double>, no offset"),
        ),
        (
            "zshift_load_offset_matrix_c_abi",
            "zshift_load_offset_matrix (C ABI, called from C++)".to_string(),
        ),
        (
            "zshift_frustum_c_abi",
            "zshift_frustum (C ABI, called from C++), no offset".to_string(),
        ),
        (
            "glm_perspective_float",
            format!("GLM {version} glm::perspective<float>, no offset"),
        ),
        (
            "zshift_perspective_c_abi",
            "zshift_perspective (C ABI, called from C++), no offset".to_string(),
        ),
        (
            "zshift_recommend_matrix_c_abi",
            "zshift_recommend_matrix (C ABI, called from C++; slope 1, 1920×1080)".to_string(),
        ),
        (
            "zshift_decal_matrix_c_abi",
            "zshift_decal_matrix, GLM's matrix in (C ABI, called from C++; slope 1, 1920×1080)"
                .to_string(),
        ),
        (
            "zshift_decal_matrix_planes_8_c_abi",
            "zshift_decal_matrix_planes, 8 planes (C ABI, called from C++; slopes 0–1.75)"
                .to_string(),
        ),
    ]
    .into_iter()
    .filter_map(|(key, label)| {
        Some(Timing {
            source: "C++ harness (g++ -O2)",
            name: label,
            ns: number_after(json, &format!("\"{key}\":"))?,
        })
    })
    .collect()
}

/// A round-by-round ratio the harnesses print (`ratio_*` keys): the median over rounds of the
/// two sides' ratio, steadier than a ratio of medians on a shared machine.
pub fn round_ratio(json: &str, key: &str) -> Option<f64> {
    number_after(json, &format!("\"{key}\":"))
}

fn number_after(text: &str, key: &str) -> Option<f64> {
    let rest = text[text.find(key)? + key.len()..].trim_start();
    let end = rest
        .find(|c: char| !(c.is_ascii_digit() || "+-.eE".contains(c)))
        .unwrap_or(rest.len());
    rest[..end].parse().ok()
}
