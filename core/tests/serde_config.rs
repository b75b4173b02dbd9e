//! The `serde` feature: every preset's configuration, with every effect on, survives a
//! JSON round trip exactly (geometry, structure, speed, defect, effects), and an
//! unknown effect key is rejected. Run with `--features serde`.
#![cfg(feature = "serde")]

use wearsim_core::effects::{EffectKind, Effects};
use wearsim_core::{presets, ModelConfig};

#[test]
fn configurations_round_trip_through_json() {
    for name in presets::NAMES {
        let mut cfg = presets::by_name(name).unwrap();
        for k in EffectKind::ALL {
            let d: Vec<_> = k.spec().params.iter().map(|p| p.default as _).collect();
            cfg.effects.set(k, &d).unwrap();
        }
        let text = serde_json::to_string(&cfg).unwrap();
        let back: ModelConfig = serde_json::from_str(&text).unwrap();
        assert_eq!(back, cfg, "{name}");
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert_eq!(v["bearing"]["elements"], cfg.bearing.elements, "{name}");
        assert!(v["effects"]["load_zone"]["depth"].is_number(), "{name}");
    }
    let bad: Result<Effects, _> = serde_json::from_str(r#"{"edge_shap": null}"#);
    assert!(bad.is_err());
    let none: Effects = serde_json::from_str("{}").unwrap();
    assert_eq!(none, Effects::NONE);
}
