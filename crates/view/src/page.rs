//! The page that plays a trajectory: one HTML file that opens from disk with no network. The
//! template (`assets/page.html`), the page's script and style (`assets/view.js`,
//! `assets/view.css`) and the vendored plotting library (`assets/vendor/uplot-1.6.32`, MIT, its
//! licence and provenance beside it) are compiled in; the trajectory document is embedded as
//! JSON, and the page can also open another trajectory file chosen by the user.

const TEMPLATE: &str = include_str!("../assets/page.html");
const VIEW_JS: &str = include_str!("../assets/view.js");
const VIEW_CSS: &str = include_str!("../assets/view.css");
const UPLOT_JS: &str = include_str!("../assets/vendor/uplot-1.6.32/uPlot.iife.min.js");
const UPLOT_CSS: &str = include_str!("../assets/vendor/uplot-1.6.32/uPlot.min.css");
const UPLOT_LICENSE: &str = include_str!("../assets/vendor/uplot-1.6.32/LICENSE");

/// The page for the trajectory document `trajectory_json` (a `touchdown.trajectory/1` document),
/// titled `title`.
pub fn page(title: &str, trajectory_json: &str) -> String {
    let licence = format!(
        "/*! uPlot 1.6.32 (https://github.com/leeoniya/uPlot), vendored from the npm registry.\n{}*/\n",
        UPLOT_LICENSE.replace("*/", "* /")
    );
    let fill = |key: &str| match key {
        "TITLE" => Some(escape_html(title)),
        "UPLOT_CSS" => Some(UPLOT_CSS.to_string()),
        "VIEW_CSS" => Some(VIEW_CSS.to_string()),
        // The embedded JSON holds no `<` (JSON has it only inside strings, where `\u003c`
        // reads the same), so it can neither close its <script> element (`</script>`) nor
        // open a comment that swallows the rest of the page (`<!--<script>`).
        "TRAJECTORY_JSON" => Some(trajectory_json.replace('<', "\\u003c")),
        "UPLOT_JS" => Some(licence.clone() + UPLOT_JS),
        "VIEW_JS" => Some(VIEW_JS.to_string()),
        _ => None,
    };
    // One pass over the template: what is filled in is never read for placeholders.
    let mut html = String::with_capacity(TEMPLATE.len() + trajectory_json.len() + UPLOT_JS.len());
    let mut rest = TEMPLATE;
    while let Some(start) = rest.find("{{") {
        let value = rest[start + 2..]
            .find("}}")
            .and_then(|end| Some((fill(&rest[start + 2..start + 2 + end])?, start + 4 + end)));
        match value {
            Some((value, after)) => {
                html.push_str(&rest[..start]);
                html.push_str(&value);
                rest = &rest[after..];
            }
            None => {
                html.push_str(&rest[..start + 2]);
                rest = &rest[start + 2..];
            }
        }
    }
    html.push_str(rest);
    html
}

/// `text` safe inside an HTML element (or an attribute's quotes).
pub(crate) fn escape_html(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every placeholder is filled, the JSON cannot end its script element, and the library's
    /// licence travels with it.
    #[test]
    fn fills_every_placeholder() {
        let html = page("a <b> & c", r#"{"scenario_name": "</script><!--<script>"}"#);
        assert!(!html.contains("{{"), "a placeholder is left");
        assert!(html.contains("a &lt;b&gt; &amp; c"));
        assert!(html.contains(r#"{"scenario_name": "\u003c/script>\u003c!--\u003cscript>"}"#));
        assert!(!html.contains("<!--"), "the page holds a comment opener");
        assert!(html.contains("Permission is hereby granted"));
        for remote in ["src=\"http", "href=\"http", "src='http", "@import"] {
            assert!(!html.contains(remote), "the page loads {remote}...");
        }
    }

    /// What is filled in is not read for placeholders: a scenario named like one stays as named.
    #[test]
    fn fills_in_one_pass() {
        let html = page("{{VIEW_JS}}", r#"{"scenario_name": "{{TITLE}}"}"#);
        assert_eq!(html.matches("{{VIEW_JS}}").count(), 1);
        assert_eq!(html.matches("{{TITLE}}").count(), 1);
    }
}

#[cfg(test)]
mod vendored {
    use sha2::{Digest, Sha256};

    /// The vendored library is the pinned package's files, unmodified: each file's SHA-256 is
    /// the one its README records from the npm registry's tarball.
    #[test]
    fn the_vendored_files_are_the_pinned_package() {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/vendor/uplot-1.6.32");
        let readme = std::fs::read_to_string(format!("{dir}/README.md")).unwrap();
        let mut checked = 0;
        for line in readme.lines().filter(|l| l.starts_with("| `")) {
            let cells: Vec<&str> = line
                .split('|')
                .map(|c| c.trim().trim_matches('`'))
                .collect();
            let (file, recorded) = (cells[1], cells[3]);
            let bytes = std::fs::read(format!("{dir}/{file}")).unwrap();
            let hash: String = Sha256::digest(&bytes)
                .iter()
                .map(|b| format!("{b:02x}"))
                .collect();
            assert_eq!(hash, recorded, "{file} differs from the vendored package");
            checked += 1;
        }
        assert_eq!(checked, 3, "the README lists the three vendored files");
    }
}
