//! The GL entry points the probe calls, loaded through the caller's function loader: a table of
//! plain function pointers, each checked for NULL when loaded, so a missing entry point becomes an
//! [`Error`] naming it instead of a call through NULL.

use std::ffi::{c_char, c_void, CStr};

use crate::error::{Error, ErrorKind, Result};

pub type Enum = u32;
pub type Uint = u32;
pub type Int = i32;
pub type Sizei = i32;
pub type Boolean = u8;

// The GL enums the probe uses (values from the OpenGL 4.6 registry).
pub(crate) const NO_ERROR: Enum = 0;
pub(crate) const LINES: Enum = 0x0001;
pub(crate) const TRIANGLES: Enum = 0x0004;
pub(crate) const FRONT: Enum = 0x0404;
pub(crate) const BACK: Enum = 0x0405;
pub(crate) const FRONT_AND_BACK: Enum = 0x0408;
pub(crate) const CULL_FACE: Enum = 0x0B44;
pub(crate) const POLYGON_SMOOTH: Enum = 0x0B41;
pub(crate) const MAX_CLIP_DISTANCES: Enum = 0x0D32;
pub(crate) const CLIP_DISTANCE0: Enum = 0x3000;
pub(crate) const POLYGON_MODE: Enum = 0x0B40;
pub(crate) const DEPTH_RANGE: Enum = 0x0B70;
pub(crate) const DEPTH_TEST: Enum = 0x0B71;
pub(crate) const DEPTH_WRITEMASK: Enum = 0x0B72;
pub(crate) const DEPTH_CLEAR_VALUE: Enum = 0x0B73;
pub(crate) const DEPTH_FUNC: Enum = 0x0B74;
pub(crate) const STENCIL_TEST: Enum = 0x0B90;
pub(crate) const VIEWPORT: Enum = 0x0BA2;
pub(crate) const ALPHA_TEST: Enum = 0x0BC0;
pub(crate) const SCISSOR_TEST: Enum = 0x0C11;
pub(crate) const PACK_SWAP_BYTES: Enum = 0x0D00;
pub(crate) const PACK_LSB_FIRST: Enum = 0x0D01;
pub(crate) const PACK_ROW_LENGTH: Enum = 0x0D02;
pub(crate) const PACK_SKIP_ROWS: Enum = 0x0D03;
pub(crate) const PACK_SKIP_PIXELS: Enum = 0x0D04;
pub(crate) const PACK_ALIGNMENT: Enum = 0x0D05;
pub(crate) const DEPTH_SCALE: Enum = 0x0D1E;
pub(crate) const DEPTH_BIAS: Enum = 0x0D1F;
pub(crate) const SUBPIXEL_BITS: Enum = 0x0D50;
pub(crate) const UNSIGNED_INT: Enum = 0x1405;
pub(crate) const FLOAT: Enum = 0x1406;
pub(crate) const DEPTH_COMPONENT: Enum = 0x1902;
pub(crate) const LINE: Enum = 0x1B01;
pub(crate) const FILL: Enum = 0x1B02;
pub(crate) const LINE_SMOOTH: Enum = 0x0B20;
pub(crate) const LINE_WIDTH: Enum = 0x0B21;
pub(crate) const POLYGON_OFFSET_LINE: Enum = 0x2A02;
pub(crate) const POLYGON_OFFSET_UNITS: Enum = 0x2A00;
pub(crate) const POLYGON_OFFSET_FILL: Enum = 0x8037;
pub(crate) const POLYGON_OFFSET_FACTOR: Enum = 0x8038;
pub(crate) const PACK_SKIP_IMAGES: Enum = 0x806B;
pub(crate) const PACK_IMAGE_HEIGHT: Enum = 0x806C;
pub(crate) const DEPTH_COMPONENT16: Enum = 0x81A5;
pub(crate) const DEPTH_COMPONENT24: Enum = 0x81A6;
pub(crate) const MAJOR_VERSION: Enum = 0x821B;
pub(crate) const MINOR_VERSION: Enum = 0x821C;
pub(crate) const MAX_VIEWPORTS: Enum = 0x825B;
pub(crate) const ARRAY_BUFFER_BINDING: Enum = 0x8894;
pub(crate) const ARRAY_BUFFER: Enum = 0x8892;
pub(crate) const STREAM_DRAW: Enum = 0x88E0;
pub(crate) const PIXEL_PACK_BUFFER: Enum = 0x88EB;
pub(crate) const PIXEL_PACK_BUFFER_BINDING: Enum = 0x88ED;
pub(crate) const DEPTH_CLAMP: Enum = 0x864F;
pub(crate) const FRAGMENT_SHADER: Enum = 0x8B30;
pub(crate) const VERTEX_SHADER: Enum = 0x8B31;
pub(crate) const COMPILE_STATUS: Enum = 0x8B81;
pub(crate) const LINK_STATUS: Enum = 0x8B82;
pub(crate) const CURRENT_PROGRAM: Enum = 0x8B8D;
pub(crate) const READ_FRAMEBUFFER_BINDING: Enum = 0x8CAA;
pub(crate) const DRAW_FRAMEBUFFER_BINDING: Enum = 0x8CA6;
pub(crate) const READ_FRAMEBUFFER: Enum = 0x8CA8;
pub(crate) const DRAW_FRAMEBUFFER: Enum = 0x8CA9;
pub(crate) const DEPTH_COMPONENT32F: Enum = 0x8CAC;
pub(crate) const FRAMEBUFFER_COMPLETE: Enum = 0x8CD5;
pub(crate) const DEPTH_ATTACHMENT: Enum = 0x8D00;
pub(crate) const FRAMEBUFFER: Enum = 0x8D40;
pub(crate) const RENDERBUFFER: Enum = 0x8D41;
pub(crate) const RENDERBUFFER_BINDING: Enum = 0x8CA7;
pub(crate) const RASTERIZER_DISCARD: Enum = 0x8C89;
pub(crate) const VERTEX_ARRAY_BINDING: Enum = 0x85B5;
pub(crate) const NONE: Enum = 0;
pub(crate) const CONTEXT_PROFILE_MASK: Enum = 0x9126;
pub(crate) const CONTEXT_COMPATIBILITY_PROFILE_BIT: Int = 0x2;
pub(crate) const CLIP_ORIGIN: Enum = 0x935C;
pub(crate) const CLIP_DEPTH_MODE: Enum = 0x935D;
pub(crate) const LOWER_LEFT: Enum = 0x8CA1;
pub(crate) const NEGATIVE_ONE_TO_ONE: Enum = 0x935E;
pub(crate) const ZERO_TO_ONE: Enum = 0x935F;
pub(crate) const POLYGON_OFFSET_CLAMP: Enum = 0x8E1B;
pub(crate) const DEPTH_BOUNDS_TEST_EXT: Enum = 0x8890;
pub(crate) const EXTENSIONS: Enum = 0x1F03;
pub(crate) const RENDERER: Enum = 0x1F01;
pub(crate) const VERSION: Enum = 0x1F02;
pub(crate) const NUM_EXTENSIONS: Enum = 0x821D;
pub(crate) const TEXTURE0: Enum = 0x84C0;
pub(crate) const ALIASED_LINE_WIDTH_RANGE: Enum = 0x846E;
pub(crate) const ACTIVE_TEXTURE: Enum = 0x84E0;
pub(crate) const MULTISAMPLE: Enum = 0x809D;
pub(crate) const SAMPLE_ALPHA_TO_COVERAGE: Enum = 0x809E;
pub(crate) const SAMPLE_ALPHA_TO_ONE: Enum = 0x809F;
pub(crate) const SAMPLE_COVERAGE: Enum = 0x80A0;
pub(crate) const SAMPLE_POSITION: Enum = 0x8E50;
pub(crate) const SAMPLE_MASK: Enum = 0x8E51;
pub(crate) const TEXTURE_2D_MULTISAMPLE: Enum = 0x9100;
pub(crate) const TEXTURE_BINDING_2D_MULTISAMPLE: Enum = 0x9104;
pub(crate) const MAX_DEPTH_TEXTURE_SAMPLES: Enum = 0x910F;

