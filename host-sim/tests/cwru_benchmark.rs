//! CWRU benchmark accuracy (Smith & Randall 2015 data set): the fixed analysis chain must
//! diagnose the family of at least 90 % of the inner- and outer-race records (0.007-0.021 in)
//! and call the normal baseline healthy. Skips with a message when the data folder is absent,
//! fails when it is absent and `CI=true` (see `io::data_dir`).

use wearsim_host::analysis::FaultFamily;
use wearsim_host::analyze::Method;
use wearsim_host::cwru_benchmark::{run_benchmark, CLASSES};

/// Target fraction of inner- and outer-race records whose family is diagnosed correctly.
const TARGET: f64 = 0.90;

#[test]
fn cwru_inner_outer_and_normal_meet_the_target() -> Result<(), Box<dyn std::error::Error>> {
    let Some(dir) = wearsim_host::io::data_dir()? else {
        eprintln!("skipping: CWRU data not found (set WEARSIM_DATA)");
        return Ok(());
    };
    if !dir.join("cwru").is_dir() {
        if std::env::var("CI").is_ok_and(|v| v == "true" || v == "1") {
            return Err(format!("{}/cwru is missing", dir.display()).into());
        }
        eprintln!("skipping: {}/cwru not found", dir.display());
        return Ok(());
    }
    let r = run_benchmark(&dir, &Method::default())?;
    let races = r.accuracy_of("inner+outer race").ok_or("no race group")?;
    let normal = r.accuracy_of("normal").ok_or("no normal group")?;
    let ball = r.accuracy_of("ball").ok_or("no ball group")?;
    eprintln!(
        "inner+outer {}/{}, normal {}/{}, ball {}/{} (reported, no target)",
        races.correct, races.total, normal.correct, normal.total, ball.correct, ball.total
    );
    // The folder holds 12 inner-race and 28 outer-race records and one baseline.
    assert_eq!(races.total, 40, "expected the 40 IR/OR records");
    assert_eq!(normal.total, 1, "expected the normal baseline");
    assert!(
        races.fraction >= TARGET,
        "inner+outer race accuracy {:.1} % < {:.0} %: {:?}",
        100.0 * races.fraction,
        100.0 * TARGET,
        r.confusion
    );
    assert_eq!(normal.correct, 1, "normal baseline diagnosed as a fault");
    // No read/analysis errors, and the confusion matrix accounts for every file.
    assert!(r.files.iter().all(|f| f.error.is_none()));
    let total: usize = r.confusion.iter().flatten().sum();
    assert_eq!(total, r.files.len());
    // A race fault is never taken for the other race (a physics-level confusion).
    let ir = CLASSES
        .iter()
        .position(|c| *c == FaultFamily::InnerRace)
        .unwrap_or(0);
    let or = CLASSES
        .iter()
        .position(|c| *c == FaultFamily::OuterRace)
        .unwrap_or(1);
    assert_eq!(
        r.confusion[ir][or] + r.confusion[or][ir],
        0,
        "{:?}",
        r.confusion
    );
    Ok(())
}
