//! The argument types: one C type per kind of enumerated argument (clip convention, depth
//! format, depth test, bias API, offset kind), so a C or C++ compiler rejects a call that passes
//! one kind where another is expected, and their conversion to the math modules' types.
//!
//! Each is a one-field struct (passed in a register exactly like the `int32_t` it wraps on
//! x86-64, AArch64 and Win64). The constants are written in the header by hand
//! (`cbindgen.toml`, `after_includes`) as `static const` objects, since cbindgen would spell them
//! as C99 compound literals; `tests/header.rs` checks that they match the Rust ones. An unknown
//! value (a struct filled by hand) is ZSHIFT_ERR_DOMAIN, with the value in the detail.

use crate::error::Result;
use crate::plan::OffsetKind;
use crate::polygon_offset::BiasApi;
use crate::precision::DepthFormat;
use crate::projection::ClipDepth;

/// A clip-space depth convention: ZSHIFT_CLIP_NEG_ONE_TO_ONE, ZSHIFT_CLIP_ZERO_TO_ONE or
/// ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE.
///
/// cbindgen:ignore
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ZshiftClip {
    /// 0, 1 or 2 (the `ZSHIFT_CLIP_*` order).
    pub value: i32,
}

/// A depth attachment's format, by its GL internal format enum: ZSHIFT_FORMAT_UNORM16 (=
/// GL_DEPTH_COMPONENT16), ZSHIFT_FORMAT_UNORM24, ZSHIFT_FORMAT_UNORM32, ZSHIFT_FORMAT_FLOAT32,
/// and the packed depth-stencil formats ZSHIFT_FORMAT_UNORM24_STENCIL8 (GL_DEPTH24_STENCIL8)
/// and ZSHIFT_FORMAT_FLOAT32_STENCIL8 (GL_DEPTH32F_STENCIL8).
///
/// cbindgen:ignore
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ZshiftFormat {
    /// The GL enum (0x81A5, 0x81A6, 0x81A7, 0x8CAC, 0x88F0 or 0x8CAD).
    pub value: u32,
}

/// The depth test the decal pass uses, by its GL enum: ZSHIFT_DEPTH_TEST_LESS (= GL_LESS),
/// ZSHIFT_DEPTH_TEST_LEQUAL, ZSHIFT_DEPTH_TEST_GREATER, ZSHIFT_DEPTH_TEST_GEQUAL.
///
/// cbindgen:ignore
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ZshiftDepthTest {
    /// The GL enum (0x0201, 0x0203, 0x0204 or 0x0206).
    pub value: u32,
}

/// The API whose constant depth bias `zshift_bias_of_shift` speaks: ZSHIFT_BIAS_OPENGL,
/// ZSHIFT_BIAS_DIRECT3D or ZSHIFT_BIAS_VULKAN.
///
/// cbindgen:ignore
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ZshiftBiasApi {
    /// 0, 1 or 2 (the `ZSHIFT_BIAS_*` order).
    pub value: i32,
}

/// Where an offset goes: ZSHIFT_OFFSET_NDC (constant, element 10) or ZSHIFT_OFFSET_RELATIVE
/// (element 14 scaled by 1 + epsilon).
///
/// cbindgen:ignore
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ZshiftOffsetKind {
    /// 0 or 1 (the `ZSHIFT_OFFSET_*` order).
    pub value: i32,
}

/// OpenGL's default NDC depth [-1, 1] (near -1, far +1), depth test GL_LESS.
///
/// cbindgen:ignore
pub const ZSHIFT_CLIP_NEG_ONE_TO_ONE: ZshiftClip = ZshiftClip { value: 0 };
/// NDC depth [0, 1] (near 0, far 1): glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE), Direct3D and
/// Vulkan clip space; depth test GL_LESS.
///
/// cbindgen:ignore
pub const ZSHIFT_CLIP_ZERO_TO_ONE: ZshiftClip = ZshiftClip { value: 1 };
/// Reversed NDC depth [0, 1] (near 1, far 0): glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE),
/// glDepthFunc(GL_GREATER), glClearDepth(0); meant for 32-bit float depth.
///
/// cbindgen:ignore
pub const ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE: ZshiftClip = ZshiftClip { value: 2 };