/// Declares the table: one field per entry point, its C name, and the error detail used when the
/// loader returns NULL for it (so each detail names its entry point, in a `'static` string).
macro_rules! entry_points {
    (
        required { $($field:ident: $name:literal fn($($arg:ty),*) $(-> $ret:ty)?;)* }
        optional { $($ofield:ident: $oname:literal fn($($oarg:ty),*) $(-> $oret:ty)?;)* }
    ) => {
        /// The probe's GL entry points. Required ones are checked at load time; optional ones
        /// (newer GL versions, compatibility profile) are `None` when the loader has none.
        #[allow(non_snake_case, clippy::type_complexity)]
        pub struct Gl {
            $(pub $field: unsafe extern "system" fn($($arg),*) $(-> $ret)?,)*
            $(pub $ofield: Option<unsafe extern "system" fn($($oarg),*) $(-> $oret)?>,)*
        }

        impl Gl {
            /// Loads every entry point through `loader`.
            ///
            /// # Safety
            /// A non-NULL pointer the loader returns for a name must be that GL function of the
            /// context current on this thread.
            pub unsafe fn load(loader: &mut dyn FnMut(&CStr) -> *const c_void) -> Result<Gl> {
                Ok(Gl {
                    $($field: {
                        let p = loader(cstr(concat!($name, "\0")));
                        if p.is_null() {
                            return Err(Error::new(
                                ErrorKind::Gl,
                                concat!("the GL loader returned NULL for ", $name,
                                        ", which the probe needs (OpenGL 3.2 or later)"),
                            ));
                        }
                        // SAFETY: the loader promises `p` is this entry point, whose C signature
                        // is the field's type.
                        std::mem::transmute::<*const c_void, unsafe extern "system" fn($($arg),*) $(-> $ret)?>(p)
                    },)*
                    $($ofield: {
                        let p = loader(cstr(concat!($oname, "\0")));
                        if p.is_null() {
                            None
                        } else {
                            // SAFETY: as above.
                            Some(std::mem::transmute::<*const c_void, unsafe extern "system" fn($($oarg),*) $(-> $oret)?>(p))
                        }
                    },)*
                })
            }
        }
    };
}

