//! `history.csv`: one row per accepted step, the same columns for every engine (SI units, named
//! in the header).

use crate::Sample;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

/// The energy columns, J, one per account of [`crate::summary::EnergyReport`], so that the balance
/// rebuilds from a row: `residual_j` = `kinetic_j` + `potential_change_j` + `footpad_j` +
/// `honeycomb_stored_j` + `honeycomb_dissipated_j` + `viscous_j` + `bearing_friction_j` +
/// `sliding_friction_j` + `mechanisms_j` − `contact_events_j` − `kinetic_initial_j`
/// (`EnergyLedger::report`).
pub const ENERGY_COLUMNS: [&str; 12] = [
    "kinetic_initial_j",
    "kinetic_j",
    "potential_change_j",
    "footpad_j",
    "honeycomb_stored_j",
    "honeycomb_dissipated_j",
    "viscous_j",
    "bearing_friction_j",
    "sliding_friction_j",
    "mechanisms_j",
    "contact_events_j",
    "residual_j",
];

/// Writes the time history of a landing as it runs, one [`Sample`] a row, whatever the engine:
/// to a file ([`History::create`]) or to any writer ([`History::to_writer`]).
pub struct History<W: Write = BufWriter<File>> {
    writer: csv::Writer<W>,
    error: Option<csv::Error>,
    row: Vec<String>,
    sample: Sample,
}

impl History {
    /// Creates `path` and writes the header for `legs` legs.
    pub fn create(path: &Path, legs: usize) -> std::io::Result<History> {
        let file = File::create(path).map_err(|e| {
            std::io::Error::new(e.kind(), format!("cannot create {}: {e}", path.display()))
        })?;
        History::to_writer(BufWriter::new(file), legs)
    }
}

impl<W: Write> History<W> {
    /// Writes the history of a landing of `legs` legs to `out`, starting with the header.
    pub fn to_writer(out: W, legs: usize) -> std::io::Result<History<W>> {
        let mut writer = csv::Writer::from_writer(out);
        let mut header: Vec<String> = [
            "t_s",
            "x_m",
            "y_m",
            "z_m",
            "vx_m_s",
            "vy_m_s",
            "vz_m_s",
            "theta_x_rad",
            "theta_y_rad",
            "theta_z_rad",
            "omega_x_rad_s",
            "omega_y_rad_s",
            "omega_z_rad_s",
            "pitch_rate_rad_s",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        for i in 1..=legs {
            for c in [
                "primary_stroke_m",
                "primary_force_n",
                "sec31_stroke_m",
                "sec31_force_n",
                "sec41_stroke_m",
                "sec41_force_n",
                "pad_x_m",
                "pad_y_m",
                "pad_z_m",
                "contact",
            ] {
                header.push(format!("leg{i}_{c}"));
            }
        }
        for i in 1..=legs {
            header.push(format!("sd_wall{i}{}_m", i % legs + 1));
        }
        for c in ENERGY_COLUMNS {
            header.push(c.to_string());
        }
        writer.write_record(&header)?;
        Ok(History {
            writer,
            error: None,
            row: Vec::with_capacity(header.len()),
            sample: Sample::new(legs),
        })
    }

    /// Flushes the file, reporting any write error met while running.
    pub fn finish(self) -> std::io::Result<()> {
        self.into_inner().map(|_| ())
    }

    /// Flushes and returns the writer, reporting any write error met while running.
    pub fn into_inner(mut self) -> std::io::Result<W> {
        if let Some(e) = self.error.take() {
            return Err(e.into());
        }
        self.writer
            .into_inner()
            .map_err(|e| std::io::Error::other(e.to_string()))
    }
}

/// A number for the CSV; a non-finite value (an undefined stability wall) is an empty cell,
/// never NaN.
fn num(x: f64) -> String {
    if x.is_finite() {
        format!("{x:.9e}")
    } else {
        String::new()
    }
}

impl<W: Write> History<W> {
    /// The sample to fill before [`History::write`] (made for the file's number of legs).
    pub fn sample_mut(&mut self) -> &mut Sample {
        &mut self.sample
    }

