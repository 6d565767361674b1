//! Divergence of two engines on one landing, channel by channel, each against a tolerance
//! written down with its reason ([`TOLERANCES`]). Every tolerance and every floor is a ratio:
//! of the channel's own value, of a strut's capacity or of the vehicle's own scales
//! ([`touchdown_scenario::scales`]), so that a dynamically similar vehicle is judged alike
//! (docs/engines.md, "Tolerances from the vehicle's scales"); a scenario may set its own
//! tolerances (`[comparison]`, [`Basis`]).

use crate::trace::{Trace, ACCELERATION_WINDOW};
use crate::{Engine, EngineRun};
use serde::Serialize;
use touchdown_record::Outcome;
use touchdown_scenario::scales::Scales;
use touchdown_scenario::{Scenario, ScenarioError};

/// A channel's tolerance and why it is that.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tolerance {
    /// The channel family, as the text reports and docs/engines.md name it.
    pub channel: &'static str,
    /// The channel family's identifier: the `quantity` of its channels.
    pub quantity: &'static str,
    /// Largest difference that passes, a ratio to what `difference_unit` names.
    pub limit: f64,
    /// What the difference and the limit are ratios to: [`OWN_VALUE`] (the channel's own
    /// value, or the energy at touchdown), [`FOOTPRINT_RADIUS`], [`TIME_SCALE`] or
    /// [`VELOCITY_SCALE`] (the vehicle's scales).
    pub difference_unit: &'static str,
    /// How the difference is measured.
    pub measured_as: &'static str,
    /// Why this tolerance.
    pub reason: &'static str,
}

/// A difference as a fraction of the channel's own value (or, for the energy, of the touchdown
/// kinetic energy): `difference_unit` of such a tolerance.
pub const OWN_VALUE: &str = "fraction";

/// A difference as a fraction of the vehicle's footprint radius ([`Scales::length_m`]).
pub const FOOTPRINT_RADIUS: &str = "footprint_radius";

/// A difference as a fraction of the vehicle's time scale ([`Scales::time_s`]).
pub const TIME_SCALE: &str = "time_scale";

/// A difference as a fraction of the vehicle's velocity scale ([`Scales::velocity_m_s`]).
pub const VELOCITY_SCALE: &str = "velocity_scale";

/// Primary strokes under this fraction of the primary's capacity are measured against it:
/// 9.5 mm on the 1/6-scale model's 135 mm, within the scatter of its drop tests' records. Each
/// ratio here and in [`TOLERANCES`] replaces an absolute value chosen on the 1/6-scale model
/// (10 mm here) and is no looser than it there.
pub const PRIMARY_STROKE_FLOOR: f64 = 0.07;

/// Secondary strokes under this fraction of the secondaries' smaller capacity are measured
/// against it: 4.8 mm on the 1/6-scale model's 107 mm (5 mm before).
pub const SECONDARY_STROKE_FLOOR: f64 = 0.045;

/// Pitch rates under this fraction of the vehicle's rate scale 1/[`Scales::time_s`] are
/// measured against it: 0.095 rad/s on the 1/6-scale model (3.81 rad/s).
pub const PITCH_RATE_FLOOR: f64 = 0.025;

/// Vertical accelerations under this fraction of the vehicle's acceleration scale
/// ([`Scales::acceleration_m_s2`], g) are measured against it: 0.98 m/s² under Earth gravity.
pub const ACCELERATION_FLOOR: f64 = 0.1;

/// Primary strokes: relative difference of the maximum stroke, strokes under
/// [`PRIMARY_STROKE_FLOOR`] of the capacity measured against it.
pub const PRIMARY_STROKE: Tolerance = Tolerance {
    channel: "primary stroke",
    quantity: "primary_stroke",
    limit: 0.05,
    difference_unit: OWN_VALUE,
    measured_as: "fraction of the larger maximum stroke (at least 7 % of the primary's capacity)",
    reason: "the agreement asked of the rebuilds on the Table I primary strokes; below 7 % of the capacity (9.5 mm on the 1/6-scale model) a stroke is within the scatter of the drop tests' records",
};

/// Secondary strokes: relative difference of the maximum stroke (compression or tension), under
/// [`SECONDARY_STROKE_FLOOR`] of the smaller capacity measured against it.
pub const SECONDARY_STROKE: Tolerance = Tolerance {
    channel: "secondary stroke",
    quantity: "secondary_stroke",
    limit: 0.10,
    difference_unit: OWN_VALUE,
    measured_as: "fraction of the larger maximum stroke (at least 4.5 % of the secondaries' smaller capacity)",
    reason: "the agreement asked of the rebuilds on the Table I secondary strokes; secondaries are short and follow the gear's swing, so twice the primaries' tolerance",
};

/// Peak pitch rate.
pub const PEAK_PITCH_RATE: Tolerance = Tolerance {
    channel: "peak pitch rate",
    quantity: "peak_pitch_rate",
    limit: 0.05,
    difference_unit: OWN_VALUE,
    measured_as: "fraction of the larger peak magnitude of either sense (at least 2.5 % of the vehicle's rate scale, the inverse of its time scale); each sense's extreme is a channel",
    reason: "the pitch rate drives the overturn; 5 % of its peak moves a stability boundary by about as much as the report's 0.05 ft/s search tolerance at 8 ft/s",
};

