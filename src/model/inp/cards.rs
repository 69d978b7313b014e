//! The Abaqus/CalculiX input format as a list of keyword cards: `*KEYWORD, PARAM=VALUE, ...`
//! followed by comma-separated data lines, `**` comments, *INCLUDE files spliced in place.
//! Keywords and parameter names are matched as Abaqus does: case-insensitive, blanks
//! ignored (`*Solid  Section` is `SOLID SECTION`). Every card and data line keeps its file and
//! line for messages.

use crate::error::{Error, Result};
use std::fmt;
use std::path::{Path, PathBuf};
use std::rc::Rc;

/// Where a card or data line was read: file and 1-based line.
#[derive(Clone, Debug)]
pub struct Location {
    pub file: Rc<PathBuf>,
    pub line: usize,
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}", self.file.display(), self.line)
    }
}

#[derive(Clone, Debug)]
pub struct DataLine {
    pub fields: Vec<String>,
    pub at: Location,
    /// The line ended with a comma (its trailing empty field dropped): a list that goes on.
    pub continues: bool,
}

#[derive(Clone, Debug)]
pub struct Card {
    /// Upper case, single blanks: "SOLID SECTION".
    pub keyword: String,
    /// (NAME, value) with NAME upper case; value "" for a bare parameter.
    pub params: Vec<(String, String)>,
    pub data: Vec<DataLine>,
    pub at: Location,
}

/// An error at a card or data line, naming it.
pub fn error_at(at: &Location, keyword: &str, message: impl fmt::Display) -> Error {
    Error::input(format!("{at}: *{keyword}: {message}"))
}

impl Card {
    pub fn error(&self, message: impl fmt::Display) -> Error {
        error_at(&self.at, &self.keyword, message)
    }

    /// The value of parameter `name` (upper case), if given.
    pub fn param(&self, name: &str) -> Option<&str> {
        self.params.iter().find(|(n, _)| n == name).map(|(_, v)| v.as_str())
    }

    pub fn has(&self, name: &str) -> bool {
        self.param(name).is_some()
    }

    /// A required parameter's value.
    pub fn required(&self, name: &str) -> Result<&str> {
        match self.param(name) {
            Some(v) if !v.is_empty() => Ok(v),
            _ => Err(self.error(format!("needs the parameter {name}="))),
        }
    }

    /// Refuses parameters outside `known` (a silently ignored option would change the model).
    pub fn only(&self, known: &[&str]) -> Result<()> {
        match self.params.iter().find(|(n, _)| !known.contains(&n.as_str())) {
            Some((n, _)) => Err(self.error(format!(
                "parameter {n} is not supported (slideline reads {})",
                if known.is_empty() { "none here".to_string() } else { known.join(", ") }
            ))),
            None => Ok(()),
        }
    }
}

impl DataLine {
    /// Field `k` as a number (an empty field is `default`, when one is allowed).
    pub fn number(&self, keyword: &str, k: usize, what: &str, default: Option<f64>) -> Result<f64> {
        match self.fields.get(k).map(|s| s.as_str()) {
            Some(s) if !s.is_empty() => parse_number(s).ok_or_else(|| error_at(&self.at, keyword, format!("{what}: '{s}' is not a number"))),
            _ => default.ok_or_else(|| error_at(&self.at, keyword, format!("missing {what} (field {})", k + 1))),
        }
    }

    /// Field `k` as a positive integer id.
    pub fn id(&self, keyword: &str, k: usize, what: &str) -> Result<u64> {
        let s = self.fields.get(k).map(|s| s.as_str()).unwrap_or("");
        s.parse::<u64>().ok().filter(|&v| v > 0).ok_or_else(|| error_at(&self.at, keyword, format!("{what}: '{s}' is not a positive integer")))
    }
}

/// Fortran-style numbers too: "1.d3", "2.E+5", "200000.".
pub(super) fn parse_number(s: &str) -> Option<f64> {
    s.parse::<f64>().ok().or_else(|| s.replace(['d', 'D'], "e").parse::<f64>().ok()).filter(|v| v.is_finite())
}

/// Upper case with runs of blanks folded to one and blanks around the text removed.
pub fn normalise(s: &str) -> String {
    s.split_whitespace().collect::<Vec<_>>().join(" ").to_uppercase()
}

