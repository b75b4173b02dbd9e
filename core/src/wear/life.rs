//! The life state machine: configuration ([`Life`]) apart from the evolving state
//! ([`LifeState`]); `life.advance(&mut state, revs, &loads)` integrates the wear laws
//! over shaft revolutions with the contact loads measured from the dynamic model, and
//! stops at the first stage transition so that the caller can measure the loads of the
//! new topography before going on.

use super::events::{Event, EventLog};
use super::material::Material;
use super::rating::{dynamic_load_rating, lubrication_factor, stribeck_factor};
use super::site::Site;
use super::stages::Stage;
use crate::bearing::{BearingGeometry, ContactKind};
use crate::contact::{ElementContact, HertzContact};
use crate::error::{check_range, ConfigError};
use crate::forces::defect::ball_defect_max_length;
use crate::kinematics::FaultOrders;
use crate::real::{exp, ln, pow, sqrt, Real, PI};
use crate::rng::Xoshiro128pp;
use crate::topography::{self, Topography};

/// Contact loads measured over a window of the dynamic model (N).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct PassLoads {
    /// Power mean (Lundberg–Palmgren exponent) of the per-pass peak element load.
    pub zone: Real,
    /// Arithmetic mean of the per-pass peak element load.
    pub zone_mean: Real,
    /// Mean per-pass peak load of an element at the defect (0 without defect).
    pub edge: Real,
    /// Cubic mean of the same (fatigue initiation grows with p⁹ ∝ Q³).
    pub edge_cubic: Real,
    /// Passes measured.
    pub passes: u32,
}

/// Configuration of a life run.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct LifeConfig {
    /// Material and tribology constants.
    pub material: Material,
    /// Film parameter λ = h/σ at the steady roughness (thesis eq. 25).
    pub lambda: Real,
    /// Steady composite roughness σ (m); 0.1 µm for ground races.
    pub roughness: Real,
    /// Initial roughness over steady roughness (running-in), ≥ 1.
    pub running_in: Real,
    /// Slip fraction of the steady state (grows with the stage).
    pub slip: Real,
    /// Revolutions after which an unfinished life is an error.
    pub cycle_cap: Real,
}

impl LifeConfig {
    /// Defaults: bearing steel, λ = 2, σ = 0.1 µm, running-in ratio 1.5, slip 1 %,
    /// cap 10⁹ revolutions.
    pub const DEFAULT: LifeConfig = LifeConfig {
        material: Material::BEARING_STEEL,
        lambda: 2.0,
        roughness: 0.1e-6,
        running_in: 1.5,
        slip: 0.01,
        cycle_cap: 1e9,
    };
}

/// What a life advance did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Advance {
    /// Revolutions integrated (≤ requested; less when a transition stopped it).
    pub revs: Real,
    /// Stage entered, if a transition happened.
    pub transition: Option<Stage>,
}

/// Inputs of the dynamic model that the wear state sets.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DynamicInputs {
    /// Defect topography (none before the dent).
    pub topography: Option<Topography>,
    /// Roughness relative to its steady value (running-in > 1).
    pub roughness_scale: Real,
    /// Slip fraction.
    pub slip: Real,
}

