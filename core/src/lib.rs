//! wearsim-core: placeholder, filled in by the core dynamics commit.
#![no_std]
#![forbid(unsafe_code)]
