//! Divergence of two engines on one landing, channel by channel, each against a tolerance
//! written down with its reason ([`TOLERANCES`]).

use crate::rounding::{own_spreads, Spread};
use crate::trace::Trace;
use crate::{Engine, EngineRun};
use serde::Serialize;
use touchdown_record::Outcome;

/// A channel's tolerance and why it is that.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tolerance {
    /// The channel family, as the text reports and docs/engines.md name it.
    pub channel: &'static str,
    /// The channel family's identifier: the `quantity` of its channels.
    pub quantity: &'static str,
    /// Largest difference that passes, in `difference_unit`.
    pub limit: f64,
    /// The unit of the difference and the limit: `fraction` (a ratio) or an SI unit.
    pub difference_unit: &'static str,
    /// How the difference is measured.
    pub measured_as: &'static str,
    /// Why this tolerance.
    pub reason: &'static str,
}

/// Primary strokes: relative difference of the maximum stroke, strokes under 10 mm measured
/// against 10 mm.
pub const PRIMARY_STROKE: Tolerance = Tolerance {
    channel: "primary stroke",
    quantity: "primary_stroke",
    limit: 0.05,
    difference_unit: "fraction",
    measured_as: "fraction of the larger maximum stroke (at least 10 mm)",
    reason: "the agreement asked of the rebuilds on the Table I primary strokes; below 10 mm a stroke is within the scatter of the drop tests' records",
};

/// Secondary strokes: relative difference of the maximum stroke (compression or tension), under
/// 5 mm measured against 5 mm.
pub const SECONDARY_STROKE: Tolerance = Tolerance {
    channel: "secondary stroke",
    quantity: "secondary_stroke",
    limit: 0.10,
    difference_unit: "fraction",
    measured_as: "fraction of the larger maximum stroke (at least 5 mm)",
    reason: "the agreement asked of the rebuilds on the Table I secondary strokes; secondaries are short and follow the gear's swing, so twice the primaries' tolerance",
};

/// Peak pitch rate.
pub const PEAK_PITCH_RATE: Tolerance = Tolerance {
    channel: "peak pitch rate",
    quantity: "peak_pitch_rate",
    limit: 0.05,
    difference_unit: "fraction",
    measured_as: "fraction of the larger peak magnitude (at least 0.1 rad/s)",
    reason: "the pitch rate drives the overturn; 5 % of its peak moves a stability boundary by about as much as the report's 0.05 ft/s search tolerance at 8 ft/s",
};

/// Time of the peak pitch rate.
pub const PEAK_PITCH_RATE_TIME: Tolerance = Tolerance {
    channel: "peak pitch rate time",
    quantity: "peak_pitch_rate_time",
    limit: 0.01,
    difference_unit: "s",
    measured_as: "the absolute difference of the times of the peaks",
    reason: "10 ms, 5 % of a 0.2 s landing: the same phase of the landing",
};

/// Time-aligned pitch-rate history, RMS of the difference.
pub const PITCH_RATE_RMS: Tolerance = Tolerance {
    channel: "pitch rate history RMS difference",
    quantity: "pitch_rate_history_rms_difference",
    limit: 0.10,
    difference_unit: "fraction",
    measured_as: "fraction of the first engine's peak magnitude",
    reason: "over the common span, the histories tell the same story when their RMS difference stays within a tenth of the peak",
};

/// Time-aligned pitch-rate history, largest difference.
pub const PITCH_RATE_MAX: Tolerance = Tolerance {
    channel: "pitch rate history largest difference",
    quantity: "pitch_rate_history_largest_difference",
    limit: 0.25,
    difference_unit: "fraction",
    measured_as: "fraction of the first engine's peak magnitude",
    reason: "a contact event a step earlier or later shifts a steep stretch of the history: a quarter of the peak allows that, not a different landing",
};

/// Peak vertical acceleration (2 ms window).
pub const PEAK_VERTICAL_ACCELERATION: Tolerance = Tolerance {
    channel: "peak vertical acceleration",
    quantity: "peak_vertical_acceleration",
    limit: 0.10,
    difference_unit: "fraction",
    measured_as: "fraction of the larger peak magnitude (at least 1 m/s²), 2 ms window",
    reason: "the load the vehicle feels; a 2 ms average filters the multibody's contact spikes as an accelerometer would",
};