/// The evolving life state; fixed size (the event log is a `heapless::Vec`).
#[derive(Debug, Clone, PartialEq)]
pub struct LifeState {
    /// Shaft revolutions so far.
    pub cycles: Real,
    /// Current stage.
    pub stage: Stage,
    /// Defect topography, once a dent exists.
    pub topography: Option<Topography>,
    /// Composite roughness σ (m).
    pub roughness: Real,
    /// Subsurface rolling-contact fatigue damage (life fraction): ISO 281's sum with the
    /// bearing's fatigue scatter; a subsurface crack opens at 1, at the dent if there is
    /// one, else under the surface of the most loaded zone.
    pub fatigue: Real,
    /// Surface damage (life fraction): the same ISO 281 integrand (loads, lubrication
    /// factor, debris) divided by the bearing's own dent scatter; the dent forms when it
    /// reaches `material.dent_fraction`.
    pub surface: Real,
    /// Crack-initiation damage at the dent (opens at 1).
    pub initiation: Real,
    /// Depth of the current crack (m), 0 before it opens.
    pub crack: Real,
    /// Depth the current crack started from (m).
    pub crack_start: Real,
    /// Asperity height when the dent formed (m).
    pub dent_asperity: Real,
    /// Height the current asperity smooths towards (m): Table 1's smoothed states — 0 for
    /// a dent, 4/30 of a fresh spall edge (work-hardened breakout edges).
    pub asperity_floor: Real,
    /// Debris level (0–1).
    pub debris: Real,
    /// Fatigue-life scatter factor of this bearing (Weibull, slope [`WEIBULL_SLOPE`],
    /// median 1): divides the ISO 281 fatigue rate.
    pub scatter: Real,
    /// Spall-propagation scatter factor of this bearing (Weibull, slope
    /// [`PROPAGATION_WEIBULL_SLOPE`], median 1), drawn independently of `scatter`: the
    /// spall's growth laws (trailing-edge breakouts from defect completion on, the
    /// propagation limit that spawns new defects) run `1/propagation_scatter` times as fast.
    pub propagation_scatter: Real,
    /// Surface-initiation scatter factor of this bearing (Weibull, slope
    /// [`INITIATION_WEIBULL_SLOPE`], median 1), drawn independently of the other two: the
    /// crack-initiation sum at the dent, `Σ (σ₀/p_ref)⁹ / N_i`, runs `1/initiation_scatter`
    /// times as fast. A surface-initiated crack at a dent shoulder starts from the flaws of
    /// a thin surface layer, not from the subsurface volume that sets the fatigue scatter.
    pub initiation_scatter: Real,
    /// Surface-damage scatter factor of this bearing (Weibull, slope [`WEIBULL_SLOPE`],
    /// median 1), drawn independently of the other three: the surface-damage sum that forms
    /// the dent runs `1/dent_scatter` times as fast. Surface and subsurface initiation
    /// compete; with one shared factor the dent formed at exactly `dent_fraction` of the
    /// bearing's own subsurface life, and the crack opened at exactly twice the dent's
    /// time in most lives (issue 14).
    pub dent_scatter: Real,
    /// Transitions so far.
    pub events: EventLog,
    /// Transitions that did not fit in the log.
    pub lost_events: u16,
}

/// Validated life model of one bearing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Life {
    cfg: LifeConfig,
    rating: Real,
    exponent: Real,
    elements: Real,
    stribeck: Real,
    passes_per_rev: Real,
    contact: HertzContact,
    element_radius: Real,
    reference_pressure: Real,
    reference_load: Real,
    kind: ContactKind,
    site: Site,
    max_length: Real,
    completed_length: Real,
}

/// Weibull slope of rolling-bearing lives (ISO 281: e = 1.11 for ball bearings).
pub const WEIBULL_SLOPE: Real = 1.11;
/// Weibull slope of the spall-propagation time, from the first spall to failure (–): 1.1,
/// the median of Hoeprich 1992's tapered-roller propagation tests (as summarised by
/// Kotzalas & Harris 2001, J. Tribol. 123, doi:10.1115/1.1308013): propagation is as
/// stochastic as initiation, not a fixed tail after it.
pub const PROPAGATION_WEIBULL_SLOPE: Real = 1.1;
/// Weibull slope of the crack-initiation life at a dent (–): 10/9, Lundberg–Palmgren's
/// dispersion exponent for point contact (ISO 281's e = 10/9 for ball bearings). The
/// dent's initiation law `Σ (σ₀/p_ref)⁹` is Lundberg–Palmgren's pressure–life law (life ∝
/// p⁻⁹ = Q⁻³), and a life law of that theory carries that theory's scatter: with a fixed
/// initiation time every long life would open its crack after the same number of passes
/// at the dent, a deterministic cap on the dent stage that narrows the spread of lives.
/// Surface and subsurface initiation then compete with independent scatter (the structure
/// of SKF's generalised bearing life model, Morales-Espejel, Gabelli & de Vries 2015,
/// Tribol. Trans. 58:894–906, surface and subsurface survival combined).
pub const INITIATION_WEIBULL_SLOPE: Real = WEIBULL_SLOPE;
/// Share of a fresh spall edge's asperity that smoothing cannot remove: Table 1's
/// smoothed large defect (4 µm) over the large defect (30 µm).
pub const SPALL_EDGE_RESIDUAL: Real =
    topography::SMOOTHED_LARGE_DEFECT.asperity_height / topography::LARGE_DEFECT.asperity_height;
