//! The syntax of an ISO 10303-21 exchange structure, as far as the STEP reader needs it: a
//! tokenizer (keywords, entity references, numbers, strings, enumerations, binaries, `$`,
//! `*`, punctuation; comments skipped) and a parser of instances `#id = KEYWORD(...)` and
//! complex instances `#id = (A(...) B(...))` into nested parameter values, with the nesting
//! bounded. The entities' meaning is the reader's (`super`).

use super::super::{FileError, MAX_NESTING, malformed};

/// A token of the exchange structure.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Token<'a> {
    /// `ISO-10303-21`.
    Magic,
    /// `END-ISO-10303-21`.
    EndMagic,
    Keyword(&'a str),
    /// `#N`.
    Ref(u64),
    /// A number without a point or exponent.
    Integer(i64),
    Real(f64),
    /// A string's raw text (quotes doubled inside); only skipped.
    Str,
    /// `.NAME.`
    Enumeration(&'a str),
    /// `"…"` hex binary; only skipped.
    Binary,
    /// `$`
    Missing,
    /// `*`
    Derived,
    Open,
    Close,
    Comma,
    Equals,
    Semicolon,
}

/// The tokenizer: whitespace and `/* … */` comments between tokens.
pub(super) struct Lexer<'a> {
    text: &'a str,
    position: usize,
    line: usize,
}

impl<'a> Lexer<'a> {
    pub(super) fn new(text: &'a str) -> Self {
        Lexer {
            text,
            position: 0,
            line: 1,
        }
    }

