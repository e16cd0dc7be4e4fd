//! The enumerated arguments (clip convention, depth format, bias API, offset kind) and their
//! conversion to the math modules' types. An unknown value is ZSHIFT_ERR_DOMAIN.

use crate::error::Result;
use crate::plan::OffsetKind;
use crate::polygon_offset::BiasApi;
use crate::precision::DepthFormat;
use crate::projection::ClipDepth;

/// `clip`: OpenGL's default NDC depth [-1, 1] (near -1, far +1), depth test GL_LESS.
pub const ZSHIFT_CLIP_NEG_ONE_TO_ONE: i32 = 0;

/// `clip`: NDC depth [0, 1] (near 0, far 1): glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE),
/// Direct3D and Vulkan clip space; depth test GL_LESS.
pub const ZSHIFT_CLIP_ZERO_TO_ONE: i32 = 1;

/// `clip`: reversed NDC depth [0, 1] (near 1, far 0): glClipControl(GL_LOWER_LEFT,
/// GL_ZERO_TO_ONE), glDepthFunc(GL_GREATER), glClearDepth(0); meant for 32-bit float depth.
pub const ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE: i32 = 2;

/// `format`: GL_DEPTH_COMPONENT16 (16-bit unsigned normalized); the value is the GL enum, so a GL internal format can be passed as is.
pub const ZSHIFT_FORMAT_UNORM16: i32 = 0x81A5;

/// `format`: GL_DEPTH_COMPONENT24 (24-bit unsigned normalized); the value is the GL enum, so a GL internal format can be passed as is.
pub const ZSHIFT_FORMAT_UNORM24: i32 = 0x81A6;

/// `format`: GL_DEPTH_COMPONENT32 (32-bit unsigned normalized); the value is the GL enum, so a GL internal format can be passed as is.
pub const ZSHIFT_FORMAT_UNORM32: i32 = 0x81A7;

/// `format`: GL_DEPTH_COMPONENT32F (32-bit float; spacing 2^(e-23) at a depth of exponent e); the
/// value is the GL enum.
pub const ZSHIFT_FORMAT_FLOAT32: i32 = 0x8CAC;

/// `api`: glPolygonOffset units (r = 1/(2^m - 1) for UNORM; implementations may apply more:
/// Mesa's llvmpipe applies 2/(2^m - 1)).
pub const ZSHIFT_BIAS_OPENGL: i32 = 0;

/// `api`: Direct3D DepthBias (r = 1/(2^m - 1) for UNORM).
pub const ZSHIFT_BIAS_DIRECT3D: i32 = 1;

/// `api`: Vulkan depthBiasConstantFactor (r = 2^-m for UNORM).
pub const ZSHIFT_BIAS_VULKAN: i32 = 2;

/// `kind`: a constant NDC depth offset through element 10 (for UNORM buffers).
pub const ZSHIFT_OFFSET_NDC: i32 = 0;

/// `kind`: a relative offset, element 14 scaled by 1 + epsilon (for reversed Z with float depth).
pub const ZSHIFT_OFFSET_RELATIVE: i32 = 1;

pub(super) fn clip_of(clip: i32) -> Result<ClipDepth> {
    match clip {
        ZSHIFT_CLIP_NEG_ONE_TO_ONE => Ok(ClipDepth::NegOneToOne),
        ZSHIFT_CLIP_ZERO_TO_ONE => Ok(ClipDepth::ZeroToOne),
        ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE => Ok(ClipDepth::ReversedZeroToOne),
        _ => Err(crate::domain::domain("unknown ZSHIFT_CLIP_* value")),
    }
}

pub(super) fn format_of(format: i32) -> Result<DepthFormat> {
    DepthFormat::from_gl_internal_format(format as u32)
}

pub(super) fn api_of(api: i32) -> Result<BiasApi> {
    match api {
        ZSHIFT_BIAS_OPENGL => Ok(BiasApi::OpenGl),
        ZSHIFT_BIAS_DIRECT3D => Ok(BiasApi::Direct3d),
        ZSHIFT_BIAS_VULKAN => Ok(BiasApi::Vulkan),
        _ => Err(crate::domain::domain("unknown ZSHIFT_BIAS_* value")),
    }
}

pub(super) fn kind_of(kind: i32) -> Result<OffsetKind> {
    match kind {
        ZSHIFT_OFFSET_NDC => Ok(OffsetKind::Ndc),
        ZSHIFT_OFFSET_RELATIVE => Ok(OffsetKind::Relative),
        _ => Err(crate::domain::domain("unknown ZSHIFT_OFFSET_* value")),
    }
}
