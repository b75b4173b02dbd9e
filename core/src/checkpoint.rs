//! Byte encoding of a [`State`] for checkpoints of long runs (dense life mode): a run
//! interrupted after a checkpoint continues from it and produces exactly the samples an
//! uninterrupted run would. Little-endian, every real as `f64` (exact for `f32` builds),
//! headed by a magic word, a format version and the element capacity.

use crate::decimate::{DelayLine, MAX_TAPS, MAX_TAPS_V3};
use crate::effects::sensor::SensorState;
use crate::effects::transfer_path::{PathState, MODES};
use crate::error::ConfigError;
use crate::model::{Model, State};
use crate::real::Real;
use crate::rng::Xoshiro128pp;
use crate::topography::Topography;

const MAGIC: u32 = 0x5753_4350; // "WSCP"
/// Version 2 appends the effects' memories (transfer path, sensor, running-in); version 3
/// appends the cached roughness amplitude and the `f32` inverse-square-root cache, which
/// are running state (a dense life refreshes the roughness only at block starts and every
/// 256 running-in steps, so re-deriving it on resume changed the samples). Versions 1 and 2
/// are still read (their roughness amplitude re-derived as before). The ninth scalar, reserved (0) before ball
/// defects existed, carries the spin angle of a ball defect; older checkpoints read it as 0,
/// which is what their (race-defect) states had. Version 4 states the capacity of its delay
/// lines, which depends on the build (512 samples with the `oversample-16` feature, 256
/// without); lines of another capacity (and the 256-sample lines of versions 1–3) are read
/// into the newest places of this build's lines, which is all a filter of a ratio both
/// builds support reads (≤ 8: ≤ 209 taps).
const VERSION: u32 = 4;

/// Largest line capacity a checkpoint may state (that of the `oversample-16` build).
const MAX_STORED_TAPS: usize = 512;
const _: () = assert!(MAX_STORED_TAPS >= MAX_TAPS);

/// Bytes needed to encode a `State<NB>`.
pub const fn encoded_len(nb: usize) -> usize {
    4 + 4 + 4 // magic, version, NB
        + 8 * 10 // y, v, g_prev, time, shaft_hz, four angles, one reserved (see encode)
        + 8 * 6 // phasors
        + 1 + 8 // has_prev, steps
        + 16 // rng
        + 8 * 2 * nb // rough, slip
        + 4 + 4 // armed, phase
        + 1 + 8 * 5 + 1 // topography option, five reals, count
        + 4 + 3 * (8 * 2 * MAX_TAPS + 4) // line capacity, delay lines
        + 8 * 2 * MODES + 16 + 8 * 2 + 8 * 2 // path, sensor rng, lp, phase, revs, run_in
        + 8 + 8 * nb // rough_sigma, rsqrt cache
}

struct Writer<'a> {
    out: &'a mut [u8],
    at: usize,
}

impl Writer<'_> {
    fn bytes(&mut self, b: &[u8]) -> Result<(), ConfigError> {
        let end = self.at + b.len();
        let max = self.out.len();
        let dst = self.out.get_mut(self.at..end).ok_or(ConfigError::TooMany {
            field: "checkpoint.buffer",
            count: end,
            max,
        })?;
        dst.copy_from_slice(b);
        self.at = end;
        Ok(())
    }
    fn u32(&mut self, v: u32) -> Result<(), ConfigError> {
        self.bytes(&v.to_le_bytes())
    }
    fn u64(&mut self, v: u64) -> Result<(), ConfigError> {
        self.bytes(&v.to_le_bytes())
    }
    #[allow(clippy::unnecessary_cast)]
    fn real(&mut self, v: Real) -> Result<(), ConfigError> {
        self.bytes(&(v as f64).to_le_bytes())
    }
}

struct Reader<'a> {
    inp: &'a [u8],
    at: usize,
}

const CORRUPT: ConfigError = ConfigError::Inconsistent {
    field: "checkpoint",
    reason: "truncated or corrupt checkpoint",
};

