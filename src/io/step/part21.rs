//! A small reader of ISO 10303-21 ("Part 21") exchange files: the DATA sections as a map from
//! instance number to its record(s). The HEADER section is skipped.
//!
//! Limits that keep it safe on any input: the text is read once, left to right (time linear in
//! its length); every allocation is proportional to the tokens read so far; lists nest at most
//! [`MAX_DEPTH`] deep (no recursion beyond it); integers beyond `i64` and malformed tokens are
//! errors, never panics.

use crate::error::{Error, Result};
use std::collections::HashMap;

/// The deepest nesting of parameter lists accepted.
pub const MAX_DEPTH: usize = 32;

/// One parameter of a record.
#[derive(Debug, Clone, PartialEq)]
pub enum Param {
    /// An integer.
    Int(i64),
    /// A real number (finite or not, as written).
    Real(f64),
    /// A string, escapes kept as written.
    Str(String),
    /// An enumeration value, without the dots (`T`, `UNSPECIFIED`, ...).
    Enum(String),
    /// A reference to instance `#n`.
    Ref(u64),
    /// `$`: no value.
    Unset,
    /// `*`: a derived value.
    Derived,
    /// A list.
    List(Vec<Param>),
    /// A typed parameter `KEYWORD(value)`.
    Typed(String, Box<Param>),
}

/// A record `NAME(parameters)`.
#[derive(Debug, Clone, PartialEq)]
pub struct Record {
    /// The entity name, upper case.
    pub name: String,
    /// Its parameters.
    pub params: Vec<Param>,
}

/// One instance of the data section: a simple record, or a complex instance made of the partial
/// records of several entity types.
#[derive(Debug, Clone, PartialEq)]
pub enum Instance {
    /// `#n = NAME(...);`
    Simple(Record),
    /// `#n = (A(...) B(...) ...);`
    Complex(Vec<Record>),
}

impl Instance {
    /// The simple record's name, or the complex instance's names joined by spaces.
    pub fn name(&self) -> String {
        match self {
            Instance::Simple(r) => r.name.clone(),
            Instance::Complex(rs) => rs
                .iter()
                .map(|r| r.name.as_str())
                .collect::<Vec<_>>()
                .join(" "),
        }
    }

    /// The record named `name`: the simple record, or that partial record of a complex one.
    pub fn record(&self, name: &str) -> Option<&Record> {
        match self {
            Instance::Simple(r) => (r.name == name).then_some(r),
            Instance::Complex(rs) => rs.iter().find(|r| r.name == name),
        }
    }
}

/// The data of a Part 21 file.
#[derive(Debug, Clone, Default)]
pub struct Part21 {
    /// The instances by number.
    pub instances: HashMap<u64, Instance>,
    /// The instance numbers in the order they were written.
    pub order: Vec<u64>,
}

/// A token of the exchange structure.
#[derive(Debug, Clone, PartialEq)]
enum Tok {
    Keyword(String),
    Ref(u64),
    Int(i64),
    Real(f64),
    Str(String),
    Enum(String),
    Dollar,
    Star,
    Open,
    Close,
    Comma,
    Equals,
    Semicolon,
}

/// An error of the file's syntax at a line.
fn syntax(line: usize, message: impl std::fmt::Display) -> Error {
    Error::Step {
        entity: None,
        message: format!("line {line}: {message}"),
    }
}

/// Splits the text into tokens, skipping white space and comments.
struct Lexer<'a> {
    text: &'a [u8],
    at: usize,
    line: usize,
}

impl<'a> Lexer<'a> {
    fn new(text: &'a str) -> Self {
        Lexer {
            text: text.as_bytes(),
            at: 0,
            line: 1,
        }
    }

    fn peek_byte(&self) -> Option<u8> {
        self.text.get(self.at).copied()
    }