/// Time of the peak pitch rate.
pub const PEAK_PITCH_RATE_TIME: Tolerance = Tolerance {
    channel: "peak pitch rate time",
    quantity: "peak_pitch_rate_time",
    limit: 0.038,
    difference_unit: TIME_SCALE,
    measured_as: "the time from each engine's peak to the nearest time the other's pitch rate is within the peak pitch rate's tolerance of its own peak (the larger of the two), as a fraction of the vehicle's time scale; each sense's extreme is a channel",
    reason: "10 ms on the 1/6-scale model (time scale 0.263 s), 5 % of a 0.2 s landing: the same phase of the landing",
};

/// Time-aligned pitch-rate history, RMS of the difference.
pub const PITCH_RATE_RMS: Tolerance = Tolerance {
    channel: "pitch rate history RMS difference",
    quantity: "pitch_rate_history_rms_difference",
    limit: 0.10,
    difference_unit: OWN_VALUE,
    measured_as: "fraction of the first engine's peak magnitude (at least 2.5 % of the rate scale)",
    reason: "over the common span, the histories tell the same story when their RMS difference stays within a tenth of the peak",
};

/// Time-aligned pitch-rate history, largest difference.
pub const PITCH_RATE_MAX: Tolerance = Tolerance {
    channel: "pitch rate history largest difference",
    quantity: "pitch_rate_history_largest_difference",
    limit: 0.25,
    difference_unit: OWN_VALUE,
    measured_as: "fraction of the first engine's peak magnitude (at least 2.5 % of the rate scale)",
    reason: "a contact event a step earlier or later shifts a steep stretch of the history: a quarter of the peak allows that, not a different landing",
};

/// Peak vertical acceleration (2 ms window).
pub const PEAK_VERTICAL_ACCELERATION: Tolerance = Tolerance {
    channel: "peak vertical acceleration",
    quantity: "peak_vertical_acceleration",
    limit: 0.10,
    difference_unit: OWN_VALUE,
    measured_as: "fraction of the larger peak magnitude (at least 10 % of the acceleration scale, g), averaged over 0.75 % of the time scale",
    reason: "the load the vehicle feels; an average over 2 ms on the 1/6-scale model filters the multibody's contact spikes as an accelerometer would",
};

/// Minimum stability distance.
pub const MIN_STABILITY_DISTANCE: Tolerance = Tolerance {
    channel: "minimum stability distance",
    quantity: "min_stability_distance",
    limit: 0.014,
    difference_unit: FOOTPRINT_RADIUS,
    measured_as: "the difference of the minima, as a fraction of the vehicle's footprint radius",
    reason: "9.5 mm of margin on the 1/6-scale model's 0.68 m footprint radius (5.7 cm at full scale): finer than the footpad's own size",
};

/// Overturning velocity (both engines unstable).
pub const OVERTURN_VELOCITY: Tolerance = Tolerance {
    channel: "overturn velocity",
    quantity: "overturn_velocity",
    limit: 0.019,
    difference_unit: VELOCITY_SCALE,
    measured_as: "the difference of the velocities at the crossing, as a fraction of the vehicle's velocity scale",
    reason: "the velocity across the wall at the crossing; 4.9 cm/s on the 1/6-scale model (velocity scale 2.58 m/s), the scale of the report's boundary-search tolerance",
};

/// Energy dissipated per mechanism.
pub const ENERGY: Tolerance = Tolerance {
    channel: "energy",
    quantity: "energy",
    limit: 0.05,
    difference_unit: OWN_VALUE,
    measured_as: "fraction of the first engine's touchdown kinetic energy",
    reason: "where the touchdown energy goes; 5 % of it per mechanism separates a shifted share from rounding",
};

/// Struts past their capacity: how far each went onto its end stop.
pub const PAST_CAPACITY: Tolerance = Tolerance {
    channel: "struts past capacity",
    quantity: "past_capacity",
    limit: 0.01,
    difference_unit: OWN_VALUE,
    measured_as: "the largest difference over the struts of the stroke past the capacity, as a fraction of the capacity (`a` and `b` count the struts past it)",
    reason: "a strut past its capacity is on its end stop, whose law is an estimate; the stop is stiff enough that 1 % of the capacity past the end carries 15-40 times the last crush load on the 1/6 model, so 1 % separates a touch of the stop from a different landing",
};

/// Every tolerance, for the documentation and the reports.
pub const TOLERANCES: [Tolerance; 11] = [
    PRIMARY_STROKE,
    SECONDARY_STROKE,
    PEAK_PITCH_RATE,
    PEAK_PITCH_RATE_TIME,
    PITCH_RATE_RMS,
    PITCH_RATE_MAX,
    PEAK_VERTICAL_ACCELERATION,
    MIN_STABILITY_DISTANCE,
    OVERTURN_VELOCITY,
    PAST_CAPACITY,
    ENERGY,
];

