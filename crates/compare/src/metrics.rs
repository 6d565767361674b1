//! Divergence of two engines on one landing, channel by channel, each against a tolerance
//! written down with its reason ([`TOLERANCES`]).

use crate::trace::Trace;
use crate::{Engine, EngineRun};
use serde::Serialize;
use touchdown_record::Outcome;

/// A channel's tolerance and why it is that.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Tolerance {
    /// The channel family.
    pub channel: &'static str,
    /// Largest difference that passes, in `unit`.
    pub limit: f64,
    /// How the difference is measured.
    pub unit: &'static str,
    /// Why this tolerance.
    pub reason: &'static str,
}

/// Primary strokes: relative difference of the maximum stroke, strokes under 10 mm measured
/// against 10 mm.
pub const PRIMARY_STROKE: Tolerance = Tolerance {
    channel: "primary stroke",
    limit: 0.05,
    unit: "fraction of the larger maximum stroke (at least 10 mm)",
    reason: "the agreement asked of the rebuilds on the Table I primary strokes; below 10 mm a stroke is within the scatter of the drop tests' records",
};

/// Secondary strokes: relative difference of the maximum stroke (compression or tension), under
/// 5 mm measured against 5 mm.
pub const SECONDARY_STROKE: Tolerance = Tolerance {
    channel: "secondary stroke",
    limit: 0.10,
    unit: "fraction of the larger maximum stroke (at least 5 mm)",
    reason: "the agreement asked of the rebuilds on the Table I secondary strokes; secondaries are short and follow the gear's swing, so twice the primaries' tolerance",
};

/// Peak pitch rate.
pub const PEAK_PITCH_RATE: Tolerance = Tolerance {
    channel: "peak pitch rate",
    limit: 0.05,
    unit: "fraction of the larger peak magnitude (at least 0.1 rad/s)",
    reason: "the pitch rate drives the overturn; 5 % of its peak moves a stability boundary by about as much as the report's 0.05 ft/s search tolerance at 8 ft/s",
};

/// Time of the peak pitch rate.
pub const PEAK_PITCH_RATE_TIME: Tolerance = Tolerance {
    channel: "peak pitch rate time",
    limit: 0.01,
    unit: "s",
    reason: "10 ms, 5 % of a 0.2 s landing: the same phase of the landing",
};

/// Time-aligned pitch-rate history, RMS of the difference.
pub const PITCH_RATE_RMS: Tolerance = Tolerance {
    channel: "pitch rate history RMS difference",
    limit: 0.10,
    unit: "fraction of the first engine's peak magnitude",
    reason: "over the common span, the histories tell the same story when their RMS difference stays within a tenth of the peak",
};

/// Time-aligned pitch-rate history, largest difference.
pub const PITCH_RATE_MAX: Tolerance = Tolerance {
    channel: "pitch rate history largest difference",
    limit: 0.25,
    unit: "fraction of the first engine's peak magnitude",
    reason: "a contact event a step earlier or later shifts a steep stretch of the history: a quarter of the peak allows that, not a different landing",
};

/// Peak vertical acceleration (2 ms window).
pub const PEAK_VERTICAL_ACCELERATION: Tolerance = Tolerance {
    channel: "peak vertical acceleration",
    limit: 0.10,
    unit: "fraction of the larger peak magnitude (at least 1 m/s²), 2 ms window",
    reason: "the load the vehicle feels; a 2 ms average filters the multibody's contact spikes as an accelerometer would",
};

/// Minimum stability distance.
pub const MIN_STABILITY_DISTANCE: Tolerance = Tolerance {
    channel: "minimum stability distance",
    limit: 0.01,
    unit: "m",
    reason: "1 cm of margin at 1/6 scale (6 cm full scale): finer than the footpad's own size",
};

/// Overturning velocity (both engines unstable).
pub const OVERTURN_VELOCITY: Tolerance = Tolerance {
    channel: "overturn velocity",
    limit: 0.05,
    unit: "m/s",
    reason: "the velocity across the wall at the crossing; 5 cm/s is the scale of the report's boundary-search tolerance",
};

