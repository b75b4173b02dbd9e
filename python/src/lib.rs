//! `wearsim._wearsim`: the native half of the `wearsim` Python package (the Python half,
//! `wearsim/__init__.py`, turns JSON strings into dicts and adds the Dask scale-out).
//! Every call that computes releases the GIL (`py.detach`). Bad input raises
//! `wearsim.ConfigError` (a `ValueError` subclass) with the message naming the field and
//! its allowed range; a failed run raises `RuntimeError`.

use numpy::{IntoPyArray, PyArray1, PyReadonlyArray1};
use pyo3::create_exception;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use std::path::PathBuf;
use wearsim_host::config::ScenarioFile;
use wearsim_host::simulate::Scenario;
use wearsim_host::sweep::{self, SweepError, SweepSpec};

mod interrupt;

// Module `wearsim`, where the class is public: pickle finds it there (as `_wearsim`, a
// name no import resolves, a ConfigError raised in a multiprocessing worker could not be
// sent back), and tracebacks read `wearsim.ConfigError`.
create_exception!(
    wearsim,
    ConfigError,
    PyValueError,
    "Bad input: the message names the field and its allowed range."
);

fn cfg_err(m: impl std::fmt::Display) -> PyErr {
    ConfigError::new_err(wearsim_host::cmd::exit::compact_numbers(&m.to_string()))
}

fn sweep_err(e: SweepError) -> PyErr {
    match e {
        SweepError::Input(m) => cfg_err(m),
        SweepError::Run(m) => PyRuntimeError::new_err(m),
        e @ SweepError::Cancelled => PyRuntimeError::new_err(e.to_string()),
    }
}

/// Merges `over` into `base` (tables recursively, anything else replaced).
fn merge(base: &mut toml::Value, over: toml::Value) {
    match (base, over) {
        (toml::Value::Table(b), toml::Value::Table(o)) => {
            for (k, v) in o {
                match b.get_mut(&k) {
                    Some(slot) if slot.is_table() && v.is_table() => merge(slot, v),
                    _ => {
                        b.insert(k, v);
                    }
                }
            }
        }
        (b, o) => *b = o,
    }
}

/// Deepest nesting of dicts and lists [`to_toml`] converts: a configuration is a few levels
/// deep (`effect[0].params.noise`). Without a bound a dict holding itself, or a list
/// nested some 10 000 deep, overflowed the native stack and killed the interpreter.
pub const MAX_DEPTH: usize = 32;

/// `obj` (a dict with string keys, list, tuple, str, bool, int, float, or a numpy scalar)
/// as a TOML value, `None` for Python's `None` (an absent key: the default). TOML rather
/// than JSON, because TOML holds NaN and infinities: they reach the field's own range check,
/// which names the field. `field` names `obj` in errors (`speed.rpm`, `effect[0]`).
fn to_toml(obj: &Bound<'_, PyAny>, field: &str) -> PyResult<Option<toml::Value>> {
    to_toml_at(obj, field, 0)
}