/// Minimum stability distance.
pub const MIN_STABILITY_DISTANCE: Tolerance = Tolerance {
    channel: "minimum stability distance",
    quantity: "min_stability_distance",
    limit: 0.01,
    difference_unit: "m",
    measured_as: "the absolute difference of the minima",
    reason: "1 cm of margin at 1/6 scale (6 cm full scale): finer than the footpad's own size",
};

/// Overturning velocity (both engines unstable).
pub const OVERTURN_VELOCITY: Tolerance = Tolerance {
    channel: "overturn velocity",
    quantity: "overturn_velocity",
    limit: 0.05,
    difference_unit: "m/s",
    measured_as: "the absolute difference of the velocities at the crossing",
    reason: "the velocity across the wall at the crossing; 5 cm/s is the scale of the report's boundary-search tolerance",
};

/// Energy dissipated per mechanism.
pub const ENERGY: Tolerance = Tolerance {
    channel: "energy",
    quantity: "energy",
    limit: 0.05,
    difference_unit: "fraction",
    measured_as: "fraction of the first engine's touchdown kinetic energy",
    reason: "where the touchdown energy goes; 5 % of it per mechanism separates a shifted share from rounding",
};

/// Struts past their capacity: how far each went onto its end stop.
pub const PAST_CAPACITY: Tolerance = Tolerance {
    channel: "struts past capacity",
    quantity: "past_capacity",
    limit: 0.01,
    difference_unit: "fraction",
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

/// One channel of a pair comparison, identified by data: its quantity (the family of its
/// tolerance), and the leg, strut or energy account it is about.
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
    /// The unit of `difference` and `tolerance`: `fraction` or an SI unit.
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
    /// What the channel is about: its quantity, leg, strut and energy account.
    pub(crate) fn key(
        &self,
    ) -> (
        &'static str,
        Option<usize>,
        Option<Strut>,
        Option<&'static str>,
    ) {
        (self.quantity, self.leg, self.strut, self.account)
    }

    /// Whether `a`, `b` and `absolute_difference` count struts rather than measure a quantity
    /// (the text reports print them as whole numbers).
    pub fn counts(&self) -> bool {
        self.unit == STRUT_COUNT
    }

    /// The channel as the text reports name it ("primary stroke leg 1", "secondary stroke leg
    /// 2 3-1", "energy: viscous").
    pub fn name(&self) -> String {
        let family = TOLERANCES
            .iter()
            .find(|t| t.quantity == self.quantity)
            .map_or(self.quantity, |t| t.channel);
        match (self.leg, self.strut, self.account) {
            (Some(leg), Some(Strut::Primary), _) => format!("{family} leg {leg}"),
            (Some(leg), Some(strut), _) => format!("{family} leg {leg} {}", strut.label()),
            (_, _, Some(account)) => format!("{family}: {}", account.replace('_', " ")),
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

/// Peak pitch rate below which a landing does not pitch, rad/s (0.06 °/s): a symmetric drop's
/// solver noise (2e-5 rad/s in rapier, whose contact solver is not symmetric).
pub const NO_PITCH: f64 = 1.0e-3;

fn relative(a: f64, b: f64, floor: f64) -> f64 {
    (a - b).abs() / a.abs().max(b.abs()).max(floor)
}

/// What a channel is about: its leg, strut or energy account.
#[derive(Default)]
struct About {
    leg: Option<usize>,
    strut: Option<Strut>,
    account: Option<&'static str>,
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

/// Every channel of two engines' runs of the same landing, judged on these two runs alone.
pub(crate) fn channels(a: &EngineRun, b: &EngineRun) -> Vec<Channel> {
    let (sa, sb) = (&a.summary, &b.summary);
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
        let d = relative(*x, *y, 0.010);
        channels.push(values(about, "m", (*x, *y), d, &PRIMARY_STROKE));
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
            let d = relative(x, y, 0.005);
            channels.push(values(about, "m", (x, y), d, &SECONDARY_STROKE));
        }
    }
    let (qa, qb) = (sa.peak_pitch_rate_rad_s, sb.peak_pitch_rate_rad_s);
    let d = relative(qa, qb, 0.1);
    channels.push(values(
        About::default(),
        "rad/s",
        (qa, qb),
        d,
        &PEAK_PITCH_RATE,
    ));
    // A landing that does not pitch (a symmetric drop) has a peak of solver noise whose time
    // means nothing: it counts as 0.
    let time_of = |q: f64, t: f64| if q.abs() < NO_PITCH { 0.0 } else { t };
    let (ta, tb) = (
        time_of(qa, sa.peak_pitch_rate_time_s),
        time_of(qb, sb.peak_pitch_rate_time_s),
    );
    let d = (ta - tb).abs();
    channels.push(values(
        About::default(),
        "s",
        (ta, tb),
        d,
        &PEAK_PITCH_RATE_TIME,
    ));
    let (rms, max) = pitch_rate_differences(&a.trace, &b.trace);
    let scale = qa.abs().max(0.1);
    for (absolute, t) in [(rms, &PITCH_RATE_RMS), (max, &PITCH_RATE_MAX)] {
        channels.push(channel(
            About::default(),
            "rad/s",
            None,
            absolute,
            absolute / scale,
            t,
        ));
    }
    let (ga, gb) = (
        a.trace.peak_vertical_acceleration().0,
        b.trace.peak_vertical_acceleration().0,
    );
    let d = relative(ga, gb, 1.0);
    channels.push(values(
        About::default(),
        "m/s^2",
        (ga, gb),
        d,
        &PEAK_VERTICAL_ACCELERATION,
    ));
    let (da, db) = (sa.min_stability_distance_m, sb.min_stability_distance_m);
    let d = (da - db).abs();
    channels.push(values(
        About::default(),
        "m",
        (da, db),
        d,
        &MIN_STABILITY_DISTANCE,
    ));
    if let (Some(va), Some(vb)) = (sa.overturn_velocity_m_s, sb.overturn_velocity_m_s) {
        let d = (va - vb).abs();
        channels.push(values(
            About::default(),
            "m/s",
            (va, vb),
            d,
            &OVERTURN_VELOCITY,
        ));
    }
    let (past_a, past_b) = (sa.past_capacity.len(), sb.past_capacity.len());
    let d = past_capacity_difference(sa, sb);
    channels.push(values(
        About::default(),
        STRUT_COUNT,
        (past_a as f64, past_b as f64),
        d,
        &PAST_CAPACITY,
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
    for (account, x, y) in accounts {
        let about = About {
            account: Some(account),
            ..About::default()
        };
        channels.push(values(about, "J", (x, y), (x - y).abs() / ke0, &ENERGY));
    }
    channels
}

/// Compares two engines' runs of the same landing, each with its rounding ensemble
/// ([`EngineRun::perturbed`]): a channel's verdict holds over every pair of members.
pub fn compare(a: &EngineRun, b: &EngineRun) -> PairComparison {
    let mut channels = channels(a, b);
    let own = [own_spreads(a), own_spreads(b)];
    let mut spreads: Vec<Spread> = channels
        .iter()
        .map(|c| Spread::of(c, [&own[0], &own[1]]))
        .collect();
    for (i, x) in a.members().iter().enumerate() {
        for (j, y) in b.members().iter().enumerate() {
            if i + j > 0 {
                let set = self::channels(x, y);
                for (c, s) in channels.iter().zip(&mut spreads) {
                    s.between(set.iter().find(|d| d.key() == c.key()));
                }
            }
        }
    }
    for (c, s) in channels.iter_mut().zip(&spreads) {
        c.ensemble_difference = s.between;
        [c.a_range, c.b_range] = s.values;
        c.rounding_spread = s.within;
        c.verdict = s.verdict(c.tolerance);
    }
    let (sa, sb) = (&a.summary, &b.summary);
    let outcome_agrees = sa.outcome == sb.outcome;
    let outcome_determined = a.outcome_determined() && b.outcome_determined();
    let worst_channel = if outcome_agrees {
        channels
            .iter()
            .enumerate()
            .max_by(|(_, x), (_, y)| {
                let failing = |c: &Channel| c.verdict == Verdict::Fail;
                (failing(x).cmp(&failing(y)))
                    .then((x.difference / x.tolerance).total_cmp(&(y.difference / y.tolerance)))
            })
            .map(|(i, _)| i)
    } else {
        None
    };
    let verdicts = channels.iter().map(|c| c.verdict);
    let verdict = if (outcome_determined && !outcome_agrees)
        || verdicts.clone().any(|v| v == Verdict::Fail)
    {
        Verdict::Fail
    } else if !outcome_determined || verdicts.clone().any(|v| v == Verdict::NotDetermined) {
        Verdict::NotDetermined
    } else {
        Verdict::Pass
    };
    PairComparison {
        a: a.engine,
        b: b.engine,
        outcome_a: sa.outcome,
        outcome_b: sb.outcome,
        outcome_agrees,
        outcome_determined,
        channels,
        worst_channel,
        verdict,
    }
}
