//! The validation plots regenerate from the committed data (docs/validation/) with the
//! project's pinned Python environment. A missing environment is a failure with the command
//! that creates it, never a skip.

use std::path::PathBuf;
use std::process::Command;

#[test]
fn validation_plots_regenerate_from_the_committed_data() {
    let root = touchdown_tests::root();
    let python = touchdown_tests::python();
    let out: PathBuf = std::env::temp_dir().join(format!("touchdown-plots-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    for script in ["plot_validation.py", "plot_cross_validation.py"] {
        let status = Command::new(&python)
            .arg(root.join("python/figures").join(script))
            .arg("--data")
            .arg(root.join("docs/validation"))
            .arg("--out")
            .arg(&out)
            .output()
            .expect("the venv's python runs");
        assert!(
            status.status.success(),
            "{script} failed:\n{}",
            String::from_utf8_lossy(&status.stderr)
        );
    }
    for name in [
        "table-i.png",
        "fig-25-26.png",
        "boundary-2-2.png",
        "cross-validation.png",
    ] {
        let bytes =
            std::fs::read(out.join(name)).unwrap_or_else(|e| panic!("{name} was not written: {e}"));
        assert!(
            bytes.starts_with(b"\x89PNG\r\n\x1a\n"),
            "{name} is not a PNG"
        );
        assert!(
            bytes.len() > 10_000,
            "{name} is suspiciously small ({} bytes)",
            bytes.len()
        );
    }
    let _ = std::fs::remove_dir_all(&out);
}
