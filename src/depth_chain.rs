//! The f32 arithmetic by which a rasterizer turns a facing vertex's eye depth into the value it
//! stores, when that arithmetic can be identified: then a decal facing the camera over a base
//! with the same f32 z needs exactly the offset this module computes, no bound at all.
//!
//! A plane facing the camera whose every corner (base and decal) has one f32 eye-space z is drawn
//! at one depth: its window-depth plane is constant, and every pixel stores what the vertices
//! compute. That value is a short chain of f32 operations — `clip_z = m10·z + m14` (two roundings,
//! or one fused), `ndc = clip_z / w` (a division, or a reciprocal and a product), the viewport
//! map `ndc·s + t` (two roundings or one fused), and for a UNORM buffer the conversion to an
//! integer. The probe ([`crate::probe`]) draws 256 facing planes per mode at several offsets and
//! keeps the one [`DepthChain`] of the candidates here that reproduces every stored value it
//! read, bit for bit; on Mesa llvmpipe that is two roundings, a reciprocal and a product, two
//! roundings, and `round-half-even(fl(w·(2^m − 1)))`. With it, the smallest number of f32 steps of
//! the offset element that puts the decal's stored depth past the base's is computed here
//! exactly ([`steps_to_pass`]), where [`crate::profile::RasterizerProfile::facing_quanta`] can
//! only give the worst of the probe's 256 phases.

use crate::projection::ClipDepth;

/// One candidate chain. See the module docs; `code` packs the four choices for the C ABI.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DepthChain {
    /// `clip_z = m10·z + m14` as one fused multiply-add (else a product and a sum).
    pub fused_clip: bool,
    /// `ndc = clip_z·(1/w)` (else `clip_z / w`).
    pub reciprocal: bool,
    /// The viewport map `ndc·s + t` as one fused multiply-add (else a product and a sum).
    pub fused_viewport: bool,
    /// How a UNORM buffer of `m` bits converts window depth `w` to its integer.
    pub conversion: Conversion,
}

/// The conversion of an f32 window depth `w` to an `m`-bit UNORM value.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Conversion {
    /// `round-half-even(fl(w·(2^m − 1)))`: the product in f32, then the integer nearest it.
    F32NearestEven,
    /// `round(w·(2^m − 1))` in exact arithmetic (f64 holds the product of an f32 and a 32-bit
    /// integer exactly), ties away from zero.
    ExactNearest,
    /// `⌊fl(w·(2^m − 1)) + ½⌋` in f32.
    F32HalfUp,
}

impl DepthChain {
    /// Every candidate the probe tries, in a fixed order (their index is [`DepthChain::code`]).
    pub fn candidates() -> impl Iterator<Item = DepthChain> {
        (0..24).map(|code| DepthChain::from_code(code).expect("codes 0..24 are candidates"))
    }

    /// The chain with index `code` in [`DepthChain::candidates`] (the C ABI's
    /// `ZshiftProfile.facing_chain`), `None` outside `0..24`.
    pub fn from_code(code: i32) -> Option<DepthChain> {
        if !(0..24).contains(&code) {
            return None;
        }
        let conversion = match code / 8 {
            0 => Conversion::F32NearestEven,
            1 => Conversion::ExactNearest,
            _ => Conversion::F32HalfUp,
        };
        Some(DepthChain {
            fused_clip: code & 1 != 0,
            reciprocal: code & 2 != 0,
            fused_viewport: code & 4 != 0,
            conversion,
        })
    }

    /// This chain's index in [`DepthChain::candidates`].
    pub fn code(self) -> i32 {
        let conversion = match self.conversion {
            Conversion::F32NearestEven => 0,
            Conversion::ExactNearest => 1,
            Conversion::F32HalfUp => 2,
        };
        8 * conversion
            + i32::from(self.fused_clip)
            + 2 * i32::from(self.reciprocal)
            + 4 * i32::from(self.fused_viewport)
    }

    /// The f32 window depth of eye depth `z` (negative) through `m10`, `m14` (`w_clip = −z`) and
    /// the viewport map of `clip` (`½·ndc + ½`, or `ndc·1 + 0`).
    pub fn window_depth(self, clip: ClipDepth, m10: f32, m14: f32, z: f32) -> f32 {
        let clip_z = if self.fused_clip {
            m10.mul_add(z, m14)
        } else {
            m10 * z + m14
        };
        let w = -z;
        let ndc = if self.reciprocal {
            clip_z * (1.0 / w)
        } else {
            clip_z / w
        };
        let (scale, shift) = match clip {
            ClipDepth::NegOneToOne => (0.5f32, 0.5f32),
            _ => (1.0, 0.0),
        };
        if self.fused_viewport {
            ndc.mul_add(scale, shift)
        } else {
            ndc * scale + shift
        }
    }