/// GL_DEPTH_COMPONENT16: 16-bit unsigned normalized.
///
/// cbindgen:ignore
pub const ZSHIFT_FORMAT_UNORM16: ZshiftFormat = ZshiftFormat { value: 0x81A5 };
/// GL_DEPTH_COMPONENT24: 24-bit unsigned normalized.
///
/// cbindgen:ignore
pub const ZSHIFT_FORMAT_UNORM24: ZshiftFormat = ZshiftFormat { value: 0x81A6 };
/// GL_DEPTH_COMPONENT32: 32-bit unsigned normalized.
///
/// cbindgen:ignore
pub const ZSHIFT_FORMAT_UNORM32: ZshiftFormat = ZshiftFormat { value: 0x81A7 };
/// GL_DEPTH_COMPONENT32F: 32-bit float (spacing 2^(e-23) at a depth of exponent e).
///
/// cbindgen:ignore
pub const ZSHIFT_FORMAT_FLOAT32: ZshiftFormat = ZshiftFormat { value: 0x8CAC };
/// GL_DEPTH24_STENCIL8: the packed depth-stencil format engines attach most; its depth is
/// stored as GL_DEPTH_COMPONENT24's.
///
/// cbindgen:ignore
pub const ZSHIFT_FORMAT_UNORM24_STENCIL8: ZshiftFormat = ZshiftFormat { value: 0x88F0 };
/// GL_DEPTH32F_STENCIL8: float depth packed with stencil; its depth is stored as
/// GL_DEPTH_COMPONENT32F's.
///
/// cbindgen:ignore
pub const ZSHIFT_FORMAT_FLOAT32_STENCIL8: ZshiftFormat = ZshiftFormat { value: 0x8CAD };

/// GL_LESS: the default depth test, for [-1, 1] and [0, 1].
///
/// cbindgen:ignore
pub const ZSHIFT_DEPTH_TEST_LESS: ZshiftDepthTest = ZshiftDepthTest { value: 0x0201 };
/// GL_LEQUAL.
///
/// cbindgen:ignore
pub const ZSHIFT_DEPTH_TEST_LEQUAL: ZshiftDepthTest = ZshiftDepthTest { value: 0x0203 };
/// GL_GREATER: the depth test of reversed Z.
///
/// cbindgen:ignore
pub const ZSHIFT_DEPTH_TEST_GREATER: ZshiftDepthTest = ZshiftDepthTest { value: 0x0204 };
/// GL_GEQUAL.
///
/// cbindgen:ignore
pub const ZSHIFT_DEPTH_TEST_GEQUAL: ZshiftDepthTest = ZshiftDepthTest { value: 0x0206 };

/// glPolygonOffset units (r = 1/(2^m - 1) for UNORM; implementations may apply more: Mesa's
/// llvmpipe applies 2/(2^m - 1)).
///
/// cbindgen:ignore
pub const ZSHIFT_BIAS_OPENGL: ZshiftBiasApi = ZshiftBiasApi { value: 0 };
/// Direct3D DepthBias (r = 1/(2^m - 1) for UNORM).
///
/// cbindgen:ignore
pub const ZSHIFT_BIAS_DIRECT3D: ZshiftBiasApi = ZshiftBiasApi { value: 1 };
/// Vulkan depthBiasConstantFactor (r = 2^-m for UNORM).
///
/// cbindgen:ignore
pub const ZSHIFT_BIAS_VULKAN: ZshiftBiasApi = ZshiftBiasApi { value: 2 };

/// A constant NDC depth offset through element 10 (for UNORM buffers).
///
/// cbindgen:ignore
pub const ZSHIFT_OFFSET_NDC: ZshiftOffsetKind = ZshiftOffsetKind { value: 0 };
/// A relative offset, element 14 scaled by 1 + epsilon (for reversed Z with float depth).
///
/// cbindgen:ignore
pub const ZSHIFT_OFFSET_RELATIVE: ZshiftOffsetKind = ZshiftOffsetKind { value: 1 };

