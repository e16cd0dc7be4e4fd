//! Which EGL display a headless context is made on.
//!
//! Mesa offers the surfaceless platform (`EGL_PLATFORM_SURFACELESS_MESA`); a GPU vendor's EGL
//! (NVIDIA's, behind glvnd) offers none of Mesa's platforms but enumerates its devices
//! (`EGL_EXT_device_enumeration`) and opens one with no window system
//! (`EGL_EXT_platform_device`). `ZSHIFT_EGL_PLATFORM` picks: `surfaceless`, `device` (the first
//! device that is not Mesa's software one, or `ZSHIFT_EGL_DEVICE=<index>`), or unset: the
//! surfaceless platform, else a device.

use std::ffi::c_void;

use khronos_egl as egl;

/// `EGL_PLATFORM_SURFACELESS_MESA`: a display with no window system.
const PLATFORM_SURFACELESS_MESA: egl::Enum = 0x31DD;
/// `EGL_PLATFORM_DEVICE_EXT`: a display on an enumerated device.
const PLATFORM_DEVICE_EXT: egl::Enum = 0x313F;

/// `eglQueryDevicesEXT(max_devices, devices, num_devices)`.
type QueryDevices = unsafe extern "system" fn(egl::Int, *mut *mut c_void, *mut egl::Int) -> u32;
/// `eglQueryDeviceStringEXT(device, name)`.
type QueryDeviceString = unsafe extern "system" fn(*mut c_void, egl::Int) -> *const i8;

/// An initialized display and how it was found (for error messages and the renderer line).
pub fn open(egl: &egl::Instance<egl::Static>) -> Result<(egl::Display, String), String> {
    let choice = std::env::var("ZSHIFT_EGL_PLATFORM").unwrap_or_default();
    match choice.as_str() {
        "surfaceless" => surfaceless(egl),
        "device" => device(egl),
        "" => surfaceless(egl)
            .or_else(|first| device(egl).map_err(|second| format!("{first}; and {second}"))),
        other => Err(format!(
            "ZSHIFT_EGL_PLATFORM={other}: expected surfaceless or device"
        )),
    }
}

fn surfaceless(egl: &egl::Instance<egl::Static>) -> Result<(egl::Display, String), String> {
    // SAFETY: the surfaceless platform takes EGL_DEFAULT_DISPLAY and no attributes.
    let display = unsafe {
        egl.get_platform_display(
            PLATFORM_SURFACELESS_MESA,
            egl::DEFAULT_DISPLAY,
            &[egl::ATTRIB_NONE],
        )
    }
    .map_err(|e| format!("eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA) failed: {e}"))?;
    egl.initialize(display)
        .map_err(|e| format!("eglInitialize(surfaceless) failed: {e}"))?;
    Ok((display, "EGL surfaceless".into()))
}

fn device(egl: &egl::Instance<egl::Static>) -> Result<(egl::Display, String), String> {
    let proc = |name: &str| {
        egl.get_proc_address(name)
            .ok_or_else(|| format!("EGL has no {name} (EGL_EXT_device_enumeration)"))
    };
    // SAFETY: the names are the EGL_EXT_device_enumeration / _query entry points, whose
    // signatures the types above state.
    let (query, string): (QueryDevices, QueryDeviceString) = unsafe {
        (
            std::mem::transmute::<extern "system" fn(), QueryDevices>(proc("eglQueryDevicesEXT")?),
            std::mem::transmute::<extern "system" fn(), QueryDeviceString>(proc(
                "eglQueryDeviceStringEXT",
            )?),
        )
    };
    let mut devices = [std::ptr::null_mut::<c_void>(); 16];
    let mut count: egl::Int = 0;
    // SAFETY: the array holds 16 devices; EGL writes at most that many and their count.
    if unsafe { query(16, devices.as_mut_ptr(), &mut count) } == 0 || count <= 0 {
        return Err("eglQueryDevicesEXT found no EGL device".into());
    }
    let devices = &devices[..count as usize];
    let extensions = |d: *mut c_void| -> String {
        // SAFETY: `d` is a device EGL just returned; EGL_EXTENSIONS is a valid name.
        let s = unsafe { string(d, egl::EXTENSIONS) };
        if s.is_null() {
            String::new()
        } else {
            // SAFETY: EGL returns a NUL-terminated string it owns.
            unsafe { std::ffi::CStr::from_ptr(s) }
                .to_string_lossy()
                .into_owned()
        }
    };
    let index = match std::env::var("ZSHIFT_EGL_DEVICE") {
        Ok(i) => i
            .parse::<usize>()
            .ok()
            .filter(|&i| i < devices.len())
            .ok_or_else(|| format!("ZSHIFT_EGL_DEVICE={i}: {} devices", devices.len()))?,
        // Mesa may list its software device beside hardware ones: prefer hardware.
        Err(_) => (0..devices.len())
            .find(|&i| !extensions(devices[i]).contains("EGL_MESA_device_software"))
            .unwrap_or(0),
    };
    // SAFETY: the device platform takes an enumerated device and no attributes.
    let display = unsafe {
        egl.get_platform_display(PLATFORM_DEVICE_EXT, devices[index], &[egl::ATTRIB_NONE])
    }
    .map_err(|e| format!("eglGetPlatformDisplay(EGL_PLATFORM_DEVICE_EXT) failed: {e}"))?;
    egl.initialize(display)
        .map_err(|e| format!("eglInitialize(device {index}) failed: {e}"))?;
    Ok((display, format!("EGL device {index} of {}", devices.len())))
}

/// The config a context is made with: none where `EGL_KHR_no_config_context` allows it (Mesa's
/// surfaceless display has no config at all), else the first OpenGL-renderable one (drawn
/// through the context's own FBO, never a surface).
pub fn config(
    egl: &egl::Instance<egl::Static>,
    display: egl::Display,
    extensions: &str,
) -> Result<egl::Config, String> {
    if extensions.contains("EGL_KHR_no_config_context") {
        // SAFETY: EGL_NO_CONFIG_KHR is the null config, allowed by EGL_KHR_no_config_context.
        return Ok(unsafe { egl::Config::from_ptr(std::ptr::null_mut()) });
    }
    let attribs = [egl::RENDERABLE_TYPE, egl::OPENGL_BIT, egl::NONE];
    egl.choose_first_config(display, &attribs)
        .map_err(|e| format!("eglChooseConfig failed: {e}"))?
        .ok_or_else(|| {
            format!("EGL offers neither EGL_KHR_no_config_context nor an OpenGL config; it offers: {extensions}")
        })
}
