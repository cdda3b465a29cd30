//! The regions Ω1–Ω6 as an SVG picture (`POST /v1/shape/regions` with
//! `Accept: image/svg+xml`): one panel per candidate side with its control triangle, the
//! regions in their colours, the picked point and the target, a panel of the weight pairs'
//! quadrilaterals when they were asked for, and a legend.
//!
//! [`render`] is pure (the JSON answer in, text out); `regions_media` chooses between it and
//! JSON by the request's `Accept` header. Each polygon's `points` are the JSON
//! answer's coordinates (x and y), written as the shortest text that reads back as the same
//! double, and mapped onto the panel by the group's `transform`, so a client reading the
//! picture gets exactly the JSON numbers.

use super::svg_path::number;
use super::wire::shape_answer::RegionsResponse;
use super::wire::shape_request::{CandidateSide, Region};

/// The picture's media type.
pub const SVG: &str = "image/svg+xml";

/// Width and height of one panel (SVG user units, pixels at scale 1).
const PANEL: f64 = 360.0;
/// Space around the drawing inside a panel, and above it for the panel's title.
const MARGIN: f64 = 24.0;
/// Height of the legend strip under the panels.
const LEGEND: f64 = 28.0;
/// Radius of the picked point and the target, in pixels.
const DOT_RADIUS: f64 = 4.5;
/// The colour of the weight pairs' regions (Okabe & Ito's reddish purple).
pub const WEIGHTS_COLOUR: &str = "#cc79a7";

/// The colour of each region (Okabe & Ito's colour-blind-safe palette; the editor uses the
/// same).
pub fn region_colour(region: Region) -> &'static str {
    match region {
        Region::Omega1 => "#e69f00",
        Region::Omega2 => "#56b4e9",
        Region::Omega3 => "#009e73",
        Region::Omega4 => "#f0e442",
        Region::Omega5 => "#0072b2",
        Region::Omega6 => "#d55e00",
    }
}

/// The region's name as drawn: `Ω1` … `Ω6`.
fn region_label(region: Region) -> &'static str {
    match region {
        Region::Omega1 => "Ω1",
        Region::Omega2 => "Ω2",
        Region::Omega3 => "Ω3",
        Region::Omega4 => "Ω4",
        Region::Omega5 => "Ω5",
        Region::Omega6 => "Ω6",
    }
}

/// What the picture shows: the regions answer, the picked curve point `s(t)` and the target
/// (x and y; a 3D curve is drawn in its x–y projection).
#[derive(Debug, Clone, Copy)]
pub struct Picture<'a> {
    /// The JSON answer of the same request.
    pub regions: &'a RegionsResponse,
    /// The picked parameter `t`.
    pub parameter: f64,
    /// `s(t)`.
    pub picked: [f64; 2],
    /// The request's target, when it has one.
    pub target: Option<[f64; 2]>,
}

/// A number of the picture is not finite (SVG has no NaN or infinity).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NonFinite;