/// Energy dissipated per mechanism.
pub const ENERGY: Tolerance = Tolerance {
    channel: "energy",
    limit: 0.05,
    unit: "fraction of the first engine's touchdown kinetic energy",
    reason: "where the touchdown energy goes; 5 % of it per mechanism separates a shifted share from rounding",
};

/// Every tolerance, for the documentation and the reports.
pub const TOLERANCES: [Tolerance; 10] = [
    PRIMARY_STROKE,
    SECONDARY_STROKE,
    PEAK_PITCH_RATE,
    PEAK_PITCH_RATE_TIME,
    PITCH_RATE_RMS,
    PITCH_RATE_MAX,
    PEAK_VERTICAL_ACCELERATION,
    MIN_STABILITY_DISTANCE,
    OVERTURN_VELOCITY,
    ENERGY,
];

/// One channel of a pair comparison.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Channel {
    /// Channel name (with the leg or strut).
    pub name: String,
    /// The first engine's value (SI); for a history channel, the difference itself.
    pub a: f64,
    /// The second engine's value (SI); NaN (null in JSON) for a history channel.
    pub b: f64,
    /// The difference, measured as the tolerance says.
    pub difference: f64,
    /// The tolerance's limit.
    pub tolerance: f64,
    /// Whether the difference is within the tolerance.
    pub pass: bool,
}

/// Two engines on one landing.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PairComparison {
    /// First engine (the reference of the relative channels).
    pub a: Engine,
    /// Second engine.
    pub b: Engine,
    /// Outcomes of the two.
    pub outcome: (Outcome, Outcome),
    /// Whether the outcomes agree.
    pub outcome_agrees: bool,
    /// Every channel.
    pub channels: Vec<Channel>,
    /// The channel furthest beyond (or nearest to) its tolerance, or "outcome".
    pub worst: String,
    /// Whether the outcomes agree and every channel passes.
    pub pass: bool,
}

/// Peak pitch rate below which a landing does not pitch, rad/s (0.06 °/s): a symmetric drop's
/// solver noise (2e-5 rad/s in rapier, whose contact solver is not symmetric).
pub const NO_PITCH: f64 = 1.0e-3;

fn relative(a: f64, b: f64, floor: f64) -> f64 {
    (a - b).abs() / a.abs().max(b.abs()).max(floor)
}

