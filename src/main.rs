//! The knotshape binary.
fn main() {}
