//! The dimension of a quantity: its powers of length, mass, force, angle and time.
//!
//! Mass and force are independent here (a file declares both units, `[units]` in
//! docs/scenario-format.md), and so is angle (a file states angles in degrees or radians). One
//! parser reads the three ways the project writes a unit:
//!
//! * the Ranges table's SI display units ([`crate::ranges::RANGES`]: `N/m`, `kg·m²`, `Pa·s²/m²`,
//!   `N/(m/s)^γ`, `N/s^i`, `Hz`, `deg/s`, empty for a pure number);
//! * the units written beside a campaign's numbers (`ft/s`, `slug*ft^2`, `lbf/ft`, `1`);
//! * the words of the fields table's dimension column (`force/length³`, `angle/time`).
//!
//! Everything after a `/` divides (`lbf/ft*s` is lbf/(ft·s)); parentheses group. The power `γ`
//! (or `exponent`) is a viscous law's exponent and `i` a polynomial coefficient's index: a unit
//! that names them is read with their values ([`Powers`]).

use crate::units::{Units, UNIT_GRAMMAR};

/// Powers of the five base quantities. Powers are real: a viscous coefficient's, N/(m/s)^γ,
/// follows its exponent γ.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Dimension {
    /// Power of length.
    pub length: f64,
    /// Power of mass.
    pub mass: f64,
    /// Power of force.
    pub force: f64,
    /// Power of angle.
    pub angle: f64,
    /// Power of time.
    pub time: f64,
}

/// The values of the symbolic powers a unit may name.
#[derive(Debug, Clone, Copy, Default)]
pub struct Powers {
    /// γ (also written `exponent`): the exponent of the viscous law of eq. (49).
    pub gamma: Option<f64>,
    /// `i`: the index of a polynomial coefficient (eq. 70's M_i, force/time^i).
    pub index: Option<f64>,
}

/// The base quantities in the order units are written (`slug*ft^2`, `lbf*s/ft`), with their
/// place in [`Dimension::powers`].
const WRITTEN: [(&str, usize); 5] = [
    ("mass", 1),
    ("force", 2),
    ("length", 0),
    ("angle", 3),
    ("time", 4),
];

impl Dimension {
    /// A pure number.
    pub const NONE: Dimension = Dimension {
        length: 0.0,
        mass: 0.0,
        force: 0.0,
        angle: 0.0,
        time: 0.0,
    };
    /// Length.
    pub const LENGTH: Dimension = Dimension {
        length: 1.0,
        ..Dimension::NONE
    };
    /// Mass.
    pub const MASS: Dimension = Dimension {
        mass: 1.0,
        ..Dimension::NONE
    };
    /// Force.
    pub const FORCE: Dimension = Dimension {
        force: 1.0,
        ..Dimension::NONE
    };
    /// Angle.
    pub const ANGLE: Dimension = Dimension {
        angle: 1.0,
        ..Dimension::NONE
    };
    /// Time.
    pub const TIME: Dimension = Dimension {
        time: 1.0,
        ..Dimension::NONE
    };

    fn powers(self) -> [f64; 5] {
        [self.length, self.mass, self.force, self.angle, self.time]
    }

    fn from_powers(p: [f64; 5]) -> Dimension {
        Dimension {
            length: p[0],
            mass: p[1],
            force: p[2],
            angle: p[3],
            time: p[4],
        }
    }

    fn times(self, other: Dimension) -> Dimension {
        let (a, b) = (self.powers(), other.powers());
        Dimension::from_powers(std::array::from_fn(|k| a[k] + b[k]))
    }

    fn pow(self, n: f64) -> Dimension {
        Dimension::from_powers(self.powers().map(|p| p * n))
    }

