//! # wearsim-frame
//!
//! The framed binary sample stream that the wearsim firmware sends over its UART, shared by the
//! firmware (encoder) and the host's `wearsim capture` (decoder). `no_std`, no allocation, no
//! panics.
//!
//! Every frame, all integers little-endian:
//!
//! | offset | size | field |
//! |---:|---:|---|
//! | 0 | 4 | sync word `A5 5A 57 53` ([`SYNC`]) |
//! | 4 | 1 | protocol version ([`VERSION`] = 1) |
//! | 5 | 1 | kind: 1 start, 2 data, 3 end ([`Kind`]) |
//! | 6 | 1 | sample format: 0 none, 1 `f32` m/s², 2 `i16` counts ([`Format`]) |
//! | 7 | 1 | flags: bit 0 = a deadline was missed while this frame filled |
//! | 8 | 4 | `seq`: frame sequence number, 0 for the start frame, +1 per frame |
//! | 12 | 4 | `first_sample`: index of the first payload sample (data frames) |
//! | 16 | 4 | `overruns`: cumulative count of missed sample deadlines |
//! | 20 | 4 | `scale` (`f32`): m/s² per unit of the payload (1.0 for `f32`, g₀·FS/32768 for counts) |
//! | 24 | 2 | `payload_len` in bytes (≤ [`MAX_PAYLOAD`]) |
//! | 26 | 2 | reserved, 0 |
//! | 28 | n | payload |
//! | 28+n | 4 | CRC-32 (IEEE 802.3, reflected, init and xor-out `FFFFFFFF`, as zlib's `crc32`) of bytes 4 ..= 27+n |
//!
//! Payloads: data frames carry `payload_len / size` samples of their format; the start frame
//! carries a [`StartInfo`], the end frame an [`EndInfo`].
#![no_std]
#![deny(missing_docs)]
#![forbid(unsafe_code)]
#![deny(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    clippy::indexing_slicing
)]

/// Sync word that starts every frame.
pub const SYNC: [u8; 4] = [0xA5, 0x5A, 0x57, 0x53];
/// Protocol version written in byte 4.
pub const VERSION: u8 = 1;
/// Header length (bytes), sync word included.
pub const HEADER_LEN: usize = 28;
/// CRC length (bytes).
pub const CRC_LEN: usize = 4;
/// Largest payload a frame may carry (bytes); a longer `payload_len` marks a corrupt frame.
pub const MAX_PAYLOAD: usize = 1024;
/// Largest frame on the wire (bytes).
pub const MAX_FRAME: usize = HEADER_LEN + MAX_PAYLOAD + CRC_LEN;

/// Frame kind (byte 5).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// First frame of a run: scenario, seed, rate ([`StartInfo`]).
    Start = 1,
    /// Samples.
    Data = 2,
    /// Last frame of a finite run: totals and the instruction budget ([`EndInfo`]).
    End = 3,
}

impl Kind {
    /// Kind from its byte, `None` for an unknown value.
    pub fn from_u8(b: u8) -> Option<Kind> {
        match b {
            1 => Some(Kind::Start),
            2 => Some(Kind::Data),
            3 => Some(Kind::End),
            _ => None,
        }
    }
}

/// Sample format of a data frame (byte 6).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// No samples (start and end frames).
    None = 0,
    /// IEEE 754 single precision, m/s², 4 bytes per sample.
    F32 = 1,
    /// Signed 16-bit counts, Q1.15 of the full-scale range, 2 bytes per sample; m/s² =
    /// counts × `scale`.
    I16 = 2,
}

impl Format {
    /// Format from its byte, `None` for an unknown value.
    pub fn from_u8(b: u8) -> Option<Format> {
        match b {
            0 => Some(Format::None),
            1 => Some(Format::F32),
            2 => Some(Format::I16),
            _ => None,
        }
    }
    /// Bytes per sample (0 for [`Format::None`]).
    pub fn sample_size(self) -> usize {
        match self {
            Format::None => 0,
            Format::F32 => 4,
            Format::I16 => 2,
        }
    }
}

