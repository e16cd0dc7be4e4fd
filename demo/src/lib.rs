//! zshift's main demonstration, shared by its headless binary (`zshift-demo`) and its windowed
//! one (`decal_window`, feature `windowed`): the scene and the methods compared ([`scene`]) and
//! the labelled pictures ([`picture`]).

pub mod picture;
pub mod scene;