/// Share of a breakout edge's height (–) above which its excess over the residual counts
/// as fresh ([`Life::representative_revs`]): a quarter, reached about
/// `edge_shakedown_passes` after the breakout (the excess falls as `exp(−3 n/N_sd)`).
pub const FRESH_EDGE: Real = 0.25;
/// Windows (–) over a fresh edge's `edge_shakedown_passes` ([`Life::representative_revs`]):
/// each block then holds loads that the shakedown changes by at most `1 − e^(−1/2)` of
/// the edge's excess.
pub const SHAKEDOWN_BLOCKS: Real = 6.0;
/// Smallest initial crack depth (m): a typical inclusion/micro-crack in bearing steel.
pub const MIN_FLAW: Real = 5e-6;

impl Life {
    /// Validates `cfg` for `bearing`; `static_load` is the most loaded element's static
    /// load (N) used when a window measured no pass; `site` is the surface whose life is
    /// computed ([`Site::of`] the base model's defect location).
    ///
    /// Per site (see [`Site`]): the passes per revolution that scale every per-pass law
    /// (BPFO, BPFI or 2·BSF over `f_r`) and the Hertz contact that turns the measured loads
    /// into pressures and contact half-widths (outer, inner, or the more stressed of the
    /// element's two). The reference pressure that normalises the initiation laws stays
    /// the outer contact's at `static_load` for every site: the material constants
    /// (`initiation_passes`, `propagation_passes`) were set on outer-race lives, so a site
    /// with a higher pressure accumulates faster instead of being renormalised away.
    pub fn new_checked(
        cfg: LifeConfig,
        bearing: &BearingGeometry,
        static_load: Real,
        site: Site,
    ) -> Result<Self, ConfigError> {
        Self::new_checked_at(cfg, bearing, static_load, static_load, site)
    }

    /// [`Life::new_checked`] with the reference pressure taken at `calibration_load` (N,
    /// the most loaded element's static load of the scenario the material constants hold
    /// for) instead of at `static_load`. A load scaled away from the scenario's (`wearsim
    /// life --load-scale`, `--loads`) then raises the initiation and propagation rates as
    /// a heavier load does (pressure ratio to the ninth power in the dent's initiation,
    /// Lundberg–Palmgren; cubed in the spawn law), rather than being normalised away with
    /// a reference that moved with it.
    pub fn new_checked_at(
        cfg: LifeConfig,
        bearing: &BearingGeometry,
        static_load: Real,
        calibration_load: Real,
        site: Site,
    ) -> Result<Self, ConfigError> {
        check_range("life.calibration_load", calibration_load, 1e-3, 1e8)?;
        let material = Material::new_checked(cfg.material)?;
        check_range("lambda", cfg.lambda, 0.05, 20.0)?;
        check_range("life.roughness", cfg.roughness, 1e-9, 5e-6)?;
        check_range("life.running_in", cfg.running_in, 1.0, 10.0)?;
        check_range("life.slip", cfg.slip, 0.0, 0.1)?;
        check_range("cycles", cfg.cycle_cap, 1.0, 1e13)?;
        check_range("life.static_load", static_load, 1e-3, 1e8)?;
        let contact = ElementContact::of(bearing);
        let orders = FaultOrders::of(bearing);
        let exponent = match bearing.contact {
            ContactKind::Point => 3.0,
            ContactKind::Line => 10.0 / 3.0,
        };
        // The element's topographies are fitted to the ball (see `Life::completed_length`);
        // a race has no such limit (min with +∞ keeps its completed length's bits).
        let max_length = match site {
            Site::Element => {
                ball_defect_max_length(bearing.element_diameter, material.failure_defects)
            }
            Site::OuterRace | Site::InnerRace => Real::INFINITY,
        };
        Ok(Life {
            cfg: LifeConfig { material, ..cfg },
            rating: dynamic_load_rating(bearing),
            exponent,
            elements: bearing.elements as Real,
            stribeck: stribeck_factor(bearing.contact),
            passes_per_rev: site.passes_per_rev(&orders),
            contact: site.contact(&contact, static_load),
            element_radius: 0.5 * bearing.element_diameter,
            reference_pressure: contact.outer.max_pressure(calibration_load),
            reference_load: static_load,
            kind: bearing.contact,
            site,
            max_length,
            completed_length: material.completed_length.min(max_length),
        })
    }

    /// The configuration.
    pub fn config(&self) -> &LifeConfig {
        &self.cfg
    }

