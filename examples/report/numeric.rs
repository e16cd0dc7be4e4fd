//! Numerical error of each way of building the offset element 10, against exact rational
//! arithmetic (every finite f64 is a rational) over a table of stiff cases.
//!
//! For each case the exact target is `T = m10·(1 + ε)` with `m10 = −(f+n)/(f−n)` and ε from
//! eq. 4.1.7, both from the f64 inputs; the exact offset is `o = m10·ε`. A variant gives an
//! offset element `x` and a plain element `p` (what the base surface is drawn with); the offset
//! the GPU sees is `x − p`. It is *lost* when `x = p`, and *short* when `|x − p| < |o|`.

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};
use zshift_harness::Gl;

#[path = "../../benches/shared/seed.rs"]
mod seed;

type Q = BigRational;

fn q(x: f64) -> Q {
    Q::from_float(x).expect("finite")
}

/// One case: the glFrustum inputs, the decal depth and the requested shift.
#[derive(Clone, Debug)]
pub struct Case {
    pub planes: &'static str,
    pub l: f64,
    pub r: f64,
    pub b: f64,
    pub t: f64,
    pub n: f64,
    pub f: f64,
    pub pz: f64,
    pub delta: f64,
}

/// Planes from ordinary to stiff; depths from the near to the far plane; shifts of 1× and 4×
/// the minimum δ of a 24-bit buffer and 1× that of a 16-bit one (eq. 4.1.9 with 002's k).
pub fn stiff_cases() -> Vec<Case> {
    let planes: [(&'static str, f64, f64); 6] = [
        ("ordinary 0.1..1000", 0.1, 1000.0),
        ("f/n = 1e6", 0.01, 1e4),
        ("f/n = 1e9", 1e-3, 1e6),
        ("f/n = 1 + 1e-6", 1.0, 1.000001),
        ("n = 1e-6, f = 1", 1e-6, 1.0),
        ("large 1e15..1e18", 1e15, 1e18),
    ];
    let mut out = Vec::new();
    for (name, n, f) in planes {
        let depths = [n, n + 0.01 * (f - n), (n * f).sqrt(), 0.5 * (n + f), f];
        for d in depths {
            let pz = -d;
            for (bits, k) in [(24, 1.0), (24, 4.0), (16, 1.0)] {
                let min = zshift::min_delta_toward(n, f, bits, pz).expect("valid case");
                let delta = k * min;
                if pz + delta >= 0.0 {
                    continue;
                }
                out.push(Case {
                    planes: name,
                    l: -0.6 * n,
                    r: 0.6 * n,
                    b: -0.45 * n,
                    t: 0.45 * n,
                    n,
                    f,
                    pz,
                    delta,
                });
            }
        }
    }
    out
}

/// The exact quantities of one case.
struct Exact {
    eps: Q,
    target: Q,
    offset: Q,
}

fn exact(c: &Case) -> Exact {
    let (n, f, pz, d) = (q(c.n), q(c.f), q(c.pz), q(c.delta));
    let m10 = -(&f + &n) / (&f - &n);
    let two = Q::from_integer(BigInt::from(2));
    let eps = -(two * &f * &n / (&f + &n)) * &d / (&pz * (&pz + &d));
    let target = &m10 * (Q::one() + &eps);
    let offset = &m10 * &eps;
    Exact {
        eps,
        target,
        offset,
    }
}

/// What one variant produced for one case.
struct Produced {
    /// ε as the variant computes it, and the ulp of its own type at the exact ε.
    eps: Option<(f64, f64)>,
    plain: f32,
    offset: f32,
}

/// Error statistics of one variant over the table.
#[derive(Clone, Debug, Default)]
pub struct VariantStats {
    pub name: String,
    pub cases: usize,
    /// Cases where the variant produced no finite matrix (or refused).
    pub failed: usize,
    /// Largest |ε − ε_exact| in ulps of the variant's own ε type (f32 or f64).
    pub eps_max_ulps: Option<f64>,
    /// Largest and median |x − T| in f32 ulps of T.
    pub m10_max_ulps: f64,
    pub m10_median_ulps: f64,
    /// Cases where the offset vanished (x = p) or pointed the wrong way.
    pub lost: usize,
    /// Cases where the offset seen, |x − p|, is smaller than the exact |o|.
    pub short: usize,
    /// Per plane set, in table order: (planes, lost, short, cases).
    pub by_planes: Vec<(&'static str, usize, usize, usize)>,
}

impl VariantStats {
    fn tally(&mut self, planes: &'static str, lost: bool, short: bool) {
        if self.by_planes.last().map(|b| b.0) != Some(planes) {
            self.by_planes.push((planes, 0, 0, 0));
        }
        let b = self.by_planes.last_mut().expect("just pushed");
        b.1 += lost as usize;
        b.2 += short as usize;
        b.3 += 1;
    }
}

fn ulp32(x: f64) -> f64 {
    let x = (x as f32).abs();
    if x < f32::MIN_POSITIVE {
        return f32::from_bits(1) as f64;
    }
    let e = ((x.to_bits() >> 23) & 0xff) as i32 - 127;
    2f64.powi(e - 23)
}

fn ulp64(x: f64) -> f64 {
    let x = x.abs();
    if x < f64::MIN_POSITIVE {
        return f64::from_bits(1);
    }
    let e = ((x.to_bits() >> 52) & 0x7ff) as i32 - 1023;
    2f64.powi(e - 52)
}

/// The variants, in table order. `glm` holds GLM's float element 10 per case, if the C++
/// harness ran.
pub fn evaluate(
    cases: &[Case],
    mesa: &mut Gl,
    glm: Option<&[f32]>,
    tick: &dyn Fn(),
) -> Result<Vec<VariantStats>, String> {
    let mut names = vec![
        "seed LoadOffsetMatrix on Mesa (glFrustum f32, f32 ε, f32 tweak)",
        "glam 0.34 f32 frustum + the seed's f32 tweak",
    ];
    if glm.is_some() {
        names.push("GLM 0.9.9 frustum<float> + the seed's f32 tweak");
    }
    names.extend(["naive f64 (all in f64, rounded to f32 once)", "zshift"]);
    let mut stats: Vec<VariantStats> = names
        .iter()
        .map(|n| VariantStats {
            name: n.to_string(),
            ..Default::default()
        })
        .collect();
    let mut m10_errors: Vec<Vec<f64>> = vec![Vec::new(); names.len()];
    for (i, c) in cases.iter().enumerate() {
        let ex = exact(c);
        let mut produced: Vec<Option<Produced>> = Vec::new();
        let seed_eps = seed::seed_epsilon(c.n, c.f, c.delta as f32, c.pz as f32);
        let seed_eps_ulp = ulp32(ex.eps.to_f64().unwrap_or(0.0));
        let tweak = |p: f32| Produced {
            eps: Some((seed_eps as f64, seed_eps_ulp)),
            plain: p,
            offset: seed::seed_tweak(p, seed_eps),
        };
        let mesa_m = mesa.legacy_frustum(c.l, c.r, c.b, c.t, c.n, c.f)?;
        produced.push(Some(tweak(mesa_m[10])));
        let glam_m = glam::camera::rh::proj::opengl::frustum(
            c.l as f32, c.r as f32, c.b as f32, c.t as f32, c.n as f32, c.f as f32,
        );
        produced.push(Some(tweak(glam_m.z_axis.z)));
        if let Some(glm) = glm {
            produced.push(Some(tweak(glm[i])));
        }
        produced.push(Some(naive_f64(c)));
        produced.push(zshift_variant(c));
        for (v, p) in produced.into_iter().enumerate() {
            let s = &mut stats[v];
            s.cases += 1;
            let Some(p) = p.filter(|p| p.offset.is_finite() && p.plain.is_finite()) else {
                s.failed += 1;
                s.tally(c.planes, true, false);
                continue;
            };
            if let Some((eps, ulp)) = p.eps {
                let e = if eps.is_finite() {
                    ((q(eps) - &ex.eps).abs() / q(ulp)).to_f64().unwrap()
                } else {
                    f64::INFINITY
                };
                s.eps_max_ulps = Some(s.eps_max_ulps.unwrap_or(0.0).max(e));
            }
            let target_ulp = ulp32(ex.target.to_f64().unwrap());
            let err = ((q(p.offset as f64) - &ex.target).abs() / q(target_ulp))
                .to_f64()
                .unwrap();
            m10_errors[v].push(err);
            let seen = q(p.offset as f64) - q(p.plain as f64);
            let lost = seen.is_zero() || seen.signum() != ex.offset.signum();
            let short = !lost && seen.abs() < ex.offset.abs();
            s.lost += lost as usize;
            s.short += short as usize;
            s.tally(c.planes, lost, short);
        }
        tick();
    }
    for (s, errs) in stats.iter_mut().zip(&mut m10_errors) {
        errs.sort_by(|a, b| a.total_cmp(b));
        s.m10_max_ulps = errs.last().copied().unwrap_or(f64::NAN);
        s.m10_median_ulps = errs.get(errs.len() / 2).copied().unwrap_or(f64::NAN);
    }
    Ok(stats)
}

/// The textbook formulas in f64, rounded to f32 once at the end.
fn naive_f64(c: &Case) -> Produced {
    let m10 = -(c.f + c.n) / (c.f - c.n);
    let eps = -2.0 * c.f * c.n / (c.f + c.n) * c.delta / (c.pz * (c.pz + c.delta));
    let exact_eps = exact(c).eps.to_f64().unwrap_or(0.0);
    Produced {
        eps: Some((eps, ulp64(exact_eps))),
        plain: m10 as f32,
        offset: (m10 * (1.0 + eps)) as f32,
    }
}

fn zshift_variant(c: &Case) -> Option<Produced> {
    let plain = zshift::frustum(c.l, c.r, c.b, c.t, c.n, c.f).ok()?;
    let m = zshift::load_offset_matrix(c.l, c.r, c.b, c.t, c.n, c.f, c.delta, c.pz).ok()?;
    let eps = zshift::epsilon(c.n, c.f, c.delta, c.pz).ok()?;
    let exact_eps = exact(c).eps.to_f64().unwrap_or(0.0);
    Some(Produced {
        eps: Some((eps, ulp64(exact_eps))),
        plain: plain.z_axis.z,
        offset: m.z_axis.z,
    })
}

/// The inputs as "l r b t n f" lines for the C++ harness's `m10` mode.
pub fn glm_input(cases: &[Case]) -> String {
    cases
        .iter()
        .map(|c| {
            format!(
                "{:e} {:e} {:e} {:e} {:e} {:e}\n",
                c.l, c.r, c.b, c.t, c.n, c.f
            )
        })
        .collect()
}