    /// Reads a unit written in any of the module's three vocabularies; `powers` gives the values
    /// of `γ` and `i` if the unit names them.
    ///
    /// ```
    /// use touchdown_scenario::dimension::{Dimension, Powers};
    /// let stiffness = Dimension::parse("N/m", Powers::default()).unwrap();
    /// assert_eq!(Dimension::parse("lbf/ft", Powers::default()).unwrap(), stiffness);
    /// assert_eq!(Dimension::parse("force/length", Powers::default()).unwrap(), stiffness);
    /// let linear = Powers { gamma: Some(1.0), index: None };
    /// assert_eq!(
    ///     Dimension::parse("N/(m/s)^γ", linear).unwrap(),
    ///     Dimension::parse("lbf*s/ft", Powers::default()).unwrap()
    /// );
    /// ```
    pub fn parse(unit: &str, powers: Powers) -> Result<Dimension, String> {
        let tokens = tokens(unit)?;
        if tokens.is_empty() {
            return Ok(Dimension::NONE);
        }
        let mut parser = Parser {
            tokens: &tokens,
            at: 0,
            powers,
        };
        let d = parser.quotient()?;
        match parser.tokens.get(parser.at) {
            None => Ok(d),
            Some(t) => Err(format!("{unit:?}: unexpected {t}")),
        }
    }

    /// The SI value of one unit of this dimension written in `units` (a file's): what a number
    /// of this dimension in the file is multiplied by on load.
    pub fn si_factor(&self, units: &Units) -> f64 {
        units.length().powf(self.length)
            * units.mass().powf(self.mass)
            * units.force().powf(self.force)
            * units.angle().powf(self.angle)
            * units.time().powf(self.time)
    }

    /// This dimension in `units` as a campaign writes a unit (`lbf/ft`, `slug*ft^2`, `1`), or
    /// `None` if a power is not a whole number from −3 to 3 (a viscous coefficient whose
    /// exponent is 1.5 has no such name).
    pub fn written_in(&self, units: &Units) -> Option<String> {
        let labels = [
            units.length_label(),
            units.mass_label(),
            units.force_label(),
            units.angle_label(),
            "s",
        ];
        let powers = self.powers();
        let (mut above, mut below) = (Vec::new(), Vec::new());
        for (label, p) in WRITTEN.map(|(_, k)| (labels[k], powers[k])) {
            if p.fract() != 0.0 || p.abs() > 3.0 {
                return None;
            }
            let n = p.abs() as u8;
            let part = if n == 1 {
                label.to_string()
            } else {
                format!("{label}^{n}")
            };
            match p {
                p if p > 0.0 => above.push(part),
                p if p < 0.0 => below.push(part),
                _ => {}
            }
        }
        let above = if above.is_empty() {
            "1".to_string()
        } else {
            above.join("*")
        };
        Some(if below.is_empty() {
            above
        } else {
            format!("{above}/{}", below.join("*"))
        })
    }

    /// This dimension in words (`force/length`, `mass·length²`, `a pure number`), for messages.
    pub fn words(&self) -> String {
        let (mut above, mut below) = (Vec::new(), Vec::new());
        let powers = self.powers();
        for (name, p) in WRITTEN.map(|(name, k)| (name, powers[k])) {
            let n = p.abs();
            let part = match ["", "", "²", "³", "⁴"].get(n as usize) {
                _ if n == 1.0 => name.to_string(),
                Some(sup) if n.fract() == 0.0 => format!("{name}{sup}"),
                _ => format!("{name}^{n}"),
            };
            match p {
                p if p > 0.0 => above.push(part),
                p if p < 0.0 => below.push(part),
                _ => {}
            }
        }
        match (above.is_empty(), below.is_empty()) {
            (true, true) => "a pure number".into(),
            (false, true) => above.join("·"),
            (true, false) => format!("1/{}", below.join("·")),
            (false, false) => format!("{}/{}", above.join("·"), below.join("·")),
        }
    }
}