/// The picture as SVG text; [`NonFinite`] when any coordinate (or the scale derived from
/// them) is not finite.
pub fn render(picture: &Picture<'_>) -> Result<String, NonFinite> {
    let weights = !picture.regions.weight_regions.is_empty();
    let panels = (picture.regions.candidates.len() + usize::from(weights)).max(1);
    let width = PANEL * panels as f64;
    let height = PANEL + LEGEND;
    let mut svg = String::with_capacity(4096);
    svg.push_str(&format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" \
         viewBox=\"0 0 {w} {h}\" font-family=\"sans-serif\" font-size=\"13\">\n",
        w = number(width),
        h = number(height),
    ));
    svg.push_str(&format!(
        "<title>Regions Ω1–Ω6 of the point at t = {}</title>\n",
        finite(picture.parameter)?
    ));
    svg.push_str(&format!(
        "<rect width=\"{}\" height=\"{}\" fill=\"#ffffff\"/>\n",
        number(width),
        number(height)
    ));
    for (index, entry) in picture.regions.candidates.iter().enumerate() {
        let candidate = &entry.candidate;
        let side = candidate.side.wire_name();
        let left = PANEL * index as f64;
        svg.push_str(&format!(
            "<g class=\"panel\" data-side=\"{side}\" transform=\"translate({} 0)\">\n",
            number(left)
        ));
        svg.push_str(&format!(
            "<rect x=\"0.5\" y=\"0.5\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#cccccc\"/>\n",
            number(PANEL - 1.0),
            number(PANEL - 1.0)
        ));
        svg.push_str(&format!(
            "<text x=\"8\" y=\"17\">{} side: knot {} moves to t</text>\n",
            side_title(candidate.side),
            candidate.moved_knot
        ));
        let triangle = candidate.triangle.as_ref().filter(|_| candidate.applicable);
        let Some(triangle) = triangle else {
            let reason = candidate
                .reason
                .as_deref()
                .unwrap_or("the side does not apply");
            svg.push_str(&format!(
                "<text x=\"8\" y=\"40\" fill=\"#b00020\">not applicable: {}</text>\n</g>\n",
                escape(reason)
            ));
            continue;
        };
        let triangle: Vec<[f64; 2]> = triangle.iter().map(|p| xy(p.as_slice())).collect();
        let mut extent = Extent::default();
        triangle.iter().for_each(|&p| extent.add(p));
        for region in &entry.regions {
            region
                .polygon
                .iter()
                .for_each(|p| extent.add(xy(p.as_slice())));
        }
        extent.add(picture.picked);
        if let Some(target) = picture.target {
            extent.add(target);
        }
        let frame = extent.fit()?;
        svg.push_str(&format!(
            "<g class=\"drawing\" transform=\"matrix({} 0 0 {} {} {})\">\n",
            finite(frame.scale)?,
            finite(-frame.scale)?,
            finite(frame.offset[0])?,
            finite(frame.offset[1])?
        ));
        for region in &entry.regions {
            let colour = region_colour(region.region);
            svg.push_str(&format!(
                "<polygon class=\"region\" data-side=\"{side}\" data-region=\"{}\" \
                 points=\"{}\" fill=\"{colour}\" fill-opacity=\"0.35\" stroke=\"{colour}\" \
                 stroke-width=\"1.5\" vector-effect=\"non-scaling-stroke\"/>\n",
                region.region.wire_name(),
                points(region.polygon.iter().map(|p| xy(p.as_slice())))?
            ));
        }
        svg.push_str(&format!(
            "<polygon class=\"triangle\" data-side=\"{side}\" points=\"{}\" fill=\"none\" \
             stroke=\"#222222\" stroke-width=\"1.5\" stroke-dasharray=\"5 3\" \
             vector-effect=\"non-scaling-stroke\"/>\n",
            points(triangle.iter().copied())?
        ));
        dots(&mut svg, picture, frame.scale)?;
        svg.push_str("</g>\n</g>\n");
    }
    if weights {
        weights_panel(
            &mut svg,
            picture,
            PANEL * picture.regions.candidates.len() as f64,
        )?;
    }
    legend(&mut svg, picture.regions, PANEL);
    svg.push_str("</svg>\n");
    Ok(svg)
}

/// The picked point and the target, inside a drawing of scale `scale`.
fn dots(svg: &mut String, picture: &Picture<'_>, scale: f64) -> Result<(), NonFinite> {
    let radius = finite(DOT_RADIUS / scale)?;
    svg.push_str(&format!(
        "<circle class=\"picked\" cx=\"{}\" cy=\"{}\" r=\"{radius}\" fill=\"#222222\"/>\n",
        finite(picture.picked[0])?,
        finite(picture.picked[1])?
    ));
    if let Some(target) = picture.target {
        svg.push_str(&format!(
            "<circle class=\"target\" cx=\"{}\" cy=\"{}\" r=\"{radius}\" fill=\"#ffffff\" \
             stroke=\"#b00020\" stroke-width=\"2\" vector-effect=\"non-scaling-stroke\"/>\n",
            finite(target[0])?,
            finite(target[1])?
        ));
    }
    Ok(())
}

