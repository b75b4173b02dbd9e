//! The sweep's index: one Parquet row per record holding every label and every parameter,
//! resolved (columns: record, shard, row, seed, preset, rpm, shaft_hz, radial_load, fault,
//! stage, fs, duration, samples, then per spec effect `effect.NAME` (on/off) and
//! `NAME.PARAM` (value, drawn whether on or not), then `config`, the record's scenario
//! file as TOML: `wearsim simulate --config` on it reproduces the record).
//! Written with the `parquet` crate's low-level writer (no arrow, no compression).

use super::record::{cells, record};
use super::shard::range;
use super::spec::SweepSpec;
use super::SweepError;
use parquet::basic::{LogicalType, Repetition, Type as Physical};
use parquet::data_type::{BoolType, ByteArray, ByteArrayType, DoubleType, Int64Type};
use parquet::file::properties::WriterProperties;
use parquet::file::writer::SerializedFileWriter;
use parquet::schema::types::Type;
use std::sync::Arc;

/// One column's values.
#[derive(Debug, Clone, PartialEq)]
pub enum Column {
    /// 64-bit integers.
    I64(Vec<i64>),
    /// 64-bit floats.
    F64(Vec<f64>),
    /// Booleans.
    Bool(Vec<bool>),
    /// UTF-8 strings.
    Str(Vec<String>),
}

/// Records per Parquet row group of the index: the index is built and written one row
/// group at a time, so its memory is bounded (about 400 bytes per row, most of it the
/// `config` text: some 26 MB per group) whatever the number of records.
pub const ROW_GROUP: u64 = 65_536;

/// The index rows of records `first..end` as named columns, in file order.
pub fn columns(
    spec: &SweepSpec,
    first: u64,
    end: u64,
) -> Result<Vec<(String, Column)>, SweepError> {
    let cells = cells(spec);
    let end = end.min(spec.records);
    let n = end.saturating_sub(first) as usize;
    let mut record_no = Vec::with_capacity(n);
    let mut shard = Vec::with_capacity(n);
    let mut row = Vec::with_capacity(n);
    let mut seed = Vec::with_capacity(n);
    let mut preset = Vec::with_capacity(n);
    let mut rpm = Vec::with_capacity(n);
    let mut shaft_hz = Vec::with_capacity(n);
    let mut load = Vec::with_capacity(n);
    let mut fault = Vec::with_capacity(n);
    let mut stage = Vec::with_capacity(n);
    let mut config = Vec::with_capacity(n);
    let mut fx_on: Vec<Vec<bool>> = vec![Vec::with_capacity(n); spec.effect.len()];
    let mut fx_val: Vec<Vec<Vec<f64>>> = Vec::new();
    {
        for i in first..end {
            let s = i / spec.per_shard();
            let rec = record(spec, &cells, i);
            let file = rec.scenario_file(spec);
            let (cfg, _) = file
                .resolve()
                .map_err(|e| SweepError::Input(format!("record {i}: {e}")))?;
            record_no.push(i as i64);
            shard.push(s as i64);
            row.push((i - range(spec, s).0) as i64);
            seed.push(rec.seed as i64);
            preset.push(rec.cell.preset.clone());
            rpm.push(rec.cell.rpm);
            shaft_hz.push(cfg.speed.shaft_hz(0.0));
            load.push(cfg.radial_load);
            fault.push(rec.cell.fault.clone());
            stage.push(rec.cell.stage.clone());
            config.push(toml::to_string(&file).map_err(|e| SweepError::Run(e.to_string()))?);
            if fx_val.is_empty() {
                fx_val = rec
                    .effects
                    .iter()
                    .map(|e| vec![Vec::with_capacity(n); e.params.len()])
                    .collect();
            }
            for (k, e) in rec.effects.iter().enumerate() {
                fx_on[k].push(e.on);
                for (j, (_, v)) in e.params.iter().enumerate() {
                    fx_val[k][j].push(*v);
                }
            }
        }
    }
    let fs = vec![spec.fs; n];
    let dur = vec![spec.duration; n];
    let samples = vec![spec.samples() as i64; n];
    let mut cols: Vec<(String, Column)> = vec![
        ("record".into(), Column::I64(record_no)),
        ("shard".into(), Column::I64(shard)),
        ("row".into(), Column::I64(row)),
        ("seed".into(), Column::I64(seed)),
        ("preset".into(), Column::Str(preset)),
        ("rpm".into(), Column::F64(rpm)),
        ("shaft_hz".into(), Column::F64(shaft_hz)),
        ("radial_load".into(), Column::F64(load)),
        ("fault".into(), Column::Str(fault)),
        ("stage".into(), Column::Str(stage)),
        ("fs".into(), Column::F64(fs)),
        ("duration".into(), Column::F64(dur)),
        ("samples".into(), Column::I64(samples)),
    ];
    let probe = record(spec, &cells, 0);
    for (k, e) in probe.effects.iter().enumerate() {
        cols.push((
            format!("effect.{}", e.name),
            Column::Bool(std::mem::take(&mut fx_on[k])),
        ));
        for (j, (p, _)) in e.params.iter().enumerate() {
            let v = fx_val
                .get_mut(k)
                .and_then(|x| x.get_mut(j))
                .map(std::mem::take)
                .unwrap_or_default();
            cols.push((format!("{}.{p}", e.name), Column::F64(v)));
        }
    }
    cols.push(("config".into(), Column::Str(config)));
    Ok(cols)
}

fn pq(e: parquet::errors::ParquetError) -> SweepError {
    SweepError::Run(format!("writing the Parquet index: {e}"))
}