/// The dimension of a unit name: SI and imperial unit names, and the words of the fields table.
fn named(name: &str) -> Option<Dimension> {
    let d = match name {
        "m" | "ft" | "in" | "length" => Dimension::LENGTH,
        "kg" | "slug" | "mass" => Dimension::MASS,
        "N" | "lbf" | "force" => Dimension::FORCE,
        "deg" | "rad" | "angle" => Dimension::ANGLE,
        "s" | "time" => Dimension::TIME,
        "Hz" => Dimension::TIME.pow(-1.0),
        "Pa" => Dimension::FORCE.times(Dimension::LENGTH.pow(-2.0)),
        _ => return None,
    };
    Some(d)
}

#[derive(Debug, Clone, PartialEq)]
enum Token {
    Name(String),
    One,
    Times,
    Over,
    Open,
    Close,
    Power(String),
}

impl std::fmt::Display for Token {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Token::Name(n) => write!(f, "{n:?}"),
            Token::One => write!(f, "\"1\""),
            Token::Times => write!(f, "a product sign"),
            Token::Over => write!(f, "a second `/`"),
            Token::Open => write!(f, "`(`"),
            Token::Close => write!(f, "`)`"),
            Token::Power(p) => write!(f, "the power {p:?}"),
        }
    }
}

fn tokens(unit: &str) -> Result<Vec<Token>, String> {
    let mut out = Vec::new();
    let mut chars = unit.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            ' ' => {}
            '*' | '·' => out.push(Token::Times),
            '/' => out.push(Token::Over),
            '(' => out.push(Token::Open),
            ')' => out.push(Token::Close),
            '²' => out.push(Token::Power("2".into())),
            '³' => out.push(Token::Power("3".into())),
            '⁴' => out.push(Token::Power("4".into())),
            '^' => {
                let mut p = String::new();
                while let Some(&n) = chars.peek() {
                    if n.is_alphanumeric() || n == '.' || n == '-' {
                        p.push(n);
                        chars.next();
                    } else {
                        break;
                    }
                }
                out.push(Token::Power(p));
            }
            '1' => out.push(Token::One),
            c if c.is_alphabetic() => {
                let mut name = c.to_string();
                while let Some(&n) = chars.peek() {
                    if n.is_alphabetic() && !matches!(n, '²' | '³' | '⁴') {
                        name.push(n);
                        chars.next();
                    } else {
                        break;
                    }
                }
                out.push(Token::Name(name));
            }
            other => return Err(format!("{unit:?}: unexpected character {other:?}")),
        }
    }
    Ok(out)
}

struct Parser<'a> {
    tokens: &'a [Token],
    at: usize,
    powers: Powers,
}

