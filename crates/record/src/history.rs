//! `history.csv`: one row per accepted step, the same columns for every engine (SI units, named
//! in the header).

use crate::energy::EnergyReport;
use crate::Sample;
use nalgebra::Vector3;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

/// The energy columns, J, one per account of [`crate::energy::EnergyReport`], so that the balance
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

/// The fields of an energy report in the order of [`ENERGY_COLUMNS`].
fn energy_fields(e: &mut EnergyReport) -> [&mut f64; 12] {
    [
        &mut e.kinetic_initial_j,
        &mut e.kinetic_j,
        &mut e.potential_change_j,
        &mut e.footpad_j,
        &mut e.honeycomb_stored_j,
        &mut e.honeycomb_dissipated_j,
        &mut e.viscous_j,
        &mut e.bearing_friction_j,
        &mut e.sliding_friction_j,
        &mut e.mechanisms_j,
        &mut e.contact_events_j,
        &mut e.residual_j,
    ]
}

/// The columns of the vehicle's state, first in every row.
const BODY_COLUMNS: [&str; 14] = [
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
];

/// The columns of each leg N, `legN_` and one of these.
const LEG_COLUMNS: [&str; 14] = [
    "primary_stroke_m",
    "primary_force_n",
    "sec31_stroke_m",
    "sec31_force_n",
    "sec41_stroke_m",
    "sec41_force_n",
    "primary_stop_force_n",
    "sec31_stop_force_n",
    "sec41_stop_force_n",
    "pad_x_m",
    "pad_y_m",
    "pad_z_m",
    "restraint_force_n",
    "contact",
];

