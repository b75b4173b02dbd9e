//! The plausible spring preload of a deep-groove ball bearing (`spring_preload`): the
//! thrust balance and the groove geometry of Harris & Kotzalas (2006) ch. 7, its
//! small-angle closed form, and the bound it puts on the `load-zone` preload.
#![allow(clippy::unnecessary_cast)] // `Real` is f32 in the `wearsim-core-f32` run

use wearsim_core::contact::ElementContact;
use wearsim_core::spring_preload::{plausible_preload, spring_force, thrust_contact};
use wearsim_core::{presets, Real};

/// Total curvature `B D` (m) of a geometry.
fn bd(b: &wearsim_core::bearing::BearingGeometry) -> f64 {
    ((b.outer_conformity + b.inner_conformity) as f64 - 1.0) * b.element_diameter as f64
}

#[test]
fn the_thrust_contact_balances_the_thrust_and_closes_the_groove_geometry() {
    for (name, clearance) in [
        ("cwru-6205-de", 0.0),
        ("cwru-6205-de", 10e-6),
        ("cwru-6203-fe", 5e-6),
    ] {
        let cfg = presets::by_name(name).unwrap();
        let b = cfg.bearing;
        let c = ElementContact::of(&b);
        let bd = bd(&b);
        let cos0 = 1.0 - 2.0 * clearance / (2.0 * bd);
        for thrust in [10.0, spring_force(&b), 2000.0] {
            let t = thrust_contact(&b, &c, clearance as Real, thrust).unwrap();
            // Every ball carries Q = K δ^{3/2} along the contact line; the thrust is the sum
            // of the axial components.
            let q = c.stiffness as f64 * t.approach.powf(1.5);
            assert!((q - t.element_load).abs() <= 1e-9 * q);
            let sum = b.elements as f64 * q * t.angle.sin();
            assert!(
                (sum - thrust).abs() <= 1e-6 * thrust,
                "{name}: {sum} N against {thrust} N"
            );
            // The groove centres stay `B D cos β₀` apart radially: (B D + δ) cos β = B D cos β₀.
            let radial = (bd + t.approach) * t.angle.cos();
            assert!(
                (radial - bd * cos0).abs() <= 1e-12 + 1e-9 * bd,
                "{name}: {radial} m"
            );
            assert!(t.angle > 0.0 && t.angle < 1.2 && t.approach > 0.0);
        }
    }
}

#[test]
fn a_light_thrust_on_a_bearing_without_clearance_follows_the_small_angle_closed_form() {
    // β₀ = 0: F = Z K (BD)^{3/2} β (β²/2)^{3/2} for small β, so
    // β = (2^{3/2} F / (Z K (BD)^{3/2}))^{1/4} and δ = B D β²/2.
    let b = presets::by_name("cwru-6205-de").unwrap().bearing;
    let c = ElementContact::of(&b);
    let bd = bd(&b);
    let z = b.elements as f64;
    let k = c.stiffness as f64;
    for thrust in [0.01, 0.1] {
        let beta = (2f64.powf(1.5) * thrust / (z * k * bd.powf(1.5))).powf(0.25);
        let t = thrust_contact(&b, &c, 0.0, thrust).unwrap();
        assert!(
            (t.angle / beta - 1.0).abs() < 1e-3,
            "{} against {beta}",
            t.angle
        );
        let delta = bd * beta * beta / 2.0;
        assert!(
            (t.approach / delta - 1.0).abs() < 2e-3,
            "{} against {delta}",
            t.approach
        );
    }
}

#[test]
fn the_load_zone_preload_bound_of_the_cwru_drive_end_is_a_spring_preload_not_an_interference() {
    let cfg = presets::by_name("cwru-6205-de").unwrap();
    let b = cfg.bearing;
    let c = ElementContact::of(&b);
    // SKF: F = 0.01 kN/mm × 25 mm = 250 N.
    assert!((spring_force(&b) - 250.0).abs() < 1e-4);
    let t = thrust_contact(&b, &c, cfg.clearance, spring_force(&b)).unwrap();
    let bound = plausible_preload(
        &b,
        &c,
        cfg.clearance,
        cfg.radial_load,
        cfg.structure.stiffness,
        4.0,
    );
    let y0 = wearsim_core::load_zone::equilibrium(
        &c,
        b.elements,
        cfg.radial_load,
        cfg.structure.stiffness,
        cfg.clearance,
    )
    .y0 as f64;
    assert!((bound - t.approach / y0).abs() < 1e-12 * bound);
    println!(
        "6205 at {} N: spring 250 N, β {:.2}°, Q {:.0} N per ball, δ {:.2} µm, y0 {:.2} µm, bound {bound:.3} y0",
        cfg.radial_load,
        t.angle.to_degrees(),
        t.element_load,
        t.approach * 1e6,
        y0 * 1e6
    );
    // The preload the issue found implausible (3.6 y0, ≈ 535 N per ball) is outside.
    assert!(bound < 3.6, "bound {bound}");
    // A heavier radial load (larger y0) lowers the bound in units of y0; the cap holds.
    let heavy = plausible_preload(
        &b,
        &c,
        cfg.clearance,
        4.0 * cfg.radial_load,
        cfg.structure.stiffness,
        4.0,
    );
    assert!(heavy < bound);
    assert_eq!(
        plausible_preload(
            &b,
            &c,
            cfg.clearance,
            cfg.radial_load,
            cfg.structure.stiffness,
            0.1
        ),
        0.1
    );
    // No radial load: the unit is undefined, the cap is returned.
    assert_eq!(
        plausible_preload(&b, &c, cfg.clearance, 0.0, cfg.structure.stiffness, 4.0),
        4.0
    );
    // Line contacts are not spring-preloaded.
    let ims = presets::by_name("ims-za2115").unwrap();
    let ci = ElementContact::of(&ims.bearing);
    assert!(thrust_contact(&ims.bearing, &ci, 0.0, 100.0).is_none());
    assert_eq!(
        plausible_preload(
            &ims.bearing,
            &ci,
            0.0,
            ims.radial_load,
            ims.structure.stiffness,
            4.0
        ),
        0.0
    );
    // Bad thrusts give no contact.
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(thrust_contact(&b, &c, 0.0, bad).is_none());
    }
}
