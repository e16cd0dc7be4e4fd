//! The checked-in C header must be exactly what cbindgen makes of `src/ffi/` today.
//! Regenerate with `ZSHIFT_BLESS=1 cargo test --test header`.

use std::path::Path;

#[test]
fn checked_in_header_matches_cbindgen() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let config = cbindgen::Config::from_file(root.join("cbindgen.toml")).expect("cbindgen.toml");
    let mut generated = Vec::new();
    cbindgen::Builder::new()
        .with_crate(root)
        .with_config(config)
        .generate()
        .expect("cbindgen failed on the crate")
        .write(&mut generated);
    let generated = String::from_utf8(generated).expect("header is UTF-8");
    let path = root.join("include/zshift.h");
    if std::env::var_os("ZSHIFT_BLESS").is_some() {
        std::fs::write(&path, &generated).expect("write include/zshift.h");
        return;
    }
    let checked_in = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        checked_in == generated,
        "include/zshift.h differs from what cbindgen generates; run `ZSHIFT_BLESS=1 cargo test --test header` and commit"
    );
}

/// The argument constants are written in the header by hand (cbindgen would spell them as C99
/// compound literals): each must be there once, with its type and the Rust value.
#[test]
fn hand_written_argument_constants_match_the_rust_ones() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let header = std::fs::read_to_string(root.join("include/zshift.h")).expect("read header");
    for &(ty, name, value) in zshift::ffi::HEADER_CONSTANTS {
        let want = if value > 9 {
            format!("static const {ty} {name} = {{ 0x{value:04X} }};")
        } else {
            format!("static const {ty} {name} = {{ {value} }};")
        };
        assert_eq!(
            header.matches(&want).count(),
            1,
            "include/zshift.h must declare `{want}` once (edit cbindgen.toml's after_includes)"
        );
        assert_eq!(
            header.matches(&format!(" {name} =")).count(),
            1,
            "{name} is declared more than once"
        );
    }
    let declared = header.matches("static const Zshift").count();
    assert_eq!(
        declared,
        zshift::ffi::HEADER_CONSTANTS.len(),
        "the header declares argument constants that src/ffi/kinds.rs does not list"
    );
}

/// Every name the header declares carries the library's prefix: a bare `#define ZERO_TO_ONE`
/// (once leaked from an internal `pub const`) breaks any engine that includes GL or
/// OpenSceneGraph headers after ours.
#[test]
fn every_declared_name_is_prefixed() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let header = std::fs::read_to_string(root.join("include/zshift.h")).expect("read header");
    let prefixed = |name: &str| {
        ["ZSHIFT_", "zshift_", "Zshift"]
            .iter()
            .any(|p| name.starts_with(p))
    };
    for line in header.lines() {
        let line = line.trim_start();
        let name = if let Some(rest) = line.strip_prefix("#define ") {
            rest.split_whitespace().next()
        } else if line.starts_with("} ") && line.ends_with(';') {
            // The name a `typedef struct { … } Name;` closes with.
            line[2..line.len() - 1].split_whitespace().last()
        } else if let Some(rest) = line.strip_prefix("ZshiftStatus ") {
            rest.split('(').next()
        } else {
            None
        };
        if let Some(name) = name {
            assert!(
                prefixed(name),
                "include/zshift.h declares `{name}` without the zshift prefix: {line:?}"
            );
        }
    }
}