/// [`to_toml`] of `obj` found `depth` dicts and lists deep.
fn to_toml_at(obj: &Bound<'_, PyAny>, field: &str, depth: usize) -> PyResult<Option<toml::Value>> {
    use pyo3::types::{PyBool, PyDict, PyFloat, PyList, PyString, PyTuple};
    let bad = |what: String| match field {
        "" => cfg_err(what),
        _ => cfg_err(format!("{field}: {what}")),
    };
    let nested = obj.is_instance_of::<PyDict>()
        || obj.is_instance_of::<PyList>()
        || obj.is_instance_of::<PyTuple>();
    if nested && depth >= MAX_DEPTH {
        return Err(bad(format!(
            "nested more than {MAX_DEPTH} dicts or lists deep (a configuration is a few levels deep: does a dict or list contain itself?)"
        )));
    }
    if obj.is_none() {
        return Ok(None);
    }
    if obj.is_instance_of::<PyBool>() {
        return Ok(Some(toml::Value::Boolean(obj.extract()?)));
    }
    if obj.is_instance_of::<PyString>() {
        return Ok(Some(toml::Value::String(obj.extract()?)));
    }
    if let Ok(d) = obj.cast::<PyDict>() {
        let mut t = toml::map::Map::new();
        for (k, v) in d.iter() {
            let k: String = k
                .extract()
                .map_err(|_| bad(format!("keys must be strings, got {k}")))?;
            let name = if field.is_empty() {
                k.clone()
            } else {
                format!("{field}.{k}")
            };
            if let Some(v) = to_toml_at(&v, &name, depth + 1)? {
                t.insert(k, v);
            }
        }
        return Ok(Some(toml::Value::Table(t)));
    }
    if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        let mut a = Vec::new();
        for (i, v) in obj.try_iter()?.enumerate() {
            let name = format!("{field}[{i}]");
            match to_toml_at(&v?, &name, depth + 1)? {
                Some(v) => a.push(v),
                None => return Err(cfg_err(format!("{name}: None is not allowed in a list"))),
            }
        }
        return Ok(Some(toml::Value::Array(a)));
    }
    // numpy arrays and scalars as the Python lists and numbers they hold (an array has an
    // `__index__` that fails, so it was refused as "out of the 64-bit integer range").
    if obj.hasattr("ndim")? && obj.hasattr("tolist")? {
        let plain = obj.call_method0("tolist")?;
        if !plain.hasattr("ndim")? {
            return to_toml_at(&plain, field, depth);
        }
    }
    // Python and numpy integers (anything with `__index__`), then anything with `__float__`.
    if !obj.is_instance_of::<PyFloat>() && obj.hasattr("__index__")? {
        return match obj.extract::<i64>() {
            Ok(i) => Ok(Some(toml::Value::Integer(i))),
            Err(_) => Err(bad(format!("{obj} is out of the 64-bit integer range"))),
        };
    }
    match obj.extract::<f64>() {
        Ok(x) => Ok(Some(toml::Value::Float(x))),
        Err(_) => Err(bad(format!(
            "expected a number, string, bool, list or dict, got {}",
            obj.get_type().name()?
        ))),
    }
}

/// The scenario file of `source` (a preset name, TOML text, or a dict) with the dict
/// `overrides` merged over it. A repeated effect is refused in the source and in the
/// result by the command line's own check (`effects::check_unique`), as `wearsim simulate`
/// refuses it (the dict and the merge bypass the TOML parser, which runs that check).
fn scenario_file(
    source: &Bound<'_, PyAny>,
    overrides: &Bound<'_, PyAny>,
) -> PyResult<ScenarioFile> {
    let (source, seed_src) = take_big_seed(source)?;
    let (overrides, seed_over) = take_big_seed(overrides)?;
    let mut v = if let Ok(text) = source.extract::<String>() {
        if wearsim_core::presets::by_name(text.trim()).is_some() {
            toml::Value::Table(toml::map::Map::from_iter([(
                "preset".to_string(),
                toml::Value::String(text.trim().to_string()),
            )]))
        } else if text.contains('=') || text.contains('[') {
            toml::from_str(&text).map_err(|e| {
                let m = wearsim_host::config::toml_error::describe(&text, &e);
                cfg_err(format!("configuration TOML: {m}"))
            })?
        } else {
            return Err(cfg_err(format!(
                "`preset` = \"{text}\" is not a preset; use one of: {} (or pass TOML text or a dict)",
                wearsim_core::presets::NAMES.join(", ")
            )));
        }
    } else {
        match to_toml(&source, "")? {
            Some(t @ toml::Value::Table(_)) => t,
            _ => {
                return Err(cfg_err(
                    "preset_or_config: expected a preset name, TOML text or a dict",
                ))
            }
        }
    };
    if let Ok(f) = v.clone().try_into::<ScenarioFile>() {
        check_effects(&f)?;
    }
    if let Some(o) = to_toml(&overrides, "")? {
        merge(&mut v, o);
    }
    let mut file: ScenarioFile = v
        .try_into()
        .map_err(|e| cfg_err(format!("configuration: {e}")))?;
    check_effects(&file)?;
    // A big seed as the dicts gave it: the overrides' seed, if any, wins over the source's.
    let over_has_seed = match overrides.cast::<pyo3::types::PyDict>() {
        Ok(d) => d.get_item("seed")?.is_some_and(|v| !v.is_none()),
        Err(_) => false,
    };
    if let Some(seed) = seed_over.or(seed_src.filter(|_| !over_has_seed)) {
        file.seed = Some(seed);
    }
    Ok(file)
}