    /// The value an `bits`-bit UNORM buffer stores for window depth `w` (clamped to [0, 1]), as
    /// an integer; for `bits == 0` (D32F) the f32's own value.
    pub fn stored(self, bits: u32, w: f32) -> f64 {
        let w = w.clamp(0.0, 1.0);
        if bits == 0 {
            return f64::from(w);
        }
        let top = (2f64.powi(bits as i32) - 1.0) as f32;
        match self.conversion {
            Conversion::F32NearestEven => f64::from((w * top).round_ties_even()),
            Conversion::ExactNearest => (f64::from(w) * f64::from(top)).round(),
            Conversion::F32HalfUp => f64::from((w * top + 0.5).floor()),
        }
    }
}

/// The smallest number of f32 steps of the offset element — element 10 toward 0 under `[−1, 1]`
/// and `[0, 1]`, element 14 away from 0 under reversed Z — after which a facing decal at eye depth
/// `z` stores a depth that passes the strict test (`GL_LESS`, `GL_GREATER` reversed) over its base
/// drawn with `m10`, `m14`, under `chain`, in a buffer of `bits` UNORM bits (0: D32F). `None` if
/// none does within `limit` steps. Every operation of the chain is monotone in the stepped
/// element, so the search bisects.
pub fn steps_to_pass(
    chain: DepthChain,
    clip: ClipDepth,
    bits: u32,
    (m10, m14): (f32, f32),
    z: f32,
    limit: u32,
) -> Option<u32> {
    let reversed = clip == ClipDepth::ReversedZeroToOne;
    let stored = |k: u32| {
        let (a, b) = stepped((m10, m14), reversed, k)?;
        Some(chain.stored(bits, chain.window_depth(clip, a, b, z)))
    };
    let base = stored(0)?;
    let passes = |k: u32| stored(k).is_some_and(|s| if reversed { s > base } else { s < base });
    if !passes(limit) {
        return None;
    }
    let (mut lo, mut hi) = (0, limit);
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if passes(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    Some(hi)
}

/// `(m10, m14)` with the offset element moved `k` f32 steps: element 10 toward 0, or under reversed
/// Z element 14 away from 0 (both keep their sign: `None` if the step would cross zero or
/// overflow).
pub fn stepped((m10, m14): (f32, f32), reversed: bool, k: u32) -> Option<(f32, f32)> {
    if reversed {
        let bits = m14.to_bits().checked_add(k)?;
        let moved = f32::from_bits(bits);
        (moved.is_finite() && m14 > 0.0).then_some((m10, moved))
    } else {
        let bits = m10.to_bits();
        // Toward 0: the magnitude's bits shrink (sign bit kept).
        let magnitude = (bits & 0x7FFF_FFFF).checked_sub(k)?;
        Some((f32::from_bits((bits & 0x8000_0000) | magnitude), m14))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_round_trip_and_stay_in_range() {
        for (i, chain) in DepthChain::candidates().enumerate() {
            assert_eq!(chain.code(), i as i32);
            assert_eq!(DepthChain::from_code(chain.code()), Some(chain));
        }
        assert_eq!(DepthChain::from_code(-1), None);
        assert_eq!(DepthChain::from_code(24), None);
    }

    /// The chain's window depth is within a few f32 roundings of the exact one, and the steps it
    /// finds pass while one fewer does not.
    #[test]
    fn steps_are_the_smallest_that_pass() {
        let chain = DepthChain::from_code(2).unwrap();
        let (n, f) = (0.1f64, 1000.0f64);
        let m10 = (-(f + n) / (f - n)) as f32;
        let m14 = (-2.0 * f * n / (f - n)) as f32;
        for i in 1..200 {
            let z = -(0.11 * 1.04f64.powi(i)) as f32;
            let exact =
                0.5 * (f64::from(m10) * f64::from(z) + f64::from(m14)) / -f64::from(z) + 0.5;
            let w = chain.window_depth(ClipDepth::NegOneToOne, m10, m14, z);
            assert!((f64::from(w) - exact).abs() < 4e-7, "{w} vs {exact}");
            for bits in [0, 16, 24] {
                let k = steps_to_pass(chain, ClipDepth::NegOneToOne, bits, (m10, m14), z, 4096)
                    .expect("passes within the limit");
                let at = |k| {
                    let (a, b) = stepped((m10, m14), false, k).unwrap();
                    chain.stored(bits, chain.window_depth(ClipDepth::NegOneToOne, a, b, z))
                };
                assert!(
                    at(k) < at(0) && at(k - 1) >= at(0),
                    "z {z}, {bits} bits: k {k}"
                );
            }
        }
    }

    #[test]
    fn stepping_moves_the_right_element_the_right_way() {
        let (a, b) = stepped((-1.5, -0.2), false, 3).unwrap();
        assert!(a > -1.5 && a < 0.0 && b == -0.2);
        let (a, b) = stepped((0.01, 0.1), true, 3).unwrap();
        assert!(b > 0.1 && a == 0.01);
        assert_eq!(stepped((-1.0e-45, -0.2), false, 2), None);
    }
}
