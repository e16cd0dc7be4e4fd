//! zshift's main demonstration, shared by its headless binary (`zshift-demo`) and its windowed
//! one (`decal_window`, feature `windowed`): the scene and the methods compared ([`scene`]) and
//! the labelled pictures ([`picture`]).
//!
//! The edges demonstration (`zshift-demo --edges DIR`): [`edges`]; the shadows demonstration
//! (`zshift-demo --shadows DIR`): [`shadows`].

pub mod edges;
pub mod picture;
pub mod scene;
pub mod shadows;