/// The panel of the weight pairs: each pair's quadrilateral and its triangle `(s₀, d_k, d_l)`.
fn weights_panel(svg: &mut String, picture: &Picture<'_>, left: f64) -> Result<(), NonFinite> {
    let regions = &picture.regions.weight_regions;
    svg.push_str(&format!(
        "<g class=\"panel\" data-method=\"weights\" transform=\"translate({} 0)\">\n",
        number(left)
    ));
    svg.push_str(&format!(
        "<rect x=\"0.5\" y=\"0.5\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#cccccc\"/>\n",
        number(PANEL - 1.0),
        number(PANEL - 1.0)
    ));
    svg.push_str(&format!(
        "<text x=\"8\" y=\"17\">Weights: {} pairs of poles</text>\n",
        regions.len()
    ));
    let mut extent = Extent::default();
    for region in regions {
        region
            .polygon
            .iter()
            .chain(region.triangle.iter())
            .for_each(|p| extent.add(xy(p.as_slice())));
    }
    extent.add(picture.picked);
    if let Some(target) = picture.target {
        extent.add(target);
    }
    let frame = extent.fit()?;
    svg.push_str(&format!(
        "<g class=\"drawing\" transform=\"matrix({} 0 0 {} {} {})\">\n",
        finite(frame.scale)?,
        finite(-frame.scale)?,
        finite(frame.offset[0])?,
        finite(frame.offset[1])?
    ));
    for region in regions {
        let [k, l] = region.poles;
        svg.push_str(&format!(
            "<polygon class=\"triangle\" data-poles=\"{k} {l}\" points=\"{}\" fill=\"none\" \
             stroke=\"#888888\" stroke-width=\"1\" stroke-dasharray=\"3 3\" \
             vector-effect=\"non-scaling-stroke\"/>\n",
            points(region.triangle.iter().map(|p| xy(p.as_slice())))?
        ));
        svg.push_str(&format!(
            "<polygon class=\"region\" data-region=\"weights\" data-poles=\"{k} {l}\" \
             points=\"{}\" fill=\"{WEIGHTS_COLOUR}\" fill-opacity=\"0.2\" stroke=\"{WEIGHTS_COLOUR}\" \
             stroke-width=\"1.5\" vector-effect=\"non-scaling-stroke\"/>\n",
            points(region.polygon.iter().map(|p| xy(p.as_slice())))?
        ));
    }
    dots(svg, picture, frame.scale)?;
    svg.push_str("</g>\n</g>\n");
    Ok(())
}

/// The legend strip: a swatch per region drawn, then the picked point and the target.
fn legend(svg: &mut String, regions: &RegionsResponse, top: f64) {
    let mut drawn: Vec<Region> = Vec::new();
    for entry in &regions.candidates {
        for region in &entry.regions {
            if !drawn.contains(&region.region) {
                drawn.push(region.region);
            }
        }
    }
    drawn.sort_by_key(|region| region.wire_name());
    svg.push_str(&format!(
        "<g class=\"legend\" transform=\"translate(8 {})\">\n",
        number(top + 8.0)
    ));
    let mut x = 0.0;
    for region in drawn {
        svg.push_str(&format!(
            "<rect x=\"{x}\" y=\"0\" width=\"12\" height=\"12\" fill=\"{c}\" fill-opacity=\"0.6\" \
             stroke=\"{c}\"/><text x=\"{}\" y=\"11\">{}</text>\n",
            number(x + 16.0),
            region_label(region),
            x = number(x),
            c = region_colour(region),
        ));
        x += 48.0;
    }
    if !regions.weight_regions.is_empty() {
        svg.push_str(&format!(
            "<rect x=\"{x}\" y=\"0\" width=\"12\" height=\"12\" fill=\"{c}\" fill-opacity=\"0.6\" \
             stroke=\"{c}\"/><text x=\"{}\" y=\"11\">weights</text>\n",
            number(x + 16.0),
            x = number(x),
            c = WEIGHTS_COLOUR,
        ));
        x += 80.0;
    }
    svg.push_str(&format!(
        "<circle cx=\"{}\" cy=\"6\" r=\"4.5\" fill=\"#222222\"/><text x=\"{}\" y=\"11\">picked \
         point</text>\n<circle cx=\"{}\" cy=\"6\" r=\"4.5\" fill=\"#ffffff\" stroke=\"#b00020\" \
         stroke-width=\"2\"/><text x=\"{}\" y=\"11\">target</text>\n",
        number(x + 6.0),
        number(x + 16.0),
        number(x + 116.0),
        number(x + 126.0)
    ));
    svg.push_str("</g>\n");
}

