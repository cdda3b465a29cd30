//! DXF `SPLINE` entities (ASCII DXF): control points, knots and weights read from the
//! `ENTITIES` and `BLOCKS` sections, and written in a minimal DXF R2000 file.
//!
//! Hand-written, on purpose: the DXF crate of the field (`dxf`, which reads whole drawings)
//! panicked on 9 of 20,000 mutated copies of a file it had written itself (a header date out
//! of range overflows chrono's arithmetic), and a service must not panic on a client's file.
//! DXF's structure is flat (group code, value; one line each), so a reader of the few group
//! codes a spline has is short and bounded by the text.
//!
//! Group codes of `SPLINE` (AutoCAD's DXF reference): `5` handle, `70` flags (4 rational),
//! `71` degree, `72`/`73`/`74` counts of knots, control points and fit points, `40` knot,
//! `41` weight, `10`/`20`/`30` control point, `11`/`21`/`31` fit point. Control points are 3D
//! (world coordinates). A spline with fit points only is counted as skipped, as are the other
//! curve entities (`LINE`, `ARC`, `CIRCLE`, `ELLIPSE`, `LWPOLYLINE`, `POLYLINE`, `HELIX`,
//! `RAY`, `XLINE`).

use super::numbers::real;
use super::{
    FileError, FileLimits, Imported, ImportedCurve, check_size, exportable_curve, exportable_knots,
    malformed,
};
use crate::spline::{Curve, KnotForm};

/// Curve entities that are counted as skipped.
const OTHER_CURVES: &[&str] = &[
    "LINE",
    "ARC",
    "CIRCLE",
    "ELLIPSE",
    "LWPOLYLINE",
    "POLYLINE",
    "HELIX",
    "RAY",
    "XLINE",
];

/// One group: its code, its value (trimmed) and the line of the code.
#[derive(Debug, Clone, Copy)]
struct Group<'a> {
    code: i32,
    value: &'a str,
    line: usize,
}

/// The groups of a DXF text, pair by pair.
struct Groups<'a> {
    lines: std::str::Lines<'a>,
    line: usize,
}

impl<'a> Iterator for Groups<'a> {
    type Item = Result<Group<'a>, FileError>;

    fn next(&mut self) -> Option<Self::Item> {
        let code = self.lines.next()?;
        let line = self.line + 1;
        self.line += 2;
        let Some(value) = self.lines.next() else {
            return Some(Err(malformed(
                line,
                "the file ends after a group code (truncated?)",
            )));
        };
        let code = match code.trim().parse::<i32>() {
            Ok(code) => code,
            Err(_) => {
                return Some(Err(malformed(
                    line,
                    format!("expected a group code, found {:?}", truncated(code)),
                )));
            }
        };
        Some(Ok(Group {
            code,
            value: value.trim(),
            line,
        }))
    }
}

/// At most 40 characters of a text, for a message.
fn truncated(text: &str) -> String {
    text.trim().chars().take(40).collect()
}

/// A spline as its groups give it.
#[derive(Default)]
struct SplineGroups {
    line: usize,
    handle: Option<String>,
    flags: i64,
    degree: Option<i64>,
    knot_count: Option<i64>,
    control_count: Option<i64>,
    knots: Vec<f64>,
    weights: Vec<f64>,
    points: Vec<[f64; 3]>,
    fit_points: usize,
}

impl SplineGroups {
    /// Takes one group of the entity.
    fn take(&mut self, group: Group<'_>) -> Result<(), FileError> {
        let number = || -> Result<f64, FileError> {
            let value: f64 = group.value.parse().map_err(|_| {
                malformed(
                    group.line + 1,
                    format!(
                        "group {} needs a number, found {:?}",
                        group.code,
                        truncated(group.value)
                    ),
                )
            })?;
            if value.is_finite() {
                Ok(value)
            } else {
                Err(malformed(group.line + 1, "numbers must be finite"))
            }
        };
        let integer = || -> Result<i64, FileError> {
            group.value.parse().map_err(|_| {
                malformed(
                    group.line + 1,
                    format!(
                        "group {} needs an integer, found {:?}",
                        group.code,
                        truncated(group.value)
                    ),
                )
            })
        };
        match group.code {
            5 => self.handle = Some(group.value.to_owned()),
            70 => self.flags = integer()?,
            71 => self.degree = Some(integer()?),
            72 => self.knot_count = Some(integer()?),
            73 => self.control_count = Some(integer()?),
            40 => self.knots.push(number()?),
            41 => self.weights.push(number()?),
            10 => self.points.push([number()?, 0.0, 0.0]),
            20 | 30 => {
                let axis = (group.code / 10 - 1) as usize;
                let Some(point) = self.points.last_mut() else {
                    return Err(malformed(
                        group.line,
                        "a control point's y or z before its x",
                    ));
                };
                point[axis] = number()?;
            }
            11 => self.fit_points += 1,
            _ => {}
        }
        Ok(())
    }

