//! `fwtool`: host-side helpers of the wearsim firmware, used by `bench.sh` and the tests.
//!
//! * `fwtool defmt ELF LOG` — decodes a defmt log (the bytes the firmware wrote through
//!   semihosting) against the firmware ELF with the `defmt-decoder` crate; one line per
//!   message, `LEVEL message`. Exit 2 on a malformed log or an ELF without defmt data.
//! * `fwtool reference PRESET SEED N OUT [f32|i16 FULL_SCALE_G]` — runs the same f32 build of
//!   the core on the host and writes the first N output samples in the firmware's wire
//!   format (little-endian f32 m/s², or i16 counts) to OUT.
//! * `fwtool budget SERIAL` — instructions per output sample from the end frame of a stream
//!   captured under QEMU `-icount shift=0` (1 instruction = 1 ns of virtual time), plus the
//!   stream's overruns; one JSON object.
//! * `fwtool size ELF [--json]` — flash (text + rodata + data image) and static RAM
//!   (data + bss + uninit) of a firmware ELF, like `size`.
use std::process::ExitCode;

use object::{Object, ObjectSection, SectionFlags, SectionKind};
use wearsim_core::sensor::SensorScale;
use wearsim_core::{presets, Model, State};

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let r = match args.first().map(String::as_str) {
        Some("defmt") => defmt_cmd(&args[1..]),
        Some("reference") => reference_cmd(&args[1..]),
        Some("size") => size_cmd(&args[1..]),
        Some("budget") => budget_cmd(&args[1..]),
        _ => Err("usage: fwtool defmt ELF LOG | reference PRESET SEED N OUT [f32|i16 FS_G] | size ELF [--json]".into()),
    };
    match r {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("fwtool: error: {e}");
            ExitCode::from(2)
        }
    }
}

fn read(path: &str) -> Result<Vec<u8>, String> {
    std::fs::read(path).map_err(|e| format!("{path}: {e}"))
}

fn defmt_cmd(a: &[String]) -> Result<(), String> {
    let [elf_path, log_path] = a else {
        return Err("usage: fwtool defmt ELF LOG".into());
    };
    let elf = read(elf_path)?;
    let log = read(log_path)?;
    let table = defmt_decoder::Table::parse(&elf)
        .map_err(|e| format!("{elf_path}: {e}"))?
        .ok_or_else(|| format!("{elf_path}: no defmt data in the ELF"))?;
    let mut dec = table.new_stream_decoder();
    dec.received(&log);
    loop {
        match dec.decode() {
            Ok(f) => {
                let level = f.level().map(|l| l.as_str()).unwrap_or("print");
                println!("{} {}", level.to_ascii_uppercase(), f.display_message());
            }
            Err(defmt_decoder::DecodeError::UnexpectedEof) => break,
            Err(defmt_decoder::DecodeError::Malformed) => {
                return Err(format!("{log_path}: malformed defmt frame"));
            }
        }
    }
    Ok(())
}

fn reference_cmd(a: &[String]) -> Result<(), String> {
    let (preset, seed, n, out) = match a {
        [p, s, n, o, ..] => (p, s, n, o),
        _ => return Err("usage: fwtool reference PRESET SEED N OUT [f32|i16 FS_G]".into()),
    };
    let seed: u64 = seed.parse().map_err(|e| format!("seed {seed:?}: {e}"))?;
    let n: usize = n.parse().map_err(|e| format!("N {n:?}: {e}"))?;
    let format = a.get(4).map(String::as_str).unwrap_or("f32");
    let fs_g: f32 = match a.get(5) {
        Some(s) => s.parse().map_err(|e| format!("full scale {s:?}: {e}"))?,
        None => 16.0,
    };
    let cfg = presets::by_name(preset).ok_or_else(|| format!("unknown preset {preset:?}"))?;
    let model = Model::new_checked(cfg).map_err(|e| format!("{e}"))?;
    let mut st = State::<16>::new(&model, seed).map_err(|e| format!("{e}"))?;
    let mut bytes = Vec::with_capacity(n * 4);
    let scale = SensorScale {
        full_scale_g: fs_g,
        bits: 16,
    };
    let mut k = 0;
    while k < n {
        if let Some(s) = model.step(&mut st) {
            match format {
                "f32" => bytes.extend_from_slice(&s.accel.to_le_bytes()),
                "i16" => bytes.extend_from_slice(&scale.counts(s.accel).to_le_bytes()),
                f => return Err(format!("unknown format {f:?} (f32 or i16)")),
            }
            k += 1;
        }
    }
    std::fs::write(out, bytes).map_err(|e| format!("{out}: {e}"))
}

fn budget_cmd(a: &[String]) -> Result<(), String> {
    let Some(path) = a.first() else {
        return Err("usage: fwtool budget SERIAL".into());
    };
    let bytes = read(path)?;
    let end = wearsim_frame::Decoder::new(&bytes).find_map(|e| match e {
        wearsim_frame::Event::Frame {
            header:
                wearsim_frame::Header {
                    kind: wearsim_frame::Kind::End,
                    ..
                },
            payload,
            ..
        } => wearsim_frame::EndInfo::from_bytes(payload),
        _ => None,
    });
    let e = end.ok_or_else(|| format!("{path}: no valid end frame"))?;
    if e.measured_samples == 0 || e.tick_hz == 0 {
        return Err(format!("{path}: the end frame carries no measurement"));
    }
    let ips = e.busy_ticks as f64 * (1e9 / e.tick_hz as f64) / e.measured_samples as f64;
    println!(
        "{}",
        serde_json::json!({"instructions_per_sample": ips, "measured_samples": e.measured_samples,
            "samples": e.total_samples, "overruns": e.overruns, "tx_drops": e.reserved})
    );
    Ok(())
}

fn size_cmd(a: &[String]) -> Result<(), String> {
    let Some(elf_path) = a.first() else {
        return Err("usage: fwtool size ELF [--json]".into());
    };
    let json = a.iter().any(|s| s == "--json");
    let data = read(elf_path)?;
    let file = object::File::parse(&*data).map_err(|e| format!("{elf_path}: {e}"))?;
    let (mut text, mut rodata, mut ram_init, mut bss) = (0u64, 0u64, 0u64, 0u64);
    for s in file.sections() {
        let alloc = match s.flags() {
            SectionFlags::Elf { sh_flags } => sh_flags & u64::from(object::elf::SHF_ALLOC) != 0,
            _ => false,
        };
        if !alloc || s.size() == 0 {
            continue;
        }
        let name = s.name().unwrap_or("");
        match s.kind() {
            SectionKind::Text => text += s.size(),
            SectionKind::ReadOnlyData | SectionKind::ReadOnlyString => rodata += s.size(),
            SectionKind::Data => ram_init += s.size(),
            SectionKind::UninitializedData => bss += s.size(),
            _ if name == ".uninit" => bss += s.size(),
            _ if s.address() >= 0x2000_0000 => bss += s.size(),
            _ => rodata += s.size(),
        }
    }
    // .data lives in RAM and its initial image in flash.
    let flash = text + rodata + ram_init;
    let ram = ram_init + bss;
    if json {
        println!(
            "{}",
            serde_json::json!({"flash_bytes": flash, "ram_bytes": ram, "text": text,
                "rodata": rodata, "data": ram_init, "bss": bss})
        );
    } else {
        println!("   text  rodata    data     bss   flash     ram  file");
        println!("{text:7} {rodata:7} {ram_init:7} {bss:7} {flash:7} {ram:7}  {elf_path}");
    }
    Ok(())
}