/// Refuses a repeated effect (the command line's rule and message).
fn check_effects(file: &ScenarioFile) -> PyResult<()> {
    wearsim_host::effects::check_unique(
        file.effect.iter().map(|e| e.name.as_str()),
        "effect",
        ".name",
    )
    .map_err(cfg_err)
}

/// `obj` without its `seed` key when `obj` is a dict whose seed is an integer above
/// TOML's (i64) range but within u64's, and that seed: seeds are u64, as on the command
/// line (`--seed 18446744073709551615`), but the conversion goes through TOML integers.
fn take_big_seed<'py>(obj: &Bound<'py, PyAny>) -> PyResult<(Bound<'py, PyAny>, Option<u64>)> {
    use pyo3::types::{PyBool, PyDict, PyFloat};
    let Ok(d) = obj.cast::<PyDict>() else {
        return Ok((obj.clone(), None));
    };
    let Some(seed) = d.get_item("seed")? else {
        return Ok((obj.clone(), None));
    };
    let int = !seed.is_instance_of::<PyBool>()
        && !seed.is_instance_of::<PyFloat>()
        && seed.hasattr("__index__")?;
    if !int || seed.extract::<i64>().is_ok() {
        return Ok((obj.clone(), None));
    }
    let Ok(big) = seed.extract::<u64>() else {
        return Err(cfg_err(format!(
            "seed = {seed} is out of range: allowed 0 ..= {}",
            u64::MAX
        )));
    };
    let rest = d.copy()?;
    rest.del_item("seed")?;
    Ok((rest.into_any(), Some(big)))
}

/// simulate(source, overrides) -> (accel ndarray, meta JSON); interruptible (Ctrl-C
/// stops the run within one chunk of samples and raises KeyboardInterrupt).
#[pyfunction]
fn simulate<'py>(
    py: Python<'py>,
    source: &Bound<'py, PyAny>,
    overrides: &Bound<'py, PyAny>,
) -> PyResult<(Bound<'py, PyArray1<f64>>, String)> {
    let file = scenario_file(source, overrides)?;
    let (cfg, run) = file.resolve().map_err(cfg_err)?;
    if cfg.channels == wearsim_core::Channels::All {
        return Err(cfg_err(
            "channels = \"all\": simulate returns the acceleration only (velocity and displacement are columns of `wearsim simulate`'s CSV); leave `channels` out or use \"acceleration\"",
        ));
    }
    let sc = Scenario::new(cfg, run).map_err(cfg_err)?;
    let out = interrupt::run(py, || wearsim_host::simulate::run(&sc, |_, _| {}))?
        .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    let meta = serde_json::json!({
        "fs": out.fs,
        "duration_s": sc.run.duration,
        "seed": sc.run.seed,
        "preset": sc.run.preset,
        "settle_s": sc.run.settle,
        "units": "m/s^2",
        "steps": out.steps,
        "wall_s": out.wall_s,
        "scenario": file,
        "config": sc.model.config(),
        "wearsim_version": env!("CARGO_PKG_VERSION"),
    });
    Ok((out.accel.into_pyarray(py), meta.to_string()))
}