    /// The curve, `None` for a spline given by fit points only.
    fn curve(self, limits: &FileLimits) -> Result<Option<ImportedCurve>, FileError> {
        let source = self
            .handle
            .clone()
            .unwrap_or_else(|| format!("line {}", self.line));
        if self.points.is_empty() && self.fit_points > 0 {
            return Ok(None);
        }
        let line = self.line;
        let bad = |what: String| malformed(line, format!("SPLINE {source}: {what}"));
        if let Some(count) = self.knot_count {
            if count != self.knots.len() as i64 {
                return Err(bad(format!(
                    "group 72 announces {count} knots, {} are given",
                    self.knots.len()
                )));
            }
        }
        if let Some(count) = self.control_count {
            if count != self.points.len() as i64 {
                return Err(bad(format!(
                    "group 73 announces {count} control points, {} are given",
                    self.points.len()
                )));
            }
        }
        let degree = match self.degree {
            Some(d) if d >= 0 => d as usize,
            _ => return Err(bad("needs its degree (group 71)".into())),
        };
        let rational = self.flags & 4 != 0;
        let weights = match (rational, self.weights.len()) {
            (_, 0) => None,
            (_, count) if count == self.points.len() => Some(self.weights),
            (_, count) => {
                return Err(bad(format!(
                    "{count} weights (group 41) for {} control points",
                    self.points.len()
                )));
            }
        };
        let curve = Curve::from_knot_form(
            degree,
            &self.points,
            KnotForm::Flat(&self.knots),
            weights.as_deref(),
            &limits.curve_limits,
        )
        .map_err(|error| FileError::InvalidCurve {
            entity: source.clone(),
            error,
        })?;
        Ok(Some(ImportedCurve { curve, source }))
    }
}

/// What the reader is inside of.
enum Entity {
    None,
    Spline(Box<SplineGroups>),
    Other,
}

/// Reads every `SPLINE` of an ASCII DXF file (its `ENTITIES` and `BLOCKS` sections).
pub fn read(text: &str, limits: &FileLimits) -> Result<Imported, FileError> {
    check_size(text, limits)?;
    if text.starts_with("AutoCAD Binary DXF") {
        return Err(malformed(
            1,
            "binary DXF is not supported; send an ASCII DXF",
        ));
    }
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut groups = Groups {
        lines: text.lines(),
        line: 0,
    };
    let mut curves = Vec::new();
    let mut skipped = 0;
    let mut entities = 0usize;
    let mut section: Option<String> = None;
    let mut expect_section_name = false;
    let mut entity = Entity::None;
    let mut ended = false;
    for group in groups.by_ref() {
        let group = group?;
        if expect_section_name {
            if group.code != 2 {
                return Err(malformed(group.line, "a SECTION needs its name (group 2)"));
            }
            section = Some(group.value.to_ascii_uppercase());
            expect_section_name = false;
            continue;
        }
        if group.code != 0 {
            if let Entity::Spline(spline) = &mut entity {
                spline.take(group)?;
            }
            continue;
        }
        // Group 0 ends the entity before it.
        if let Entity::Spline(spline) = std::mem::replace(&mut entity, Entity::None) {
            match spline.curve(limits)? {
                Some(curve) => curves.push(curve),
                None => skipped += 1,
            }
        }
        let name = group.value.to_ascii_uppercase();
        match (name.as_str(), section.as_deref()) {
            ("EOF", None) => {
                ended = true;
                break;
            }
            ("SECTION", None) => expect_section_name = true,
            ("SECTION", Some(_)) => {
                return Err(malformed(
                    group.line,
                    "a SECTION inside a SECTION (ENDSEC missing)",
                ));
            }
            ("ENDSEC", Some(_)) => section = None,
            (_, None) => {
                return Err(malformed(
                    group.line,
                    format!("{} outside a SECTION", truncated(group.value)),
                ));
            }
            (_, Some(section)) => {
                entities += 1;
                if entities > limits.max_entities {
                    return Err(FileError::TooManyEntities {
                        max: limits.max_entities,
                    });
                }
                if section == "ENTITIES" || section == "BLOCKS" {
                    entity = if name == "SPLINE" {
                        Entity::Spline(Box::new(SplineGroups {
                            line: group.line + 1,
                            ..SplineGroups::default()
                        }))
                    } else {
                        if OTHER_CURVES.contains(&name.as_str()) {
                            skipped += 1;
                        }
                        Entity::Other
                    };
                }
            }
        }
    }
    if !ended {
        return Err(malformed(
            groups.line.max(1),
            "the file ends without 0/EOF (truncated?)",
        ));
    }
    Ok(Imported {
        curves,
        surfaces: Vec::new(),
        skipped,
    })
}

/// Fewest decimals of a written knot tolerance: `1e-10`, what ezdxf writes itself.
const MIN_KNOT_TOLERANCE_DECIMALS: usize = 10;

/// Most decimals of a written knot tolerance: `1e-300` is still a normal double, and its
/// logarithm is exact in the readers' libraries (knots that would need more, below about
/// `1e-283` in magnitude, may be rounded by a reader that honours the tolerance).
const MAX_KNOT_TOLERANCE_DECIMALS: usize = 300;