/// Which strut of a leg a channel is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Strut {
    /// The primary strut.
    #[serde(rename = "primary")]
    Primary,
    /// The secondary strut from B3 (the report's 3-1; `sec31` in history.csv).
    #[serde(rename = "sec31")]
    Secondary31,
    /// The secondary strut from B4 (the report's 4-1; `sec41` in history.csv).
    #[serde(rename = "sec41")]
    Secondary41,
}

impl Strut {
    /// The strut as the text reports name it.
    pub fn label(self) -> &'static str {
        match self {
            Strut::Primary => "primary",
            Strut::Secondary31 => "3-1",
            Strut::Secondary41 => "4-1",
        }
    }
}

/// The sense of a pitch-rate extreme: each sense's extreme is a channel of its own, so that a
/// landing that rocks with two swings of nearly one magnitude is compared swing by swing, not
/// by which of the two happened to be the larger (docs/engines.md, "Channels and tolerances").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Sense {
    /// The largest pitch rate (≥ 0; `max_pitch_rate_rad_s` of the summary).
    Positive,
    /// The smallest pitch rate (≤ 0; `min_pitch_rate_rad_s` of the summary).
    Negative,
}

impl Sense {
    /// The sense as the text reports name it.
    pub fn label(self) -> &'static str {
        match self {
            Sense::Positive => "positive",
            Sense::Negative => "negative",
        }
    }

    /// The summary's extreme of the pitch rate in this sense and its time, (rad/s, s).
    fn extreme(self, s: &touchdown_record::Summary) -> (f64, f64) {
        match self {
            Sense::Positive => (s.max_pitch_rate_rad_s, s.max_pitch_rate_time_s),
            Sense::Negative => (s.min_pitch_rate_rad_s, s.min_pitch_rate_time_s),
        }
    }

    /// +1 or −1: the pitch rate times it is the rate in this sense.
    fn sign(self) -> f64 {
        match self {
            Sense::Positive => 1.0,
            Sense::Negative => -1.0,
        }
    }
}

/// How far, s, time `t` is from the nearest state of `run`'s trace at which its pitch rate
/// lies within `band` (rad/s) of its extreme in `sense` (the summary's, at its own time
/// whether or not the trace holds that state). Only the states its summary measured count
/// (up to the crossing of an overturn).
fn from_near_peak(run: &EngineRun, sense: Sense, band: f64, t: f64) -> f64 {
    let s = &run.summary;
    let end = match (s.outcome, s.decision_time_s) {
        (Outcome::Unstable, Some(crossing)) => crossing,
        _ => f64::INFINITY,
    };
    let (extreme, at) = sense.extreme(s);
    let (trace, k) = (&run.trace, sense.sign());
    (trace.t.iter().zip(&trace.pitch_rate))
        .take_while(|(ti, _)| **ti <= end)
        .filter(|(_, q)| k * **q >= k * extreme - band)
        .fold((t - at).abs(), |d, (ti, _)| d.min((t - ti).abs()))
}

/// One channel of a pair comparison, identified by data: its quantity (the family of its
/// tolerance), and the leg, strut, energy account or sense it is about.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Channel {
    /// The quantity compared: the `quantity` of its [`Tolerance`].
    pub quantity: &'static str,
    /// The leg, numbered from 1 (stroke channels).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub leg: Option<usize>,
    /// The strut (stroke channels).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub strut: Option<Strut>,
    /// The energy account, as history.csv's column without `_j` (energy channels).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub account: Option<&'static str>,
    /// The sense of a pitch-rate extreme (the peak pitch rate channels).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sense: Option<Sense>,
    /// The SI unit of `a`, `b` and `absolute_difference`.
    pub unit: &'static str,
    /// The first engine's value (left out of the history channels, which compare two time
    /// series).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub a: Option<f64>,
    /// The second engine's value (left out of the history channels).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub b: Option<f64>,
    /// How far apart the engines are, in `unit`: |a − b|, or for a history channel the RMS or
    /// the largest difference of the time-aligned histories.
    pub absolute_difference: f64,
    /// The difference as the tolerance measures it, in `difference_unit`.
    pub difference: f64,
    /// What `difference` and `tolerance` are ratios to: `fraction` (of the channel's own
    /// value), `footprint_radius`, `time_scale` or `velocity_scale` (the vehicle's scales).
    pub difference_unit: &'static str,
    /// The tolerance's limit, in `difference_unit`.
    pub tolerance: f64,
    /// Smallest and largest difference between a member of the first engine's rounding
    /// ensemble and one of the second's ([`crate::rounding`]), in `difference_unit`.
    pub ensemble_difference: [f64; 2],
    /// Smallest and largest value of the first engine over its ensemble, in `unit` (left out
    /// of the history channels).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub a_range: Option<[f64; 2]>,
    /// Smallest and largest value of the second engine over its ensemble, in `unit` (left out
    /// of the history channels).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub b_range: Option<[f64; 2]>,
    /// Largest difference between two members of the first engine's ensemble, then of the
    /// second's, in `difference_unit`: how far rounding alone moves the channel.
    pub rounding_spread: [f64; 2],
    /// The difference against the tolerance over the ensemble.
    pub verdict: Verdict,
}