/// scenario_toml(source) -> the scenario `source` (a dict, TOML text or a preset name, as
/// `simulate` takes it) as TOML text, checked as `simulate` checks it; for the file-level
/// commands' `--config` (`life(config={...})`).
#[pyfunction]
fn scenario_toml(source: &Bound<'_, PyAny>) -> PyResult<String> {
    let none = pyo3::types::PyDict::new(source.py());
    let file = scenario_file(source, none.as_any())?;
    file.resolve().map_err(cfg_err)?;
    toml::to_string(&file).map_err(|e| cfg_err(format!("config: {e}")))
}

/// effects() -> JSON of the effect registry.
#[pyfunction]
fn effects() -> String {
    wearsim_host::effects::catalogue_json().to_string()
}

/// bearings() -> JSON of the catalogue bearings (geometries of public data sets that are no
/// model preset) with their kinematic orders and sources.
#[pyfunction]
fn bearings() -> PyResult<String> {
    let rows =
        wearsim_host::cmd::presets::bearings().map_err(|e| PyRuntimeError::new_err(e.message))?;
    Ok(serde_json::Value::Array(rows).to_string())
}

/// presets() -> JSON of the presets with derived frequencies.
#[pyfunction]
fn presets() -> PyResult<String> {
    let rows =
        wearsim_host::cmd::presets::catalogue().map_err(|e| PyRuntimeError::new_err(e.message))?;
    Ok(serde_json::Value::Array(rows).to_string())
}

/// analyze(signal, fs, bearing, rpm, geometry, trust_rpm) -> JSON of `wearsim analyze
/// --json`; `geometry` is `--bearing-geometry`'s `elements=N,ball=MM,pitch=MM,angle=DEG`,
/// `trust_rpm` is `--trust-rpm`.
#[pyfunction]
#[pyo3(signature = (signal, fs, bearing=None, rpm=None, geometry=None, trust_rpm=false))]
fn analyze(
    py: Python<'_>,
    signal: PyReadonlyArray1<'_, f64>,
    fs: f64,
    bearing: Option<String>,
    rpm: Option<f64>,
    geometry: Option<String>,
    trust_rpm: bool,
) -> PyResult<String> {
    use wearsim_host::io::record::{MAX_FS, MIN_FS};
    // Named here: the reader's check would name the temporary file, shown as `signal`.
    if !(fs.is_finite() && (MIN_FS..=MAX_FS).contains(&fs)) {
        return Err(cfg_err(format!(
            "fs = {fs} Hz is out of range: allowed {MIN_FS} Hz ..= {MAX_FS} Hz"
        )));
    }
    let x: Vec<f64> = signal.as_array().iter().copied().collect();
    py.detach(move || {
        let dir = tempfile::tempdir().map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        let path = dir.path().join("signal.npy");
        // The temporary file is this call's detail: messages and the result name the
        // argument, `signal`, instead.
        let tmp = path.display().to_string();
        write_npy_f64(&path, &x).map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        let args = wearsim_host::analyze::AnalyzeArgs {
            rpm,
            trust_rpm,
            fs: Some(fs),
            bearing,
            bearing_geometry: geometry,
            json: true,
            ..wearsim_host::analyze::AnalyzeArgs::for_file(path)
        };
        // A geometry error is about the `bearing` argument, not the signal.
        let named = |m: String| {
            m.replace(
                &format!("{tmp}: bearing-geometry"),
                "bearing: bearing-geometry",
            )
            .replace(&tmp, "signal")
        };
        let (mut a, _) = wearsim_host::analyze::analyze(&args).map_err(|e| match e {
            wearsim_host::analyze::AnalyzeError::Input(m) => cfg_err(named(m)),
            wearsim_host::analyze::AnalyzeError::Run(m) => PyRuntimeError::new_err(named(m)),
        })?;
        a.file = PathBuf::from("signal");
        serde_json::to_string(&a).map_err(|e| PyRuntimeError::new_err(e.to_string()))
    })
}

