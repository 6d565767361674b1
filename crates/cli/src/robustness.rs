//! `touchdown robustness`: the stiff and extreme catalogue on every engine.

use crate::args::Format;
use crate::{out, outln, settings};
use anyhow::Result;
use std::path::Path;
use touchdown_scenario::schema::Engine;

/// `touchdown robustness`: the stiff and extreme catalogue.
pub fn robustness(
    root: &Path,
    engines: &[Engine],
    cases: Option<Vec<String>>,
    search: bool,
    format: Format,
) -> Result<()> {
    use touchdown_compare::robustness::{self, CATALOGUE};
    let chosen: Vec<_> = match &cases {
        None => CATALOGUE.to_vec(),
        Some(names) => names
            .iter()
            .enumerate()
            .map(|(i, n)| {
                if names[..i].contains(n) {
                    anyhow::bail!("--cases: {n:?} is named twice: name each case once");
                }
                CATALOGUE
                    .iter()
                    .find(|c| c.name == n)
                    .copied()
                    .ok_or_else(|| {
                        let known: Vec<_> = CATALOGUE.iter().map(|c| c.name).collect();
                        anyhow::anyhow!(
                            "--cases: no case {n:?} (the catalogue: {})",
                            known.join(", ")
                        )
                    })
            })
            .collect::<Result<_>>()?,
    };
    let r = robustness::run_catalogue(&root.join("scenarios"), &chosen, engines, search, |m| {
        eprintln!("  {m}")
    })?;
    match format {
        Format::Text => out!("{}", robustness::text(&r, &chosen))?,
        Format::Json => {
            let options = serde_json::json!({
                "engines": engines,
                "cases": chosen.iter().map(|c| c.name).collect::<Vec<_>>(),
                "search": search,
            });
            let settings = settings(&[], options);
            let document = touchdown_record::Document::new("robustness", None, &settings, &r);
            outln!("{}", document.pretty())?;
        }
    }
    Ok(())
}
