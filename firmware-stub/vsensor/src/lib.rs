//! # wearsim-vsensor
//!
//! A register-level model of the ST **ISM330DHCX** industrial 6-axis IMU (accelerometer used
//! for vibration monitoring: ±2/4/8/16 g, 16-bit, output data rates up to 6667 Hz, tagged
//! FIFO) whose accelerometer Z axis reads wearsim samples. It implements
//! [`embedded_hal::i2c::I2c`], so the unmodified `ism330dhcx` driver from crates.io talks to
//! it as to the real part. `no_std`, no allocation, no panics.
//!
//! Modelled registers (datasheet DS13012): `WHO_AM_I` (0x0F = 0x6B), `CTRL1_XL` (0x10:
//! ODR_XL, FS_XL, LPF2 bit stored), `CTRL3_C` (0x12: BOOT, BDU, IF_INC, SW_RESET),
//! `STATUS_REG` (0x1E: XLDA), `OUT_TEMP` (0x20–0x21, 0 = 25 °C), gyroscope outputs (0x22–0x27,
//! always 0), accelerometer outputs `OUTX_L_A`…`OUTZ_H_A` (0x28–0x2D; X = Y = 0, Z = the
//! simulated radial acceleration; gravity is not added), `FIFO_CTRL1..4` (0x07–0x0A:
//! watermark, BDR_XL, FIFO_MODE), `FIFO_STATUS1/2` (0x3A–0x3B: unread words, overrun, full,
//! watermark flags) and `FIFO_DATA_OUT_TAG` + 6 data bytes (0x78–0x7E, accelerometer tag 0x02).
//! Every other register reads back what was written (reset value 0).
//!
//! Timing: [`Ism330Model::push_sample`] is called at the simulator's output rate; the model
//! keeps every k-th sample with `k = round(source_rate / ODR)` (20 kHz / 6667 Hz = 3), as the
//! sample clock of the part. The part's own digital low-pass filters are not modelled: feed
//! it a simulator rate that is a multiple of the ODR and whose content is band-limited (the
//! core's anti-alias filter leaves 0–0.4·fs).

#![no_std]
#![deny(missing_docs)]
#![forbid(unsafe_code)]
#![deny(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    clippy::indexing_slicing
)]

use embedded_hal::i2c::{ErrorKind, ErrorType, I2c, NoAcknowledgeSource, Operation};
use wearsim_core::sensor::SensorScale;
use wearsim_core::Real;

/// I2C address with SA0 high (the driver's default).
pub const ADDRESS_SA0_HIGH: u8 = 0x6B;
/// I2C address with SA0 low.
pub const ADDRESS_SA0_LOW: u8 = 0x6A;
/// Value of `WHO_AM_I`.
pub const WHO_AM_I_VALUE: u8 = 0x6B;
/// FIFO capacity of the model in words (the part holds up to 9 kB, ~1300 words; the model
/// keeps RAM small).
pub const FIFO_WORDS: usize = 128;

/// Register addresses used by the model.
pub mod reg {
    /// FIFO_CTRL1: watermark low bits.
    pub const FIFO_CTRL1: u8 = 0x07;
    /// FIFO_CTRL2: watermark bit 8 and options.
    pub const FIFO_CTRL2: u8 = 0x08;
    /// FIFO_CTRL3: BDR_XL (bits 3:0), BDR_GY (7:4).
    pub const FIFO_CTRL3: u8 = 0x09;
    /// FIFO_CTRL4: FIFO_MODE (bits 2:0).
    pub const FIFO_CTRL4: u8 = 0x0A;
    /// WHO_AM_I.
    pub const WHO_AM_I: u8 = 0x0F;
    /// CTRL1_XL: ODR_XL (7:4), FS_XL (3:2), LPF2_XL_EN (1).
    pub const CTRL1_XL: u8 = 0x10;
    /// CTRL3_C: BOOT (7), BDU (6), IF_INC (2), SW_RESET (0).
    pub const CTRL3_C: u8 = 0x12;
    /// STATUS_REG: XLDA (0), GDA (1), TDA (2).
    pub const STATUS_REG: u8 = 0x1E;
    /// OUTX_L_A: first accelerometer output byte.
    pub const OUTX_L_A: u8 = 0x28;
    /// OUTZ_H_A: last accelerometer output byte.
    pub const OUTZ_H_A: u8 = 0x2D;
    /// FIFO_STATUS1: unread words, low 8 bits.
    pub const FIFO_STATUS1: u8 = 0x3A;
    /// FIFO_STATUS2: unread words bits 9:8 and flags.
    pub const FIFO_STATUS2: u8 = 0x3B;
    /// FIFO_DATA_OUT_TAG.
    pub const FIFO_DATA_OUT_TAG: u8 = 0x78;
    /// Last FIFO data byte (FIFO_DATA_OUT_Z_H).
    pub const FIFO_DATA_OUT_Z_H: u8 = 0x7E;
}