    fn skip_blank(&mut self) -> Result<()> {
        loop {
            match self.peek_byte() {
                Some(b'\n') => {
                    self.line += 1;
                    self.at += 1;
                }
                Some(c) if c.is_ascii_whitespace() => self.at += 1,
                Some(b'/') if self.text.get(self.at + 1) == Some(&b'*') => {
                    let start = self.line;
                    self.at += 2;
                    loop {
                        match self.peek_byte() {
                            None => return Err(syntax(start, "unterminated comment")),
                            Some(b'*') if self.text.get(self.at + 1) == Some(&b'/') => {
                                self.at += 2;
                                break;
                            }
                            Some(c) => {
                                if c == b'\n' {
                                    self.line += 1;
                                }
                                self.at += 1;
                            }
                        }
                    }
                }
                _ => return Ok(()),
            }
        }
    }

    fn take_while(&mut self, f: impl Fn(u8) -> bool) -> &'a str {
        let start = self.at;
        while self.peek_byte().is_some_and(&f) {
            self.at += 1;
        }
        // Only ASCII bytes are taken, so this is a char boundary.
        std::str::from_utf8(&self.text[start..self.at]).unwrap_or("")
    }

    /// The next token, or `None` at the end of the text.
    fn next(&mut self) -> Result<Option<Tok>> {
        self.skip_blank()?;
        let line = self.line;
        let Some(c) = self.peek_byte() else {
            return Ok(None);
        };
        let single = |t: Tok| -> Result<Option<Tok>> { Ok(Some(t)) };
        match c {
            b'(' | b')' | b',' | b'=' | b';' | b'$' | b'*' => {
                self.at += 1;
                single(match c {
                    b'(' => Tok::Open,
                    b')' => Tok::Close,
                    b',' => Tok::Comma,
                    b'=' => Tok::Equals,
                    b';' => Tok::Semicolon,
                    b'$' => Tok::Dollar,
                    _ => Tok::Star,
                })
            }
            b'#' => {
                self.at += 1;
                let digits = self.take_while(|b| b.is_ascii_digit());
                let n = digits
                    .parse::<u64>()
                    .map_err(|_| syntax(line, format!("bad instance name `#{digits}`")))?;
                single(Tok::Ref(n))
            }
            b'\'' => {
                self.at += 1;
                let mut s = Vec::new();
                loop {
                    match self.peek_byte() {
                        None => return Err(syntax(line, "unterminated string")),
                        Some(b'\'') if self.text.get(self.at + 1) == Some(&b'\'') => {
                            s.push(b'\'');
                            self.at += 2;
                        }
                        Some(b'\'') => {
                            self.at += 1;
                            break;
                        }
                        Some(b) => {
                            if b == b'\n' {
                                self.line += 1;
                            }
                            s.push(b);
                            self.at += 1;
                        }
                    }
                }
                single(Tok::Str(String::from_utf8_lossy(&s).into_owned()))
            }
            b'.' => {
                self.at += 1;
                let name = self.take_while(|b| b.is_ascii_alphanumeric() || b == b'_');
                if self.peek_byte() != Some(b'.') || name.is_empty() {
                    return Err(syntax(line, "bad enumeration value"));
                }
                self.at += 1;
                single(Tok::Enum(name.to_ascii_uppercase()))
            }
            b'+' | b'-' | b'0'..=b'9' => self.number(line).map(Some),
            c if c.is_ascii_alphabetic() || c == b'_' || c == b'!' => {
                let word = self.take_while(|b| {
                    b.is_ascii_alphanumeric() || b == b'_' || b == b'-' || b == b'!'
                });
                single(Tok::Keyword(word.to_ascii_uppercase()))
            }
            other => Err(syntax(
                line,
                format!("unexpected character `{}`", other.escape_ascii()),
            )),
        }
    }

    fn number(&mut self, line: usize) -> Result<Tok> {
        let start = self.at;
        if matches!(self.peek_byte(), Some(b'+' | b'-')) {
            self.at += 1;
        }
        let digits = self.take_while(|b| b.is_ascii_digit());
        if digits.is_empty() {
            return Err(syntax(line, "a sign without digits"));
        }
        let mut real = false;
        if self.peek_byte() == Some(b'.') {
            real = true;
            self.at += 1;
            self.take_while(|b| b.is_ascii_digit());
        }
        if real && matches!(self.peek_byte(), Some(b'E' | b'e')) {
            self.at += 1;
            if matches!(self.peek_byte(), Some(b'+' | b'-')) {
                self.at += 1;
            }
            if self.take_while(|b| b.is_ascii_digit()).is_empty() {
                return Err(syntax(line, "an exponent without digits"));
            }
        }
        let text = std::str::from_utf8(&self.text[start..self.at]).unwrap_or("");
        if real {
            text.parse::<f64>()
                .map(Tok::Real)
                .map_err(|_| syntax(line, format!("bad real `{text}`")))
        } else {
            text.parse::<i64>()
                .map(Tok::Int)
                .map_err(|_| syntax(line, format!("integer `{text}` out of range")))
        }
    }
}

