//! Output samples in runs: [`Model::fill`] and [`Model::fill_observed`] step the model
//! and take the anti-alias filter's outputs four output periods at a time
//! ([`AntiAlias::outputs_block`](crate::decimate::AntiAlias::outputs_block)). The filter
//! does not feed back into the dynamics, so its outputs can wait for the block's last
//! step; each is the sum [`Model::step`] takes, in the same order, so the samples have
//! its bits, while the four sums' additions overlap instead of forming one chain of
//! `taps` dependent additions per sample (the scalar step's largest serial cost).

use super::{Channels, Model, Sample, State};
use crate::decimate::BLOCK;

impl Model {
    /// Fills `out` with output samples, what as many calls of [`Model::step`] give;
    /// returns how many were written (all of them).
    pub fn fill<const NB: usize>(&self, st: &mut State<NB>, out: &mut [Sample]) -> usize {
        self.fill_observed(st, out, |_| {})
    }

    /// [`Model::fill`], calling `observe` with the state after every internal step (for
    /// meters that read [`State::stats`] and the angles each step, as a life's pass meter
    /// does).
    pub fn fill_observed<const NB: usize>(
        &self,
        st: &mut State<NB>,
        out: &mut [Sample],
        mut observe: impl FnMut(&State<NB>),
    ) -> usize {
        let blocks = self.aa.block_span().is_some();
        let all = self.cfg.channels == Channels::All;
        let mut written = 0;
        for chunk in out.chunks_mut(BLOCK) {
            if blocks && chunk.len() == BLOCK {
                for _ in 0..BLOCK {
                    while !self.advance(st) {
                        observe(st);
                    }
                    observe(st);
                }
                let accel = self.aa.outputs_block(&st.lines[0]);
                let (vel, disp) = if all {
                    (
                        self.aa.outputs_block(&st.lines[1]),
                        self.aa.outputs_block(&st.lines[2]),
                    )
                } else {
                    ([0.0; BLOCK], [0.0; BLOCK])
                };
                for (((slot, a), v), d) in chunk.iter_mut().zip(accel).zip(vel).zip(disp) {
                    *slot = self.sample(st, a, (v, d));
                }
            } else {
                for slot in chunk.iter_mut() {
                    loop {
                        let s = self.step(st);
                        observe(st);
                        if let Some(s) = s {
                            *slot = s;
                            break;
                        }
                    }
                }
            }
            written += chunk.len();
        }
        written
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::effects::sensor::Params as SensorParams;
    use crate::error::ConfigError;
    use crate::presets;

    /// `fill` (blocks of four outputs) and `fill_observed` give the bits of as many
    /// `step` calls, at ratios 4 to 8 with all three channels and a stateful sensor chain
    /// (noise, low-pass, hum), for a length that is no multiple of four (the tail is taken
    /// one sample at a time); the observer sees every internal step, and the states end
    /// equal.
    #[test]
    fn blocks_of_outputs_keep_the_steps_bits() -> Result<(), ConfigError> {
        let Some(base) = presets::by_name("cwru-6205-de") else {
            return Err(ConfigError::Inconsistent {
                field: "preset",
                reason: "cwru-6205-de is missing",
            });
        };
        for ratio in [4u32, 5, 6, 8] {
            let mut cfg = base.clone();
            cfg.oversample = Some(ratio);
            cfg.channels = Channels::All;
            cfg.effects.sensor = Some(SensorParams {
                noise: 0.05,
                corner_hz: 4000.0,
                hum: 0.02,
                hum_hz: 60.0,
                hum_harmonics: 0.3,
            });
            let model = Model::new_checked(cfg)?;
            assert!(model.anti_alias().block_span().is_some());
            let n = 4 * 37 + 3;
            let mut by_step: State<16> = State::new(&model, 9)?;
            let mut want = [Sample::default(); 4 * 37 + 3];
            for slot in want.iter_mut() {
                *slot = loop {
                    if let Some(s) = model.step(&mut by_step) {
                        break s;
                    }
                };
            }
            let mut filled: State<16> = State::new(&model, 9)?;
            let mut got = [Sample::default(); 4 * 37 + 3];
            let mut steps_seen = 0u64;
            let written = model.fill_observed(&mut filled, &mut got, |s| {
                steps_seen += 1;
                assert_eq!(s.steps, steps_seen);
            });
            assert_eq!(written, n);
            assert_eq!(steps_seen, by_step.steps);
            for (g, w) in got.iter().zip(&want) {
                assert_eq!(g.accel.to_bits(), w.accel.to_bits());
                assert_eq!(g.vel.to_bits(), w.vel.to_bits());
                assert_eq!(g.disp.to_bits(), w.disp.to_bits());
            }
            assert!(got.iter().any(|s| s.accel != 0.0 && s.vel != 0.0));
            // The next sample after either path is the same: nothing was left behind.
            let next = loop {
                if let Some(s) = model.step(&mut by_step) {
                    break s;
                }
            };
            let mut one = [Sample::default(); 1];
            model.fill(&mut filled, &mut one);
            assert_eq!(one[0].accel.to_bits(), next.accel.to_bits());
        }
        Ok(())
    }
}
