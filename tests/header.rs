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