    /// ISO 281 basic dynamic load rating used (N).
    pub fn rating(&self) -> Real {
        self.rating
    }

    /// Initial state; `seed` draws the bearing's fatigue-life scatter (Weibull, slope
    /// [`WEIBULL_SLOPE`], median 1), then, independently, its spall-propagation scatter
    /// (slope [`PROPAGATION_WEIBULL_SLOPE`], median 1), its surface-initiation scatter
    /// (slope [`INITIATION_WEIBULL_SLOPE`], median 1) and its dent scatter (slope
    /// [`WEIBULL_SLOPE`], median 1), in that order (a factor added later is drawn last, so
    /// the earlier ones keep their values for every seed).
    pub fn initial_state(&self, seed: u64) -> LifeState {
        let mut rng = Xoshiro128pp::from_u64(seed ^ 0x5EED_11FE);
        let mut median_one_weibull = |slope: Real| {
            let u = 0.5 * (rng.uniform_pm1() + 1.0); // [0, 1)
            let u = u.clamp(1e-6, 1.0 - 1e-6);
            pow(-ln(1.0 - u) / ln(2.0), 1.0 / slope)
        };
        let scatter = median_one_weibull(WEIBULL_SLOPE);
        let propagation_scatter = median_one_weibull(PROPAGATION_WEIBULL_SLOPE);
        let initiation_scatter = median_one_weibull(INITIATION_WEIBULL_SLOPE);
        let dent_scatter = median_one_weibull(WEIBULL_SLOPE);
        LifeState {
            cycles: 0.0,
            stage: Stage::RunningIn,
            topography: None,
            roughness: self.cfg.roughness * self.cfg.running_in,
            fatigue: 0.0,
            surface: 0.0,
            initiation: 0.0,
            crack: 0.0,
            crack_start: 0.0,
            dent_asperity: 0.0,
            asperity_floor: 0.0,
            debris: 0.0,
            scatter,
            propagation_scatter,
            initiation_scatter,
            dent_scatter,
            events: EventLog::new(),
            lost_events: 0,
        }
    }

    /// What the dynamic model must simulate for the state `st`.
    pub fn dynamic_inputs(&self, st: &LifeState) -> DynamicInputs {
        // Slip grows with the stage (thesis §4.1.6: "the amount is related to the wear
        // evolution stages"): ×1 up to the dent, ×4 in damage growth.
        const SLIP_GROWTH: [Real; 10] = [1.0, 1.0, 1.0, 1.2, 1.5, 2.0, 2.5, 3.0, 4.0, 4.0];
        let growth = SLIP_GROWTH.get(st.stage.index()).copied().unwrap_or(1.0);
        DynamicInputs {
            topography: st.topography.map(|t| Topography {
                debris: st.debris.min(1.0),
                ..t
            }),
            roughness_scale: st.roughness / self.cfg.roughness,
            slip: self.cfg.slip * growth,
        }
    }

    fn film(&self) -> Real {
        self.cfg.lambda * self.cfg.roughness
    }

    /// Film parameter at the current roughness.
    pub fn lambda_now(&self, st: &LifeState) -> Real {
        self.film() / st.roughness
    }

    /// Stress-concentration factor of an asperity of height `h` in a contact of
    /// rolling-direction half-width `b` (after Hannes & Alfredsson 2011).
    fn kt(&self, h: Real, b: Real) -> Real {
        if b <= 0.0 {
            return 1.0;
        }
        1.0 + self.cfg.material.asperity_beta * sqrt(h / b)
    }