fn channel(name: String, a: f64, b: f64, difference: f64, t: &Tolerance) -> Channel {
    Channel {
        name,
        a,
        b,
        difference,
        tolerance: t.limit,
        pass: difference <= t.limit,
    }
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

/// Compares two engines' runs of the same landing.
pub fn compare(a: &EngineRun, b: &EngineRun) -> PairComparison {
    let (sa, sb) = (&a.summary, &b.summary);
    let mut channels = Vec::new();
    for (i, (x, y)) in sa
        .max_primary_stroke_m
        .iter()
        .zip(&sb.max_primary_stroke_m)
        .enumerate()
    {
        channels.push(channel(
            format!("primary stroke leg {}", i + 1),
            *x,
            *y,
            relative(*x, *y, 0.010),
            &PRIMARY_STROKE,
        ));
    }
    let secondary = |s: &touchdown_record::Summary, i: usize, j: usize| {
        s.max_secondary_compression_m[i][j].max(s.max_secondary_tension_m[i][j])
    };
    for i in 0..sa.max_primary_stroke_m.len() {
        for (j, name) in ["3-1", "4-1"].into_iter().enumerate() {
            let (x, y) = (secondary(sa, i, j), secondary(sb, i, j));
            channels.push(channel(
                format!("secondary stroke leg {} {name}", i + 1),
                x,
                y,
                relative(x, y, 0.005),
                &SECONDARY_STROKE,
            ));
        }
    }
    let (qa, qb) = (sa.peak_pitch_rate_rad_s, sb.peak_pitch_rate_rad_s);
    channels.push(channel(
        "peak pitch rate".into(),
        qa,
        qb,
        relative(qa, qb, 0.1),
        &PEAK_PITCH_RATE,
    ));
    // A landing that does not pitch (a symmetric drop) has a peak of solver noise whose time
    // means nothing: it counts as 0.
    let time_of = |q: f64, t: f64| if q.abs() < NO_PITCH { 0.0 } else { t };
    let (ta, tb) = (
        time_of(qa, sa.peak_pitch_rate_time_s),
        time_of(qb, sb.peak_pitch_rate_time_s),
    );
    channels.push(channel(
        "peak pitch rate time".into(),
        ta,
        tb,
        (ta - tb).abs(),
        &PEAK_PITCH_RATE_TIME,
    ));
    let (rms, max) = pitch_rate_differences(&a.trace, &b.trace);
    let scale = qa.abs().max(0.1);
    // History channels: `a` holds the difference itself (rad/s), `b` is not applicable.
    channels.push(channel(
        "pitch rate history RMS difference".into(),
        rms,
        f64::NAN,
        rms / scale,
        &PITCH_RATE_RMS,
    ));
    channels.push(channel(
        "pitch rate history largest difference".into(),
        max,
        f64::NAN,
        max / scale,
        &PITCH_RATE_MAX,
    ));
    let (ga, gb) = (
        a.trace.peak_vertical_acceleration().0,
        b.trace.peak_vertical_acceleration().0,
    );
    channels.push(channel(
        "peak vertical acceleration".into(),
        ga,
        gb,
        relative(ga, gb, 1.0),
        &PEAK_VERTICAL_ACCELERATION,
    ));
    let (da, db) = (sa.min_stability_distance_m, sb.min_stability_distance_m);
    channels.push(channel(
        "minimum stability distance".into(),
        da,
        db,
        (da - db).abs(),
        &MIN_STABILITY_DISTANCE,
    ));
    if let (Some(va), Some(vb)) = (sa.overturn_velocity_m_s, sb.overturn_velocity_m_s) {
        channels.push(channel(
            "overturn velocity".into(),
            va,
            vb,
            (va - vb).abs(),
            &OVERTURN_VELOCITY,
        ));
    }
    let (ea, eb) = (&sa.energy, &sb.energy);
    let ke0 = ea.kinetic_initial_j.max(f64::MIN_POSITIVE);
    for (name, x, y) in [
        (
            "energy: honeycomb dissipated",
            ea.honeycomb_dissipated_j,
            eb.honeycomb_dissipated_j,
        ),
        ("energy: viscous", ea.viscous_j, eb.viscous_j),
        (
            "energy: bearing friction",
            ea.bearing_friction_j,
            eb.bearing_friction_j,
        ),
        (
            "energy: sliding friction",
            ea.sliding_friction_j,
            eb.sliding_friction_j,
        ),
        (
            "energy: contact events",
            ea.contact_events_j,
            eb.contact_events_j,
        ),
    ] {
        channels.push(channel(name.into(), x, y, (x - y).abs() / ke0, &ENERGY));
    }
    // The optional mechanisms' account only where a scene has them.
    let (x, y) = (ea.mechanisms_j, eb.mechanisms_j);
    if x != 0.0 || y != 0.0 {
        let name = "energy: mechanisms".into();
        channels.push(channel(name, x, y, (x - y).abs() / ke0, &ENERGY));
    }
    let outcome_agrees = sa.outcome == sb.outcome;
    let worst = if outcome_agrees {
        channels
            .iter()
            .max_by(|x, y| (x.difference / x.tolerance).total_cmp(&(y.difference / y.tolerance)))
            .map(|c| c.name.clone())
            .unwrap_or_default()
    } else {
        "outcome".to_string()
    };
    let pass = outcome_agrees && channels.iter().all(|c| c.pass);
    PairComparison {
        a: a.engine,
        b: b.engine,
        outcome: (sa.outcome, sb.outcome),
        outcome_agrees,
        channels,
        worst,
        pass,
    }
}