/// The stability-wall columns of a landing of `legs` legs: wall i joins footpads i and i + 1.
fn wall_columns(legs: usize) -> impl Iterator<Item = String> {
    (1..=legs).map(move |i| format!("sd_wall{i}{}_m", i % legs + 1))
}

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
        let mut header: Vec<String> = BODY_COLUMNS.iter().map(|s| s.to_string()).collect();
        for i in 1..=legs {
            header.extend(LEG_COLUMNS.iter().map(|c| format!("leg{i}_{c}")));
        }
        header.extend(wall_columns(legs));
        header.extend(ENERGY_COLUMNS.iter().map(|c| c.to_string()));
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
                g.stop_force[0],
                g.stop_force[1],
                g.stop_force[2],
                g.pad_position.x,
                g.pad_position.y,
                g.pad_position.z,
                g.restraint_force,
            ] {
                row.push(num(x));
            }
            row.push(g.contact.to_string());
        }
        for sd in &s.stability_distance {
            row.push(num(*sd));
        }
        let mut e = s.energy;
        for x in energy_fields(&mut e) {
            row.push(num(*x));
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

/// Why a `history.csv` could not be read back.
#[derive(Debug, thiserror::Error)]
pub enum HistoryReadError {
    /// The file could not be opened or parsed as CSV.
    #[error("{path}: {source}")]
    Csv {
        /// The file.
        path: String,
        /// The CSV reader's error.
        source: csv::Error,
    },
    /// A column the history always has is missing.
    #[error("{path}: no column {column}")]
    MissingColumn {
        /// The file.
        path: String,
        /// The column.
        column: String,
    },
    /// A cell is not a number (or, for `legN_contact`, not a contact code).
    #[error("{path}: row {row}, column {column}: {value:?} is not a number")]
    BadCell {
        /// The file.
        path: String,
        /// The data row, 1-based.
        row: usize,
        /// The column.
        column: String,
        /// The cell.
        value: String,
    },
}

/// Reads a `history.csv` written by [`History`] back, calling `each` with every row as a
/// [`Sample`] (the number of legs from the header): the reader of the files an engine writes
/// outside this process (the MuJoCo runner). The energy columns fill the matching fields of
/// [`Sample::energy`]; an empty stability-distance cell is NaN, as written. Returns the number
/// of legs.
pub fn read(path: &Path, mut each: impl FnMut(&Sample)) -> Result<usize, HistoryReadError> {
    let name = || path.display().to_string();
    let csv_error = |source| HistoryReadError::Csv {
        path: name(),
        source,
    };
    let mut reader = csv::Reader::from_path(path).map_err(csv_error)?;
    let header = reader.headers().map_err(csv_error)?.clone();
    let column = |c: &str| {
        header
            .iter()
            .position(|h| h == c)
            .ok_or_else(|| HistoryReadError::MissingColumn {
                path: name(),
                column: c.to_string(),
            })
    };
    let legs = (1..)
        .take_while(|n| {
            header
                .iter()
                .any(|h| h == format!("leg{n}_primary_stroke_m"))
        })
        .count();
    let columns = |names: &[String]| {
        names
            .iter()
            .map(|c| column(c))
            .collect::<Result<Vec<_>, _>>()
    };
    let body = columns(&BODY_COLUMNS.map(String::from))?;
    let leg_columns = (1..=legs)
        .map(|i| columns(&LEG_COLUMNS.map(|c| format!("leg{i}_{c}"))))
        .collect::<Result<Vec<_>, _>>()?;
    let walls = columns(&wall_columns(legs).collect::<Vec<_>>())?;
    let energy = columns(&ENERGY_COLUMNS.map(String::from))?;
    let mut sample = Sample::new(legs);
    let mut record = csv::StringRecord::new();
    let mut row = 0;
    while reader.read_record(&mut record).map_err(csv_error)? {
        row += 1;
        let bad = |c: usize| HistoryReadError::BadCell {
            path: name(),
            row,
            column: header[c].to_string(),
            value: record[c].to_string(),
        };
        let num = |c: usize| record[c].parse::<f64>().map_err(|_| bad(c));
        // In the order of BODY_COLUMNS.
        let b = |k: usize| num(body[k]);
        let v = |k: usize| Ok::<_, HistoryReadError>(Vector3::new(b(k)?, b(k + 1)?, b(k + 2)?));
        sample.t = b(0)?;
        sample.position = v(1)?;
        sample.velocity = v(4)?;
        sample.theta = v(7)?;
        sample.omega = v(10)?;
        sample.pitch_rate = b(13)?;
        for (leg, c) in sample.legs.iter_mut().zip(&leg_columns) {
            leg.primary_stroke = num(c[0])?;
            leg.primary_force = num(c[1])?;
            leg.secondary_stroke = [num(c[2])?, num(c[4])?];
            leg.secondary_force = [num(c[3])?, num(c[5])?];
            leg.stop_force = [num(c[6])?, num(c[7])?, num(c[8])?];
            leg.pad_position = Vector3::new(num(c[9])?, num(c[10])?, num(c[11])?);
            leg.restraint_force = num(c[12])?;
            leg.contact = record[c[13]].parse::<u8>().map_err(|_| bad(c[13]))?;
        }
        for (sd, &c) in sample.stability_distance.iter_mut().zip(&walls) {
            *sd = if record[c].is_empty() {
                f64::NAN
            } else {
                num(c)?
            };
        }
        for (field, &c) in energy_fields(&mut sample.energy).into_iter().zip(&energy) {
            *field = num(c)?;
        }
        each(&sample);
    }
    Ok(legs)
}

#[cfg(test)]
mod read_tests {
    use super::*;

    /// A history written and read back gives the samples written, the undefined wall included.
    #[test]
    fn reads_back_what_it_writes() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("history.csv");
        let mut history = History::create(&path, 3).unwrap();
        let mut written = Vec::new();
        for k in 0..4 {
            let s = history.sample_mut();
            s.t = 1.0e-3 * k as f64;
            s.position = Vector3::new(0.1, -0.2, 1.5 - 0.01 * k as f64);
            s.theta = Vector3::new(0.01, 0.02, -0.03);
            s.pitch_rate = -0.5 * k as f64;
            s.legs[1].primary_stroke = 0.002 * k as f64;
            s.legs[1].secondary_force = [12.5, -3.0];
            s.legs[1].stop_force = [3.0e4, 0.0, -2.5e3];
            s.legs[2].pad_position = Vector3::new(1.0, 2.0, -0.25);
            s.legs[2].contact = (k % 3) as u8;
            s.stability_distance = vec![0.5, f64::NAN, 0.25];
            s.energy.viscous_j = 7.0 * k as f64;
            s.energy.residual_j = -1.0e-3;
            written.push(s.clone());
            history.write();
        }
        history.finish().unwrap();
        let mut read = Vec::new();
        assert_eq!(read_history(&path, &mut read), 3);
        assert_eq!(read.len(), written.len());
        for (r, w) in read.iter().zip(&written) {
            assert!(r.stability_distance[1].is_nan());
            let mut r = r.clone();
            r.stability_distance[1] = 0.0;
            let mut w = w.clone();
            w.stability_distance[1] = 0.0;
            assert_eq!(r, w);
        }
    }

    fn read_history(path: &Path, out: &mut Vec<Sample>) -> usize {
        read(path, |s| out.push(s.clone())).unwrap()
    }

    /// A missing column and a cell that is not a number are named with the file.
    #[test]
    fn names_the_file_and_the_cell() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("history.csv");
        std::fs::write(&path, "t_s,x_m\n0,1\n").unwrap();
        let e = read(&path, |_| {}).unwrap_err().to_string();
        assert!(
            e.contains("history.csv") && e.contains("no column y_m"),
            "{e}"
        );
        let mut history = History::create(&path, 1).unwrap();
        history.write();
        history.finish().unwrap();
        let text = std::fs::read_to_string(&path)
            .unwrap()
            .replacen("0.000000000e0", "x", 1);
        std::fs::write(&path, text).unwrap();
        let e = read(&path, |_| {}).unwrap_err().to_string();
        assert!(e.contains("row 1, column t_s: \"x\""), "{e}");
    }
}