/// A channel's or a pair's verdict.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Verdict {
    /// Within the tolerance on every pair of ensemble members.
    Pass,
    /// Beyond the tolerance on every pair of ensemble members.
    Fail,
    /// Not determined at this precision: a change of the order of rounding flips the verdict,
    /// or moves the channel on one engine by more than its tolerance.
    NotDetermined,
}

impl Verdict {
    /// As the text reports write it.
    pub fn label(self) -> &'static str {
        match self {
            Verdict::Pass => "pass",
            Verdict::Fail => "FAIL",
            Verdict::NotDetermined => "not determined",
        }
    }
}

/// The unit of a channel that counts struts (past their capacity): its values are whole
/// numbers.
const STRUT_COUNT: &str = "struts";

impl Channel {
    /// What the channel is about: its quantity, leg, strut, energy account and sense.
    pub(crate) fn key(&self) -> Key {
        (
            self.quantity,
            self.leg,
            self.strut,
            self.account,
            self.sense,
        )
    }

    /// Whether `a`, `b` and `absolute_difference` count struts rather than measure a quantity
    /// (the text reports print them as whole numbers).
    pub fn counts(&self) -> bool {
        self.unit == STRUT_COUNT
    }

    /// The channel as the text reports name it ("primary stroke leg 1", "secondary stroke leg
    /// 2 3-1", "energy: viscous", "peak pitch rate, negative").
    pub fn name(&self) -> String {
        let family = TOLERANCES
            .iter()
            .find(|t| t.quantity == self.quantity)
            .map_or(self.quantity, |t| t.channel);
        match (self.leg, self.strut, self.account, self.sense) {
            (Some(leg), Some(Strut::Primary), _, _) => format!("{family} leg {leg}"),
            (Some(leg), Some(strut), _, _) => format!("{family} leg {leg} {}", strut.label()),
            (_, _, Some(account), _) => format!("{family}: {}", account.replace('_', " ")),
            (_, _, _, Some(sense)) => format!("{family}, {}", sense.label()),
            _ => family.to_string(),
        }
    }
}

/// Two engines on one landing.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PairComparison {
    /// First engine (the reference of the relative channels).
    pub a: Engine,
    /// Second engine.
    pub b: Engine,
    /// The first engine's outcome.
    pub outcome_a: Outcome,
    /// The second engine's outcome.
    pub outcome_b: Outcome,
    /// Whether the outcomes agree.
    pub outcome_agrees: bool,
    /// Whether each engine lands with one outcome over its rounding ensemble.
    pub outcome_determined: bool,
    /// Every channel.
    pub channels: Vec<Channel>,
    /// The index in `channels` of the channel furthest beyond (or nearest to) its tolerance,
    /// a failing one first; left out when the outcomes disagree (the outcome is then the
    /// worst).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub worst_channel: Option<usize>,
    /// A fail if the outcomes disagree on every member or a channel fails; a pass if they
    /// agree on every member and every channel passes; not determined otherwise.
    pub verdict: Verdict,
}

impl PairComparison {
    /// The worst, as the text reports name it: a channel, or "outcome".
    pub fn worst(&self) -> String {
        match self.worst_channel {
            Some(i) => self.channels[i].name(),
            None => "outcome".into(),
        }
    }
}

/// Peak pitch rate below which a landing does not pitch, as a fraction of the vehicle's rate
/// scale: 0.00095 rad/s (0.05 °/s) on the 1/6-scale model, where a symmetric drop's solver
/// noise is 2e-5 rad/s in rapier (whose contact solver is not symmetric).
pub const NO_PITCH: f64 = 2.5e-4;

/// What a landing's channels are judged against: the vehicle's own scales and every channel
/// family's tolerance, the testbench's ([`TOLERANCES`]) or the one the scenario sets
/// (`[comparison]`).
#[derive(Debug, Clone, PartialEq)]
pub struct Basis {
    /// The vehicle's scales.
    pub scales: Scales,
    /// Every channel family's tolerance, in the order of [`TOLERANCES`].
    pub tolerances: [Tolerance; 11],
    /// Leg i's mirror image is leg `mirror[i]` (numbered from 0), its secondaries exchanged,
    /// when the landing is its own mirror image (`touchdown_scenario::mirror::self_mirror`):
    /// each leg's strokes are then landed twice ([`crate::rounding`]).
    pub mirror: Option<Vec<usize>>,
}

impl Basis {
    /// The basis of the scenario `sc`: its scales, and the tolerances with those it sets.
    pub fn of(sc: &Scenario) -> Result<Basis, ScenarioError> {
        let mut tolerances = TOLERANCES;
        for (quantity, limit) in sc.comparison.set() {
            for t in tolerances.iter_mut().filter(|t| t.quantity == quantity) {
                t.limit = limit;
            }
        }
        Ok(Basis {
            scales: Scales::of(sc)?,
            tolerances,
            mirror: touchdown_scenario::mirror::self_mirror(sc),
        })
    }