fn write_npy_f64(path: &std::path::Path, x: &[f64]) -> std::io::Result<()> {
    let header = format!(
        "{{'descr': '<f8', 'fortran_order': False, 'shape': ({},), }}",
        x.len()
    );
    let mut h = header.into_bytes();
    while (10 + h.len() + 1) % 64 != 0 {
        h.push(b' ');
    }
    h.push(b'\n');
    let mut buf = Vec::with_capacity(10 + h.len() + 8 * x.len());
    buf.extend_from_slice(b"\x93NUMPY\x01\x00");
    buf.extend_from_slice(&(h.len() as u16).to_le_bytes());
    buf.extend_from_slice(&h);
    for v in x {
        buf.extend_from_slice(&v.to_le_bytes());
    }
    std::fs::write(path, buf)
}

/// cli(argv) -> (exit code, message): runs one `wearsim` subcommand in-process (file
/// level: `life` and `gap` write into their `--out` directory). Ctrl-C stops it
/// (`wearsim_host::cancel`: no report is written; a dense life keeps a checkpoint) and
/// raises KeyboardInterrupt.
#[pyfunction]
fn cli(py: Python<'_>, argv: Vec<String>) -> PyResult<(u8, String)> {
    interrupt::run(py, move || cli_run(argv))
}

/// The work of [`cli`].
fn cli_run(argv: Vec<String>) -> (u8, String) {
    use clap::Parser;
    let mut full = vec!["wearsim".to_string()];
    full.extend(argv);
    match wearsim_host::cmd::Cli::try_parse_from(full) {
        Err(e) => (2, e.to_string()),
        Ok(c) => match c.command {
            None => (2, "no subcommand".into()),
            Some(cmd) => match wearsim_host::cmd::dispatch(cmd) {
                Ok(()) => (0, String::new()),
                Err(e) => (e.code, wearsim_host::cmd::exit::compact_numbers(&e.message)),
            },
        },
    }
}

/// Checks `part = (I, N)`: 0 <= I < N.
fn check_part(part: Option<(u64, u64)>) -> PyResult<()> {
    match part {
        Some((i, n)) if n == 0 || i >= n => {
            Err(cfg_err(format!("part = ({i}, {n}): expected 0 <= I < N")))
        }
        _ => Ok(()),
    }
}

/// sweep_plan(spec_toml, part) -> JSON {shards, records, samples}: parses and validates a
/// spec and `part`.
#[pyfunction]
#[pyo3(signature = (spec, part=None))]
fn sweep_plan(spec: &str, part: Option<(u64, u64)>) -> PyResult<String> {
    check_part(part)?;
    let s = SweepSpec::parse(spec, "spec").map_err(cfg_err)?;
    sweep::validate(&s).map_err(sweep_err)?;
    Ok(serde_json::json!({
        "shards": s.shards(), "records": s.records, "samples_per_record": s.samples(),
        "duration": s.duration,
    })
    .to_string())
}

/// sweep_prepare(spec_toml, out): creates or checks the data set directory.
#[pyfunction]
fn sweep_prepare(py: Python<'_>, spec: &str, out: PathBuf) -> PyResult<()> {
    let s = SweepSpec::parse(spec, "spec").map_err(cfg_err)?;
    py.detach(|| {
        sweep::validate(&s)?;
        sweep::prepare_dir(&s, &out)
    })
    .map_err(sweep_err)
}

/// sweep_shard(spec_toml, out, s) -> records generated (0 when already complete).
#[pyfunction]
fn sweep_shard(py: Python<'_>, spec: &str, out: PathBuf, shard: u64) -> PyResult<u64> {
    let s = SweepSpec::parse(spec, "spec").map_err(cfg_err)?;
    py.detach(|| sweep::shard::run_shard(&s, &out, shard))
        .map_err(sweep_err)
}

/// sweep_finalize(spec_toml, out) -> (complete, bytes).
#[pyfunction]
fn sweep_finalize(py: Python<'_>, spec: &str, out: PathBuf) -> PyResult<(bool, u64)> {
    let s = SweepSpec::parse(spec, "spec").map_err(cfg_err)?;
    py.detach(|| sweep::finalize(&s, &out)).map_err(sweep_err)
}