/// The Parquet schema of the index, from the columns of its first row group.
fn schema(cols: &[(String, Column)]) -> Result<Arc<Type>, SweepError> {
    let mut fields = Vec::with_capacity(cols.len());
    for (name, c) in cols {
        let b = match c {
            Column::I64(_) => Type::primitive_type_builder(name, Physical::INT64),
            Column::F64(_) => Type::primitive_type_builder(name, Physical::DOUBLE),
            Column::Bool(_) => Type::primitive_type_builder(name, Physical::BOOLEAN),
            Column::Str(_) => Type::primitive_type_builder(name, Physical::BYTE_ARRAY)
                .with_logical_type(Some(LogicalType::String)),
        };
        fields.push(Arc::new(
            b.with_repetition(Repetition::REQUIRED)
                .build()
                .map_err(pq)?,
        ));
    }
    Ok(Arc::new(
        Type::group_type_builder("wearsim_sweep")
            .with_fields(fields)
            .build()
            .map_err(pq)?,
    ))
}

/// Writes the whole index of `spec` as Parquet to `out`, one row group of [`ROW_GROUP`]
/// records at a time (deterministic: same spec, same bytes).
pub fn write_parquet<W: std::io::Write + Send>(spec: &SweepSpec, out: W) -> Result<(), SweepError> {
    write_grouped(spec, out, ROW_GROUP)
}

/// [`write_parquet`] with row groups of `group` records.
fn write_grouped<W: std::io::Write + Send>(
    spec: &SweepSpec,
    out: W,
    group: u64,
) -> Result<(), SweepError> {
    let props = Arc::new(
        WriterProperties::builder()
            .set_created_by(format!("wearsim {}", crate::VERSION))
            .build(),
    );
    let mut w: Option<SerializedFileWriter<W>> = None;
    let mut out = Some(out);
    let mut first = 0;
    while first < spec.records {
        let end = (first + group.max(1)).min(spec.records);
        let cols = columns(spec, first, end)?;
        if w.is_none() {
            if let Some(o) = out.take() {
                w = Some(SerializedFileWriter::new(o, schema(&cols)?, props.clone()).map_err(pq)?);
            }
        }
        let Some(w) = w.as_mut() else {
            return Err(SweepError::Run("index: no Parquet writer".into()));
        };
        row_group(w, &cols)?;
        first = end;
    }
    let Some(w) = w else {
        return Err(SweepError::Run(
            "index: a sweep has at least one record".into(),
        ));
    };
    w.close().map_err(pq)?;
    Ok(())
}

/// Appends one row group holding `cols` to `w`.
fn row_group<W: std::io::Write + Send>(
    w: &mut SerializedFileWriter<W>,
    cols: &[(String, Column)],
) -> Result<(), SweepError> {
    let mut rg = w.next_row_group().map_err(pq)?;
    let mut k = 0;
    while let Some(mut col) = rg.next_column().map_err(pq)? {
        let Some((_, c)) = cols.get(k) else {
            return Err(SweepError::Run(
                "index: more Parquet columns than data".into(),
            ));
        };
        match c {
            Column::I64(v) => col.typed::<Int64Type>().write_batch(v, None, None),
            Column::F64(v) => col.typed::<DoubleType>().write_batch(v, None, None),
            Column::Bool(v) => col.typed::<BoolType>().write_batch(v, None, None),
            Column::Str(v) => {
                let b: Vec<ByteArray> = v.iter().map(|s| ByteArray::from(s.as_str())).collect();
                col.typed::<ByteArrayType>().write_batch(&b, None, None)
            }
        }
        .map_err(pq)?;
        col.close().map_err(pq)?;
        k += 1;
    }
    rg.close().map_err(pq)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use parquet::file::reader::{FileReader, SerializedFileReader};
    use parquet::record::RowAccessor;

    /// An index written in row groups holds every record once, in order, with its shard
    /// and row within the shard, whatever the group size, and the same bytes every time.
    /// (A sweep of up to [`ROW_GROUP`] records is one group: the bytes of the whole-index
    /// writer before it, checked with `diff -r` on `python/examples/small-sweep.toml`.)
    #[test]
    fn row_groups_hold_every_record_once_in_order() {
        let spec = SweepSpec::parse(
            "seed = 3\nrecords = 23\nrecords_per_shard = 5\nduration = 0.01\nfs = 12000.0\n\
             [grid]\npreset = [\"cwru-6205-de\"]\nrpm = [1797.0, 1750.0]\n\
             fault = [\"inner\", \"outer\"]\nstage = [\"large-defect\"]\n",
            "test",
        )
        .expect("spec");
        let mut one = Vec::new();
        write_grouped(&spec, &mut one, 1000).expect("one group");
        let mut seven = Vec::new();
        write_grouped(&spec, &mut seven, 7).expect("groups of 7");
        let mut again = Vec::new();
        write_grouped(&spec, &mut again, 7).expect("again");
        assert_eq!(seven, again, "deterministic");
        for (bytes, groups) in [(one, 1), (seven, 4)] {
            let dir = tempfile::tempdir().expect("tempdir");
            let path = dir.path().join("index.parquet");
            std::fs::write(&path, &bytes).expect("write");
            let file = std::fs::File::open(&path).expect("open");
            let r = SerializedFileReader::new(file).expect("parquet");
            assert_eq!(r.metadata().num_row_groups(), groups);
            assert_eq!(r.metadata().file_metadata().num_rows(), 23);
            let rows: Vec<(i64, i64, i64)> = r
                .get_row_iter(None)
                .expect("rows")
                .map(|row| {
                    let row = row.expect("row");
                    (
                        row.get_long(0).unwrap(),
                        row.get_long(1).unwrap(),
                        row.get_long(2).unwrap(),
                    )
                })
                .collect();
            let want: Vec<(i64, i64, i64)> = (0..23).map(|i| (i, i / 5, i % 5)).collect();
            assert_eq!(rows, want);
        }
    }
}