    /// Writes the sample as a row (the first write error is kept for [`History::finish`]).
    pub fn write(&mut self) {
        if self.error.is_some() {
            return;
        }
        let s = &self.sample;
        let row = &mut self.row;
        row.clear();
        row.push(num(s.t));
        for x in s
            .position
            .iter()
            .chain(s.velocity.iter())
            .chain(s.theta.iter())
            .chain(s.omega.iter())
        {
            row.push(num(*x));
        }
        row.push(num(s.pitch_rate));
        for g in &s.legs {
            for x in [
                g.primary_stroke,
                g.primary_force,
                g.secondary_stroke[0],
                g.secondary_force[0],
                g.secondary_stroke[1],
                g.secondary_force[1],
                g.pad_position.x,
                g.pad_position.y,
                g.pad_position.z,
            ] {
                row.push(num(x));
            }
            row.push(g.contact.to_string());
        }
        for sd in &s.stability_distance {
            row.push(num(*sd));
        }
        let e = &s.energy;
        // In the order of ENERGY_COLUMNS.
        for x in [
            e.kinetic_initial_j,
            e.kinetic_j,
            e.potential_change_j,
            e.footpad_j,
            e.honeycomb_stored_j,
            e.honeycomb_dissipated_j,
            e.viscous_j,
            e.bearing_friction_j,
            e.sliding_friction_j,
            e.mechanisms_j,
            e.contact_events_j,
            e.residual_j,
        ] {
            row.push(num(x));
        }
        if let Err(e) = self.writer.write_record(row.iter()) {
            self.error = Some(e);
        }
    }
}

/// Thins the history file at `path` to every `every`-th row (the first row, row `every`, row
/// 2·`every`, ...) and the last row, the header kept (`touchdown run --every N`); the same for
/// every engine, since each writes the same file. Returns the rows kept.
pub fn decimate(path: &Path, every: usize) -> std::io::Result<usize> {
    use std::io::{BufRead, BufReader};
    if every <= 1 {
        return Ok(BufReader::new(File::open(path)?)
            .lines()
            .count()
            .saturating_sub(1));
    }
    let thinned = path.with_extension("csv.thinning");
    let mut out = BufWriter::new(File::create(&thinned)?);
    let mut lines = BufReader::new(File::open(path)?).lines();
    if let Some(header) = lines.next() {
        writeln!(out, "{}", header?)?;
    }
    let (mut kept, mut last) = (0, None);
    for (i, line) in lines.enumerate() {
        let line = line?;
        if i % every == 0 {
            writeln!(out, "{line}")?;
            kept += 1;
            last = None;
        } else {
            last = Some(line);
        }
    }
    if let Some(line) = last {
        writeln!(out, "{line}")?;
        kept += 1;
    }
    out.flush()?;
    drop(out);
    std::fs::rename(&thinned, path)?;
    Ok(kept)
}

#[cfg(test)]
mod decimate_tests {
    use super::*;

    #[test]
    fn keeps_the_header_every_nth_row_and_the_last() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("history.csv");
        let rows: Vec<String> = (0..10).map(|i| format!("{i},x")).collect();
        std::fs::write(&path, format!("t_s,a\n{}\n", rows.join("\n"))).unwrap();
        assert_eq!(decimate(&path, 4).unwrap(), 4);
        let text = std::fs::read_to_string(&path).unwrap();
        assert_eq!(text, "t_s,a\n0,x\n4,x\n8,x\n9,x\n");
        // A last row already kept is not written twice.
        std::fs::write(&path, "t_s,a\n0,x\n1,x\n2,x\n").unwrap();
        assert_eq!(decimate(&path, 2).unwrap(), 2);
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "t_s,a\n0,x\n2,x\n");
    }
}