/// The fixed fields of a frame header.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Header {
    /// Frame kind.
    pub kind: Kind,
    /// Sample format of the payload.
    pub format: Format,
    /// Flags (bit 0: deadline missed while this frame filled).
    pub flags: u8,
    /// Frame sequence number.
    pub seq: u32,
    /// Index of the first sample of a data frame.
    pub first_sample: u32,
    /// Cumulative missed sample deadlines.
    pub overruns: u32,
    /// m/s² per payload unit.
    pub scale: f32,
}

/// Flag bit: a sample deadline was missed while this frame filled.
pub const FLAG_OVERRUN: u8 = 1;

/// Payload of the start frame (48 bytes).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StartInfo {
    /// Preset name, ASCII, NUL-padded.
    pub preset: [u8; 24],
    /// Seed of the model's random generator.
    pub seed: u64,
    /// Output sample rate (Hz).
    pub rate_hz: f32,
    /// Internal steps per output sample.
    pub oversample: u32,
    /// Samples the run will send (0 = unbounded).
    pub total_samples: u32,
    /// Build flavour: 1 = hard-float f32 (M4F), 2 = soft-float f32 (M3), 0 = other.
    pub flavour: u32,
}

/// Length of [`StartInfo`] on the wire.
pub const START_LEN: usize = 48;

impl StartInfo {
    /// The preset name as text (up to the first NUL; invalid UTF-8 gives `""`).
    pub fn preset_name(&self) -> &str {
        let n = self
            .preset
            .iter()
            .position(|b| *b == 0)
            .unwrap_or(self.preset.len());
        core::str::from_utf8(self.preset.get(..n).unwrap_or(&[])).unwrap_or("")
    }
    /// Encodes into 48 bytes.
    pub fn to_bytes(&self) -> [u8; START_LEN] {
        let mut b = [0u8; START_LEN];
        put(&mut b, 0, &self.preset);
        put(&mut b, 24, &self.seed.to_le_bytes());
        put(&mut b, 32, &self.rate_hz.to_le_bytes());
        put(&mut b, 36, &self.oversample.to_le_bytes());
        put(&mut b, 40, &self.total_samples.to_le_bytes());
        put(&mut b, 44, &self.flavour.to_le_bytes());
        b
    }
    /// Decodes from a payload; `None` if it is not 48 bytes long.
    pub fn from_bytes(p: &[u8]) -> Option<StartInfo> {
        if p.len() != START_LEN {
            return None;
        }
        let mut preset = [0u8; 24];
        preset.copy_from_slice(p.get(..24)?);
        Some(StartInfo {
            preset,
            seed: u64::from_le_bytes(arr(p, 24)?),
            rate_hz: f32::from_le_bytes(arr(p, 32)?),
            oversample: u32::from_le_bytes(arr(p, 36)?),
            total_samples: u32::from_le_bytes(arr(p, 40)?),
            flavour: u32::from_le_bytes(arr(p, 44)?),
        })
    }
}

/// Payload of the end frame (32 bytes).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EndInfo {
    /// Samples sent in data frames.
    pub total_samples: u32,
    /// Data frames sent.
    pub data_frames: u32,
    /// Missed sample deadlines (sample ring empty when the timer ticked).
    pub overruns: u32,
    /// Timer ticks the CPU spent producing samples (model, conversion, framing, UART).
    pub busy_ticks: u64,
    /// Frequency of the tick counter (Hz).
    pub tick_hz: u32,
    /// Samples measured in `busy_ticks` (a bench run measures a free-running loop).
    pub measured_samples: u32,
    /// Reserved, 0.
    pub reserved: u32,
}

/// Length of [`EndInfo`] on the wire.
pub const END_LEN: usize = 32;