    pub(super) fn bytes(&self) -> &'a [u8] {
        self.text.as_bytes()
    }

    /// Skips whitespace and comments.
    pub(super) fn skip_blank(&mut self) -> Result<(), FileError> {
        let bytes = self.bytes();
        loop {
            match bytes.get(self.position) {
                Some(b'\n') => {
                    self.line += 1;
                    self.position += 1;
                }
                Some(b) if b.is_ascii_whitespace() => self.position += 1,
                Some(b'/') if bytes.get(self.position + 1) == Some(&b'*') => {
                    let start_line = self.line;
                    let rest = &self.text[self.position + 2..];
                    let Some(end) = rest.find("*/") else {
                        return Err(malformed(start_line, "a comment is not closed"));
                    };
                    self.line += rest[..end].bytes().filter(|&b| b == b'\n').count();
                    self.position += end + 4;
                }
                _ => return Ok(()),
            }
        }
    }

    /// The next token, `None` at the end of the text.
    pub(super) fn next(&mut self) -> Result<Option<Token<'a>>, FileError> {
        self.skip_blank()?;
        let bytes = self.bytes();
        let start = self.position;
        let Some(&first) = bytes.get(start) else {
            return Ok(None);
        };
        let single = |token| Ok(Some(token));
        match first {
            b'(' => {
                self.position += 1;
                single(Token::Open)
            }
            b')' => {
                self.position += 1;
                single(Token::Close)
            }
            b',' => {
                self.position += 1;
                single(Token::Comma)
            }
            b'=' => {
                self.position += 1;
                single(Token::Equals)
            }
            b';' => {
                self.position += 1;
                single(Token::Semicolon)
            }
            b'$' => {
                self.position += 1;
                single(Token::Missing)
            }
            b'*' => {
                self.position += 1;
                single(Token::Derived)
            }
            b'\'' => self.string(),
            b'"' => {
                let rest = &self.text[start + 1..];
                let Some(end) = rest.find('"') else {
                    return Err(malformed(self.line, "a binary value is not closed"));
                };
                self.position = start + end + 2;
                single(Token::Binary)
            }
            b'#' => {
                let digits = self.take_while(start + 1, |b| b.is_ascii_digit());
                let id = self.text[start + 1..digits]
                    .parse::<u64>()
                    .map_err(|_| malformed(self.line, "an entity name must be # and digits"))?;
                self.position = digits;
                single(Token::Ref(id))
            }
            b'.' if bytes
                .get(start + 1)
                .is_some_and(|b| b.is_ascii_alphabetic() || *b == b'_') =>
            {
                let end = self.take_while(start + 1, |b| b.is_ascii_alphanumeric() || b == b'_');
                if bytes.get(end) != Some(&b'.') {
                    return Err(malformed(self.line, "an enumeration must end with ."));
                }
                self.position = end + 1;
                single(Token::Enumeration(&self.text[start + 1..end]))
            }
            b'+' | b'-' | b'.' | b'0'..=b'9' => self.number(),
            b if b.is_ascii_alphabetic() || b == b'!' || b == b'_' => {
                for (magic, token) in [
                    ("ISO-10303-21", Token::Magic),
                    ("END-ISO-10303-21", Token::EndMagic),
                ] {
                    if self.text[start..].starts_with(magic) {
                        self.position = start + magic.len();
                        return single(token);
                    }
                }
                let end = self.take_while(start + 1, |b| b.is_ascii_alphanumeric() || b == b'_');
                self.position = end;
                single(Token::Keyword(&self.text[start..end]))
            }
            _ => Err(malformed(
                self.line,
                format!(
                    "unexpected character {:?}",
                    self.text[start..].chars().next().unwrap_or('?')
                ),
            )),
        }
    }

    /// The end of the run of bytes from `from` that satisfy `accept`.
    pub(super) fn take_while(&self, from: usize, accept: impl Fn(u8) -> bool) -> usize {
        from + self.bytes()[from..]
            .iter()
            .take_while(|&&b| accept(b))
            .count()
    }

    /// A string `'…'` (a quote inside is doubled).
    pub(super) fn string(&mut self) -> Result<Option<Token<'a>>, FileError> {
        let bytes = self.bytes();
        let start_line = self.line;
        let mut i = self.position + 1;
        loop {
            match bytes.get(i) {
                None => return Err(malformed(start_line, "a string is not closed")),
                Some(b'\'') if bytes.get(i + 1) == Some(&b'\'') => i += 2,
                Some(b'\'') => break,
                Some(b'\n') => {
                    self.line += 1;
                    i += 1;
                }
                Some(_) => i += 1,
            }
        }
        self.position = i + 1;
        Ok(Some(Token::Str))
    }

    /// An integer or a real: `[sign] digits [. digits] [E [sign] digits]`.
    pub(super) fn number(&mut self) -> Result<Option<Token<'a>>, FileError> {
        let bytes = self.bytes();
        let start = self.position;
        let mut i = start;
        if matches!(bytes.get(i), Some(b'+' | b'-')) {
            i += 1;
        }
        let digits_start = i;
        i = self.take_while(i, |b| b.is_ascii_digit());
        let mut is_real = false;
        if bytes.get(i) == Some(&b'.') {
            is_real = true;
            i = self.take_while(i + 1, |b| b.is_ascii_digit());
        }
        if i == digits_start || bytes[digits_start] == b'.' {
            return Err(malformed(self.line, "a number must start with a digit"));
        }
        if matches!(bytes.get(i), Some(b'E' | b'e')) {
            is_real = true;
            i += 1;
            if matches!(bytes.get(i), Some(b'+' | b'-')) {
                i += 1;
            }
            let exponent_start = i;
            i = self.take_while(i, |b| b.is_ascii_digit());
            if i == exponent_start {
                return Err(malformed(self.line, "a number's exponent has no digits"));
            }
        }
        self.position = i;
        let text = &self.text[start..i];
        if is_real {
            let value: f64 = text
                .parse()
                .map_err(|_| malformed(self.line, format!("{text} is not a number")))?;
            if !value.is_finite() {
                return Err(malformed(
                    self.line,
                    format!("{text} is beyond the range of doubles"),
                ));
            }
            Ok(Some(Token::Real(value)))
        } else {
            let value: i64 = text
                .parse()
                .map_err(|_| malformed(self.line, format!("the integer {text} is too large")))?;
            Ok(Some(Token::Integer(value)))
        }
    }
}

/// A parameter value.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Value<'a> {
    /// `$`, `*`, a string, a binary: present, never read.
    Other,
    Integer(i64),
    Real(f64),
    Enumeration(&'a str),
    Ref(u64),
    /// `KEYWORD(value)`.
    Typed(&'a str, Box<Value<'a>>),
    List(Vec<Value<'a>>),
}

/// One record of an instance: `KEYWORD(parameters)`.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Record<'a> {
    pub(super) keyword: &'a str,
    pub(super) parameters: Vec<Value<'a>>,
}

/// The parser over the token stream, with one token of look-ahead.
pub(super) struct Parser<'a> {
    lexer: Lexer<'a>,
    peeked: Option<Option<Token<'a>>>,
}

impl<'a> Parser<'a> {
    /// A parser at the start of `text`.
    pub(super) fn new(text: &'a str) -> Self {
        Parser {
            lexer: Lexer::new(text),
            peeked: None,
        }
    }

