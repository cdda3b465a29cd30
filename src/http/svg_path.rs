//! The SVG path `d` string of a planar, non-rational curve of degree 1, 2 or 3: `M` to the
//! first point, then one `L`, `Q` or `C` command per Bézier piece (a new `M` after a jump).

use crate::spline::{BezierPiece, Curve, Dimension};

/// The path of `pieces` (the curve's Bézier pieces, in order), or `None` when SVG cannot
/// draw the curve exactly: 3D, rational, or of degree above 3.
///
/// Numbers are written as the shortest text that reads back as the same double ([`number`]).
/// Each piece's first point is its predecessor's last and is not repeated, except after a
/// knot of multiplicity `degree + 1`, where the curve jumps: there a new `M` starts.
pub fn svg_path(curve: &Curve, pieces: &[BezierPiece]) -> Option<String> {
    let command = match curve.degree() {
        1 => 'L',
        2 => 'Q',
        3 => 'C',
        _ => return None,
    };
    if curve.dimension() != Dimension::Two || curve.is_rational() {
        return None;
    }
    let jumps = curve.jump_knots();
    let mut path = String::with_capacity(pieces.len() * (curve.degree() * 24 + 2) + 24);
    for (index, piece) in pieces.iter().enumerate() {
        let mut points = piece.control_points();
        let Some(first) = points.next() else {
            continue;
        };
        if index == 0 || jumps.contains(&piece.domain.0) {
            if index > 0 {
                path.push(' ');
            }
            path.push('M');
            push_pair(&mut path, first);
        }
        path.push(' ');
        path.push(command);
        for point in points {
            push_pair(&mut path, point);
        }
    }
    Some(path)
}

/// Appends ` x y`.
fn push_pair(path: &mut String, point: [f64; 3]) {
    for value in &point[..2] {
        path.push(' ');
        path.push_str(&number(*value));
    }
}

/// The shortest text that reads back as `value`: Rust's `Display` and `LowerExp` of `f64`
/// both write the fewest digits that round-trip, the first without an exponent (whole
/// numbers without `.0`), the second with one (`1e300`, `1e-7`, which SVG's number grammar
/// accepts); the shorter is taken, and both zeros are `0`. Precondition: `value` is finite.
pub fn number(value: f64) -> String {
    if value == 0.0 {
        return "0".to_owned();
    }
    let plain = value.to_string();
    let exponent = format!("{value:e}");
    if exponent.len() < plain.len() {
        exponent
    } else {
        plain
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_short_and_read_back_exactly() {
        for (value, text) in [
            (0.0, "0"),
            (-0.0, "0"),
            (1.0, "1"),
            (-3.0, "-3"),
            (0.1, "0.1"),
            (1.5, "1.5"),
        ] {
            assert_eq!(number(value), text);
        }
        for value in [
            0.1 + 0.2,
            1e300,
            -1e-7,
            123456789.125,
            f64::MAX,
            f64::MIN_POSITIVE,
            5e-324,
            2.0f64.powi(60),
        ] {
            let text = number(value);
            assert_eq!(text.parse::<f64>().unwrap(), value, "{text}");
            assert!(text.len() <= 24, "{text}");
        }
    }
}