impl EndInfo {
    /// Encodes into 32 bytes.
    pub fn to_bytes(&self) -> [u8; END_LEN] {
        let mut b = [0u8; END_LEN];
        put(&mut b, 0, &self.total_samples.to_le_bytes());
        put(&mut b, 4, &self.data_frames.to_le_bytes());
        put(&mut b, 8, &self.overruns.to_le_bytes());
        put(&mut b, 12, &self.busy_ticks.to_le_bytes());
        put(&mut b, 20, &self.tick_hz.to_le_bytes());
        put(&mut b, 24, &self.measured_samples.to_le_bytes());
        put(&mut b, 28, &self.reserved.to_le_bytes());
        b
    }
    /// Decodes from a payload; `None` if it is not 32 bytes long.
    pub fn from_bytes(p: &[u8]) -> Option<EndInfo> {
        if p.len() != END_LEN {
            return None;
        }
        Some(EndInfo {
            total_samples: u32::from_le_bytes(arr(p, 0)?),
            data_frames: u32::from_le_bytes(arr(p, 4)?),
            overruns: u32::from_le_bytes(arr(p, 8)?),
            busy_ticks: u64::from_le_bytes(arr(p, 12)?),
            tick_hz: u32::from_le_bytes(arr(p, 20)?),
            measured_samples: u32::from_le_bytes(arr(p, 24)?),
            reserved: u32::from_le_bytes(arr(p, 28)?),
        })
    }
}

fn put(dst: &mut [u8], at: usize, src: &[u8]) {
    if let Some(d) = dst.get_mut(at..at + src.len()) {
        d.copy_from_slice(src);
    }
}

fn arr<const N: usize>(p: &[u8], at: usize) -> Option<[u8; N]> {
    p.get(at..at + N)?.try_into().ok()
}

// Built at compile time; the index is always in range.
#[allow(clippy::indexing_slicing)]
const CRC_TABLE: [u32; 256] = {
    let mut t = [0u32; 256];
    let mut i = 0;
    while i < 256 {
        let mut c = i as u32;
        let mut k = 0;
        while k < 8 {
            c = if c & 1 != 0 {
                0xEDB8_8320 ^ (c >> 1)
            } else {
                c >> 1
            };
            k += 1;
        }
        t[i] = c;
        i += 1;
    }
    t
};

/// Incremental CRC-32 (IEEE, reflected; `crc32(b"123456789") = 0xCBF43926`).
#[derive(Debug, Clone, Copy)]
pub struct Crc32(u32);

impl Default for Crc32 {
    fn default() -> Self {
        Self::new()
    }
}

impl Crc32 {
    /// A fresh CRC.
    pub const fn new() -> Self {
        Crc32(0xFFFF_FFFF)
    }
    /// Feeds bytes.
    #[inline]
    pub fn update(&mut self, data: &[u8]) {
        let mut c = self.0;
        for b in data {
            let i = ((c ^ *b as u32) & 0xFF) as usize;
            c = CRC_TABLE.get(i).copied().unwrap_or(0) ^ (c >> 8);
        }
        self.0 = c;
    }
    /// The CRC of everything fed.
    pub fn finish(&self) -> u32 {
        !self.0
    }
}

/// CRC-32 of `data` in one go.
pub fn crc32(data: &[u8]) -> u32 {
    let mut c = Crc32::new();
    c.update(data);
    c.finish()
}

/// Writes a complete frame (header, payload, CRC) into `out`; returns its length, or `None`
/// if the payload exceeds [`MAX_PAYLOAD`] or `out` is too short.
pub fn encode(h: &Header, payload: &[u8], out: &mut [u8]) -> Option<usize> {
    let len = HEADER_LEN + payload.len() + CRC_LEN;
    if payload.len() > MAX_PAYLOAD || out.len() < len {
        return None;
    }
    write_header(h, payload.len() as u16, out)?;
    out.get_mut(HEADER_LEN..HEADER_LEN + payload.len())?
        .copy_from_slice(payload);
    seal(out, payload.len())
}

/// Writes the header for a payload of `payload_len` bytes into `out[..HEADER_LEN]`.
pub fn write_header(h: &Header, payload_len: u16, out: &mut [u8]) -> Option<()> {
    let b = out.get_mut(..HEADER_LEN)?;
    b.fill(0);
    put(b, 0, &SYNC);
    put(b, 4, &[VERSION, h.kind as u8, h.format as u8, h.flags]);
    put(b, 8, &h.seq.to_le_bytes());
    put(b, 12, &h.first_sample.to_le_bytes());
    put(b, 16, &h.overruns.to_le_bytes());
    put(b, 20, &h.scale.to_le_bytes());
    put(b, 24, &payload_len.to_le_bytes());
    Some(())
}