/// sweep_run(spec_toml, out, threads, part) -> JSON report (local threads; `threads` in
/// 1 ..= [`wearsim_host::lanes::MAX_WORKERS`], the command line's rule).
#[pyfunction]
#[pyo3(signature = (spec, out, threads, part=None))]
fn sweep_run(
    py: Python<'_>,
    spec: &str,
    out: PathBuf,
    threads: usize,
    part: Option<(u64, u64)>,
) -> PyResult<String> {
    check_part(part)?;
    let threads = wearsim_host::lanes::workers("threads =", Some(threads)).map_err(cfg_err)?;
    let s = SweepSpec::parse(spec, "spec").map_err(cfg_err)?;
    let shards = sweep::shard_set(&s, part);
    let r = interrupt::run(py, || sweep::run(&s, &out, &shards, threads, &|_, _| {}))?
        .map_err(sweep_err)?;
    serde_json::to_string(&r).map_err(|e| PyRuntimeError::new_err(e.to_string()))
}

/// read_record(path, channel) -> (samples ndarray, meta JSON): any measurement file
/// `wearsim analyze` reads (CWRU `.mat`, CSV, WAV, NPY, IMS snapshot).
#[pyfunction]
#[pyo3(signature = (path, channel=None))]
fn read_record<'py>(
    py: Python<'py>,
    path: PathBuf,
    channel: Option<String>,
) -> PyResult<(Bound<'py, PyArray1<f64>>, String)> {
    let opts = wearsim_host::io::ReadOptions {
        channel,
        fs: None,
        rpm: None,
    };
    let rec = py
        .detach(|| wearsim_host::io::read_any(&path, &opts))
        .map_err(cfg_err)?;
    let meta = serde_json::json!({
        "fs": rec.fs, "rpm": rec.rpm, "channel": rec.channel, "unit": rec.unit,
        "bearing": rec.bearing, "source": rec.source, "meta": rec.meta,
    });
    Ok((rec.samples.into_pyarray(py), meta.to_string()))
}

/// The native module.
#[pymodule]
fn _wearsim(m: &Bound<'_, PyModule>) -> PyResult<()> {
    // numpy's C API and rust-numpy's borrow-checking API are imported lazily on first use,
    // and a failure there panics: a Ctrl-C pending at the first `simulate` of a process
    // raised PanicException ("Failed to access NumPy array API capsule: KeyboardInterrupt"),
    // which `except Exception` does not catch. Loaded once here, at import (`wearsim`
    // imports numpy first, so both are lookups of modules already loaded).
    {
        use numpy::PyArrayMethods;
        let probe = PyArray1::<f64>::zeros(m.py(), 0, false);
        drop(probe.readonly());
    }
    m.add("ConfigError", m.py().get_type::<ConfigError>())?;
    m.add("__version__", wearsim_host::VERSION)?;
    m.add("MAX_WORKERS", wearsim_host::lanes::MAX_WORKERS)?;
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    m.add_function(wrap_pyfunction!(scenario_toml, m)?)?;
    m.add_function(wrap_pyfunction!(effects, m)?)?;
    m.add_function(wrap_pyfunction!(presets, m)?)?;
    m.add_function(wrap_pyfunction!(bearings, m)?)?;
    m.add_function(wrap_pyfunction!(analyze, m)?)?;
    m.add_function(wrap_pyfunction!(cli, m)?)?;
    m.add_function(wrap_pyfunction!(read_record, m)?)?;
    m.add_function(wrap_pyfunction!(sweep_plan, m)?)?;
    m.add_function(wrap_pyfunction!(sweep_prepare, m)?)?;
    m.add_function(wrap_pyfunction!(sweep_shard, m)?)?;
    m.add_function(wrap_pyfunction!(sweep_finalize, m)?)?;
    m.add_function(wrap_pyfunction!(sweep_run, m)?)?;
    Ok(())
}