impl Parser<'_> {
    fn next(&mut self) -> Option<&Token> {
        let t = self.tokens.get(self.at);
        self.at += 1;
        t
    }

    fn peek(&self) -> Option<&Token> {
        self.tokens.get(self.at)
    }

    /// product [`/` product]: everything after the `/` divides.
    fn quotient(&mut self) -> Result<Dimension, String> {
        let above = self.product()?;
        if self.peek() != Some(&Token::Over) {
            return Ok(above);
        }
        self.at += 1;
        let below = self.product()?;
        if self.peek() == Some(&Token::Over) {
            return Err(
                "at most one `/` (everything after it divides: \"lbf/ft*s\" is lbf/(ft·s))".into(),
            );
        }
        Ok(above.times(below.pow(-1.0)))
    }

    fn product(&mut self) -> Result<Dimension, String> {
        let mut d = self.factor()?;
        while self.peek() == Some(&Token::Times) {
            self.at += 1;
            d = d.times(self.factor()?);
        }
        Ok(d)
    }

    fn factor(&mut self) -> Result<Dimension, String> {
        let base = match self.next().cloned() {
            Some(Token::Name(n)) => {
                named(&n).ok_or_else(|| format!("unknown unit {n:?} (expected {UNIT_GRAMMAR})"))?
            }
            Some(Token::One) => Dimension::NONE,
            Some(Token::Open) => {
                let d = self.quotient()?;
                match self.next() {
                    Some(Token::Close) => d,
                    _ => return Err("a `(` without its `)`".into()),
                }
            }
            Some(t) => return Err(format!("unexpected {t}")),
            None => return Err("a unit is missing".into()),
        };
        let Some(Token::Power(p)) = self.peek().cloned() else {
            return Ok(base);
        };
        self.at += 1;
        let n = match p.as_str() {
            "γ" | "exponent" => self
                .powers
                .gamma
                .ok_or("the power γ: the viscous exponent is not known here")?,
            "i" => self
                .powers
                .index
                .ok_or("the power i: the coefficient's index is not known here")?,
            digits => digits
                .parse::<f64>()
                .ok()
                .filter(|n| n.is_finite())
                .ok_or_else(|| format!("the power {digits:?} (expected a number)"))?,
        };
        Ok(base.pow(n))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn d(unit: &str) -> Dimension {
        Dimension::parse(unit, Powers::default()).unwrap()
    }

    #[test]
    fn the_three_vocabularies_agree() {
        assert_eq!(d("kg·m²"), d("slug*ft^2"));
        assert_eq!(d("kg·m²"), d("mass·length²"));
        assert_eq!(d("Pa·s²/m²"), d("force·time²/length⁴"));
        assert_eq!(d("Pa/m"), d("lbf/ft^3"));
        assert_eq!(d("Hz"), d("1/s"));
        assert_eq!(d("deg/s"), d("angle/time"));
        assert_eq!(d(""), Dimension::NONE);
        assert_eq!(d("1"), Dimension::NONE);
        assert_ne!(d("ft/s"), d("ft"));
        assert_ne!(d("kg"), d("N"), "mass and force are independent");
    }

    #[test]
    fn everything_after_the_slash_divides_and_parentheses_group() {
        assert_eq!(d("lbf/ft*s"), d("N/(m·s)"));
        let gamma = |g| Powers {
            gamma: Some(g),
            index: None,
        };
        assert_eq!(
            Dimension::parse("N/(m/s)^γ", gamma(2.0)).unwrap(),
            d("lbf*s^2/ft^2")
        );
        let third = Powers {
            gamma: None,
            index: Some(3.0),
        };
        assert_eq!(Dimension::parse("N/s^i", third).unwrap(), d("lbf/s^3"));
        assert!(Dimension::parse("N/(m/s)^γ", Powers::default()).is_err());
        assert!(Dimension::parse("ft/s/s", Powers::default()).is_err());
        assert!(Dimension::parse("furlong", Powers::default()).is_err());
        assert!(Dimension::parse("(ft", Powers::default()).is_err());
    }

    #[test]
    fn written_in_a_files_units_and_in_words() {
        let u: Units = toml::from_str(
            "length = \"ft\"\nmass = \"slug\"\nforce = \"lbf\"\nangle = \"deg\"\ntime = \"s\"",
        )
        .unwrap();
        assert_eq!(d("N/m").written_in(&u).unwrap(), "lbf/ft");
        assert_eq!(d("kg·m²").written_in(&u).unwrap(), "slug*ft^2");
        assert_eq!(d("Hz").written_in(&u).unwrap(), "1/s");
        assert_eq!(d("").written_in(&u).unwrap(), "1");
        assert_eq!(d("Pa·s²/m²").words(), "force·time²/length⁴");
        assert_eq!(d("").words(), "a pure number");
        let odd = Powers {
            gamma: Some(1.5),
            index: None,
        };
        assert!(Dimension::parse("N/(m/s)^γ", odd)
            .unwrap()
            .written_in(&u)
            .is_none());
        assert!(
            (d("lbf/ft").si_factor(&u) - crate::units::POUND_FORCE / crate::units::FOOT).abs()
                < 1e-9
        );
    }
}
