//! Candidate effects on the command line (`--effect NAME[:PARAM=VALUE,...]`), in the
//! scenario file (`[[effect]]` with `name` and `params`) and in `wearsim effects`. The
//! catalogue (names, units, defaults, bounds) is the core's effect registry
//! ([`wearsim_core::effects::EffectKind`], each effect's [`EffectSpec`]); parameters not
//! given take their default.

use serde::{Deserialize, Serialize};
use serde_json::{json, Value};
use std::collections::BTreeMap;
use wearsim_core::effects::{EffectKind, EffectSpec, Effects};

/// One `[[effect]]` table, or one `--effect` argument.
#[derive(Debug, Clone, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct EffectSection {
    /// Effect name (`wearsim effects`).
    pub name: String,
    /// Parameter values; absent ones take the default.
    #[serde(default)]
    pub params: BTreeMap<String, f64>,
}

fn names() -> String {
    EffectKind::ALL
        .iter()
        .map(|k| k.name())
        .collect::<Vec<_>>()
        .join(", ")
}

/// The effect called `name`; an unknown name is an error listing the known ones.
pub fn kind(name: &str) -> Result<EffectKind, String> {
    EffectKind::from_name(name)
        .map_err(|_| format!("unknown effect `{name}`; known effects: {}", names()))
}

fn lookup(name: &str) -> Result<(EffectKind, &'static EffectSpec), String> {
    kind(name).map(|k| (k, k.spec()))
}

/// Parses `NAME[:PARAM=VALUE,...]`.
pub fn parse_arg(spec: &str) -> Result<EffectSection, String> {
    let (name, rest) = match spec.split_once(':') {
        Some((n, r)) => (n.trim(), r.trim()),
        None => (spec.trim(), ""),
    };
    lookup(name)?;
    let mut params = BTreeMap::new();
    for kv in rest.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        let Some((k, v)) = kv.split_once('=') else {
            return Err(format!(
                "effect `{name}`: `{kv}` is not PARAM=VALUE (in --effect {spec})"
            ));
        };
        let value: f64 = v.trim().parse().map_err(|_| {
            format!(
                "effect `{name}`: parameter `{}` = `{}` is not a number",
                k.trim(),
                v.trim()
            )
        })?;
        if params.insert(k.trim().to_string(), value).is_some() {
            return Err(format!(
                "effect `{name}`: parameter `{}` is given twice (in --effect {spec}); give each parameter once",
                k.trim()
            ));
        }
    }
    Ok(EffectSection {
        name: name.to_string(),
        params,
    })
}

/// Switches `sec` on in `fx`: unknown effects or parameters and out-of-bounds values are
/// rejected with a message naming them and the bounds.
pub fn apply(fx: &mut Effects, sec: &EffectSection) -> Result<(), String> {
    let (kind, info) = lookup(&sec.name)?;
    for k in sec.params.keys() {
        if !info.params.iter().any(|p| p.name == k) {
            let known: Vec<&str> = info.params.iter().map(|p| p.name).collect();
            return Err(format!(
                "effect `{}` has no parameter `{k}`; its parameters: {}",
                info.name,
                known.join(", ")
            ));
        }
    }
    let mut values = Vec::with_capacity(info.params.len());
    for p in info.params {
        let v = sec.params.get(p.name).copied().unwrap_or(p.default);
        if !(v >= p.min && v <= p.max) {
            let unit = if p.unit == "-" { "" } else { p.unit };
            return Err(format!(
                "effect `{}`: parameter `{}` = {v} is outside its bounds [{}, {}] {unit}",
                info.name, p.name, p.min, p.max
            )
            .trim_end()
            .to_string());
        }
        values.push(v);
    }
    fx.set(kind, &values)
        .map_err(|e| format!("effect `{}`: {e}", info.name))
}

/// Checks that no effect name appears twice in `names` (one scenario file's
/// `[[effect]]` tables, one command line's `--effect` arguments or one sweep's
/// `[[effect]]` draws; `what` names the list and `field` the entry's field, if any, in
/// the message): a repeated effect would silently lose the first one's parameters.
pub fn check_unique<'a>(
    names: impl IntoIterator<Item = &'a str>,
    what: &str,
    field: &str,
) -> Result<(), String> {
    let mut seen: Vec<&str> = Vec::new();
    for (i, name) in names.into_iter().enumerate() {
        if let Some(j) = seen.iter().position(|o| *o == name) {
            return Err(format!(
                "`{what}[{i}]{field}` = \"{name}\" repeats `{what}[{j}]`: give each effect once, with all its parameters"
            ));
        }
        seen.push(name);
    }
    Ok(())
}

