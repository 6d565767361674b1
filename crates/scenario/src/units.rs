//! Units a scenario file states its values in. Every scenario declares its unit system
//! explicitly in `[units]`; nothing is assumed. Internally everything is SI.

use serde::{Deserialize, Serialize};

/// What a unit may be built from, for messages about one that is not.
pub const UNIT_GRAMMAR: &str =
    "m, ft, in, kg, slug, N, lbf, deg, rad, s, their products with * and powers ^2, one /, or 1";

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
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
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
    /// The file's `[similarity]` ratios of length, mass and time (not written in `[units]`):
    /// one each unless the loader reads a similar vehicle ([`Units::similar`]).
    #[serde(skip)]
    ratios: Ratios,
}

/// Ratios of length, mass and time of a dynamically similar vehicle; dimensionless.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Ratios {
    length: f64,
    mass: f64,
    time: f64,
}

impl Default for Ratios {
    fn default() -> Self {
        Ratios {
            length: 1.0,
            mass: 1.0,
            time: 1.0,
        }
    }
}

/// Metres per foot (exact).
pub const FOOT: f64 = 0.3048;
/// Newtons per pound-force (exact, from the standard pound and g0).
pub const POUND_FORCE: f64 = 4.448_221_615_260_5;
/// Kilograms per slug (lbf·s²/ft).
pub const SLUG: f64 = POUND_FORCE / FOOT;

