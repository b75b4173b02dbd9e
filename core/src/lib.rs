//! # wearsim-core
//!
//! A `#![no_std]`, allocation-free, panic-free model of the vibration of a rolling-element
//! bearing, after El-Thalji (2016), *Dynamic modelling and fault analysis of wear
//! evolution in rolling bearings* (VTT Science 126; publications III and IV).
//!
//! * [`bearing`], [`kinematics`], [`ring_modes`], [`contact`], [`load_zone`]: geometry,
//!   eq. 17–23, Hertz contact and the static load zone;
//! * [`forces`]: the force diagrams (imbalance, waviness/roughness, defect formulations,
//!   the five-step load function, slip);
//! * [`speed`]: speed profiles; [`integrate`]: fixed-step integrators;
//!   [`decimate`]: the anti-alias decimator; [`model`]: configuration apart from state;
//! * [`presets`]: the reference bearings; [`sensor`]: fixed-point sensor counts;
//!   [`rng`]: the seeded generator; [`topography`]: Table 1.
//!
//! Every fallible constructor returns [`error::ConfigError`] naming the field and its
//! allowed range; after validation nothing in the step can panic (proved at link time by
//! `firmware-stub/nopanic`: an image that links only if no panic is reachable).
#![no_std]
#![forbid(unsafe_code)]
#![deny(missing_docs)]
// `Real` is f64 or f32 by package (`wearsim-core-f32`): casts that are no-ops in one build are needed in the other.
#![allow(clippy::unnecessary_cast)]
#![deny(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    clippy::indexing_slicing
)]

pub mod bearing;
pub mod checkpoint;
pub mod contact;
pub mod decimate;
pub mod effects;
pub mod error;
pub mod forces;
pub mod integrate;
pub mod kinematics;
pub mod load_zone;
pub mod model;
pub mod presets;
pub mod real;
pub mod ring_modes;
pub mod rng;
pub mod sensor;
pub mod speed;
pub mod spring_preload;
pub mod topography;
pub mod wear;

pub use error::ConfigError;
pub use model::{Channels, Model, ModelConfig, Sample, State, Structure};
pub use real::Real;