/// A one-token look-ahead parser over the lexer.
struct Parser<'a> {
    lex: Lexer<'a>,
    ahead: Option<Tok>,
}

impl Parser<'_> {
    fn peek(&mut self) -> Result<Option<&Tok>> {
        if self.ahead.is_none() {
            self.ahead = self.lex.next()?;
        }
        Ok(self.ahead.as_ref())
    }

    fn bump(&mut self) -> Result<Option<Tok>> {
        match self.ahead.take() {
            Some(t) => Ok(Some(t)),
            None => self.lex.next(),
        }
    }

    fn expect(&mut self, want: Tok, what: &str) -> Result<()> {
        let line = self.lex.line;
        match self.bump()? {
            Some(t) if t == want => Ok(()),
            Some(t) => Err(syntax(line, format!("expected {what}, found {t:?}"))),
            None => Err(syntax(
                line,
                format!("expected {what}, found the end of the file"),
            )),
        }
    }

    /// `( [param {, param}] )`, the opening parenthesis already read.
    fn list(&mut self, depth: usize) -> Result<Vec<Param>> {
        let line = self.lex.line;
        if depth > MAX_DEPTH {
            return Err(syntax(
                line,
                format!("lists nested deeper than {MAX_DEPTH}"),
            ));
        }
        let mut out = Vec::new();
        if self.peek()? == Some(&Tok::Close) {
            self.bump()?;
            return Ok(out);
        }
        loop {
            out.push(self.param(depth)?);
            let line = self.lex.line;
            match self.bump()? {
                Some(Tok::Comma) => {}
                Some(Tok::Close) => return Ok(out),
                Some(t) => return Err(syntax(line, format!("expected `,` or `)`, found {t:?}"))),
                None => return Err(syntax(line, "unterminated list")),
            }
        }
    }

    fn param(&mut self, depth: usize) -> Result<Param> {
        let line = self.lex.line;
        Ok(match self.bump()? {
            Some(Tok::Int(n)) => Param::Int(n),
            Some(Tok::Real(x)) => Param::Real(x),
            Some(Tok::Str(s)) => Param::Str(s),
            Some(Tok::Enum(s)) => Param::Enum(s),
            Some(Tok::Ref(n)) => Param::Ref(n),
            Some(Tok::Dollar) => Param::Unset,
            Some(Tok::Star) => Param::Derived,
            Some(Tok::Open) => Param::List(self.list(depth + 1)?),
            Some(Tok::Keyword(k)) => {
                self.expect(Tok::Open, "`(` after a type name")?;
                let inner = self.list(depth + 1)?;
                let value = match <[Param; 1]>::try_from(inner) {
                    Ok([v]) => v,
                    Err(v) => Param::List(v),
                };
                Param::Typed(k, Box::new(value))
            }
            Some(t) => return Err(syntax(line, format!("expected a parameter, found {t:?}"))),
            None => {
                return Err(syntax(
                    line,
                    "expected a parameter, found the end of the file",
                ))
            }
        })
    }

    /// `NAME ( params )`, the name already read.
    fn record(&mut self, name: String) -> Result<Record> {
        self.expect(Tok::Open, "`(` after an entity name")?;
        Ok(Record {
            name,
            params: self.list(1)?,
        })
    }

    /// Skips tokens up to and including the next `;` (header entries, section keywords).
    fn skip_statement(&mut self) -> Result<()> {
        let line = self.lex.line;
        loop {
            match self.bump()? {
                Some(Tok::Semicolon) => return Ok(()),
                Some(_) => {}
                None => return Err(syntax(line, "unterminated statement")),
            }
        }
    }
}