/// Reads `path` and its includes into cards.
pub fn read(path: &Path) -> Result<Vec<Card>> {
    let text = std::fs::read_to_string(path).map_err(|source| Error::Read { path: path.to_path_buf(), source })?;
    let mut cards = Vec::new();
    parse_into(&text, path, &mut cards, 0)?;
    Ok(cards)
}

/// Parses `text` (read from `path`) and appends its cards, splicing includes in.
pub fn parse_into(text: &str, path: &Path, cards: &mut Vec<Card>, depth: usize) -> Result<()> {
    let file = Rc::new(path.to_path_buf());
    let lines: Vec<&str> = text.lines().collect();
    let mut k = 0;
    while k < lines.len() {
        let at = Location { file: file.clone(), line: k + 1 };
        let line = lines[k].trim_end_matches('\r');
        k += 1;
        let trimmed = line.trim();
        if trimmed.is_empty() || trimmed.starts_with("**") {
            continue;
        }
        if let Some(rest) = trimmed.strip_prefix('*') {
            // a keyword line ending in a comma continues on the next line
            let mut full = rest.to_string();
            while full.trim_end().ends_with(',') && k < lines.len() && !lines[k].trim_start().starts_with('*') {
                full.push_str(lines[k].trim());
                k += 1;
            }
            let mut parts = full.split(',');
            let keyword = normalise(parts.next().unwrap_or(""));
            let mut params = Vec::new();
            for p in parts.filter(|p| !p.trim().is_empty()) {
                let (name, value) = match p.split_once('=') {
                    Some((n, v)) => (normalise(n), v.trim().to_string()),
                    None => (normalise(p), String::new()),
                };
                params.push((name, value));
            }
            let card = Card { keyword, params, data: Vec::new(), at };
            if card.keyword == "INCLUDE" {
                card.only(&["INPUT"])?;
                let name = card.required("INPUT")?.trim_matches('"');
                let included = path.parent().unwrap_or(Path::new(".")).join(name);
                if depth > 20 {
                    return Err(card.error("includes nested more than 20 deep (does a file include itself?)"));
                }
                let text = std::fs::read_to_string(&included).map_err(|e| card.error(format!("cannot read '{}': {e}", included.display())))?;
                parse_into(&text, &included, cards, depth + 1)?;
            } else {
                cards.push(card);
            }
            continue;
        }
        let Some(card) = cards.last_mut() else {
            return Err(Error::input(format!("{at}: data line '{trimmed}' before any keyword")));
        };
        let mut fields: Vec<String> = trimmed.split(',').map(|f| f.trim().to_string()).collect();
        let continues = fields.len() > 1 && fields.last().is_some_and(|f| f.is_empty());
        if continues {
            fields.pop();
        }
        card.data.push(DataLine { fields, at, continues });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Vec<Card>> {
        let mut cards = Vec::new();
        parse_into(text, Path::new("deck.inp"), &mut cards, 0)?;
        Ok(cards)
    }

    #[test]
    fn keywords_and_parameters_are_matched_as_abaqus_does() {
        let cards = parse("** comment\n*Solid  section , elset = Plies,\n   material=Steel\n1.\n\n*node\n1, 2.5, 3d0,\n").unwrap();
        assert_eq!(cards.len(), 2);
        assert_eq!(cards[0].keyword, "SOLID SECTION");
        assert_eq!(cards[0].param("ELSET"), Some("Plies"));
        assert_eq!(cards[0].param("MATERIAL"), Some("Steel"));
        assert_eq!(cards[0].data.len(), 1);
        assert_eq!(cards[1].keyword, "NODE");
        assert_eq!(cards[1].data[0].fields, ["1", "2.5", "3d0"]);
        assert_eq!(cards[1].data[0].number("NODE", 2, "z", None).unwrap(), 3.0);
        assert_eq!(cards[1].data[0].at.line, 7);
    }

    #[test]
    fn a_missing_include_names_the_line() {
        let err = parse("*NODE\n1, 0, 0\n*INCLUDE, INPUT=nowhere.inc\n").unwrap_err().to_string();
        assert!(err.contains("deck.inp:3") && err.contains("nowhere.inc"), "{err}");
    }

    #[test]
    fn data_before_a_keyword_is_refused() {
        let err = parse("1, 2, 3\n").unwrap_err().to_string();
        assert!(err.contains("deck.inp:1") && err.contains("before any keyword"), "{err}");
    }
}
