//! Units a scenario file states its values in. Every scenario declares its unit system
//! explicitly in `[units]`; nothing is assumed. Internally everything is SI.

use serde::{Deserialize, Serialize};

/// Length unit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum LengthUnit {
    /// metre
    #[serde(rename = "m")]
    Metre,
    /// international foot, 0.3048 m
    #[serde(rename = "ft")]
    Foot,
    /// inch, 0.0254 m
    #[serde(rename = "in")]
    Inch,
}

/// Mass unit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum MassUnit {
    /// kilogram
    #[serde(rename = "kg")]
    Kilogram,
    /// slug = lbf·s²/ft ≈ 14.5939 kg
    #[serde(rename = "slug")]
    Slug,
}

/// Force unit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum ForceUnit {
    /// newton
    #[serde(rename = "N")]
    Newton,
    /// pound-force, 4.4482216152605 N
    #[serde(rename = "lbf")]
    PoundForce,
}

/// Angle unit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum AngleUnit {
    /// degree
    #[serde(rename = "deg")]
    Degree,
    /// radian
    #[serde(rename = "rad")]
    Radian,
}

/// Time unit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum TimeUnit {
    /// second
    #[serde(rename = "s")]
    Second,
}

/// The unit system of one scenario file (`[units]`, every field required).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Units {
    /// "m", "ft" or "in".
    pub length: LengthUnit,
    /// "kg" or "slug".
    pub mass: MassUnit,
    /// "N" or "lbf".
    pub force: ForceUnit,
    /// "deg" or "rad".
    pub angle: AngleUnit,
    /// "s".
    pub time: TimeUnit,
}

/// Metres per foot (exact).
pub const FOOT: f64 = 0.3048;
/// Newtons per pound-force (exact, from the standard pound and g0).
pub const POUND_FORCE: f64 = 4.448_221_615_260_5;
/// Kilograms per slug (lbf·s²/ft).
pub const SLUG: f64 = POUND_FORCE / FOOT;

impl Units {
    /// SI value of one length unit, m.
    pub fn length(&self) -> f64 {
        match self.length {
            LengthUnit::Metre => 1.0,
            LengthUnit::Foot => FOOT,
            LengthUnit::Inch => 0.0254,
        }
    }
    /// SI value of one mass unit, kg.
    pub fn mass(&self) -> f64 {
        match self.mass {
            MassUnit::Kilogram => 1.0,
            MassUnit::Slug => SLUG,
        }
    }
    /// SI value of one force unit, N.
    pub fn force(&self) -> f64 {
        match self.force {
            ForceUnit::Newton => 1.0,
            ForceUnit::PoundForce => POUND_FORCE,
        }
    }
    /// SI value of one angle unit, rad.
    pub fn angle(&self) -> f64 {
        match self.angle {
            AngleUnit::Degree => std::f64::consts::PI / 180.0,
            AngleUnit::Radian => 1.0,
        }
    }
    /// SI value of one time unit, s.
    pub fn time(&self) -> f64 {
        match self.time {
            TimeUnit::Second => 1.0,
        }
    }
    /// Velocity, m/s per (length/time).
    pub fn velocity(&self) -> f64 {
        self.length() / self.time()
    }
    /// Acceleration, m/s² per (length/time²).
    pub fn acceleration(&self) -> f64 {
        self.length() / (self.time() * self.time())
    }
    /// Angular rate, rad/s per (angle/time).
    pub fn angular_rate(&self) -> f64 {
        self.angle() / self.time()
    }
    /// Moment or product of inertia, kg·m² per (mass·length²).
    pub fn inertia(&self) -> f64 {
        self.mass() * self.length() * self.length()
    }
    /// Spring rate, N/m per (force/length).
    pub fn stiffness(&self) -> f64 {
        self.force() / self.length()
    }
    /// Viscous coefficient of eq. (49), N/(m/s)^γ per force/(length/time)^γ.
    pub fn viscous_coefficient(&self, exponent: f64) -> f64 {
        self.force() / self.velocity().powf(exponent)
    }
    /// Short label of the length unit, for reports.
    pub fn length_label(&self) -> &'static str {
        match self.length {
            LengthUnit::Metre => "m",
            LengthUnit::Foot => "ft",
            LengthUnit::Inch => "in",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slug_is_consistent_with_lbf_and_ft() {
        // 1 lbf accelerates 1 slug at 1 ft/s².
        assert!((SLUG * FOOT - POUND_FORCE).abs() < 1e-12);
        assert!((SLUG - 14.593_902_937).abs() < 1e-8);
    }
}