    /// Advances `st` by up to `revs` revolutions with the measured `loads`; stops at the
    /// first transition. Never panics; a state in `Failure` does not change.
    pub fn advance(&self, st: &mut LifeState, revs: Real, loads: &PassLoads) -> Advance {
        let m = &self.cfg.material;
        let mut done = 0.0;
        if st.stage == Stage::Failure || revs.is_nan() || revs <= 0.0 {
            return Advance {
                revs: 0.0,
                transition: None,
            };
        }
        let q_zone = if loads.zone > 0.0 {
            loads.zone
        } else {
            self.reference_load
        };
        let q_zone_mean = if loads.zone_mean > 0.0 {
            loads.zone_mean
        } else {
            q_zone
        };
        let q_edge = if loads.edge_cubic > 0.0 {
            loads.edge_cubic
        } else {
            q_zone
        };
        let p_zone = self.contact.max_pressure(q_zone_mean);
        let p_edge = self.contact.max_pressure(q_edge);
        let (_, b) = self.contact.semi_axes(q_zone_mean);
        let p_mean = 2.0 / 3.0 * p_zone;
        let load = self.elements * q_zone / self.stribeck;
        let n_p = self.passes_per_rev;
        let mut guard = 0u32;
        while done < revs && guard < 200_000 {
            guard += 1;
            let remaining = revs - done;
            let lambda = self.lambda_now(st);
            let interaction = (1.0 - lambda / 3.0).clamp(0.0, 1.0);
            let slide = self.cfg.slip * 2.0 * b; // sliding distance per pass (m)
            let archard = m.abrasion * p_mean / m.hardness * slide; // depth per pass (m)

            // Rates per revolution.
            let a_l = lubrication_factor(lambda);
            let iso_rate = pow(load / self.rating, self.exponent) * (1.0 + 2.0 * st.debris)
                / (1e6 * m.life_factor * a_l);
            let fatigue_rate = iso_rate / st.scatter;
            let surface_rate = iso_rate / st.dent_scatter;
            let rough_rate = if st.stage == Stage::RunningIn {
                -n_p * archard * interaction
            } else {
                0.0
            };
            let h = st.topography.map(|t| t.asperity_height).unwrap_or(0.0);
            let kt = self.kt(h, b);
            let sigma0 = p_edge * kt;
            let excess = h - st.asperity_floor;
            // An excess within 64 ulp of `h` is the floor: the step below removes 2 % of
            // the excess, which under ~50 ulp rounds away, so the edge would never reach
            // its floor and every step would stay too short to advance `cycles` (seen in
            // f32 on a 2.7 µm ball-spall edge floor: the life stalled). In f64 the
            // threshold (~10⁻²⁰ m) is far below any excess a step leaves.
            // The asperity's excess over its floor decays by plastic flattening at the
            // relative rate `h_decay` (per revolution) and loses `h_abr` (m per
            // revolution) to abrasion: a breakout edge shakes down within
            // `edge_shakedown_passes`, a dent's shoulder flattens by the over-rolling of
            // eq. 24.
            let (h_decay, h_abr) = if excess > 64.0 * Real::EPSILON * h {
                let abr = if h > self.film() {
                    archard * (0.2 + interaction)
                } else {
                    0.0
                };
                let plastic = if st.stage.has_breakout_edge() {
                    3.0 / m.edge_shakedown_passes
                } else {
                    let w_a = sigma0;
                    let omega = 1.12 * sqrt(w_a * p_mean) / m.youngs_modulus; // eq. 24 (relative)
                    m.overrolling * omega
                };
                (n_p * plastic, n_p * abr)
            } else {
                (0.0, 0.0)
            };
            let h_rate = -(h_decay * excess + h_abr);
            let depth = st.topography.map(|t| t.depth).unwrap_or(0.0);
            let flaw = (depth + h).max(MIN_FLAW);
            let dk_flaw = 1.12 * sigma0 * sqrt(PI * flaw);
            let init_rate = match st.stage {
                Stage::Dent | Stage::DentSmoothing if dk_flaw >= m.k_threshold => {
                    n_p * pow(sigma0 / self.reference_pressure, 9.0)
                        / (m.initiation_passes * st.initiation_scatter)
                }
                Stage::DefectSmoothing | Stage::DamageGrowth => {
                    let r = sigma0 / self.reference_pressure;
                    n_p * r * r * r / (m.propagation_passes * st.propagation_scatter)
                }
                _ => 0.0,
            };
            let crack_rate = if st.crack > 0.0 {
                let dk = 1.12 * sigma0 * sqrt(PI * st.crack);
                let delta_pl = dk * dk / (2.0 * m.youngs_modulus * m.yield_strength);
                // From the first spall on, its trailing-edge cracks are spall propagation
                // and carry the bearing's propagation scatter.
                let spread = if st.stage == Stage::DefectCompletion {
                    st.propagation_scatter
                } else {
                    1.0
                };
                n_p * m.crack_c0 * pow(delta_pl, m.crack_m0) / spread
            } else {
                0.0
            };
            let debris_rate = -n_p * st.debris / m.debris_flush_passes;

            // Step: at most the remaining revolutions, small relative changes, and
            // landing exactly on the next threshold of a linear accumulator.
            let mut dt = remaining;
            if st.stage == Stage::SteadyState && surface_rate > 0.0 {
                dt = dt.min(((m.dent_fraction - st.surface) / surface_rate).max(0.0));
            }
            if matches!(
                st.stage,
                Stage::SteadyState | Stage::Dent | Stage::DentSmoothing
            ) && fatigue_rate > 0.0
            {
                dt = dt.min(((1.0 - st.fatigue) / fatigue_rate).max(0.0));
            }
            if init_rate > 0.0 {
                dt = dt.min(((1.0 - st.initiation) / init_rate).max(0.0));
            }
            if rough_rate < 0.0 {
                dt = dt.min(0.05 * (st.roughness - self.cfg.roughness).max(1e-12) / -rough_rate);
            }
            if h_rate < 0.0 {
                dt = dt.min(0.02 * excess / -h_rate);
            }
            if crack_rate > 0.0 {
                dt = dt.min(0.02 * st.crack / crack_rate);
            }
            if debris_rate < 0.0 {
                dt = dt.min(0.05 * st.debris / -debris_rate);
            }
            let dt = dt.max(remaining.min(1e-3));

            st.fatigue += fatigue_rate * dt;
            st.surface += surface_rate * dt;
            st.roughness = (st.roughness + rough_rate * dt).max(self.cfg.roughness);
            st.initiation += init_rate * dt;
            st.crack += crack_rate * dt;
            st.debris = (st.debris + debris_rate * dt).max(0.0);
            if let Some(t) = st.topography.as_mut() {
                // The decay integrated exactly over the step (its rate is frozen within it).
                let flattened = st.asperity_floor + excess * exp(-h_decay * dt) - h_abr * dt;
                if h_rate < 0.0 {
                    t.asperity_height = flattened.max(st.asperity_floor);
                }
            }
            st.cycles += dt;
            done += dt;

            if let Some(next) = self.transition(st) {
                self.enter(st, next);
                return Advance {
                    revs: done,
                    transition: Some(next),
                };
            }
        }
        Advance {
            revs: done,
            transition: None,
        }
    }