fn side_title(side: CandidateSide) -> &'static str {
    match side {
        CandidateSide::Right => "Right",
        CandidateSide::Left => "Left",
    }
}

/// The bounding box of what a panel draws.
#[derive(Debug, Clone, Copy)]
struct Extent {
    low: [f64; 2],
    high: [f64; 2],
}

impl Default for Extent {
    fn default() -> Self {
        Extent {
            low: [f64::INFINITY; 2],
            high: [f64::NEG_INFINITY; 2],
        }
    }
}

/// The map from curve coordinates to a panel: `(x, y) ↦ (scale x + offset_x, -scale y +
/// offset_y)` (SVG's y points down).
#[derive(Debug, Clone, Copy)]
struct Fit {
    scale: f64,
    offset: [f64; 2],
}

impl Extent {
    fn add(&mut self, point: [f64; 2]) {
        for ((low, high), value) in self.low.iter_mut().zip(&mut self.high).zip(point) {
            *low = low.min(value);
            *high = high.max(value);
        }
    }

    /// The largest scale that fits the box into the panel below its title, centred.
    fn fit(&self) -> Result<Fit, NonFinite> {
        let size = [self.high[0] - self.low[0], self.high[1] - self.low[1]];
        let room = PANEL - 2.0 * MARGIN;
        let longest = size[0].max(size[1]);
        let scale = if longest > 0.0 { room / longest } else { 1.0 };
        if !(scale.is_finite() && scale > 0.0) {
            return Err(NonFinite);
        }
        let centre = [
            0.5 * (self.low[0] + self.high[0]),
            0.5 * (self.low[1] + self.high[1]),
        ];
        let offset = [
            0.5 * PANEL - scale * centre[0],
            MARGIN + 0.5 * (PANEL - MARGIN) + scale * centre[1],
        ];
        Ok(Fit { scale, offset })
    }
}

/// The x and y of a wire point (2 or 3 coordinates).
fn xy(point: &[f64]) -> [f64; 2] {
    [
        point.first().copied().unwrap_or(f64::NAN),
        point.get(1).copied().unwrap_or(f64::NAN),
    ]
}

/// `value` as the shortest round-trip text, or [`NonFinite`].
fn finite(value: f64) -> Result<String, NonFinite> {
    if value.is_finite() {
        Ok(number(value))
    } else {
        Err(NonFinite)
    }
}

/// An SVG `points` list: `x,y x,y …`.
fn points(vertices: impl Iterator<Item = [f64; 2]>) -> Result<String, NonFinite> {
    let mut text = String::new();
    for [x, y] in vertices {
        if !text.is_empty() {
            text.push(' ');
        }
        text.push_str(&finite(x)?);
        text.push(',');
        text.push_str(&finite(y)?);
    }
    Ok(text)
}

/// Text with XML's five special characters escaped.
fn escape(text: &str) -> String {
    let mut escaped = String::with_capacity(text.len());
    for character in text.chars() {
        match character {
            '&' => escaped.push_str("&amp;"),
            '<' => escaped.push_str("&lt;"),
            '>' => escaped.push_str("&gt;"),
            '"' => escaped.push_str("&quot;"),
            '\'' => escaped.push_str("&apos;"),
            other => escaped.push(other),
        }
    }
    escaped
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_is_escaped() {
        assert_eq!(escape("a<b & \"c\"'"), "a&lt;b &amp; &quot;c&quot;&apos;");
    }

    #[test]
    fn an_empty_answer_is_still_a_picture() {
        let regions = RegionsResponse {
            candidates: Vec::new(),
            families: Vec::new(),
            weight_regions: Vec::new(),
        };
        let picture = Picture {
            regions: &regions,
            parameter: 0.5,
            picked: [0.0, 0.0],
            target: None,
        };
        let svg = render(&picture).unwrap();
        assert!(svg.starts_with("<svg") && svg.ends_with("</svg>\n"));
        let nan = Picture {
            parameter: f64::NAN,
            ..picture
        };
        assert_eq!(render(&nan), Err(NonFinite));
    }
}
