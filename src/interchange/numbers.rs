//! Numbers as STEP and DXF write them.

/// `value` (finite) in the fewest digits that read back to the same double (at most 17
/// significant digits), as `d.dddE±x`: STEP's REAL syntax (a point in the mantissa) that DXF
/// readers take too.
pub fn real(value: f64) -> String {
    // `{:e}` is Rust's shortest round-trip form in scientific notation: `1.25e-7`, `3e0`.
    let shortest = format!("{value:e}");
    let (mantissa, exponent) = shortest.split_once('e').unwrap_or((&shortest, "0"));
    let point = if mantissa.contains('.') { "" } else { "." };
    format!("{mantissa}{point}E{exponent}")
}

#[cfg(test)]
mod tests {
    use super::real;

    #[test]
    fn reals_read_back_exactly_and_always_have_a_point() {
        for value in [
            0.0,
            -0.0,
            1.0,
            -2.5,
            0.1,
            1.0 / 3.0,
            std::f64::consts::TAU,
            1e-300,
            f64::MAX,
            f64::MIN_POSITIVE,
            5e-324,
            123456789.0,
        ] {
            let text = real(value);
            assert!(text.contains('.') && text.contains('E'), "{text}");
            let back: f64 = text.parse().unwrap();
            assert_eq!(back.to_bits(), value.to_bits(), "{text}");
        }
        assert_eq!(real(1.0), "1.E0");
        assert_eq!(real(-0.125), "-1.25E-1");
    }
}