    /// The tolerance of the channel family `family` on this landing.
    fn tolerance(&self, family: &Tolerance) -> Tolerance {
        (self.tolerances.iter())
            .find(|t| t.quantity == family.quantity)
            .copied()
            .unwrap_or(*family)
    }

    /// The window the vertical accelerations are averaged over, s: [`ACCELERATION_WINDOW`] of
    /// the time scale.
    pub fn acceleration_window_s(&self) -> f64 {
        ACCELERATION_WINDOW * self.scales.time_s
    }

    /// The rate scale 1/[`Scales::time_s`], rad/s.
    fn rate(&self) -> f64 {
        1.0 / self.scales.time_s
    }
}

fn relative(a: f64, b: f64, floor: f64) -> f64 {
    (a - b).abs() / a.abs().max(b.abs()).max(floor)
}

/// What a channel is about: its quantity, leg, strut, energy account and sense.
pub(crate) type Key = (
    &'static str,
    Option<usize>,
    Option<Strut>,
    Option<&'static str>,
    Option<Sense>,
);

/// What a channel is about: its leg, strut, energy account or sense.
#[derive(Default)]
struct About {
    leg: Option<usize>,
    strut: Option<Strut>,
    account: Option<&'static str>,
    sense: Option<Sense>,
}

/// A channel of two values `a` and `b` (`unit`), or of a history difference when they are
/// `None`: `absolute` apart, `difference` as the tolerance `t` measures it.
fn channel(
    about: About,
    unit: &'static str,
    values: Option<(f64, f64)>,
    absolute: f64,
    difference: f64,
    t: &Tolerance,
) -> Channel {
    Channel {
        quantity: t.quantity,
        leg: about.leg,
        strut: about.strut,
        account: about.account,
        sense: about.sense,
        unit,
        a: values.map(|v| v.0),
        b: values.map(|v| v.1),
        absolute_difference: absolute,
        difference,
        difference_unit: t.difference_unit,
        tolerance: t.limit,
        ensemble_difference: [difference; 2],
        a_range: values.map(|v| [v.0; 2]),
        b_range: values.map(|v| [v.1; 2]),
        rounding_spread: [0.0; 2],
        verdict: if difference <= t.limit {
            Verdict::Pass
        } else {
            Verdict::Fail
        },
    }
}

/// A channel of two values `x` and `y` (`unit`), their difference measured by `difference`.
fn values(
    about: About,
    unit: &'static str,
    (x, y): (f64, f64),
    difference: f64,
    t: &Tolerance,
) -> Channel {
    channel(about, unit, Some((x, y)), (x - y).abs(), difference, t)
}

/// Time-aligned pitch-rate differences over the common span: RMS and largest, rad/s (`b`
/// interpolated at `a`'s times).
pub(crate) fn pitch_rate_differences(a: &Trace, b: &Trace) -> (f64, f64) {
    let end = a.end().min(b.end());
    let (mut sum, mut n, mut max) = (0.0, 0usize, 0.0f64);
    for (t, q) in a.t.iter().zip(&a.pitch_rate) {
        if *t > end {
            break;
        }
        let d = q - b.at(&b.pitch_rate, *t);
        sum += d * d;
        n += 1;
        max = max.max(d.abs());
    }
    ((sum / n.max(1) as f64).sqrt(), max)
}

/// The largest difference over the struts of the stroke past the capacity, as a fraction of
/// the capacity (zero for a strut within its capacity on both engines).
fn past_capacity_difference(a: &touchdown_record::Summary, b: &touchdown_record::Summary) -> f64 {
    let past = |s: &touchdown_record::Summary, strut: &str| {
        s.past_capacity
            .iter()
            .find(|p| p.strut == strut)
            .map_or(0.0, |p| p.stroke_of_capacity - 1.0)
    };
    a.past_capacity
        .iter()
        .chain(&b.past_capacity)
        .map(|p| (past(a, &p.strut) - past(b, &p.strut)).abs())
        .fold(0.0, f64::max)
}

/// The stroke channels (each leg's primary, then each leg's secondaries) of two summaries of
/// the same landing, judged against `basis`: the first of [`channels`].
pub(crate) fn stroke_channels(
    sa: &touchdown_record::Summary,
    sb: &touchdown_record::Summary,
    basis: &Basis,
) -> Vec<Channel> {
    let tolerance = |family: &Tolerance| basis.tolerance(family);
    let caps = &sa.strut_capacity;
    let primary_floor = PRIMARY_STROKE_FLOOR * caps.primary.stroke_m;
    let secondary_floor = SECONDARY_STROKE_FLOOR
        * (caps.secondary_compression.stroke_m).min(caps.secondary_tension.stroke_m);
    let mut channels = Vec::new();
    for (i, (x, y)) in sa
        .max_primary_stroke_m
        .iter()
        .zip(&sb.max_primary_stroke_m)
        .enumerate()
    {
        let about = About {
            leg: Some(i + 1),
            strut: Some(Strut::Primary),
            ..About::default()
        };
        let d = relative(*x, *y, primary_floor);
        channels.push(values(about, "m", (*x, *y), d, &tolerance(&PRIMARY_STROKE)));
    }
    let secondary = |s: &touchdown_record::Summary, i: usize, j: usize| {
        s.max_secondary_compression_m[i][j].max(s.max_secondary_tension_m[i][j])
    };
    for i in 0..sa.max_primary_stroke_m.len() {
        for (j, strut) in [Strut::Secondary31, Strut::Secondary41]
            .into_iter()
            .enumerate()
        {
            let (x, y) = (secondary(sa, i, j), secondary(sb, i, j));
            let about = About {
                leg: Some(i + 1),
                strut: Some(strut),
                ..About::default()
            };
            let d = relative(x, y, secondary_floor);
            channels.push(values(about, "m", (x, y), d, &tolerance(&SECONDARY_STROKE)));
        }
    }
    channels
}

