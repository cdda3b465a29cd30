//! Small fixed-size vector helpers: points are `[f64; 3]` (2D curves keep `z = 0`).

/// A point or vector in 3D; 2D curves store `z = 0`.
pub type Point = [f64; 3];

/// `a + b`.
#[inline]
pub fn add(a: Point, b: Point) -> Point {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// `a - b`.
#[inline]
pub fn sub(a: Point, b: Point) -> Point {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `s · a`.
#[inline]
pub fn scale(a: Point, s: f64) -> Point {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// Dot product `a · b`.
#[inline]
pub fn dot(a: Point, b: Point) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Cross product `a × b`.
#[inline]
pub fn cross(a: Point, b: Point) -> Point {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Euclidean length `|a|`.
#[inline]
pub fn norm(a: Point) -> f64 {
    dot(a, a).sqrt()
}

/// Euclidean distance `|a - b|`.
#[inline]
pub fn distance(a: Point, b: Point) -> f64 {
    norm(sub(a, b))
}