fn cstr(name: &'static str) -> &'static CStr {
    // Every name is a literal followed by "\0", with no interior NUL.
    CStr::from_bytes_with_nul(name.as_bytes()).unwrap_or(c"")
}

entry_points! {
    required {
        GetError: "glGetError" fn() -> Enum;
        GetIntegerv: "glGetIntegerv" fn(Enum, *mut Int);
        GetFloatv: "glGetFloatv" fn(Enum, *mut f32);
        GetDoublev: "glGetDoublev" fn(Enum, *mut f64);
        GetBooleanv: "glGetBooleanv" fn(Enum, *mut Boolean);
        IsEnabled: "glIsEnabled" fn(Enum) -> Boolean;
        Enable: "glEnable" fn(Enum);
        Disable: "glDisable" fn(Enum);
        GenFramebuffers: "glGenFramebuffers" fn(Sizei, *mut Uint);
        DeleteFramebuffers: "glDeleteFramebuffers" fn(Sizei, *const Uint);
        BindFramebuffer: "glBindFramebuffer" fn(Enum, Uint);
        FramebufferRenderbuffer: "glFramebufferRenderbuffer" fn(Enum, Enum, Enum, Uint);
        CheckFramebufferStatus: "glCheckFramebufferStatus" fn(Enum) -> Enum;
        GenRenderbuffers: "glGenRenderbuffers" fn(Sizei, *mut Uint);
        DeleteRenderbuffers: "glDeleteRenderbuffers" fn(Sizei, *const Uint);
        BindRenderbuffer: "glBindRenderbuffer" fn(Enum, Uint);
        RenderbufferStorage: "glRenderbufferStorage" fn(Enum, Enum, Sizei, Sizei);
        DrawBuffer: "glDrawBuffer" fn(Enum);
        ReadBuffer: "glReadBuffer" fn(Enum);
        Viewport: "glViewport" fn(Int, Int, Sizei, Sizei);
        DepthRange: "glDepthRange" fn(f64, f64);
        DepthFunc: "glDepthFunc" fn(Enum);
        DepthMask: "glDepthMask" fn(Boolean);
        ClearDepth: "glClearDepth" fn(f64);
        Clear: "glClear" fn(u32);
        PolygonOffset: "glPolygonOffset" fn(f32, f32);
        PolygonMode: "glPolygonMode" fn(Enum, Enum);
        LineWidth: "glLineWidth" fn(f32);
        PixelStorei: "glPixelStorei" fn(Enum, Int);
        ReadPixels: "glReadPixels" fn(Int, Int, Sizei, Sizei, Enum, Enum, *mut c_void);
        CreateShader: "glCreateShader" fn(Enum) -> Uint;
        ShaderSource: "glShaderSource" fn(Uint, Sizei, *const *const c_char, *const Int);
        CompileShader: "glCompileShader" fn(Uint);
        GetShaderiv: "glGetShaderiv" fn(Uint, Enum, *mut Int);
        DeleteShader: "glDeleteShader" fn(Uint);
        CreateProgram: "glCreateProgram" fn() -> Uint;
        AttachShader: "glAttachShader" fn(Uint, Uint);
        BindAttribLocation: "glBindAttribLocation" fn(Uint, Uint, *const c_char);
        LinkProgram: "glLinkProgram" fn(Uint);
        GetProgramiv: "glGetProgramiv" fn(Uint, Enum, *mut Int);
        DeleteProgram: "glDeleteProgram" fn(Uint);
        UseProgram: "glUseProgram" fn(Uint);
        GenVertexArrays: "glGenVertexArrays" fn(Sizei, *mut Uint);
        DeleteVertexArrays: "glDeleteVertexArrays" fn(Sizei, *const Uint);
        BindVertexArray: "glBindVertexArray" fn(Uint);
        GenBuffers: "glGenBuffers" fn(Sizei, *mut Uint);
        DeleteBuffers: "glDeleteBuffers" fn(Sizei, *const Uint);
        BindBuffer: "glBindBuffer" fn(Enum, Uint);
        BufferData: "glBufferData" fn(Enum, isize, *const c_void, Enum);
        EnableVertexAttribArray: "glEnableVertexAttribArray" fn(Uint);
        VertexAttribPointer: "glVertexAttribPointer" fn(Uint, Int, Enum, Boolean, Sizei, *const c_void);
        DrawArrays: "glDrawArrays" fn(Enum, Int, Sizei);
        GetStringi: "glGetStringi" fn(Enum, Uint) -> *const u8;
        GetString: "glGetString" fn(Enum) -> *const u8;
        GetUniformLocation: "glGetUniformLocation" fn(Uint, *const c_char) -> Int;
        UniformMatrix4fv: "glUniformMatrix4fv" fn(Int, Sizei, Boolean, *const f32);
        Uniform1i: "glUniform1i" fn(Int, Int);
        GenTextures: "glGenTextures" fn(Sizei, *mut Uint);
        DeleteTextures: "glDeleteTextures" fn(Sizei, *const Uint);
        BindTexture: "glBindTexture" fn(Enum, Uint);
        ActiveTexture: "glActiveTexture" fn(Enum);
        TexImage2DMultisample: "glTexImage2DMultisample" fn(Enum, Sizei, Enum, Sizei, Sizei, Boolean);
        FramebufferTexture2D: "glFramebufferTexture2D" fn(Enum, Enum, Enum, Uint, Int);
        GetMultisamplefv: "glGetMultisamplefv" fn(Enum, Uint, *mut f32);
    }
    optional {
        ClipControl: "glClipControl" fn(Enum, Enum);
        ViewportIndexedf: "glViewportIndexedf" fn(Uint, f32, f32, f32, f32);
        GetFloati_v: "glGetFloati_v" fn(Enum, Uint, *mut f32);
        DepthRangeIndexed: "glDepthRangeIndexed" fn(Uint, f64, f64);
        GetDoublei_v: "glGetDoublei_v" fn(Enum, Uint, *mut f64);
        IsEnabledi: "glIsEnabledi" fn(Enum, Uint) -> Boolean;
        Enablei: "glEnablei" fn(Enum, Uint);
        Disablei: "glDisablei" fn(Enum, Uint);
        PolygonOffsetClamp: "glPolygonOffsetClamp" fn(f32, f32, f32);
        PixelTransferf: "glPixelTransferf" fn(Enum, f32);
    }
}

impl Gl {
    /// Drops the optional entry points this context does not support. Some loaders (Mesa's
    /// `eglGetProcAddress`) return a stub for any name, so NULL alone does not tell: the GL
    /// version and extension list decide. Returns `(major, minor, compatibility profile)`.
    ///
    /// # Errors
    /// A context older than OpenGL 3.2 (no `GL_MAJOR_VERSION`, or a smaller one).
    pub unsafe fn settle(&mut self) -> Result<(Int, Int, bool)> {
        let (major, minor) = (self.integer(MAJOR_VERSION), self.integer(MINOR_VERSION));
        if self.failed() || (major, minor) < (3, 2) {
            return Err(Error::new(
                ErrorKind::Gl,
                "the current GL context is older than OpenGL 3.2 (GL_MAJOR_VERSION/GL_MINOR_VERSION), \
                 or no context is current on this thread",
            ));
        }
        let compatibility =
            self.integer(CONTEXT_PROFILE_MASK) & CONTEXT_COMPATIBILITY_PROFILE_BIT != 0;
        let at_least = |a: Int, b: Int| (major, minor) >= (a, b);
        if !(at_least(4, 5) || self.has_extension(b"GL_ARB_clip_control")) {
            self.ClipControl = None;
        }
        if !(at_least(4, 1) || self.has_extension(b"GL_ARB_viewport_array")) {
            self.ViewportIndexedf = None;
            self.GetFloati_v = None;
            self.DepthRangeIndexed = None;
            self.GetDoublei_v = None;
        }
        if !(at_least(4, 6)
            || self.has_extension(b"GL_ARB_polygon_offset_clamp")
            || self.has_extension(b"GL_EXT_polygon_offset_clamp"))
        {
            self.PolygonOffsetClamp = None;
        }
        if !compatibility {
            self.PixelTransferf = None;
        }
        self.check("reading GL_CONTEXT_PROFILE_MASK raised a GL error")?;
        Ok((major, minor, compatibility))
    }

    /// Whether `glGetStringi(GL_EXTENSIONS, i)` lists `name`.
    pub unsafe fn has_extension(&self, name: &[u8]) -> bool {
        let count = self.integer(NUM_EXTENSIONS).max(0) as Uint;
        (0..count).any(|i| {
            let p = (self.GetStringi)(EXTENSIONS, i);
            !p.is_null() && CStr::from_ptr(p.cast()).to_bytes() == name
        })
    }

    /// `glGetString(name)`, lossily as UTF-8 (empty if NULL).
    pub unsafe fn string(&self, name: Enum) -> String {
        let p = (self.GetString)(name);
        if p.is_null() {
            return String::new();
        }
        CStr::from_ptr(p.cast()).to_string_lossy().into_owned()
    }

    /// One integer state value.
    pub unsafe fn integer(&self, pname: Enum) -> Int {
        let mut v = [0; 4];
        (self.GetIntegerv)(pname, v.as_mut_ptr());
        v[0]
    }

    /// Whether `glGetError` reports anything; drains it (up to 16 codes) either way.
    pub unsafe fn failed(&self) -> bool {
        let mut any = false;
        for _ in 0..16 {
            if (self.GetError)() == NO_ERROR {
                break;
            }
            any = true;
        }
        any
    }

    /// `Err(detail)` if GL reported an error since the last check.
    pub unsafe fn check(&self, detail: &'static str) -> Result<()> {
        if self.failed() {
            Err(Error::new(ErrorKind::Gl, detail))
        } else {
            Ok(())
        }
    }
}