/// Appends the CRC after a header and `payload_len` payload bytes already in `out`; returns
/// the frame length.
pub fn seal(out: &mut [u8], payload_len: usize) -> Option<usize> {
    let end = HEADER_LEN + payload_len;
    let crc = crc32(out.get(4..end)?);
    out.get_mut(end..end + CRC_LEN)?
        .copy_from_slice(&crc.to_le_bytes());
    Some(end + CRC_LEN)
}

/// One event of the stream decoder.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Event<'a> {
    /// A frame whose CRC matched.
    Frame {
        /// Its header.
        header: Header,
        /// Its payload.
        payload: &'a [u8],
        /// Byte offset of its sync word in the input.
        offset: usize,
    },
    /// Bytes that are not a valid frame: no sync word, a bad header, or a CRC mismatch.
    Corrupt {
        /// Byte offset where the bad span starts.
        offset: usize,
        /// Bytes skipped.
        len: usize,
        /// Why.
        reason: CorruptReason,
    },
    /// The input ends inside a frame (a truncated stream).
    Truncated {
        /// Byte offset of the incomplete frame's sync word.
        offset: usize,
        /// Bytes left.
        len: usize,
    },
}

/// Why a span of bytes is not a frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CorruptReason {
    /// Bytes before the next sync word.
    NoSync,
    /// Unknown version, kind or format, or a payload length over the limit or not a whole
    /// number of samples.
    BadHeader,
    /// The CRC does not match.
    BadCrc,
}

impl CorruptReason {
    /// Short description.
    pub fn as_str(self) -> &'static str {
        match self {
            CorruptReason::NoSync => "bytes without a sync word",
            CorruptReason::BadHeader => "invalid header",
            CorruptReason::BadCrc => "CRC mismatch",
        }
    }
}

/// Iterator of [`Event`]s over a complete byte buffer (a captured stream). After a bad
/// frame it resynchronises at the next sync word after the bad one's first byte.
#[derive(Debug, Clone)]
pub struct Decoder<'a> {
    buf: &'a [u8],
    pos: usize,
}

impl<'a> Decoder<'a> {
    /// A decoder over `buf`.
    pub fn new(buf: &'a [u8]) -> Self {
        Decoder { buf, pos: 0 }
    }

    fn find_sync(&self, from: usize) -> Option<usize> {
        let rest = self.buf.get(from..)?;
        rest.windows(4).position(|w| w == SYNC).map(|p| p + from)
    }

    fn parse_at(&self, at: usize) -> Result<(Header, usize, usize), Option<CorruptReason>> {
        // Err(None): truncated.
        let b = self.buf.get(at..).unwrap_or(&[]);
        let Some(h) = b.get(..HEADER_LEN) else {
            return Err(None);
        };
        let hb = |i: usize| h.get(i).copied().unwrap_or(0);
        let (Some(kind), Some(format)) = (Kind::from_u8(hb(5)), Format::from_u8(hb(6))) else {
            return Err(Some(CorruptReason::BadHeader));
        };
        let plen = u16::from_le_bytes([hb(24), hb(25)]) as usize;
        let size_ok = match (kind, format) {
            (Kind::Data, Format::F32 | Format::I16) => plen.is_multiple_of(format.sample_size()),
            (Kind::Start, Format::None) => plen == START_LEN,
            (Kind::End, Format::None) => plen == END_LEN,
            _ => false,
        };
        if hb(4) != VERSION || plen > MAX_PAYLOAD || !size_ok {
            return Err(Some(CorruptReason::BadHeader));
        }
        let total = HEADER_LEN + plen + CRC_LEN;
        let Some(frame) = b.get(..total) else {
            return Err(None);
        };
        let body = frame.get(4..HEADER_LEN + plen).unwrap_or(&[]);
        let crc_bytes = frame.get(HEADER_LEN + plen..).unwrap_or(&[]);
        let want = u32::from_le_bytes(crc_bytes.try_into().unwrap_or([0; 4]));
        if crc32(body) != want {
            return Err(Some(CorruptReason::BadCrc));
        }
        let word = |i: usize| u32::from_le_bytes([hb(i), hb(i + 1), hb(i + 2), hb(i + 3)]);
        Ok((
            Header {
                kind,
                format,
                flags: hb(7),
                seq: word(8),
                first_sample: word(12),
                overruns: word(16),
                scale: f32::from_bits(word(20)),
            },
            plen,
            total,
        ))
    }
}