/// Parses the text of a Part 21 file.
///
/// Errors: [`Error::Step`] (no entity) naming the line of the first syntax error: a file that
/// does not start with `ISO-10303-21;`, has no `DATA` section, a malformed token or instance, a
/// list nested deeper than [`MAX_DEPTH`], an instance number used twice.
pub fn parse(text: &str) -> Result<Part21> {
    let mut p = Parser {
        lex: Lexer::new(text),
        ahead: None,
    };
    match p.bump()? {
        Some(Tok::Keyword(k)) if k == "ISO-10303-21" => p.expect(Tok::Semicolon, "`;`")?,
        _ => {
            return Err(syntax(
                1,
                "not a STEP file (no `ISO-10303-21;` at the start)",
            ))
        }
    }
    let mut out = Part21::default();
    let mut data_sections = 0;
    loop {
        let line = p.lex.line;
        match p.bump()? {
            Some(Tok::Keyword(k)) if k == "END-ISO-10303-21" => break,
            Some(Tok::Keyword(k)) if k == "DATA" => {
                p.skip_statement()?;
                data_sections += 1;
                data_section(&mut p, &mut out)?;
            }
            // HEADER, its entries, ENDSEC and other sections' statements.
            Some(_) => p.skip_statement()?,
            None => return Err(syntax(line, "no `END-ISO-10303-21;`")),
        }
    }
    if data_sections == 0 {
        return Err(syntax(p.lex.line, "no DATA section"));
    }
    Ok(out)
}

/// The instances of one DATA section, up to its `ENDSEC;`.
fn data_section(p: &mut Parser<'_>, out: &mut Part21) -> Result<()> {
    loop {
        let line = p.lex.line;
        match p.bump()? {
            Some(Tok::Keyword(k)) if k == "ENDSEC" => {
                return p.expect(Tok::Semicolon, "`;` after ENDSEC");
            }
            Some(Tok::Ref(id)) => {
                p.expect(Tok::Equals, "`=` after an instance name")?;
                let line = p.lex.line;
                let inst = match p.bump()? {
                    Some(Tok::Keyword(name)) => Instance::Simple(p.record(name)?),
                    Some(Tok::Open) => {
                        let mut parts = Vec::new();
                        loop {
                            let line = p.lex.line;
                            match p.bump()? {
                                Some(Tok::Close) => break,
                                Some(Tok::Keyword(name)) => parts.push(p.record(name)?),
                                t => {
                                    return Err(syntax(
                                        line,
                                        format!("expected a partial record, found {t:?}"),
                                    ))
                                }
                            }
                        }
                        Instance::Complex(parts)
                    }
                    t => return Err(syntax(line, format!("expected a record, found {t:?}"))),
                };
                p.expect(Tok::Semicolon, "`;` after an instance")?;
                if out.instances.insert(id, inst).is_some() {
                    return Err(Error::Step {
                        entity: Some(id),
                        message: format!("line {line}: instance #{id} is defined twice"),
                    });
                }
                out.order.push(id);
            }
            Some(t) => return Err(syntax(line, format!("expected an instance, found {t:?}"))),
            None => return Err(syntax(line, "unterminated DATA section")),
        }
    }
}