/// Output data rate (Hz) of an ODR_XL / BDR_XL code; 0 for power-down.
pub fn odr_hz(code: u8) -> Real {
    match code & 0x0F {
        1 => 12.5,
        2 => 26.0,
        3 => 52.0,
        4 => 104.0,
        5 => 208.0,
        6 => 416.0,
        7 => 833.0,
        8 => 1666.0,
        9 => 3332.0,
        10 => 6667.0,
        11 => 1.6,
        _ => 0.0,
    }
}

/// Full scale (g) of an FS_XL code.
pub fn full_scale_g(code: u8) -> Real {
    match code & 0b11 {
        0b00 => 2.0,
        0b01 => 16.0,
        0b10 => 4.0,
        _ => 8.0,
    }
}

/// The register model. Feed samples with [`push_sample`](Self::push_sample); access it over
/// I2C (it is an [`I2c`] bus with one device on it).
#[derive(Debug, Clone)]
pub struct Ism330Model {
    address: u8,
    source_rate: Real,
    regs: [u8; 128],
    pointer: u8,
    odr_count: u32,
    bdr_count: u32,
    fifo: [[u8; 7]; FIFO_WORDS],
    fifo_head: usize,
    fifo_len: usize,
    fifo_out: [u8; 7],
    tag_cnt: u8,
    overrun: bool,
    /// FIFO words lost to overrun since reset.
    pub fifo_overruns: u32,
    /// Samples that reached the output registers since reset.
    pub output_samples: u32,
}

impl Ism330Model {
    /// A part at `address` (0x6A or 0x6B) fed at `source_rate` Hz (the simulator's output
    /// rate), in its reset state (power-down).
    pub fn new(address: u8, source_rate: Real) -> Self {
        let mut m = Ism330Model {
            address,
            source_rate,
            regs: [0; 128],
            pointer: 0,
            odr_count: 0,
            bdr_count: 0,
            fifo: [[0; 7]; FIFO_WORDS],
            fifo_head: 0,
            fifo_len: 0,
            fifo_out: [0; 7],
            tag_cnt: 0,
            overrun: false,
            fifo_overruns: 0,
            output_samples: 0,
        };
        m.reset();
        m
    }

    fn reset(&mut self) {
        self.regs = [0; 128];
        self.set(reg::WHO_AM_I, WHO_AM_I_VALUE);
        self.set(reg::CTRL3_C, 0x04); // IF_INC
        self.fifo_len = 0;
        self.overrun = false;
        self.odr_count = 0;
        self.bdr_count = 0;
    }

    fn get(&self, r: u8) -> u8 {
        self.regs.get(r as usize & 0x7F).copied().unwrap_or(0)
    }
    fn set(&mut self, r: u8, v: u8) {
        if let Some(x) = self.regs.get_mut(r as usize & 0x7F) {
            *x = v;
        }
    }

    /// Configured full scale (g).
    pub fn full_scale_g(&self) -> Real {
        full_scale_g(self.get(reg::CTRL1_XL) >> 2)
    }
    /// Configured output data rate (Hz), 0 in power-down.
    pub fn odr_hz(&self) -> Real {
        odr_hz(self.get(reg::CTRL1_XL) >> 4)
    }
    /// Unread FIFO words.
    pub fn fifo_len(&self) -> usize {
        self.fifo_len
    }

    fn decimation(&self, rate: Real) -> u32 {
        if rate <= 0.0 {
            return 0;
        }
        let k = self.source_rate / rate + 0.5;
        if k < 1.0 {
            1
        } else {
            k as u32
        }
    }

    /// Feeds one simulator sample (m/s², the radial acceleration on the part's Z axis).
    pub fn push_sample(&mut self, accel: Real) {
        let scale = SensorScale {
            full_scale_g: self.full_scale_g(),
            bits: 16,
        };
        let k = self.decimation(self.odr_hz());
        if k == 0 {
            return;
        }
        self.odr_count += 1;
        if self.odr_count < k {
            return;
        }
        self.odr_count = 0;
        let z = scale.counts(accel).to_le_bytes();
        let data = [0, 0, 0, 0, z[0], z[1]];
        for (i, b) in data.iter().enumerate() {
            self.set(reg::OUTX_L_A + i as u8, *b);
        }
        self.set(reg::STATUS_REG, self.get(reg::STATUS_REG) | 1);
        self.output_samples = self.output_samples.wrapping_add(1);

        let mode = self.get(reg::FIFO_CTRL4) & 0b111;
        let kb = self.decimation(odr_hz(self.get(reg::FIFO_CTRL3)));
        if mode == 0 || kb == 0 {
            return;
        }
        // The batch rate counts output samples of the ODR clock.
        self.bdr_count += k;
        if self.bdr_count < kb {
            return;
        }
        self.bdr_count = 0;
        let tag = (0x02 << 3) | ((self.tag_cnt & 0b11) << 1);
        self.tag_cnt = self.tag_cnt.wrapping_add(1);
        let word = [tag, data[0], data[1], data[2], data[3], data[4], data[5]];
        if self.fifo_len == FIFO_WORDS {
            self.fifo_overruns = self.fifo_overruns.wrapping_add(1);
            self.overrun = true;
            if mode == 0b001 {
                return; // FIFO mode stops when full
            }
            // Continuous: the oldest word is overwritten.
            self.fifo_head = (self.fifo_head + 1) % FIFO_WORDS;
            self.fifo_len -= 1;
        }
        let tail = (self.fifo_head + self.fifo_len) % FIFO_WORDS;
        if let Some(w) = self.fifo.get_mut(tail) {
            *w = word;
        }
        self.fifo_len += 1;
    }

