//! `wearsim features DIR --layout ims|femto|xjtu|auto --out FILE.csv`: a folder of raw
//! snapshots of a run-to-failure test into the documented feature table and its sidecar
//! (`docs/feature-tables.md`); arguments, the run ([`crate::features::convert`]) and what
//! is printed.

use crate::cmd::args::CliError;
use crate::cmd::report::print_json;
use crate::features::{convert, FeatureOptions, FeaturesError, RawLayout};
use crate::io::feature_table::FeatureTableError;
use crate::io::IoError;
use clap::Args;
use std::path::PathBuf;

/// `wearsim features` arguments.
#[derive(Debug, Clone, Args)]
pub struct FeaturesArgs {
    /// Folder of raw snapshot files of one test (IMS time-stamp files, FEMTO acc_*.csv, XJTU-SY N.csv).
    pub dir: PathBuf,
    /// Layout of the snapshot files (`auto`: recognised from the first file's content).
    #[arg(long, value_enum, default_value_t = RawLayout::Auto)]
    pub layout: RawLayout,
    /// Table to write (`.csv`); its sidecar goes next to it (`.json`).
    #[arg(long)]
    pub out: PathBuf,
    /// Channel: IMS 1..8 (default 1), FEMTO horiz|vert (default horiz), XJTU-SY header (default horizontal).
    #[arg(long)]
    pub channel: Option<String>,
    /// Shaft speed, rpm (IMS: 2000; FEMTO and XJTU-SY: what the data set's folder names state, `Bearing1_1`, `35Hz12kN`, else required).
    #[arg(long, allow_negative_numbers = true)]
    pub rpm: Option<f64>,
    /// Radial load, N (IMS: 6000 lbf = 26 689 N; FEMTO and XJTU-SY: as `--rpm`).
    #[arg(long)]
    pub load_n: Option<f64>,
    /// wearsim preset of the bearing, or a catalogue bearing that stands for its geometry (`mfpt-nice`, `paderborn-6203`, `xjtu-ldk-uer204`) (IMS: ims-za2115, dropped by another --bearing-geometry, --rpm or --load-n); refused when it contradicts the geometry or operating point.
    #[arg(long)]
    pub preset: Option<String>,
    /// Bearing geometry `elements=N,ball=D,pitch=P,angle=DEG` (mm, degrees; XJTU-SY: LDK UER204).
    #[arg(long)]
    pub bearing_geometry: Option<String>,
    /// Which bearing, free text (default: the folder name).
    #[arg(long)]
    pub bearing_id: Option<String>,
    /// Failure mode: outer-race, inner-race, rolling-element, cage, none, unknown (default); `gap --life` trains only on a life that failed.
    #[arg(long)]
    pub failure_mode: Option<String>,
    /// Machine-readable summary on stdout.
    #[arg(long)]
    pub json: bool,
}

/// `wearsim features`: convert, then print the summary (or `--json`). Every refusal is
/// bad input (exit 2) and writes nothing.
pub fn run(a: &FeaturesArgs) -> Result<(), CliError> {
    if let Some(p) = &a.preset {
        // A model preset, or a catalogue bearing that stands for its geometry (as in a
        // sidecar's `bearing.preset`).
        if crate::geometry::named_geometry(p).is_none() {
            let catalogue: Vec<&str> = crate::geometry::CATALOGUE.iter().map(|e| e.name).collect();
            return Err(CliError::input(format!(
                "--preset {p}: unknown (a model preset, see `wearsim presets`, or a catalogue bearing: {})",
                catalogue.join(", ")
            )));
        }
    }
    if a.bearing_id
        .as_deref()
        .is_some_and(|id| id.trim().is_empty())
    {
        return Err(CliError::input(
            "--bearing-id: empty (free text naming the bearing; leave it out for the folder name)",
        ));
    }
    let o = FeatureOptions {
        channel: a.channel.clone(),
        rpm: a.rpm,
        load_n: a.load_n,
        preset: a.preset.clone(),
        geometry: a.bearing_geometry.clone(),
        bearing_id: a.bearing_id.clone(),
        failure_mode: a.failure_mode.clone(),
    };
    // Writing the table failed (disk full, permissions after the lock was taken): the run
    // failed; everything else is an input the table cannot be made from.
    let s = convert(&a.dir, a.layout, &a.out, &o).map_err(|e| match e {
        FeaturesError::Table(FeatureTableError::Io(IoError::Io {
            op: "create temporary" | "write" | "rename" | "remove old sidecar",
            ..
        })) => CliError::run(e),
        e => CliError::input(e),
    })?;
    if a.json {
        print_json(&s)?;
    } else {
        println!(
            "{} snapshots ({:?} layout) over {:.2} h: RMS {:.4} -> {:.4} {} (x{:.2}); {} skipped{}",
            s.snapshots,
            s.layout,
            s.hours,
            s.rms_first_last.0,
            s.rms_first_last.1,
            s.meta.unit,
            s.rms_first_last.1 / s.rms_first_last.0,
            s.skipped.len(),
            if s.missing.is_empty() {
                String::new()
            } else {
                format!("; missing from the numbering: {}", s.missing.join(", "))
            }
        );
        for (what, v, src, flag) in [
            ("speed", s.meta.rpm, &s.rpm_source, "--rpm"),
            ("load", s.meta.radial_load_n, &s.load_source, "--load-n"),
        ] {
            if src.starts_with("folder name") {
                println!("{what} {v} from the {src}; {flag} overrides");
            }
        }
        println!("wrote {} and {}", s.csv.display(), s.sidecar.display());
    }
    Ok(())
}
