//! What the reporting commands share: the Markdown + JSON report pair, the formatting of an
//! optional figure, and printing a result as JSON (`--json`).

use crate::cmd::args::CliError;

/// `x` with `digits` decimals, or `none`.
pub fn fig(x: Option<f64>, digits: usize) -> String {
    x.map(|v| format!("{v:.digits$}"))
        .unwrap_or_else(|| "none".into())
}

/// Prints `v` as pretty JSON on stdout; a value that cannot be serialised fails the run.
pub fn print_json(v: &impl serde::Serialize) -> Result<(), CliError> {
    println!(
        "{}",
        serde_json::to_string_pretty(v).map_err(CliError::run)?
    );
    Ok(())
}

/// Writes `out/STEM.md` and `out/STEM.json` (each atomically), then prints the JSON
/// (`json`) or the Markdown and the files written.
pub fn write_report(
    out: &std::path::Path,
    stem: &str,
    md: &str,
    v: &impl serde::Serialize,
    json: bool,
) -> Result<(), CliError> {
    let mdp = out.join(format!("{stem}.md"));
    crate::life::output::write_atomic(&mdp, md.as_bytes())
        .map_err(|e| CliError::run(format!("{}: {e}", mdp.display())))?;
    let jp = out.join(format!("{stem}.json"));
    let js = serde_json::to_string_pretty(v).map_err(CliError::run)?;
    crate::life::output::write_atomic(&jp, js.as_bytes())
        .map_err(|e| CliError::run(format!("{}: {e}", jp.display())))?;
    if json {
        println!("{js}");
    } else {
        print!("{md}");
        println!("wrote {}\nwrote {}", mdp.display(), jp.display());
    }
    Ok(())
}
