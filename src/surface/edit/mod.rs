//! Editing a surface's shape: move a surface point `S(ũ, ṽ)` onto a target (docs/method.md
//! §41–§48).

pub mod knots;
