//! Files: the project's own log format ([`pdrlog`]), the formats other apps record ([`import`])
//! and track exports ([`export`]). May import: `engine` only; `sim` and the layers above import
//! `io`, never the reverse.
//!
//! Inside `io`, [`lines`] (bounded line reading) is below [`pdrlog`], which is below [`import`].

pub mod export;
pub mod fusion_words;
pub mod import;
pub mod lines;
pub mod pdrlog;

use std::fmt;

/// A problem with one field of one line of an input file.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ParseError {
    /// File name as given by the caller.
    pub file: String,
    /// 1-based line number.
    pub line: u64,
    /// 1-based column (field index) when known.
    pub column: Option<usize>,
    /// Field name when known.
    pub field: Option<String>,
    /// What is wrong.
    pub message: String,
}

impl fmt::Display for ParseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}", self.file, self.line)?;
        if let Some(c) = self.column {
            write!(f, ":{c}")?;
        }
        if let Some(name) = &self.field {
            write!(f, " field `{name}`")?;
        }
        write!(f, ": {}", self.message)
    }
}

impl std::error::Error for ParseError {}

/// A parse error for one field of one line.
pub fn field_error(
    file: &str,
    line: u64,
    column: usize,
    field: &str,
    message: impl Into<String>,
) -> ParseError {
    ParseError {
        file: file.to_string(),
        line,
        column: Some(column),
        field: Some(field.to_string()),
        message: message.into(),
    }
}

/// An error about a whole file.
pub fn file_error(file: &str, line: u64, message: impl Into<String>) -> ParseError {
    ParseError {
        file: file.to_string(),
        line,
        column: None,
        field: None,
        message: message.into(),
    }
}