impl<'a> Iterator for Decoder<'a> {
    type Item = Event<'a>;

    fn next(&mut self) -> Option<Event<'a>> {
        if self.pos >= self.buf.len() {
            return None;
        }
        let start = self.pos;
        let Some(at) = self.find_sync(start) else {
            // No sync word in the rest: a partial sync word at the very end is a truncation.
            let rest = self.buf.len() - start;
            self.pos = self.buf.len();
            let tail = self.buf.get(start..).unwrap_or(&[]);
            let partial = (1..4.min(rest + 1))
                .rev()
                .find(|k| tail.ends_with(SYNC.get(..*k).unwrap_or(&[])));
            return Some(match partial {
                Some(k) if k == rest => Event::Truncated {
                    offset: start,
                    len: rest,
                },
                _ => Event::Corrupt {
                    offset: start,
                    len: rest,
                    reason: CorruptReason::NoSync,
                },
            });
        };
        if at > start {
            self.pos = at;
            return Some(Event::Corrupt {
                offset: start,
                len: at - start,
                reason: CorruptReason::NoSync,
            });
        }
        match self.parse_at(at) {
            Ok((header, plen, total)) => {
                self.pos = at + total;
                Some(Event::Frame {
                    header,
                    payload: self
                        .buf
                        .get(at + HEADER_LEN..at + HEADER_LEN + plen)
                        .unwrap_or(&[]),
                    offset: at,
                })
            }
            Err(reason) => {
                // Skip to the next sync word after this one's first byte.
                let next = self.find_sync(at + 1).unwrap_or(self.buf.len());
                self.pos = next;
                Some(match reason {
                    Some(reason) => Event::Corrupt {
                        offset: at,
                        len: next - at,
                        reason,
                    },
                    None if next == self.buf.len() => Event::Truncated {
                        offset: at,
                        len: next - at,
                    },
                    // A frame cut short and followed by another sync word: its bytes are lost.
                    None => Event::Corrupt {
                        offset: at,
                        len: next - at,
                        reason: CorruptReason::BadHeader,
                    },
                })
            }
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::indexing_slicing)]
mod tests {
    use super::*;

    #[test]
    fn crc_check_value() {
        assert_eq!(crc32(b"123456789"), 0xCBF4_3926);
    }

    fn data_frame(seq: u32, vals: &[f32], out: &mut [u8]) -> usize {
        let mut p = [0u8; 64];
        for (i, v) in vals.iter().enumerate() {
            p[4 * i..4 * i + 4].copy_from_slice(&v.to_le_bytes());
        }
        let h = Header {
            kind: Kind::Data,
            format: Format::F32,
            flags: 0,
            seq,
            first_sample: seq * vals.len() as u32,
            overruns: 0,
            scale: 1.0,
        };
        encode(&h, &p[..4 * vals.len()], out).unwrap()
    }

    #[test]
    fn round_trip_and_resync() {
        let mut buf = [0u8; 512];
        let a = data_frame(0, &[1.0, 2.0], &mut buf);
        let b = data_frame(1, &[3.0, 4.0], &mut buf[a..]);
        let mut ok = buf;
        let n = a + b;
        let frames: usize = Decoder::new(&ok[..n])
            .filter(|e| matches!(e, Event::Frame { .. }))
            .count();
        assert_eq!(frames, 2);
        ok[HEADER_LEN + 1] ^= 0x10; // flip a payload bit of frame 0
        let ev: [Option<Event>; 3] = {
            let mut d = Decoder::new(&ok[..n]);
            [d.next(), d.next(), d.next()]
        };
        assert!(matches!(
            ev[0],
            Some(Event::Corrupt {
                reason: CorruptReason::BadCrc,
                ..
            })
        ));
        assert!(matches!(
            ev[1],
            Some(Event::Frame {
                header: Header { seq: 1, .. },
                ..
            })
        ));
        assert!(ev[2].is_none());
        // Truncated.
        let mut d = Decoder::new(&buf[..n - 3]);
        assert!(matches!(d.next(), Some(Event::Frame { .. })));
        assert!(matches!(d.next(), Some(Event::Truncated { .. })));
        assert!(d.next().is_none());
    }
}
