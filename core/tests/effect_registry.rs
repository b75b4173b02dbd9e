//! The effect registry (`wearsim_core::effects`): one entry per effect, names that
//! round-trip through `EffectKind`, bounds written once and enforced by every entry point,
//! and a misspelled name rejected everywhere.
// Written against `Real` (f64 or f32 by package): casts that are no-ops in one precision are
// needed in the other.
#![allow(clippy::unnecessary_cast)]

use wearsim_core::effects::{self, Effects, CATALOGUE};
use wearsim_core::{ConfigError, Real};

#[test]
fn catalogue_is_consistent() {
    let mut names: Vec<&str> = CATALOGUE.iter().map(|e| e.name).collect();
    names.sort();
    names.dedup();
    assert_eq!(names.len(), 9);
    for e in CATALOGUE.iter() {
        let defaults: Vec<Real> = e.params.iter().map(|p| p.default as Real).collect();
        let mut fx = Effects::NONE;
        fx.set_named(e.name, &defaults)
            .unwrap_or_else(|err| panic!("{}: default rejected: {err}", e.name));
        assert!(fx.any());
        for (i, p) in e.params.iter().enumerate() {
            assert!(
                p.min <= p.default && p.default <= p.max,
                "{}.{}",
                e.name,
                p.name
            );
            // Just outside each bound: rejected, naming `effect.param` and the bounds.
            for bad in [
                p.min - 1e-3 * (1.0 + p.min.abs()),
                p.max + 1e-3 * (1.0 + p.max.abs()),
            ] {
                let mut v = defaults.clone();
                v[i] = bad as Real;
                match Effects::NONE.clone().set_named(e.name, &v) {
                    Err(ConfigError::OutOfRange {
                        field, min, max, ..
                    }) => {
                        assert_eq!(field, format!("{}.{}", e.name, p.name));
                        // The bounds are checked in the precision of `Real`.
                        let bound = |b: f64| b as Real as f64;
                        assert_eq!((min, max), (bound(p.min), bound(p.max)), "{field}");
                    }
                    other => panic!("{}.{} = {bad}: {other:?}", e.name, p.name),
                }
            }
        }
    }
    assert!(Effects::NONE.clone().set_named("ball-defect", &[]).is_err());
}

/// The registry: names round-trip through `EffectKind`, every parameter's error field is
/// `effect.param`, the values read back are those set, and a misspelled name is an error.
#[test]
fn registry_round_trips_and_rejects_unknown_names() {
    use wearsim_core::effects::{EffectKind, EffectParams, COUNT};
    assert_eq!(EffectKind::ALL.len(), COUNT);
    for (k, e) in EffectKind::ALL.iter().zip(CATALOGUE.iter()) {
        assert_eq!(k.spec(), e);
        assert_eq!(EffectKind::from_name(k.name()), Ok(*k));
        for p in e.params {
            assert_eq!(p.field, format!("{}.{}", e.name, p.name));
        }
        for f in e.fit.fitted {
            assert!(e.param(f.name).is_some(), "{}: fitted `{}`", e.name, f.name);
        }
        for (n, _) in e.fit.fixed {
            assert!(e.param(n).is_some(), "{}: fixed `{n}`", e.name);
        }
        // Distinct in-bounds values read back unchanged and in order.
        let v: Vec<Real> = e
            .params
            .iter()
            .enumerate()
            .map(|(i, p)| {
                (p.min + (p.max - p.min) * (i as f64 + 1.0) / (e.params.len() as f64 + 2.0)) as Real
            })
            .collect();
        let mut fx = Effects::NONE;
        fx.set(*k, &v).unwrap();
        assert!(fx.is_on(*k));
        let got = fx.get(*k).unwrap();
        assert_eq!(&got[..v.len()], &v[..], "{}", e.name);
        fx.clear(*k);
        assert_eq!(fx, Effects::NONE);
        // A wrong count is rejected.
        assert!(fx.set(*k, &v[..v.len() - 1]).is_err());
    }
    // The per-file validation uses the same bounds.
    let p = effects::slip::Params { fraction: 0.3 };
    assert!(matches!(
        p.checked(),
        Err(ConfigError::OutOfRange { field: "slip.fraction", max, .. }) if max == 0.2 as Real as f64
    ));
    for bad in ["edge_shape", "Slip", "loadzone", ""] {
        assert!(EffectKind::from_name(bad).is_err(), "{bad}");
        assert!(effects::info(bad).is_none());
        let mut fx = Effects::NONE;
        assert!(fx.set_named(bad, &[]).is_err());
    }
}