    /// The stage the state has reached, if it differs from its current one.
    fn transition(&self, st: &LifeState) -> Option<Stage> {
        let m = &self.cfg.material;
        match st.stage {
            Stage::RunningIn => {
                let done = st.roughness <= 1.05 * self.cfg.roughness || self.lambda_now(st) >= 3.0;
                done.then_some(Stage::SteadyState)
            }
            // Subsurface initiation first when both limits fall in one step (the step
            // lands exactly on the nearer one, so a tie is only a tie).
            Stage::SteadyState if st.fatigue >= 1.0 => Some(Stage::CrackOpening),
            Stage::SteadyState => (st.surface >= m.dent_fraction).then_some(Stage::Dent),
            Stage::Dent | Stage::DentSmoothing => {
                if st.initiation >= 1.0 || st.fatigue >= 1.0 {
                    Some(Stage::CrackOpening)
                } else if st.stage == Stage::Dent
                    && st.topography.map(|t| t.asperity_height).unwrap_or(0.0)
                        <= 0.5 * st.dent_asperity
                {
                    Some(Stage::DentSmoothing)
                } else {
                    None
                }
            }
            Stage::CrackOpening => {
                (st.crack >= 2.0 * st.crack_start).then_some(Stage::CrackPropagation)
            }
            Stage::CrackPropagation => {
                (st.crack >= m.spall_depth).then_some(Stage::DefectCompletion)
            }
            Stage::DefectCompletion => {
                if st.crack >= m.spall_depth {
                    let grown = st.topography.map(|t| t.length).unwrap_or(0.0)
                        + m.breakout_ratio * m.spall_depth;
                    if grown >= self.completed_length {
                        return Some(Stage::DefectSmoothing);
                    }
                    // Growth within the stage: handled in `enter` via a self-transition.
                    return Some(Stage::DefectCompletion);
                }
                None
            }
            Stage::DefectSmoothing | Stage::DamageGrowth => {
                if st.initiation >= 1.0 {
                    let count = st.topography.map(|t| t.count).unwrap_or(1) + 1;
                    if count >= m.failure_defects {
                        Some(Stage::Failure)
                    } else {
                        Some(Stage::DamageGrowth)
                    }
                } else {
                    None
                }
            }
            Stage::Failure => None,
        }
    }

