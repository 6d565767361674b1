//! `touchdown boundary`: its vertical velocities read from `--vv`, the study asked of
//! `touchdown_validation::boundary`, its output written where the arguments say.

use crate::args::{BoundaryArgs, TableFormat};
use crate::{out, outln};
use anyhow::{bail, Context, Result};
use touchdown_scenario::units::Short;
use touchdown_validation::boundary::{self, EnginePoint};

/// Parses the vertical velocities FROM:TO:STEP, or one vertical velocity, written as in the
/// scenario files (negative down): finite, FROM and TO negative, STEP > 0 and at most
/// [`boundary::MAX_GRID_POINTS`] velocities, FROM, FROM ± STEP, ... towards TO.
fn range(spec: &str) -> Result<Vec<f64>> {
    let parts: Vec<f64> = spec
        .split(':')
        .map(|s| s.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .with_context(|| {
            format!("--vv {spec:?}: expected FROM:TO:STEP numbers (--vv=-4:-12:2) or one (--vv=-8)")
        })?;
    let [from, to, step] = match parts[..] {
        [one] => [one, one, 1.0],
        [from, to, step] => [from, to, step],
        _ => bail!("--vv {spec:?}: expected FROM:TO:STEP (--vv=-4:-12:2) or one vertical velocity (--vv=-8)"),
    };
    if !(from.is_finite() && to.is_finite() && step.is_finite()) {
        bail!("--vv {spec:?}: expected finite FROM:TO:STEP numbers");
    }
    if !(step > 0.0 && from < 0.0 && to < 0.0) {
        bail!(
            "--vv {spec:?}: expected vertical velocities as the scenario files write them, \
             negative down (e.g. --vv=-4:-12:2), and STEP > 0"
        );
    }
    let n = ((to - from).abs() / step + 1e-9).floor();
    if n.is_nan() || n >= boundary::MAX_GRID_POINTS as f64 {
        bail!(
            "--vv {spec:?}: expected at most {} vertical velocities from FROM to TO (a STEP ≥ {}), got {}",
            boundary::MAX_GRID_POINTS,
            Short((to - from).abs() / (boundary::MAX_GRID_POINTS - 1) as f64),
            Short(n + 1.0)
        );
    }
    let sign = if to < from { -1.0 } else { 1.0 };
    Ok((0..=n as usize)
        .map(|i| from + sign * step * i as f64)
        .collect())
}

/// `touchdown boundary`.
pub fn boundary(args: BoundaryArgs) -> Result<()> {
    let BoundaryArgs {
        scenario,
        set,
        vv,
        vh_start,
        vh_step,
        vh_max,
        tol,
        scan_step,
        stop_restitution: restitutions,
        engines,
        format,
        out,
        plot,
    } = args;
    let asked = boundary::Asked {
        vh_start,
        vh_step,
        vh_max,
        tolerance: tol,
        scan_step,
    };
    let (scenario, set, out) = (scenario.as_path(), set.set.as_slice(), out.as_deref());
    let (engines, restitutions) = (engines.as_slice(), restitutions.as_slice());
    let vvs = range(&vv)?;
    let (base, _) = crate::load(scenario, set)?;
    let overrides = crate::overrides(set);
    let study = boundary::Request {
        base: &base,
        overrides: &overrides,
        vv: &vvs,
        vv_argument: "--vv",
        asked,
        engines,
        restitutions,
    }
    .resolve()?;
    crate::warn(study.scenario());
    let bar = crate::progress_bar(0, "landings");
    let (id, settings) = (study.scenario_id(), study.document_settings());
    // JSON Lines: each point as soon as it and those before it are found; the first error
    // writing them ends the command once the search returns.
    let unwritten = std::sync::Mutex::new(None);
    let stream = |p: &EnginePoint| {
        if format == TableFormat::Json {
            let line = study.document_line(p, &id, &settings);
            if let Err(e) = bar.suspend(|| outln!("{line}")) {
                if let Ok(mut first) = unwritten.lock() {
                    first.get_or_insert(e);
                }
            }
        }
    };
    let points = study.run(&|| bar.inc(1), &stream)?;
    bar.finish_and_clear();
    if let Some(e) = unwritten.into_inner().ok().flatten() {
        return Err(e);
    }
    match format {
        TableFormat::Json => {}
        TableFormat::Csv => out!("{}", study.csv(&points)?)?,
        TableFormat::Text => out!("{}", study.text(&points))?,
    }
    if let Some(dir) = out {
        let lines: Vec<String> = points
            .iter()
            .map(|p| study.document_line(p, &id, &settings) + "\n")
            .collect();
        let data = crate::out_file(dir, "boundary-", scenario, "jsonl")?;
        std::fs::write(&data, lines.concat())
            .with_context(|| format!("cannot write {}", data.display()))?;
        if !plot {
            return Ok(());
        }
        // The plot says what the search varies and holds, and on which engines.
        let png = data.with_extension("png");
        crate::plots::boundaries(&data, &study.scenario().file.name, &study.unit(), &png)?;
    }
    Ok(())
}

#[cfg(test)]
mod boundary_tests {
    use super::*;

    #[test]
    fn vv_ranges_are_finite_negative_and_bounded() {
        assert_eq!(range("-4:-8:2").unwrap(), vec![-4.0, -6.0, -8.0]);
        assert_eq!(range("-8:-4:2").unwrap(), vec![-8.0, -6.0, -4.0]);
        assert_eq!(range("-0.1:-0.4:0.1").unwrap().len(), 4);
        assert_eq!(range("-2.5").unwrap(), vec![-2.5]);
        for bad in [
            "4:8:2",
            "0:-4:1",
            "-4:-8:0",
            "-4:-8:-1",
            "nan:-8:1",
            "-4:-inf:1",
            "-1:-1e9:1",
            "-1:-2",
            "2.5",
            "-1:-2:1:1",
        ] {
            let e = range(bad).unwrap_err().to_string();
            assert!(
                e.starts_with("--vv") && e.contains("expected"),
                "{bad}: {e}"
            );
        }
        assert!(range("-1:-10000:1").is_ok() && range("-1:-10001:1").is_err());
    }
}
