//! Writing results: a minimal CSV builder (quoted when needed) and text
//! files, with the path in every error.

use crate::LabError;
use std::path::Path;

/// Formats a number for CSV: shortest round-trip form.
pub fn num(x: f64) -> String {
    if x.is_nan() {
        "NaN".into()
    } else {
        format!("{x:e}")
    }
}

/// A CSV table built in memory.
pub struct Csv {
    text: String,
}

fn field(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

impl Csv {
    /// A table with the given header.
    pub fn new(header: &[&str]) -> Csv {
        let mut text = header
            .iter()
            .map(|h| field(h))
            .collect::<Vec<_>>()
            .join(",");
        text.push('\n');
        Csv { text }
    }

    /// Appends a row.
    pub fn row(&mut self, cells: &[String]) {
        self.text += &cells.iter().map(|c| field(c)).collect::<Vec<_>>().join(",");
        self.text.push('\n');
    }

    /// Writes the table to `path`.
    pub fn write(&self, path: &Path) -> Result<(), LabError> {
        write_text(path, &self.text)
    }
}

/// Writes `text` to `path`.
pub fn write_text(path: &Path, text: &str) -> Result<(), LabError> {
    std::fs::write(path, text).map_err(|source| LabError::Io {
        path: path.display().to_string(),
        source,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fields_with_commas_or_quotes_are_quoted() {
        let mut c = Csv::new(&["a", "b"]);
        c.row(&["x,y".into(), "say \"hi\"".into()]);
        assert_eq!(c.text, "a,b\n\"x,y\",\"say \"\"hi\"\"\"\n");
        assert_eq!(num(1.5e-7), "1.5e-7");
    }
}