    /// Applies the topography change of entering `next` and logs it.
    fn enter(&self, st: &mut LifeState, next: Stage) {
        let m = &self.cfg.material;
        let breakout = m.breakout_ratio * m.spall_depth;
        let fresh_crack = |h: Real| (0.25 * h).max(MIN_FLAW);
        let logged = next != st.stage;
        match next {
            Stage::Dent => {
                st.topography = Some(Topography {
                    length: self.fit_length(topography::REAL_DENT.length),
                    ..topography::REAL_DENT
                });
                st.dent_asperity = topography::REAL_DENT.asperity_height;
                st.asperity_floor = topography::SMOOTHED_DENT.asperity_height;
            }
            Stage::CrackOpening => {
                // From the dent's depth and shoulder, or, for a subsurface crack without a
                // dent, from an inclusion-sized flaw.
                let start = st.topography.map_or(0.0, |t| t.depth + t.asperity_height);
                st.crack = start.max(MIN_FLAW);
                st.crack_start = st.crack;
            }
            Stage::DefectCompletion | Stage::DefectSmoothing => {
                let completed = next == Stage::DefectSmoothing;
                let length = match (st.stage, st.topography) {
                    (Stage::DefectCompletion, Some(t)) => {
                        (t.length + breakout).min(self.completed_length)
                    }
                    _ => self.fit_length(breakout),
                };
                // Table 1 landmarks: fresh edges of 20 µm up to medium size, 30 µm for
                // large defects.
                let h = if length >= 2e-3 { 30e-6 } else { 20e-6 };
                st.asperity_floor = h * SPALL_EDGE_RESIDUAL;
                st.topography = Some(Topography {
                    asperity_height: h,
                    length,
                    width: (0.6 * length).max(50e-6),
                    depth: m.spall_depth,
                    count: 1,
                    debris: 0.0,
                });
                st.debris += m.debris_per_breakout;
                // Until completion the trailing-edge crack restarts from a fresh flaw; once
                // complete, new defects come from the propagation accumulator instead.
                st.crack = if completed { 0.0 } else { fresh_crack(h) };
                st.crack_start = st.crack;
                st.initiation = 0.0;
            }
            Stage::DamageGrowth | Stage::Failure => {
                if let Some(t) = st.topography.as_mut() {
                    t.count = t.count.saturating_add(1);
                    t.asperity_height = topography::LARGE_DEFECT.asperity_height;
                }
                st.asperity_floor = topography::LARGE_DEFECT.asperity_height * SPALL_EDGE_RESIDUAL;
                st.debris += m.debris_per_breakout;
                st.initiation = 0.0;
            }
            _ => {}
        }
        let event = Event {
            stage: next,
            cycles: st.cycles,
            topography: st.topography.unwrap_or(topography::SMOOTHED_DENT),
            crack: st.crack,
        };
        st.stage = next;
        // Stage changes and spawned defects are logged; growth steps of the defect within
        // its completion stage are not (the snapshots show them).
        if (logged || next == Stage::DamageGrowth) && st.events.push(event).is_err() {
            st.lost_events = st.lost_events.saturating_add(1);
        }
    }

    /// Checks that the dynamic model `base` of a life run can carry the wear history: its
    /// defect location, if any, must exist on the bearing — a ball defect's `element` in
    /// `0 ..= elements − 1` ([`DefectLocation::check_fit`](crate::forces::defect::DefectLocation::check_fit),
    /// `defect.element`), checked here because the life builds the model of the first
    /// defect only at the dent. Race, ball and no defect are all carried: the topographies
    /// grown on a ball are fitted to it ([`Life::completed_length`]).
    pub fn check_base(base: &crate::model::ModelConfig) -> Result<(), ConfigError> {
        match base.defect {
            Some(d) => d.location.check_fit(&base.bearing, &topography::REAL_DENT),
            None => Ok(()),
        }
    }

    /// `length` (m) fitted to the site: at most the ball's limit at the failure count on an
    /// element (see [`Life::completed_length`]), unchanged on a race.
    fn fit_length(&self, length: Real) -> Real {
        length.min(self.max_length)
    }

