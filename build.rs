//! Gives the shared library an ELF SONAME, `libzshift.so.<major>`, so programs linked against it
//! record the ABI they were built for (as distributions ship C libraries: `libzshift.so` ->
//! `libzshift.so.0` -> `libzshift.so.0.1.0`, made by scripts/install). The major is the crate's
//! major version. Only ELF targets (Linux, the BSDs) have SONAMEs; elsewhere nothing is added.

fn main() {
    let os = std::env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    let major = std::env::var("CARGO_PKG_VERSION_MAJOR").unwrap_or_else(|_| "0".into());
    if matches!(
        os.as_str(),
        "linux" | "android" | "freebsd" | "netbsd" | "openbsd" | "dragonfly"
    ) {
        println!("cargo:rustc-cdylib-link-arg=-Wl,-soname,libzshift.so.{major}");
    }
    println!("cargo:rerun-if-changed=build.rs");
}