    fn fifo_status(&self, second: bool) -> u8 {
        let n = self.fifo_len as u16;
        if !second {
            return n as u8;
        }
        let wtm =
            (self.get(reg::FIFO_CTRL1) as u16) | ((self.get(reg::FIFO_CTRL2) as u16 & 1) << 8);
        let mut v = ((n >> 8) & 0b11) as u8;
        if self.overrun {
            v |= (1 << 3) | (1 << 6);
        }
        if self.fifo_len == FIFO_WORDS {
            v |= 1 << 5;
        }
        if wtm != 0 && n >= wtm {
            v |= 1 << 7;
        }
        v
    }

    fn read_byte(&mut self, r: u8) -> u8 {
        match r {
            reg::FIFO_STATUS1 => self.fifo_status(false),
            reg::FIFO_STATUS2 => self.fifo_status(true),
            reg::FIFO_DATA_OUT_TAG => {
                // Reading the tag pops the next word into the output bytes.
                if self.fifo_len > 0 {
                    self.fifo_out = self.fifo.get(self.fifo_head).copied().unwrap_or([0; 7]);
                    self.fifo_head = (self.fifo_head + 1) % FIFO_WORDS;
                    self.fifo_len -= 1;
                    self.overrun = false;
                } else {
                    self.fifo_out = [0; 7];
                }
                self.fifo_out[0]
            }
            0x79..=reg::FIFO_DATA_OUT_Z_H => self
                .fifo_out
                .get((r - reg::FIFO_DATA_OUT_TAG) as usize)
                .copied()
                .unwrap_or(0),
            reg::OUTX_L_A..=reg::OUTZ_H_A => {
                self.set(reg::STATUS_REG, self.get(reg::STATUS_REG) & !1);
                self.get(r)
            }
            _ => self.get(r),
        }
    }

    fn write_byte(&mut self, r: u8, v: u8) {
        match r {
            reg::WHO_AM_I | reg::STATUS_REG | reg::FIFO_STATUS1 | reg::FIFO_STATUS2 => {}
            reg::OUTX_L_A..=reg::OUTZ_H_A => {}
            reg::FIFO_DATA_OUT_TAG..=reg::FIFO_DATA_OUT_Z_H => {}
            reg::CTRL3_C if v & 1 != 0 => self.reset(),
            reg::CTRL3_C => self.set(r, v & !0x80), // BOOT completes at once
            reg::FIFO_CTRL4 => {
                if v & 0b111 == 0 {
                    self.fifo_len = 0; // bypass empties the FIFO
                    self.overrun = false;
                }
                self.set(r, v);
            }
            _ => self.set(r, v),
        }
    }

    fn next(&self, r: u8) -> u8 {
        if self.get(reg::CTRL3_C) & 0x04 == 0 {
            return r;
        }
        if r == reg::FIFO_DATA_OUT_Z_H {
            reg::FIFO_DATA_OUT_TAG // the FIFO output window wraps
        } else {
            r.wrapping_add(1) & 0x7F
        }
    }
}

impl ErrorType for Ism330Model {
    type Error = ErrorKind;
}

impl I2c for Ism330Model {
    fn transaction(
        &mut self,
        address: u8,
        operations: &mut [Operation<'_>],
    ) -> Result<(), Self::Error> {
        if address != self.address {
            return Err(ErrorKind::NoAcknowledge(NoAcknowledgeSource::Address));
        }
        for op in operations.iter_mut() {
            match op {
                Operation::Write(bytes) => {
                    let Some((first, rest)) = bytes.split_first() else {
                        continue;
                    };
                    self.pointer = *first & 0x7F;
                    for b in rest {
                        self.write_byte(self.pointer, *b);
                        self.pointer = self.next(self.pointer);
                    }
                }
                Operation::Read(buf) => {
                    for b in buf.iter_mut() {
                        *b = self.read_byte(self.pointer);
                        self.pointer = self.next(self.pointer);
                    }
                }
            }
        }
        Ok(())
    }
}