/// Every argument constant as the header spells it, with its value: what `tests/header.rs`
/// compares with the hand-written block of `include/zshift.h`.
pub const HEADER_CONSTANTS: &[(&str, &str, i64)] = &[
    (
        "ZshiftClip",
        "ZSHIFT_CLIP_NEG_ONE_TO_ONE",
        ZSHIFT_CLIP_NEG_ONE_TO_ONE.value as i64,
    ),
    (
        "ZshiftClip",
        "ZSHIFT_CLIP_ZERO_TO_ONE",
        ZSHIFT_CLIP_ZERO_TO_ONE.value as i64,
    ),
    (
        "ZshiftClip",
        "ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE",
        ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE.value as i64,
    ),
    (
        "ZshiftFormat",
        "ZSHIFT_FORMAT_UNORM16",
        ZSHIFT_FORMAT_UNORM16.value as i64,
    ),
    (
        "ZshiftFormat",
        "ZSHIFT_FORMAT_UNORM24",
        ZSHIFT_FORMAT_UNORM24.value as i64,
    ),
    (
        "ZshiftFormat",
        "ZSHIFT_FORMAT_UNORM32",
        ZSHIFT_FORMAT_UNORM32.value as i64,
    ),
    (
        "ZshiftFormat",
        "ZSHIFT_FORMAT_FLOAT32",
        ZSHIFT_FORMAT_FLOAT32.value as i64,
    ),
    (
        "ZshiftFormat",
        "ZSHIFT_FORMAT_UNORM24_STENCIL8",
        ZSHIFT_FORMAT_UNORM24_STENCIL8.value as i64,
    ),
    (
        "ZshiftFormat",
        "ZSHIFT_FORMAT_FLOAT32_STENCIL8",
        ZSHIFT_FORMAT_FLOAT32_STENCIL8.value as i64,
    ),
    (
        "ZshiftDepthTest",
        "ZSHIFT_DEPTH_TEST_LESS",
        ZSHIFT_DEPTH_TEST_LESS.value as i64,
    ),
    (
        "ZshiftDepthTest",
        "ZSHIFT_DEPTH_TEST_LEQUAL",
        ZSHIFT_DEPTH_TEST_LEQUAL.value as i64,
    ),
    (
        "ZshiftDepthTest",
        "ZSHIFT_DEPTH_TEST_GREATER",
        ZSHIFT_DEPTH_TEST_GREATER.value as i64,
    ),
    (
        "ZshiftDepthTest",
        "ZSHIFT_DEPTH_TEST_GEQUAL",
        ZSHIFT_DEPTH_TEST_GEQUAL.value as i64,
    ),
    (
        "ZshiftBiasApi",
        "ZSHIFT_BIAS_OPENGL",
        ZSHIFT_BIAS_OPENGL.value as i64,
    ),
    (
        "ZshiftBiasApi",
        "ZSHIFT_BIAS_DIRECT3D",
        ZSHIFT_BIAS_DIRECT3D.value as i64,
    ),
    (
        "ZshiftBiasApi",
        "ZSHIFT_BIAS_VULKAN",
        ZSHIFT_BIAS_VULKAN.value as i64,
    ),
    (
        "ZshiftOffsetKind",
        "ZSHIFT_OFFSET_NDC",
        ZSHIFT_OFFSET_NDC.value as i64,
    ),
    (
        "ZshiftOffsetKind",
        "ZSHIFT_OFFSET_RELATIVE",
        ZSHIFT_OFFSET_RELATIVE.value as i64,
    ),
];

pub(super) fn clip_of(clip: ZshiftClip) -> Result<ClipDepth> {
    match clip {
        ZSHIFT_CLIP_NEG_ONE_TO_ONE => Ok(ClipDepth::NegOneToOne),
        ZSHIFT_CLIP_ZERO_TO_ONE => Ok(ClipDepth::ZeroToOne),
        ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE => Ok(ClipDepth::ReversedZeroToOne),
        _ => Err(crate::domain::domain(
            "the clip convention is not a ZSHIFT_CLIP_* value (0, 1 or 2)",
        )
        .with_integer("clip", i64::from(clip.value))),
    }
}

/// The depth format of a GL internal format enum; `name` is the argument or field that held it.
pub(super) fn format_of(format: ZshiftFormat) -> Result<DepthFormat> {
    format_named(format.value, "format")
}

/// [`format_of`] for a raw GL enum held by the field `name` (the scene's `depth_format`).
pub(super) fn format_named(format: u32, name: &'static str) -> Result<DepthFormat> {
    DepthFormat::from_gl_internal_format(format).map_err(|e| e.with_code(name, format))
}

pub(super) fn api_of(api: ZshiftBiasApi) -> Result<BiasApi> {
    match api {
        ZSHIFT_BIAS_OPENGL => Ok(BiasApi::OpenGl),
        ZSHIFT_BIAS_DIRECT3D => Ok(BiasApi::Direct3d),
        ZSHIFT_BIAS_VULKAN => Ok(BiasApi::Vulkan),
        _ => Err(
            crate::domain::domain("the bias API is not a ZSHIFT_BIAS_* value (0, 1 or 2)")
                .with_integer("api", i64::from(api.value)),
        ),
    }
}

pub(super) fn kind_of(kind: ZshiftOffsetKind) -> Result<OffsetKind> {
    match kind {
        ZSHIFT_OFFSET_NDC => Ok(OffsetKind::Ndc),
        ZSHIFT_OFFSET_RELATIVE => Ok(OffsetKind::Relative),
        _ => Err(
            crate::domain::domain("the offset kind is not a ZSHIFT_OFFSET_* value (0 or 1)")
                .with_integer("kind", i64::from(kind.value)),
        ),
    }
}
