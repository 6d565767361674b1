//! `history.csv`: one row per accepted step.

use anyhow::{Context, Result};
use std::fs::File;
use std::io::BufWriter;
use std::path::Path;
use touchdown_core::{Observer, Simulation};

/// Writes the time history of a landing as it runs.
pub struct Recorder {
    writer: csv::Writer<BufWriter<File>>,
    error: Option<csv::Error>,
    row: Vec<String>,
}

impl Recorder {
    /// Creates `path` and writes the header for `legs` legs.
    pub fn create(path: &Path, legs: usize) -> Result<Recorder> {
        let file =
            File::create(path).with_context(|| format!("cannot create {}", path.display()))?;
        let mut writer = csv::Writer::from_writer(BufWriter::new(file));
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
        for c in [
            "kinetic_j",
            "potential_change_j",
            "honeycomb_dissipated_j",
            "honeycomb_stored_j",
            "friction_j",
            "residual_j",
        ] {
            header.push(c.to_string());
        }
        writer.write_record(&header)?;
        Ok(Recorder {
            writer,
            error: None,
            row: Vec::with_capacity(header.len()),
        })
    }

    /// Flushes the file, reporting any write error met while running.
    pub fn finish(mut self) -> Result<()> {
        if let Some(e) = self.error.take() {
            return Err(e.into());
        }
        self.writer.flush()?;
        Ok(())
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

impl Observer for Recorder {
    fn observe(&mut self, sim: &Simulation) {
        if self.error.is_some() {
            return;
        }
        let v = sim.vehicle();
        let row = &mut self.row;
        row.clear();
        row.push(num(sim.time()));
        for x in v
            .position
            .iter()
            .chain(v.velocity.iter())
            .chain(v.theta.iter())
            .chain(v.omega.iter())
        {
            row.push(num(*x));
        }
        row.push(num(v.omega_inertial().x));
        for (g, p) in sim.gear().iter().zip(sim.footpads()) {
            let f = g.f_secondary();
            for x in [
                g.primary_stroke,
                g.f2p,
                g.secondary_stroke[0],
                f[0],
                g.secondary_stroke[1],
                f[1],
                p.position.x,
                p.position.y,
                p.position.z,
            ] {
                row.push(num(x));
            }
            row.push(p.state.code().to_string());
        }
        for sd in sim.stability_distances() {
            row.push(num(*sd));
        }
        let e = sim.energy();
        for x in [
            e.kinetic_j,
            e.potential_change_j,
            e.honeycomb_dissipated_j,
            e.honeycomb_stored_j,
            e.viscous_j + e.bearing_friction_j + e.sliding_friction_j,
            e.residual_j,
        ] {
            row.push(num(x));
        }
        if let Err(e) = self.writer.write_record(row.iter()) {
            self.error = Some(e);
        }
    }
}
