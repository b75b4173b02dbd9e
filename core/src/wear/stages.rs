//! The wear stages in the order they occur (thesis §4.2.2, publication III Fig. 3).

/// A wear stage. The order of the variants is the order of life; the stage machine
/// only ever moves forward. A life whose subsurface fatigue sum reaches its limit before
/// the surface forms a dent goes from steady state straight to crack opening (a
/// subsurface-initiated spall); every other stage is passed in order.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Stage {
    /// Fresh surfaces wear in: roughness falls to its steady value.
    RunningIn,
    /// Steady state: rolling-contact fatigue accumulates.
    SteadyState,
    /// A dent with a raised shoulder has formed.
    Dent,
    /// Over-rolling and abrasion have halved the dent's shoulder.
    DentSmoothing,
    /// A crack has opened: at the dent's trailing edge, or under the surface when the
    /// subsurface fatigue sum reached its limit first.
    CrackOpening,
    /// The crack propagates (its depth has doubled).
    CrackPropagation,
    /// The crack broke out: a spall exists and grows at its trailing edge.
    DefectCompletion,
    /// The spall reached its completed size; its edges are being smoothed.
    DefectSmoothing,
    /// New defects spawn from the completed one.
    DamageGrowth,
    /// End of life.
    Failure,
}

impl Stage {
    /// All stages in order.
    pub const ALL: [Stage; 10] = [
        Stage::RunningIn,
        Stage::SteadyState,
        Stage::Dent,
        Stage::DentSmoothing,
        Stage::CrackOpening,
        Stage::CrackPropagation,
        Stage::DefectCompletion,
        Stage::DefectSmoothing,
        Stage::DamageGrowth,
        Stage::Failure,
    ];

    /// Short kebab-case name.
    pub fn name(self) -> &'static str {
        match self {
            Stage::RunningIn => "running-in",
            Stage::SteadyState => "steady-state",
            Stage::Dent => "dent",
            Stage::DentSmoothing => "dent-smoothing",
            Stage::CrackOpening => "crack-opening",
            Stage::CrackPropagation => "crack-propagation",
            Stage::DefectCompletion => "defect-completion",
            Stage::DefectSmoothing => "defect-smoothing",
            Stage::DamageGrowth => "damage-growth",
            Stage::Failure => "failure",
        }
    }

    /// Whether the defect of this stage is a broken-out spall whose edges are fracture
    /// edges (defect completion onwards), rather than a dent's plastic shoulder.
    pub fn has_breakout_edge(self) -> bool {
        self >= Stage::DefectCompletion
    }

    /// Index 0..=9 in life order.
    pub fn index(self) -> usize {
        self as usize
    }

    /// Publication IV's sampled event (1–9) that this stage's onset illustrates:
    /// (1) normal operation, (2) mild roughness and waviness, (3) excitation of the
    /// natural frequency, (4) dent, (5) dent smoothing, (6) slippage, (7) defect
    /// completion, (8) defect smoothing, (9) damage growth. `None` for failure.
    pub fn publication_event(self) -> Option<u8> {
        match self {
            Stage::SteadyState => Some(1),
            Stage::RunningIn => Some(2),
            Stage::CrackOpening => Some(3),
            Stage::Dent => Some(4),
            Stage::DentSmoothing => Some(5),
            Stage::CrackPropagation => Some(6),
            Stage::DefectCompletion => Some(7),
            Stage::DefectSmoothing => Some(8),
            Stage::DamageGrowth => Some(9),
            Stage::Failure => None,
        }
    }
}