impl Units {
    /// These units with every length, mass and time multiplied by `length`, `mass` and `time`
    /// (dimensionless ratios): read in them, a file describes the dynamically similar vehicle
    /// (`[similarity]`, docs/scenario-format.md). Every other dimension follows from the three:
    /// a force scales as mass·length/time², a stiffness as mass/time², an angle not at all.
    pub fn similar(self, length: f64, mass: f64, time: f64) -> Units {
        Units {
            ratios: Ratios {
                length: self.ratios.length * length,
                mass: self.ratios.mass * mass,
                time: self.ratios.time * time,
            },
            ..self
        }
    }
    /// SI value of one length unit, m.
    pub fn length(&self) -> f64 {
        self.ratios.length
            * match self.length {
                LengthUnit::Metre => 1.0,
                LengthUnit::Foot => FOOT,
                LengthUnit::Inch => 0.0254,
            }
    }
    /// SI value of one mass unit, kg.
    pub fn mass(&self) -> f64 {
        self.ratios.mass
            * match self.mass {
                MassUnit::Kilogram => 1.0,
                MassUnit::Slug => SLUG,
            }
    }
    /// SI value of one force unit, N.
    pub fn force(&self) -> f64 {
        let r = &self.ratios;
        r.mass * r.length / (r.time * r.time)
            * match self.force {
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
        self.ratios.time
            * match self.time {
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
    /// Checks a unit written beside a number meant for this file (`"ft/s"`, `"deg"`,
    /// `"lbf/ft"`, `"slug*ft^2"`, `"1/s"`, or `"1"` for a pure number): every unit it names must
    /// be the file's own for that quantity, so that a number written in other units is refused
    /// rather than read in the file's. Returns the unit as a name suffix (`ft_s`, `deg`,
    /// `lbf_ft`, `slug_ft2`, `per_s`, `dimensionless`) or what is wrong.
    pub fn suffix_of(&self, unit: &str) -> Result<String, String> {
        let unit = unit.trim();
        if unit == "1" {
            return Ok("dimensionless".into());
        }
        let mut suffix = Vec::new();
        for (n, part) in unit.split('/').enumerate() {
            if n > 1 {
                return Err(format!(
                    "{unit:?}: at most one `/` (everything after it divides: \"lbf/ft*s\" is lbf/(ft·s))"
                ));
            }
            if n == 0 && part.trim() == "1" {
                // a reciprocal, "1/s" (a lone "1" returned above): nothing above the `/`
                suffix.push("per".to_string());
                continue;
            }
            for token in part.split('*') {
                let (name, power) = token.split_once('^').unwrap_or((token, "1"));
                if !matches!(power, "1" | "2" | "3") {
                    return Err(format!("{unit:?}: power {power:?} (expected 1, 2 or 3)"));
                }
                let (own, quantity) = match name.trim() {
                    "m" | "ft" | "in" => (self.length_label(), "lengths"),
                    "kg" | "slug" => (self.mass_label(), "masses"),
                    "N" | "lbf" => (self.force_label(), "forces"),
                    "deg" | "rad" => (self.angle_label(), "angles"),
                    "s" => ("s", "times"),
                    other => {
                        return Err(format!(
                            "{unit:?}: unknown unit {other:?} (expected {})",
                            UNIT_GRAMMAR
                        ))
                    }
                };
                if name.trim() != own {
                    return Err(format!(
                        "{unit:?}: the scenario states {quantity} in {own}, not {}: write the numbers in the scenario's units",
                        name.trim()
                    ));
                }
                suffix.push(if power == "1" {
                    own.to_string()
                } else {
                    format!("{own}{power}")
                });
            }
        }
        Ok(suffix.join("_"))
    }

    /// The file's mass unit as written.
    pub fn mass_label(&self) -> &'static str {
        match self.mass {
            MassUnit::Kilogram => "kg",
            MassUnit::Slug => "slug",
        }
    }

    /// The file's force unit as written.
    pub fn force_label(&self) -> &'static str {
        match self.force {
            ForceUnit::Newton => "N",
            ForceUnit::PoundForce => "lbf",
        }
    }

    /// The file's angle unit as written.
    pub fn angle_label(&self) -> &'static str {
        match self.angle {
            AngleUnit::Degree => "deg",
            AngleUnit::Radian => "rad",
        }
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

    /// The unit, in this file's units, of a quantity whose SI unit is `si` (as the ranges
    /// table writes it: `N`, `m`, `kg`, `N/m`, `kg·m²`, `m/s`, `rad`, and `deg` for angles):
    /// each metre, kilogram, newton and angle unit becomes the file's length, mass, force and
    /// angle unit.
    pub fn file_unit_of(&self, si: &str) -> String {
        let mut out = String::new();
        let mut word = String::new();
        let flush = |word: &mut String, out: &mut String| {
            out.push_str(match word.as_str() {
                "m" => self.length_label(),
                "kg" => self.mass_label(),
                "N" => self.force_label(),
                "rad" | "deg" => self.angle_label(),
                other => other,
            });
            word.clear();
        };
        for c in si.chars() {
            if c.is_alphabetic() && !matches!(c, '²' | '³' | 'γ') {
                word.push(c);
            } else {
                flush(&mut word, &mut out);
                out.push(c);
            }
        }
        flush(&mut word, &mut out);
        out
    }
}

#[cfg(test)]
mod file_unit_tests {
    use super::*;

    #[test]
    fn si_units_become_the_files() {
        let u: Units = toml::from_str(
            "length = \"ft\"\nmass = \"slug\"\nforce = \"lbf\"\nangle = \"deg\"\ntime = \"s\"",
        )
        .unwrap();
        assert_eq!(u.file_unit_of("N/m"), "lbf/ft");
        assert_eq!(u.file_unit_of("kg·m²"), "slug·ft²");
        assert_eq!(u.file_unit_of("m/s"), "ft/s");
        assert_eq!(u.file_unit_of("N/(m/s)^γ"), "lbf/(ft/s)^γ");
        assert_eq!(u.file_unit_of("s"), "s");
        assert_eq!(u.file_unit_of("rad"), "deg");
    }