/// Every channel of two engines' runs of the same landing, judged on these two runs alone
/// against the first run's [`Basis`] (both are of one scenario).
pub(crate) fn channels(a: &EngineRun, b: &EngineRun) -> Vec<Channel> {
    let (sa, sb) = (&a.summary, &b.summary);
    let basis = &a.basis;
    let tolerance = |family: &Tolerance| basis.tolerance(family);
    let rate_floor = PITCH_RATE_FLOOR * basis.rate();
    let mut channels = stroke_channels(sa, sb, basis);
    // Each sense's extreme against the larger peak of either engine in either sense: the
    // landing's pitching scale, so that a small swing back is judged by what it does to the
    // landing, not by its own size.
    let (qa, qb) = (sa.peak_pitch_rate_rad_s, sb.peak_pitch_rate_rad_s);
    let peak = qa.abs().max(qb.abs()).max(rate_floor);
    // A sense the landing does not pitch in (a symmetric drop either way) has an extreme of
    // solver noise whose time means nothing: it counts as 0.
    let no_pitch = NO_PITCH * basis.rate();
    let time_of = |(q, t): (f64, f64)| if q.abs() < no_pitch { 0.0 } else { t };
    let (rate, time) = (
        tolerance(&PEAK_PITCH_RATE),
        tolerance(&PEAK_PITCH_RATE_TIME),
    );
    for sense in [Sense::Positive, Sense::Negative] {
        let about = || About {
            sense: Some(sense),
            ..About::default()
        };
        let (ea, eb) = (sense.extreme(sa), sense.extreme(sb));
        let d = (ea.0 - eb.0).abs() / peak;
        channels.push(values(about(), "rad/s", (ea.0, eb.0), d, &rate));
        // The times of the extremes, each against the other engine's times within the rate's
        // tolerance of its own extreme: on a plateau of the pitch rate (a vehicle rocking at
        // one rate for a while) the time of its exact extreme is decided by ripples far
        // below the tolerance, and these times are the ones the rate cannot tell apart.
        let (ta, tb) = (time_of(ea), time_of(eb));
        let apart = if ta == 0.0 || tb == 0.0 {
            (ta - tb).abs()
        } else {
            let band = rate.limit * peak;
            from_near_peak(b, sense, band, ta).max(from_near_peak(a, sense, band, tb))
        };
        let d = apart / basis.scales.time_s;
        channels.push(channel(about(), "s", Some((ta, tb)), apart, d, &time));
    }
    let (rms, max) = pitch_rate_differences(&a.trace, &b.trace);
    let scale = qa.abs().max(rate_floor);
    for (absolute, t) in [
        (rms, tolerance(&PITCH_RATE_RMS)),
        (max, tolerance(&PITCH_RATE_MAX)),
    ] {
        channels.push(channel(
            About::default(),
            "rad/s",
            None,
            absolute,
            absolute / scale,
            &t,
        ));
    }
    let (ga, gb) = (
        a.trace.peak_vertical_acceleration().0,
        b.trace.peak_vertical_acceleration().0,
    );
    let d = relative(ga, gb, ACCELERATION_FLOOR * basis.scales.acceleration_m_s2);
    channels.push(values(
        About::default(),
        "m/s^2",
        (ga, gb),
        d,
        &tolerance(&PEAK_VERTICAL_ACCELERATION),
    ));
    let (da, db) = (sa.min_stability_distance_m, sb.min_stability_distance_m);
    let d = (da - db).abs() / basis.scales.length_m;
    channels.push(values(
        About::default(),
        "m",
        (da, db),
        d,
        &tolerance(&MIN_STABILITY_DISTANCE),
    ));
    if let (Some(va), Some(vb)) = (sa.overturn_velocity_m_s, sb.overturn_velocity_m_s) {
        let d = (va - vb).abs() / basis.scales.velocity_m_s;
        channels.push(values(
            About::default(),
            "m/s",
            (va, vb),
            d,
            &tolerance(&OVERTURN_VELOCITY),
        ));
    }
    let (past_a, past_b) = (sa.past_capacity.len(), sb.past_capacity.len());
    let d = past_capacity_difference(sa, sb);
    channels.push(values(
        About::default(),
        STRUT_COUNT,
        (past_a as f64, past_b as f64),
        d,
        &tolerance(&PAST_CAPACITY),
    ));
    let (ea, eb) = (&sa.energy, &sb.energy);
    let ke0 = ea.kinetic_initial_j.max(f64::MIN_POSITIVE);
    let mut accounts = vec![
        (
            "honeycomb_dissipated",
            ea.honeycomb_dissipated_j,
            eb.honeycomb_dissipated_j,
        ),
        ("viscous", ea.viscous_j, eb.viscous_j),
        (
            "bearing_friction",
            ea.bearing_friction_j,
            eb.bearing_friction_j,
        ),
        (
            "sliding_friction",
            ea.sliding_friction_j,
            eb.sliding_friction_j,
        ),
        ("contact_events", ea.contact_events_j, eb.contact_events_j),
    ];
    // The optional mechanisms' account only where a scene has them.
    if ea.mechanisms_j != 0.0 || eb.mechanisms_j != 0.0 {
        accounts.push(("mechanisms", ea.mechanisms_j, eb.mechanisms_j));
    }
    let energy = tolerance(&ENERGY);
    for (account, x, y) in accounts {
        let about = About {
            account: Some(account),
            ..About::default()
        };
        channels.push(values(about, "J", (x, y), (x - y).abs() / ke0, &energy));
    }
    channels
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::run;
    use std::path::{Path, PathBuf};
    use touchdown_record::Summary;

    fn scenario(name: &str) -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../scenarios")
            .join(name)
    }

    /// The similarity ratios of length, mass and time of the twin in these tests: the 1/6-scale
    /// model at full scale on the Moon.
    const L: f64 = 6.0;
    const M: f64 = 216.0;
    const T: f64 = 6.0;

    /// The factor a quantity of the summary scales by on the twin, from the unit its field's
    /// name (or the nearest enclosing one) ends with.
    fn factor(name: &str) -> Option<f64> {
        [
            ("_m_s2", L / (T * T)),
            ("_rad_s", 1.0 / T),
            ("_n_m", M / (T * T)),
            ("_m_s", L / T),
            ("_j", M * L * L / (T * T)),
            ("_n", M * L / (T * T)),
            ("_m", L),
            ("_s", T),
        ]
        .into_iter()
        .find(|(suffix, _)| name.ends_with(suffix))
        .map(|(_, f)| f)
    }

    fn scaled_value(v: &mut serde_json::Value, f: Option<f64>) {
        match v {
            serde_json::Value::Object(map) => {
                for (k, x) in map.iter_mut() {
                    scaled_value(x, factor(k).or(f));
                }
            }
            serde_json::Value::Array(xs) => xs.iter_mut().for_each(|x| scaled_value(x, f)),
            serde_json::Value::Number(n) => {
                if let (Some(f), Some(x), false) = (f, n.as_f64(), n.is_u64()) {
                    *v = serde_json::json!(x * f);
                }
            }
            _ => {}
        }
    }

    /// `run` as the twin would land if it landed exactly as `run` does: every value in the
    /// similarity's ratios, judged against the twin's `basis`.
    fn twin_of(run: &EngineRun, basis: &Basis) -> EngineRun {
        let mut summary = serde_json::to_value(&run.summary).unwrap();
        scaled_value(&mut summary, None);
        let summary: Summary = serde_json::from_value(summary).unwrap();
        let r = &run.trace;
        let trace = Trace {
            t: r.t.iter().map(|t| t * T).collect(),
            vz: r.vz.iter().map(|v| v * L / T).collect(),
            pitch_rate: r.pitch_rate.iter().map(|q| q / T).collect(),
            attitude: r.attitude.clone(),
            primary_stroke: r.primary_stroke.iter().map(|x| x * L).collect(),
            legs: r.legs,
            acceleration_window_s: r.acceleration_window_s * T,
        };
        EngineRun {
            summary,
            trace,
            basis: basis.clone(),
            perturbed: Vec::new(),
            recording: None,
            engine: run.engine,
        }
    }

    #[test]
    fn a_similar_vehicle_is_judged_alike_channel_by_channel() {
        // Two different landings of the figure 25-26 configuration (one unstable), and the
        // same two as the Froude twin would land them: every channel measures the same
        // dimensionless difference against the same tolerance.
        let path = scenario("fig-25-26.toml");
        let load = |over: &[(&str, f64)]| Scenario::load_with(&path, over).unwrap();
        let twin = [
            ("similarity.length", L),
            ("similarity.mass", M),
            ("similarity.time", T),
        ];
        let basis = Basis::of(&load(&twin)).unwrap();
        for other in [
            ("touchdown.vertical_velocity", -9.0),
            ("touchdown.horizontal_velocity[1]", 27.0),
        ] {
            let a = run(Engine::Core, &path, &load(&[])).unwrap();
            let b = run(Engine::Core, &path, &load(&[other])).unwrap();
            let (a2, b2) = (twin_of(&a, &basis), twin_of(&b, &basis));
            let (original, similar) = (channels(&a, &b), channels(&a2, &b2));
            assert_eq!(original.len(), similar.len());
            let mut failing = 0;
            for (x, y) in original.iter().zip(&similar) {
                assert_eq!(x.key(), y.key());
                let close = (x.difference - y.difference).abs() <= 1e-9 * x.difference.max(1e-12);
                assert!(
                    close,
                    "{}: {} against {}",
                    x.name(),
                    x.difference,
                    y.difference
                );
                assert_eq!(x.tolerance, y.tolerance, "{}", x.name());
                assert_eq!(x.verdict, y.verdict, "{}", x.name());
                failing += usize::from(x.verdict == Verdict::Fail);
            }
            // the pairs are different landings: their comparison fails somewhere
            assert!(failing > 0, "{other:?}");
        }
    }

    /// `run` with its pitch rate replaced by `q(t)` at times 0 to 0.2 s, 0.1 ms apart (the
    /// summary's extremes and peak set from them as the engines measure them).
    fn pitching(run: &EngineRun, q: impl Fn(f64) -> f64) -> EngineRun {
        let mut run = run.clone();
        let t: Vec<f64> = (0..=2000).map(|i| i as f64 * 1e-4).collect();
        let mut extremes =
            touchdown_record::Extremes::new(1, touchdown_record::StrutCapacities::default());
        for ti in &t {
            extremes.update_pitch_rate(*ti, q(*ti));
        }
        let s = &mut run.summary;
        let [low, high] = extremes.pitch_rate_extremes();
        (s.min_pitch_rate_rad_s, s.min_pitch_rate_time_s) = low;
        (s.max_pitch_rate_rad_s, s.max_pitch_rate_time_s) = high;
        (s.peak_pitch_rate_rad_s, s.peak_pitch_rate_time_s) = extremes.peak_pitch_rate();
        run.trace = Trace {
            pitch_rate: t.iter().map(|ti| q(*ti)).collect(),
            vz: vec![0.0; t.len()],
            attitude: vec![[0.0; 3]; t.len()],
            primary_stroke: vec![0.0; t.len()],
            legs: 1,
            t,
            ..run.trace
        };
        run
    }

    /// A landing that rocks one way on a plateau of its pitch rate (rippled by 1 %) and swings
    /// back as far: two engines whose swings agree within 2 % pass on the pitch rate in either
    /// sense and on when each extreme came, although the larger swing is nose-down on one
    /// and nose-up on the other and their plateaus' ripples put their exact extremes 25 ms
    /// apart (2.5 times the time tolerance on this vehicle); a swing back 20 % stronger fails.
    #[test]
    fn a_rocking_landing_is_judged_swing_by_swing() {
        let path = scenario("table-i-2-2-vv4.toml");
        let real = run(Engine::Core, &path, &Scenario::load(&path).unwrap()).unwrap();
        let plateau = |t: f64| (-((t - 0.06) / 0.05).powi(8)).exp();
        let swing = |t: f64| (-((t - 0.14) / 0.01).powi(2)).exp();
        let rocking = |ripple_at: f64, back: f64| {
            move |t: f64| {
                let ripple =
                    1.0 + 0.01 * (2.0 * std::f64::consts::PI * (t - ripple_at) / 0.05).cos();
                -plateau(t) * ripple + back * swing(t)
            }
        };
        let a = pitching(&real, rocking(0.06, 1.0));
        let b = pitching(&real, rocking(0.035, 1.02));
        assert!(a.summary.peak_pitch_rate_rad_s < 0.0 && b.summary.peak_pitch_rate_rad_s > 0.0);
        let time_apart = (a.summary.min_pitch_rate_time_s - b.summary.min_pitch_rate_time_s).abs();
        assert!(time_apart > 2.0 * PEAK_PITCH_RATE_TIME.limit * a.basis.scales.time_s);
        let verdicts = |b: &EngineRun| {
            let set = channels(&a, b);
            let of = |quantity: &str, sense| {
                let c = set
                    .iter()
                    .find(|c| c.quantity == quantity && c.sense == Some(sense));
                c.unwrap().verdict
            };
            [Sense::Positive, Sense::Negative]
                .map(|s| [of("peak_pitch_rate", s), of("peak_pitch_rate_time", s)])
        };
        assert_eq!(verdicts(&b), [[Verdict::Pass; 2]; 2]);
        let stronger = pitching(&real, rocking(0.035, 1.2));
        assert_eq!(
            verdicts(&stronger),
            [[Verdict::Fail, Verdict::Pass], [Verdict::Pass; 2]]
        );
    }

    #[test]
    fn a_landing_sets_its_own_tolerances() {
        let path = scenario("fig-25-26.toml");
        let own = Scenario::load_with(
            &path,
            &[
                ("comparison.min_stability_distance", 0.5),
                ("comparison.primary_stroke", 0.2),
            ],
        )
        .unwrap();
        let basis = Basis::of(&own).unwrap();
        let limit = |t: &Tolerance| basis.tolerance(t).limit;
        assert_eq!(limit(&MIN_STABILITY_DISTANCE), 0.5);
        assert_eq!(limit(&PRIMARY_STROKE), 0.2);
        assert_eq!(limit(&SECONDARY_STROKE), SECONDARY_STROKE.limit);
        let e = Scenario::load_with(&path, &[("comparison.energy", -0.1)])
            .unwrap_err()
            .to_string();
        assert!(e.contains("comparison.energy"), "{e}");
    }
}
