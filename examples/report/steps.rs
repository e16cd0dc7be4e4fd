//! Depth step against distance for each depth convention: how far apart two surfaces at eye
//! distance d must be for the depth buffer to store different values.
//!
//! UNORM buffers: zshift's exact step (Walker's eq. 3 generalised, seed 001). Float buffers: a
//! first-order model, the largest of three spacings carried to eye space through `|dw/dd|`:
//! the f32 spacing of the stored window depth `w(d)`; for the standard mapping, half the f32
//! spacing of the NDC value `2w − 1` it is computed from (the [−1, 1] range wastes the
//! precision near 0); and the f32 spacing of the eye depth itself, `ulp(d)`, below which no
//! vertex position can resolve. Window depths: standard `w = f(d−n)/(d(f−n))`, reversed Z with
//! a [0, 1] clip range `w = n(f−d)/(d(f−n))`, reversed Z with an infinite far plane `w = n/d`.

/// One curve: label and (distance, step) points.
pub struct Curve {
    pub label: String,
    pub points: Vec<(f64, f64)>,
}

fn f32_spacing(w: f64) -> f64 {
    let x = (w as f32).abs();
    if x < f32::MIN_POSITIVE {
        return f32::from_bits(1) as f64;
    }
    let e = ((x.to_bits() >> 23) & 0xff) as i32 - 127;
    2f64.powi(e - 23)
}

/// The curves for planes `n`, `f`, at `count` log-spaced distances in [n, f].
pub fn curves(n: f64, f: f64, count: usize) -> Vec<Curve> {
    let ds: Vec<f64> = (0..count)
        .map(|i| n * (f / n).powf(i as f64 / (count - 1) as f64))
        .collect();
    let slope = |d: f64| n * f / (d * d * (f - n));
    let mut out = Vec::new();
    for bits in [16u32, 24] {
        out.push(Curve {
            label: format!("D{bits} UNORM, NDC [-1,1] (exact)"),
            points: ds
                .iter()
                .map(|&d| {
                    (
                        d,
                        zshift::depth_resolution(n, f, bits, d).expect("in range"),
                    )
                })
                .collect(),
        });
    }
    let float =
        |label: &str, standard: bool, w: &dyn Fn(f64) -> f64, dw: &dyn Fn(f64) -> f64| Curve {
            label: label.to_string(),
            points: ds
                .iter()
                .map(|&d| {
                    let mut window = f32_spacing(w(d));
                    if standard {
                        window = window.max(0.5 * f32_spacing(2.0 * w(d) - 1.0));
                    }
                    (d, (window / dw(d)).max(f32_spacing(d)))
                })
                .collect(),
        };
    out.push(float(
        "D32F, NDC [-1,1] (standard)",
        true,
        &|d| f * (d - n) / (d * (f - n)),
        &slope,
    ));
    out.push(float(
        "D32F reversed Z, clip [0,1]",
        false,
        &|d| n * (f - d) / (d * (f - n)),
        &slope,
    ));
    out.push(float(
        "D32F reversed Z, infinite far",
        false,
        &|d| n / d,
        &|d| n / (d * d),
    ));
    out
}
