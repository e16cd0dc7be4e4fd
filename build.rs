//! Gives the shared library an ELF SONAME, `libzshift.so.<major>`, so programs linked against it
//! record the ABI they were built for, as distributions ship C libraries (`libzshift.so` ->
//! `libzshift.so.0` -> `libzshift.so.0.1.0`, laid out by scripts/install). The major is the
//! crate's major version. Only ELF targets (Linux, the BSDs) have SONAMEs; elsewhere nothing is
//! added.
//!
//! A program linked against the build tree (`-Ltarget/release -lzshift`, as tests/c, examples/c
//! and the C++ benchmark harness do) records that SONAME too, so the loader looks for
//! `libzshift.so.0` next to `libzshift.so`: this script puts the link
//! `target/<profile>/libzshift.so.0 -> libzshift.so` there, as an install would.

use std::path::{Path, PathBuf};

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    let os = std::env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    let major = std::env::var("CARGO_PKG_VERSION_MAJOR").unwrap_or_else(|_| "0".into());
    let elf = [
        "linux",
        "android",
        "freebsd",
        "netbsd",
        "openbsd",
        "dragonfly",
    ];
    if !elf.contains(&os.as_str()) {
        return;
    }
    let soname = format!("libzshift.so.{major}");
    println!("cargo:rustc-cdylib-link-arg=-Wl,-soname,{soname}");
    if let Some(dir) = profile_dir() {
        link_soname(&dir, &soname);
    }
}

/// The directory cargo writes the library to: OUT_DIR is `<profile dir>/build/<package>-<hash>/out`.
fn profile_dir() -> Option<PathBuf> {
    let out = PathBuf::from(std::env::var_os("OUT_DIR")?);
    let dir = out.ancestors().nth(3)?;
    dir.join("build").is_dir().then(|| dir.to_path_buf())
}

/// `dir/<soname> -> libzshift.so`, unless something is already there. Failing to make it only
/// costs programs linked against the build tree their run-time lookup, so it is a warning.
#[cfg(unix)]
fn link_soname(dir: &Path, soname: &str) {
    let link = dir.join(soname);
    if link.symlink_metadata().is_err() {
        if let Err(e) = std::os::unix::fs::symlink("libzshift.so", &link) {
            println!(
                "cargo:warning=cannot link {} -> libzshift.so: {e}",
                link.display()
            );
        }
    }
}

#[cfg(not(unix))]
fn link_soname(_: &Path, _: &str) {}