/// Checks a flag's list of effect names (`--effects a,b`): each a known effect
/// ([`wearsim_core::effects::info`]) and none listed twice; the message names the flag.
pub fn check_listed(names: &[String], flag: &str) -> Result<(), String> {
    for (i, e) in names.iter().enumerate() {
        if wearsim_core::effects::info(e).is_none() {
            return Err(format!(
                "{flag}: unknown effect `{e}` (see `wearsim effects`)"
            ));
        }
        if names[..i].contains(e) {
            return Err(format!(
                "{flag}: `{e}` is listed twice; list each effect once"
            ));
        }
    }
    Ok(())
}

/// Builds the effects of a list of sections (a later section of the same effect wins:
/// the command line's `--effect` replaces the scenario file's; within one source a
/// repeat is refused by [`check_unique`]).
pub fn build(sections: &[EffectSection]) -> Result<Effects, String> {
    let mut fx = Effects::NONE;
    for s in sections {
        apply(&mut fx, s)?;
    }
    Ok(fx)
}

/// The catalogue as JSON: a list of effects with their parameters.
pub fn catalogue_json() -> Value {
    Value::Array(
        EffectKind::ALL
            .iter()
            .map(|k| {
                let e = k.spec();
                json!({
                    "name": e.name,
                    "description": e.summary,
                    "params": e.params.iter().map(|p| json!({
                        "name": p.name, "unit": p.unit, "default": p.default,
                        "min": p.min, "max": p.max, "description": p.doc,
                    })).collect::<Vec<_>>(),
                })
            })
            .collect(),
    )
}

/// The catalogue as text.
pub fn catalogue_text() -> String {
    let mut s = String::new();
    for e in EffectKind::ALL.iter().map(|k| k.spec()) {
        s.push_str(&format!("{:<18} {}\n", e.name, e.summary));
        for p in e.params {
            s.push_str(&format!(
                "    {:<15} {:>6}  default {:<8} bounds [{}, {}]  {}\n",
                p.name, p.unit, p.default, p.min, p.max, p.doc
            ));
        }
    }
    s.push_str("usage: --effect NAME[:PARAM=VALUE,...] (repeatable), or [[effect]] name = \"...\", params = { ... } in the scenario file\n");
    s
}

#[cfg(test)]
mod tests {
    use crate::config::ScenarioFile;

    /// `--effects sensor,sensor` was accepted (and fitted twice); an unknown name and a
    /// repeat are named with the flag.
    #[test]
    fn a_flags_effect_list_names_an_unknown_or_repeated_effect() {
        let list = |v: &[&str]| v.iter().map(|s| s.to_string()).collect::<Vec<_>>();
        assert!(super::check_listed(&list(&["sensor", "slip"]), "--effects").is_ok());
        let e = super::check_listed(&list(&["sensor", "slip", "sensor"]), "--effects").unwrap_err();
        assert!(e.contains("--effects: `sensor` is listed twice"), "{e}");
        let e = super::check_listed(&list(&["sensr"]), "--effects").unwrap_err();
        assert!(e.contains("unknown effect `sensr`"), "{e}");
    }

    #[test]
    fn a_repeated_effect_is_refused_and_the_command_line_replaces_the_file() {
        let text = "preset = \"thesis-61810\"\n[[effect]]\nname = \"slip\"\nparams = { fraction = 0.02 }\n[[effect]]\nname = \"slip\"\nparams = { fraction = 0.05 }\n";
        let e = ScenarioFile::parse(text, "t.toml").unwrap_err().to_string();
        assert!(
            e.contains("`effect[1].name` = \"slip\" repeats `effect[0]`"),
            "{e}"
        );

        let one = "preset = \"thesis-61810\"\n[[effect]]\nname = \"slip\"\nparams = { fraction = 0.02 }\n";
        let mut f = ScenarioFile::parse(one, "t.toml").unwrap();
        crate::cmd::args::add_effect_args(&mut f, &["slip:fraction=0.05".into()]).unwrap();
        assert_eq!(f.effect.len(), 1);
        assert_eq!(f.effect[0].params.get("fraction"), Some(&0.05));

        let twice = ["slip:fraction=0.05".to_string(), "slip".to_string()];
        let e = crate::cmd::args::add_effect_args(&mut f, &twice).unwrap_err();
        assert_eq!(e.code, crate::cmd::exit::BAD_INPUT);
        let e = e.message;
        assert!(
            e.contains("`--effect[1]` = \"slip\" repeats `--effect[0]`"),
            "{e}"
        );
        // Nothing of a refused command line reaches the scenario.
        assert_eq!(f.effect[0].params.get("fraction"), Some(&0.05));
    }

    /// A parameter given twice in one `--effect` is named (the last value was kept,
    /// silently).
    #[test]
    fn a_parameter_given_twice_is_refused() {
        let e = super::parse_arg("sensor:noise=1,noise=2").unwrap_err();
        assert!(e.contains("parameter `noise` is given twice"), "{e}");
        assert!(super::parse_arg("sensor:noise=1,hum=0.1").is_ok());
    }
}
