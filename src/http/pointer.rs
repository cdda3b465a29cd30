//! JSON Pointers (RFC 6901) into request bodies, for naming the offending field of an error.

use std::fmt;

/// A JSON Pointer such as `/curve/knots/4`, built token by token (tokens are escaped).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct JsonPointer(String);

impl JsonPointer {
    /// The pointer to the whole document (the empty string).
    pub fn root() -> Self {
        JsonPointer(String::new())
    }

    /// This pointer extended by an object key or array index.
    pub fn push(mut self, token: impl fmt::Display) -> Self {
        self.0.push('/');
        let token = token.to_string();
        self.0
            .push_str(&token.replace('~', "~0").replace('/', "~1"));
        self
    }
}

impl fmt::Display for JsonPointer {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl From<&str> for JsonPointer {
    /// A pointer from `/`-separated unescaped tokens, e.g. `"/curve/knots"`.
    fn from(path: &str) -> Self {
        path.split('/')
            .filter(|token| !token.is_empty())
            .fold(JsonPointer::root(), JsonPointer::push)
    }
}

/// The pointer to where serde failed. For a missing field, serde reports the enclosing
/// object; the field's name, taken from the message, is appended so the pointer names it.
pub fn pointer_from_serde_path(path: &serde_path_to_error::Path, message: &str) -> JsonPointer {
    use serde_path_to_error::Segment;
    let mut pointer = JsonPointer::root();
    for segment in path.iter() {
        pointer = match segment {
            Segment::Seq { index } => pointer.push(index),
            Segment::Map { key } => pointer.push(key),
            Segment::Enum { variant } => pointer.push(variant),
            Segment::Unknown => pointer,
        };
    }
    if let Some(field) = message
        .strip_prefix("missing field `")
        .and_then(|rest| rest.split('`').next())
    {
        pointer = pointer.push(field);
    }
    pointer
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tokens_are_escaped() {
        let pointer = JsonPointer::root().push("a/b").push("m~n").push(3);
        assert_eq!(pointer.to_string(), "/a~1b/m~0n/3");
    }

    #[test]
    fn pointers_parse_from_slash_paths() {
        assert_eq!(
            JsonPointer::from("/curve/knots").push(4).to_string(),
            "/curve/knots/4"
        );
        assert_eq!(JsonPointer::from("").to_string(), "");
    }
}