    pub(super) fn line(&self) -> usize {
        self.lexer.line
    }

    pub(super) fn peek(&mut self) -> Result<Option<Token<'a>>, FileError> {
        if self.peeked.is_none() {
            self.peeked = Some(self.lexer.next()?);
        }
        Ok(self.peeked.flatten())
    }

    pub(super) fn next(&mut self) -> Result<Option<Token<'a>>, FileError> {
        match self.peeked.take() {
            Some(token) => Ok(token),
            None => self.lexer.next(),
        }
    }

    /// The next token, which the file must have.
    pub(super) fn required(&mut self, what: &str) -> Result<Token<'a>, FileError> {
        self.next()?.ok_or_else(|| {
            malformed(
                self.line(),
                format!("the file ends where {what} was expected (truncated?)"),
            )
        })
    }

    pub(super) fn expect(&mut self, token: Token<'a>, what: &str) -> Result<(), FileError> {
        let found = self.required(what)?;
        if found != token {
            return Err(malformed(
                self.line(),
                format!("expected {what}, found {}", describe(found)),
            ));
        }
        Ok(())
    }

    pub(super) fn expect_keyword(&mut self, keyword: &str) -> Result<(), FileError> {
        match self.required(keyword)? {
            Token::Keyword(k) if k.eq_ignore_ascii_case(keyword) => Ok(()),
            other => Err(malformed(
                self.line(),
                format!("expected {keyword}, found {}", describe(other)),
            )),
        }
    }

    /// `( value, … )` after the opening parenthesis was read.
    pub(super) fn list(&mut self, depth: usize) -> Result<Vec<Value<'a>>, FileError> {
        if depth > MAX_NESTING {
            return Err(FileError::TooDeep { line: self.line() });
        }
        let mut values = Vec::new();
        if self.peek()? == Some(Token::Close) {
            self.next()?;
            return Ok(values);
        }
        loop {
            values.push(self.value(depth)?);
            match self.required(") or ,")? {
                Token::Comma => {}
                Token::Close => return Ok(values),
                other => {
                    return Err(malformed(
                        self.line(),
                        format!("expected , or ), found {}", describe(other)),
                    ));
                }
            }
        }
    }

    pub(super) fn value(&mut self, depth: usize) -> Result<Value<'a>, FileError> {
        Ok(match self.required("a parameter")? {
            Token::Missing | Token::Derived | Token::Str | Token::Binary => Value::Other,
            Token::Integer(value) => Value::Integer(value),
            Token::Real(value) => Value::Real(value),
            Token::Enumeration(name) => Value::Enumeration(name),
            Token::Ref(id) => Value::Ref(id),
            Token::Open => Value::List(self.list(depth + 1)?),
            Token::Keyword(keyword) => {
                self.expect(Token::Open, "( after a type name")?;
                if depth + 1 > MAX_NESTING {
                    return Err(FileError::TooDeep { line: self.line() });
                }
                let inner = self.value(depth + 1)?;
                self.expect(Token::Close, ") after a typed value")?;
                Value::Typed(keyword, Box::new(inner))
            }
            other => {
                return Err(malformed(
                    self.line(),
                    format!("expected a parameter, found {}", describe(other)),
                ));
            }
        })
    }

    /// `KEYWORD ( parameters )` whose keyword was read.
    pub(super) fn record(&mut self, keyword: &'a str) -> Result<Record<'a>, FileError> {
        self.expect(Token::Open, "( after an entity name")?;
        let parameters = self.list(1)?;
        Ok(Record {
            keyword,
            parameters,
        })
    }
}

/// A token as an error message names it.
pub(super) fn describe(token: Token<'_>) -> String {
    match token {
        Token::Magic => "ISO-10303-21".into(),
        Token::EndMagic => "END-ISO-10303-21".into(),
        Token::Keyword(k) => k.into(),
        Token::Ref(id) => format!("#{id}"),
        Token::Integer(v) => v.to_string(),
        Token::Real(v) => v.to_string(),
        Token::Str => "a string".into(),
        Token::Enumeration(e) => format!(".{e}."),
        Token::Binary => "a binary value".into(),
        Token::Missing => "$".into(),
        Token::Derived => "*".into(),
        Token::Open => "(".into(),
        Token::Close => ")".into(),
        Token::Comma => ",".into(),
        Token::Equals => "=".into(),
        Token::Semicolon => ";".into(),
    }
}
