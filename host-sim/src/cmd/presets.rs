//! `wearsim presets` and `wearsim effects`: the built-in presets with their derived
//! frequencies, and the catalogue of candidate effects.

use crate::cmd::args::CliError;
use serde_json::json;

/// `wearsim effects`.
pub fn effects(json: bool) -> Result<(), CliError> {
    if json {
        crate::cmd::report::print_json(&crate::effects::catalogue_json())?;
    } else {
        print!("{}", crate::effects::catalogue_text());
    }
    Ok(())
}

/// `wearsim presets`.
pub fn run(json: bool) -> Result<(), CliError> {
    let rows = catalogue()?;
    print_catalogue(json, rows)
}

/// Every preset with its geometry and derived frequencies (the `--json` rows).
pub fn catalogue() -> Result<Vec<serde_json::Value>, CliError> {
    let mut rows = vec![];
    for name in wearsim_core::presets::NAMES {
        let Some(cfg) = wearsim_core::presets::by_name(name) else {
            continue;
        };
        let model = wearsim_core::Model::new_checked(cfg.clone())
            .map_err(|e| CliError::run(format!("preset {name}: {e}")))?;
        let shaft_hz = cfg.speed.shaft_hz(0.0);
        let k = model.frequencies_at(shaft_hz);
        let waviness = crate::summary::waviness_hz(&model, shaft_hz);
        let o = model.orders();
        rows.push(json!({
            "name": name,
            "description": crate::cmd::args::preset_description(name),
            "elements": cfg.bearing.elements,
            "element_diameter_m": cfg.bearing.element_diameter,
            "pitch_diameter_m": cfg.bearing.pitch_diameter,
            "contact_angle_deg": cfg.bearing.contact_angle.to_degrees(),
            "shaft_hz": k.shaft_hz,
            "orders": {"ftf": o.ftf, "bpfo": o.bpfo, "bpfi": o.bpfi, "bsf": o.bsf},
            "hz": {"ftf": k.ftf, "bpfo": k.bpfo, "bpfi": k.bpfi, "bsf": k.bsf, "waviness": waviness},
            "natural_hz": k.natural_hz,
            "damping_ratio": model.damping_ratio(),
            "fs": cfg.output_rate,
            "oversample": model.oversample(),
        }));
    }
    Ok(rows)
}

fn print_catalogue(json: bool, rows: Vec<serde_json::Value>) -> Result<(), CliError> {
    if json {
        crate::cmd::report::print_json(&rows)?;
        return Ok(());
    }
    println!(
        "{:<18} {:>3} {:>8} {:>8} {:>6} {:>8} {:>8} {:>8} {:>8} {:>8} {:>9} {:>7}",
        "preset",
        "N",
        "Bd mm",
        "P mm",
        "deg",
        "1x Hz",
        "FTF",
        "BPFO",
        "BPFI",
        "BSF",
        "fn Hz",
        "zeta"
    );
    for r in &rows {
        println!(
            "{:<18} {:>3} {:>8.3} {:>8.2} {:>6.2} {:>8.2} {:>8.2} {:>8.2} {:>8.2} {:>8.2} {:>9.1} {:>7.3}",
            r["name"].as_str().unwrap_or(""),
            r["elements"],
            r["element_diameter_m"].as_f64().unwrap_or(0.0) * 1e3,
            r["pitch_diameter_m"].as_f64().unwrap_or(0.0) * 1e3,
            r["contact_angle_deg"].as_f64().unwrap_or(0.0),
            r["shaft_hz"].as_f64().unwrap_or(0.0),
            r["hz"]["ftf"].as_f64().unwrap_or(0.0),
            r["hz"]["bpfo"].as_f64().unwrap_or(0.0),
            r["hz"]["bpfi"].as_f64().unwrap_or(0.0),
            r["hz"]["bsf"].as_f64().unwrap_or(0.0),
            r["natural_hz"].as_f64().unwrap_or(0.0),
            r["damping_ratio"].as_f64().unwrap_or(0.0),
        );
    }
    for r in &rows {
        println!(
            "  {}: {}",
            r["name"].as_str().unwrap_or(""),
            r["description"].as_str().unwrap_or("")
        );
    }
    println!(
        "\ncatalogue bearings (a geometry, no model: `--bearing NAME` in analyze, gap and features; a simulation scales the nearest preset's structure to it)"
    );
    println!(
        "{:<18} {:>3} {:>8} {:>8} {:>6} {:>8} {:>8} {:>8} {:>8}   (orders of the shaft speed)",
        "bearing", "N", "Bd mm", "P mm", "deg", "FTF", "BPFO", "BPFI", "BSF"
    );
    for b in bearings()? {
        println!(
            "{:<18} {:>3} {:>8.3} {:>8.2} {:>6.2} {:>8.4} {:>8.4} {:>8.4} {:>8.4}",
            b["name"].as_str().unwrap_or(""),
            b["elements"],
            b["ball_mm"].as_f64().unwrap_or(0.0),
            b["pitch_mm"].as_f64().unwrap_or(0.0),
            b["angle_deg"].as_f64().unwrap_or(0.0),
            b["orders"]["ftf"].as_f64().unwrap_or(0.0),
            b["orders"]["bpfo"].as_f64().unwrap_or(0.0),
            b["orders"]["bpfi"].as_f64().unwrap_or(0.0),
            b["orders"]["bsf"].as_f64().unwrap_or(0.0),
        );
        println!("  {}", b["source"].as_str().unwrap_or(""));
    }
    Ok(())
}

/// The catalogue bearings ([`crate::geometry::CATALOGUE`]): bearings of public data sets
/// that are geometries, not model presets, with their kinematic orders (FTF, BPFO, BPFI,
/// BSF per shaft revolution, eq. 17–20 of the thesis) and the source of their numbers.
pub fn bearings() -> Result<Vec<serde_json::Value>, CliError> {
    crate::geometry::CATALOGUE
        .iter()
        .map(|e| {
            let g = e.geometry;
            let m = g
                .model()
                .map_err(|err| CliError::run(format!("catalogue bearing {}: {err}", e.name)))?;
            let k = crate::kinematics::of_config(&m.model, 60.0)
                .map_err(|err| CliError::run(format!("catalogue bearing {}: {err}", e.name)))?;
            Ok(json!({
                "name": e.name,
                "description": e.description,
                "elements": g.elements,
                "ball_mm": g.ball_mm,
                "pitch_mm": g.pitch_mm,
                "angle_deg": g.angle_deg,
                "orders": {"ftf": k.ftf, "bpfo": k.bpfo, "bpfi": k.bpfi, "bsf": k.bsf},
                "source": e.source,
            }))
        })
        .collect()
}
