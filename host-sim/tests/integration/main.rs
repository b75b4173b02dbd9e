//! host-sim's integration tests, one module per subject, in one test binary: one link of
//! the `wearsim` library and its dependencies instead of one per file (CI's build time),
//! and the long tests (a lifetime gap, the twins) share the machine's cores with the
//! short ones instead of running alone in their own process. Run one subject with
//! `cargo test -p wearsim-host --test integration gap_life::`. `output_mode.rs` stays a
//! binary of its own: it changes the process-wide umask.

mod support;

mod analyze_cli;
mod capture_cli;
mod cli;
mod cwru_benchmark;
mod dense_faults;
mod diagnosis_invariance;
mod effects_cli;
mod feature_folders;
mod feature_tables;
mod firmware_qemu;
mod gap_cells;
mod gap_cli;
mod gap_cwru;
mod gap_life;
mod gap_life_roles;
mod gap_own_output;
mod gap_probe_c;
mod gap_roles;
mod gap_validate;
mod hostile_inputs;
mod ims_compare;
mod ims_validate;
mod io_fuzz;
mod life;
mod life_ball;
mod life_cap;
mod life_interval;
mod life_lanes;
mod life_sites;
mod out_dirs;
mod probe2;
mod probe3;
mod probe4;
mod probe_sweep;
mod readers;
mod reference_hashes;
mod rig_tables;
mod slip_jitter;
mod slow_rig;
mod sweep_cli;