/// The knot tolerance written as group 42 of a `SPLINE` with `knots`, as its number of
/// decimals `n` (the tolerance is `10⁻ⁿ`): the fewest, at least
/// [`MIN_KNOT_TOLERANCE_DECIMALS`], such that
///
/// * every knot rounded to `n` decimals reads back as the same double: a reader that
///   rounds the knots to the tolerance's decimals (ezdxf's `construction_tool()`:
///   `round(k, -int(log10(tolerance)))`) keeps them as written;
/// * `10⁻ⁿ` is at most a tenth of the smallest gap between distinct knots: a reader that
///   takes knots closer than the tolerance as equal merges none.
///
/// A fixed `1e-7` (written before) rounded the knots of 30 of 30 random curves in ezdxf and
/// moved their points by up to `2e-6` of the size.
fn knot_tolerance_decimals(knots: &[f64]) -> usize {
    let kept = |n: usize| {
        knots
            .iter()
            .all(|&k| format!("{k:.n$}").parse::<f64>() == Ok(k))
    };
    // The decimals of the shortest round-trip form, `d.ddd e x`: digits after the point
    // minus the exponent.
    let shortest = knots
        .iter()
        .map(|k| {
            let text = format!("{k:e}");
            let (mantissa, exponent) = text.split_once('e').unwrap_or((&text, "0"));
            let fraction = mantissa.split_once('.').map_or(0, |(_, f)| f.len());
            let exponent: i64 = exponent.parse().unwrap_or(0);
            usize::try_from(fraction as i64 - exponent).unwrap_or(0)
        })
        .max()
        .unwrap_or(0);
    let smallest_gap = knots
        .windows(2)
        .map(|w| w[1] - w[0])
        .filter(|&gap| gap > 0.0)
        .fold(f64::INFINITY, f64::min);
    let gap_decimals = if smallest_gap.is_finite() {
        // 10⁻ⁿ <= gap / 10.
        (1.0 - smallest_gap.log10()).ceil().max(0.0) as usize
    } else {
        0
    };
    let mut n = shortest
        .max(gap_decimals)
        .clamp(MIN_KNOT_TOLERANCE_DECIMALS, MAX_KNOT_TOLERANCE_DECIMALS);
    // The rounding to `n` decimals is the nearest such decimal to the knot, at least as
    // near as the shortest form; next to a power of two that may still read back one unit
    // off, so it is checked.
    while n < MAX_KNOT_TOLERANCE_DECIMALS && !kept(n) {
        n += 1;
    }
    n
}

/// A minimal DXF R2000 (`AC1015`) file with one `SPLINE` per curve in its `ENTITIES`
/// section: the full knot vector (`n + p + 2` values), the control points (`z = 0` for 2D
/// curves), weights for rational curves (flag 4); planar curves with flag 8 and normal
/// `(0, 0, 1)`. A periodic curve is written as the clamped curve over its period. Numbers in
/// full precision; the knot tolerance (group 42) small enough that readers keep the knots as
/// written ([`knot_tolerance_decimals`]).
pub fn write(curves: &[Curve]) -> String {
    let mut out = String::new();
    let mut pair = |code: i32, value: &str| {
        out.push_str(&format!("{code:>3}\n{value}\n"));
    };
    let first_handle = 0x100usize;
    pair(0, "SECTION");
    pair(2, "HEADER");
    pair(9, "$ACADVER");
    pair(1, "AC1015");
    pair(9, "$HANDSEED");
    pair(5, &format!("{:X}", first_handle + curves.len() + 1));
    pair(0, "ENDSEC");
    pair(0, "SECTION");
    pair(2, "ENTITIES");
    for (index, curve) in curves.iter().map(exportable_curve).enumerate() {
        let curve = &curve;
        let knots = exportable_knots(curve);
        let planar = curve.control_points().iter().all(|p| p[2] == 0.0);
        let flags = if planar { 8 } else { 0 } + if curve.is_rational() { 4 } else { 0 };
        pair(0, "SPLINE");
        pair(5, &format!("{:X}", first_handle + index));
        pair(100, "AcDbEntity");
        pair(8, "0");
        pair(100, "AcDbSpline");
        if planar {
            pair(210, "0.0");
            pair(220, "0.0");
            pair(230, "1.0");
        }
        pair(70, &flags.to_string());
        pair(71, &curve.degree().to_string());
        pair(72, &knots.len().to_string());
        pair(73, &curve.control_points().len().to_string());
        pair(74, "0");
        pair(42, &format!("1.E-{}", knot_tolerance_decimals(&knots)));
        pair(43, "0.0000001");
        for &u in &knots {
            pair(40, &real(u));
        }
        if let Some(weights) = curve.weights() {
            for &w in weights {
                pair(41, &real(w));
            }
        }
        for point in curve.control_points() {
            pair(10, &real(point[0]));
            pair(20, &real(point[1]));
            pair(30, &real(point[2]));
        }
    }
    pair(0, "ENDSEC");
    pair(0, "EOF");
    out
}

#[cfg(test)]
mod tests;
