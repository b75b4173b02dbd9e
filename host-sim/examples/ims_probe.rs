fn main() {
    let c = wearsim_host::life::ims::compare(std::path::Path::new("/work/shared/data"), 1).unwrap();
    println!("onset meas {:?} sim {:?} err {:?} dist {:.2} dB rms {:.2} mean; end {:?}; life h {:.1} revs {:.3e} uncal {:.3e} a {:.3e} sim {:.3e}", c.onset_measured, c.onset_simulated, c.onset_error, c.distance_db_rms, c.distance_db_mean_abs, c.end_ratio, c.measured_life_h, c.measured_life_revs, c.uncalibrated_life_revs, c.life_factor, c.simulated_life_revs);
    println!("{:?}", c.stages);
}