impl Reader<'_> {
    fn take<const N: usize>(&mut self) -> Result<[u8; N], ConfigError> {
        let s = self.inp.get(self.at..self.at + N).ok_or(CORRUPT)?;
        let mut a = [0u8; N];
        a.copy_from_slice(s);
        self.at += N;
        Ok(a)
    }
    fn u8(&mut self) -> Result<u8, ConfigError> {
        Ok(self.take::<1>()?[0])
    }
    fn u32(&mut self) -> Result<u32, ConfigError> {
        Ok(u32::from_le_bytes(self.take::<4>()?))
    }
    fn u64(&mut self) -> Result<u64, ConfigError> {
        Ok(u64::from_le_bytes(self.take::<8>()?))
    }
    fn real(&mut self) -> Result<Real, ConfigError> {
        let v = f64::from_le_bytes(self.take::<8>()?);
        if v.is_finite() {
            Ok(v as Real)
        } else {
            Err(CORRUPT)
        }
    }
}

impl<const NB: usize> State<NB> {
    /// Encodes the state into `out` (at least [`encoded_len`]`(NB)` bytes); returns the
    /// number of bytes written.
    pub fn encode(&self, out: &mut [u8]) -> Result<usize, ConfigError> {
        let mut w = Writer { out, at: 0 };
        w.u32(MAGIC)?;
        w.u32(VERSION)?;
        w.u32(NB as u32)?;
        let p = self.parts();
        for v in [
            p.y,
            p.v,
            p.g_prev,
            p.time,
            p.shaft_hz,
            p.shaft_angle,
            p.cage_angle,
            p.wave_angle,
            p.spin_angle,
            0.0,
        ] {
            w.real(v)?;
        }
        for (c, s) in [p.shaft_cs, p.cage_cs, p.wave_cs] {
            w.real(c)?;
            w.real(s)?;
        }
        w.bytes(&[p.has_prev as u8])?;
        w.u64(p.steps)?;
        for word in p.rng.state_words() {
            w.u32(word)?;
        }
        for v in p.rough.iter().chain(p.slip.iter()) {
            w.real(*v)?;
        }
        w.u32(p.armed)?;
        w.u32(p.phase)?;
        match p.topography {
            Some(t) => {
                w.bytes(&[1])?;
                for v in [t.asperity_height, t.length, t.width, t.depth, t.debris] {
                    w.real(v)?;
                }
                w.bytes(&[t.count])?;
            }
            None => {
                w.bytes(&[0])?;
                for _ in 0..5 {
                    w.real(0.0)?;
                }
                w.bytes(&[0])?;
            }
        }
        w.u32(MAX_TAPS as u32)?;
        for line in p.lines.iter() {
            let (buf, pos) = line.raw();
            for v in buf.iter() {
                w.real(*v)?;
            }
            w.u32(pos as u32)?;
        }
        for v in p.path.raw() {
            w.real(v)?;
        }
        let (words, lp, ph) = p.sensor.raw();
        for word in words {
            w.u32(word)?;
        }
        for v in [lp, ph, p.revs, p.run_in, p.rough_sigma] {
            w.real(v)?;
        }
        for v in p.rsqrt.iter() {
            w.real(v.get())?;
        }
        Ok(w.at)
    }