    /// Completed defect length of the site (m), where breakouts stop lengthening the defect
    /// and it enters defect smoothing. On a race, `material.completed_length` (Table 1's
    /// 3 mm large defect). On a rolling element, the smaller of that and
    /// [`ball_defect_max_length`] at `material.failure_defects`: the longest defect whose
    /// whole failure pattern (`failure_defects` defects at a pitch of 1.5 lengths) still
    /// spans at most half the ball's circumference `π r_b`, beyond which it would be under
    /// both races at once and no longer a localized defect
    /// ([`DefectLocation::check_fit`](crate::forces::defect::DefectLocation::check_fit)).
    /// Growth of a ball's spall saturates there (2.27 mm on the CWRU 6205's 7.94 mm ball,
    /// 1.13 mm on the 61810's 3.97 mm ball, with 4 failure defects); further damage shows
    /// as spawned defects, edge asperities and debris, never as length, so no topography
    /// the life simulates is refused by `check_fit` at any count up to failure.
    pub fn completed_length(&self) -> Real {
        self.completed_length
    }

    /// The dynamic-model configuration for wear state `st`: `base` with the state's defect
    /// topography (on `base`'s defect location and formulation, or the outer race at the
    /// load-zone centre), roughness scaled by running-in and slip grown with the stage.
    /// `base` is expected to pass [`Life::check_base`].
    pub fn model_config(
        &self,
        base: &crate::model::ModelConfig,
        st: &LifeState,
    ) -> crate::model::ModelConfig {
        let inputs = self.dynamic_inputs(st);
        let mut cfg = base.clone();
        cfg.defect = match (cfg.defect, inputs.topography) {
            // `fit` leaves the life's own topographies unchanged (they are grown within the
            // limit); it guards states built by hand against `check_fit`.
            (Some(d), Some(t)) => Some(crate::forces::defect::DefectConfig {
                topography: d.location.fit(&cfg.bearing, t),
                ..d
            }),
            (None, Some(t)) => Some(crate::presets::outer_race_defect(t)),
            (_, None) => None,
        };
        if let Some(r) = cfg.roughness.as_mut() {
            r.rms *= inputs.roughness_scale;
        }
        // Debris acts on the model only through the roughness multiplier
        // `1 + debris_gain·debris` (`Roughness::step_sigma`). Once the flushing has taken
        // it below what that multiplier resolves in this number type (or with no
        // roughness), the model is the one with none, bit for bit; it is passed as 0 so
        // that successive windows compare equal (the host driver renders equal models
        // together) instead of differing by a decaying 10⁻⁸⁰.
        let gain = cfg.roughness.map_or(0.0, |r| r.debris_gain);
        if let Some(d) = cfg.defect.as_mut() {
            if 1.0 + gain * d.topography.debris == 1.0 {
                d.topography.debris = 0.0;
            }
        }
        cfg.slip = Some(crate::forces::slip::Slip {
            fraction: inputs.slip,
        });
        cfg
    }

    /// The surface whose life is computed.
    pub fn site(&self) -> Site {
        self.site
    }

    /// Passes over the site per shaft revolution (–): BPFO, BPFI or 2·BSF over `f_r`.
    pub fn passes_per_rev(&self) -> Real {
        self.passes_per_rev
    }

    /// The longest block (revolutions) over which the pass loads measured for `st` stay
    /// representative of the wear: unbounded, except while a fresh breakout edge shakes
    /// down (its excess over the residual more than [`FRESH_EDGE`] of its height), when
    /// it is `edge_shakedown_passes / (SHAKEDOWN_BLOCKS · passes per revolution)`. A fresh
    /// edge's pass loads fall within those passes, so a driver that held them for a whole
    /// snapshot interval grew the spall as if the edge never shook down and shortened
    /// every life after its first spall, by more the longer the interval.
    pub fn representative_revs(&self, st: &LifeState) -> Real {
        match st.topography {
            Some(t)
                if st.stage.has_breakout_edge()
                    && t.asperity_height - st.asperity_floor > FRESH_EDGE * t.asperity_height =>
            {
                self.cfg.material.edge_shakedown_passes / (SHAKEDOWN_BLOCKS * self.passes_per_rev)
            }
            _ => Real::INFINITY,
        }
    }

    /// The Hertz contact of the site.
    pub fn contact(&self) -> HertzContact {
        self.contact
    }

    /// The reference Hertz pressure (Pa) of the static most loaded element at the outer
    /// race under the calibration load (the normalisation of the initiation laws for every
    /// site; see [`Life::new_checked_at`]).
    pub fn reference_pressure(&self) -> Real {
        self.reference_pressure
    }

    /// Whether `kind` is the contact the life was built for.
    pub fn contact_kind(&self) -> ContactKind {
        self.kind
    }
}