    /// A campaign's dispersion writes its unit beside its numbers; the unit becomes the record
    /// column's name suffix. A rate such as a contact's natural frequency is written `1/s`.
    #[test]
    fn a_unit_beside_numbers_names_its_column() {
        let u: Units = toml::from_str(
            "length = \"ft\"\nmass = \"slug\"\nforce = \"lbf\"\nangle = \"deg\"\ntime = \"s\"",
        )
        .unwrap();
        assert_eq!(u.suffix_of("ft/s").unwrap(), "ft_s");
        assert_eq!(u.suffix_of("slug*ft^2").unwrap(), "slug_ft2");
        assert_eq!(u.suffix_of("1").unwrap(), "dimensionless");
        assert_eq!(u.suffix_of("1/s").unwrap(), "per_s");
        assert_eq!(u.suffix_of("1/ft^2").unwrap(), "per_ft2");
        let other = u.suffix_of("1/m").unwrap_err();
        assert!(other.contains("in ft, not m"), "{other}");
        for wrong in ["1*s", "s/1", "1/1", "2/s"] {
            assert!(u.suffix_of(wrong).is_err(), "{wrong} accepted");
        }
    }
}

/// A number in short notation, for messages: at most six significant digits, trailing zeros
/// dropped, plain between 1e-4 and 1e5 (`0.5`, `-2`, `32.174`, `8700`) and scientific outside
/// (`1.23e+05`, `-1e-300`, `4.94066e-324`), like C's `%g`; `NaN`, `inf` and `-inf` as such.
/// Every number a scenario error or warning prints goes through it, so that a hostile value
/// never prints as a 300-digit expansion; other crates may use it for the same reason.
///
/// ```
/// use touchdown_scenario::units::short;
/// assert_eq!(short(0.5), "0.5");
/// assert_eq!(short(-1e-300), "-1e-300");
/// assert_eq!(short(123_000.0), "1.23e+05");
/// assert_eq!(short(8700.0), "8700");
/// ```
pub fn short(x: f64) -> String {
    Short(x).to_string()
}

/// [`short`] as a [`Display`](std::fmt::Display) wrapper: `format!("got {}", Short(x))`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Short(pub f64);

impl std::fmt::Display for Short {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        const DIGITS: usize = 6;
        let x = self.0;
        if !x.is_finite() {
            return write!(f, "{x}");
        }
        if x == 0.0 {
            return f.write_str("0");
        }
        // Rounded to DIGITS significant digits first, so that the exponent is the rounded one.
        let sci = format!("{:.*e}", DIGITS - 1, x);
        let (mantissa, exponent) = sci.split_once('e').unwrap_or((&sci, "0"));
        let exponent: i32 = exponent.parse().unwrap_or(0);
        if (-4..5).contains(&exponent) {
            let decimals = (DIGITS as i32 - 1 - exponent).max(0) as usize;
            let plain = format!("{x:.decimals$}");
            f.write_str(trim_zeros(&plain))
        } else {
            let sign = if exponent < 0 { '-' } else { '+' };
            write!(
                f,
                "{}e{sign}{:02}",
                trim_zeros(mantissa),
                exponent.unsigned_abs()
            )
        }
    }
}

/// `1.2300` → `1.23`, `2.000` → `2`; a number without a decimal point is left alone.
fn trim_zeros(s: &str) -> &str {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.')
    } else {
        s
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

    #[test]
    fn short_numbers_are_short() {
        let cases = [
            (0.5, "0.5"),
            (-2.0, "-2"),
            (1.5, "1.5"),
            (-0.2, "-0.2"),
            (32.174, "32.174"),
            (8700.0, "8700"),
            (99_999.0, "99999"),
            (100_000.0, "1e+05"),
            (123_000.0, "1.23e+05"),
            (0.0001, "0.0001"),
            (0.000_099, "9.9e-05"),
            (1e-7, "1e-07"),
            (-1e-300, "-1e-300"),
            (1e300, "1e+300"),
            (f64::MIN_POSITIVE / 4.0, "5.56268e-309"),
            (5e-324, "4.94066e-324"),
            (f64::MAX, "1.79769e+308"),
            (9.2e18, "9.2e+18"),
            (1.0 / 3.0, "0.333333"),
            (2.0 / 3.0 * 1e5, "66666.7"),
            (999_999.5, "1e+06"),
            (0.0, "0"),
            (-0.0, "0"),
            (f64::NAN, "NaN"),
            (f64::INFINITY, "inf"),
            (f64::NEG_INFINITY, "-inf"),
        ];
        for (x, want) in cases {
            assert_eq!(short(x), want, "{x:e}");
            assert!(short(x).len() <= 13, "{x:e}");
        }
    }
}