    /// Decodes a state encoded by [`State::encode`] for `model` (whose defect shape is
    /// re-derived from the stored topography).
    pub fn decode(model: &Model, bytes: &[u8]) -> Result<Self, ConfigError> {
        let mut r = Reader { inp: bytes, at: 0 };
        let magic = r.u32()?;
        let version = r.u32()?;
        if magic != MAGIC || !(1..=VERSION).contains(&version) || r.u32()? != NB as u32 {
            return Err(ConfigError::Inconsistent {
                field: "checkpoint",
                reason: "not a wearsim state checkpoint of this version and capacity",
            });
        }
        let mut st = State::<NB>::new(model, 0)?;
        let mut scalars = [0.0 as Real; 10];
        for v in scalars.iter_mut() {
            *v = r.real()?;
        }
        let mut cs = [(0.0 as Real, 0.0 as Real); 3];
        for v in cs.iter_mut() {
            *v = (r.real()?, r.real()?);
        }
        let has_prev = r.u8()? != 0;
        let steps = r.u64()?;
        let rng = Xoshiro128pp::from_state_words([r.u32()?, r.u32()?, r.u32()?, r.u32()?]);
        let mut rough = [0.0 as Real; NB];
        let mut slip = [0.0 as Real; NB];
        for v in rough.iter_mut().chain(slip.iter_mut()) {
            *v = r.real()?;
        }
        let armed = r.u32()?;
        let phase = r.u32()?;
        let has_topo = r.u8()? != 0;
        let mut t5 = [0.0 as Real; 5];
        for v in t5.iter_mut() {
            *v = r.real()?;
        }
        let count = r.u8()?;
        let [asperity_height, length, width, depth, debris] = t5;
        let topography = has_topo.then_some(Topography {
            asperity_height,
            length,
            width,
            depth,
            count,
            debris,
        });
        // Version 4 states the lines' capacity (that of the build that wrote it); older
        // versions had 256.
        let cap = if version >= 4 {
            r.u32()? as usize
        } else {
            MAX_TAPS_V3
        };
        if cap == 0 || cap > MAX_STORED_TAPS {
            return Err(CORRUPT);
        }
        let mut lines = [DelayLine::default(); 3];
        for line in lines.iter_mut() {
            if cap == MAX_TAPS {
                let mut buf = [0.0 as Real; 2 * MAX_TAPS];
                for v in buf.iter_mut() {
                    *v = r.real()?;
                }
                *line = DelayLine::from_raw(buf, r.u32()? as usize);
            } else {
                // A line of another capacity, stored twice: its history, oldest first, is
                // the `cap` samples from its position on; its newest samples (as many as
                // this build's lines hold) go into a fresh line, all that a filter of a
                // ratio both builds support reads.
                let mut buf = [0.0 as Real; 2 * MAX_STORED_TAPS];
                let stored = buf.get_mut(..2 * cap).ok_or(CORRUPT)?;
                for v in stored.iter_mut() {
                    *v = r.real()?;
                }
                let pos = r.u32()? as usize % cap;
                let hist = buf.get(pos..pos + cap).unwrap_or(&[]);
                let keep = hist.len().saturating_sub(MAX_TAPS);
                for &x in hist.get(keep..).unwrap_or(&[]) {
                    line.push(x);
                }
            }
        }
        let fresh = st.parts();
        let (mut path, mut sensor, mut revs, mut run_in) =
            (fresh.path, fresh.sensor, fresh.revs, fresh.run_in);
        let (mut rough_sigma, mut rsqrt) = (fresh.rough_sigma, [0.0 as Real; NB]);
        if version >= 2 {
            let mut z = [0.0 as Real; 2 * MODES];
            for v in z.iter_mut() {
                *v = r.real()?;
            }
            path = PathState::from_raw(z);
            let words = [r.u32()?, r.u32()?, r.u32()?, r.u32()?];
            let (lp, ph) = (r.real()?, r.real()?);
            sensor = SensorState::from_raw(words, lp, ph);
            revs = r.real()?;
            run_in = r.real()?;
        }
        if version >= 3 {
            rough_sigma = r.real()?;
            for v in rsqrt.iter_mut() {
                *v = r.real()?;
            }
        }
        // The defect shape is derived from the topography; the restore below then puts
        // back every running value (the roughness amplitude included).
        if let Some(t) = topography {
            st.set_topography(model, t)?;
        }
        let [y, v, g_prev, time, shaft_hz, shaft_angle, cage_angle, wave_angle, spin_angle, _] =
            scalars;
        st.restore(crate::model::StateParts {
            y,
            v,
            g_prev,
            has_prev,
            steps,
            time,
            shaft_hz,
            shaft_angle,
            cage_angle,
            wave_angle,
            spin_angle,
            shaft_cs: cs[0],
            cage_cs: cs[1],
            wave_cs: cs[2],
            rng,
            rough,
            slip,
            armed,
            topography: st.topography(),
            lines,
            phase: phase % model.oversample().max(1),
            path,
            sensor,
            revs,
            run_in,
            rough_sigma,
            rsqrt: rsqrt.map(core::cell::Cell::new),
        });
        if version < 3 {
            st.refresh_rough(model);
        }
        Ok(st)
    }
}
