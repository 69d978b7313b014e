//! PNG pictures (plotters, bitmap backend): x-y curves and the deformed mesh coloured by an
//! element field. Text uses the bundled DejaVu Sans, so a machine without system fonts draws
//! the same pictures.

use crate::error::{Error, Result};
use crate::fe::shape::Shape;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::{register_font, FontStyle};
use std::path::Path;
use std::sync::Once;

static FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");

fn use_bundled_font() {
    static REGISTER: Once = Once::new();
    REGISTER.call_once(|| {
        // the bytes are a valid TrueType font checked in with the source: cannot fail
        let _ = register_font("sans-serif", FontStyle::Normal, FONT);
    });
}

/// Writes RGB `pixels` of `size` to `path` as a PNG: a full disk or a read-only place is
/// named in the file system's words (the bitmap backend's own writer gave its error's Debug
/// text).
fn write_png(path: &Path, size: (u32, u32), pixels: &[u8]) -> Result<()> {
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::new(&mut bytes, size.0, size.1);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    // each row's best filter: flat colour fields and lines then pack as tightly as the image
    // crate's encoder did (uncompressed rows are five times larger)
    encoder.set_adaptive_filter(png::AdaptiveFilterType::Adaptive);
    let encoded = encoder.write_header().and_then(|mut w| w.write_image_data(pixels));
    encoded.map_err(|e| Error::Output { path: path.to_path_buf(), message: format!("cannot encode the picture: {e}") })?;
    std::fs::write(path, &bytes).map_err(|e| Error::Output { path: path.to_path_buf(), message: e.to_string() })
}

fn draw_err(path: &Path) -> impl Fn(&dyn std::fmt::Display) -> Error + '_ {
    move |e| Error::Output { path: path.to_path_buf(), message: format!("cannot draw the picture: {e}") }
}

/// One labelled curve of an x-y plot.
pub struct Curve {
    pub label: String,
    pub points: Vec<(f64, f64)>,
}

/// A labelled point drawn as a marker (a published value, say).
pub struct Marker {
    pub label: String,
    pub at: (f64, f64),
}

/// Line plot of `curves` with `markers`, axes from 0 (or below, if data are) to the data's
/// maximum plus a margin.
/// How a line plot's axes are ranged.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Axes {
    /// From the origin to the data (force against displacement, room below for a negative
    /// part of a load cycle); legend upper left, above a curve that rises from the origin.
    FromOrigin,
    /// Around the data alone (log10 values of a study); legend upper right.
    DataRange,
}

pub fn line_plot(path: &Path, title: &str, x_label: &str, y_label: &str, curves: &[Curve], markers: &[Marker], axes: Axes) -> Result<()> {
    xy_plot(path, (title, x_label, y_label), (&[], &[]), curves, markers, axes, false)
}

/// As [`line_plot`], each curve's points drawn as unjoined dots (a study's variants, one
/// colour per kind).
pub fn point_plot(path: &Path, title: &str, x_label: &str, y_label: &str, kinds: &[Curve], axes: Axes) -> Result<()> {
    xy_plot(path, (title, x_label, y_label), (&[], &[]), kinds, &[], axes, true)
}

/// A diagram: `boundaries` drawn as thin black lines (a region map's), each of `regions`' labels
/// written at its point, `kinds` as dots, one colour per kind (the points computed in it), axes
/// from the origin.
pub fn diagram(path: &Path, title: &str, x_label: &str, y_label: &str, (boundaries, regions): (&[Curve], &[Marker]), kinds: &[Curve]) -> Result<()> {
    xy_plot(path, (title, x_label, y_label), (boundaries, regions), kinds, &[], Axes::FromOrigin, true)
}

fn xy_plot(
    path: &Path,
    (title, x_label, y_label): (&str, &str, &str),
    (boundaries, regions): (&[Curve], &[Marker]),
    curves: &[Curve],
    markers: &[Marker],
    axes: Axes,
    dots: bool,
) -> Result<()> {
    use_bundled_font();
    let err = draw_err(path);
    let points: Vec<(f64, f64)> = (boundaries.iter().chain(curves))
        .flat_map(|c| c.points.iter().copied())
        .chain(markers.iter().map(|m| m.at))
        .filter(|p| p.0.is_finite() && p.1.is_finite())
        .collect();
    let (mut x0, mut x1, mut y0, mut y1) = match (axes, points.first()) {
        (Axes::DataRange, Some(&(x, y))) => (x, x, y, y),
        _ => (0.0f64, f64::MIN_POSITIVE, 0.0f64, f64::MIN_POSITIVE),
    };
    for &(x, y) in &points {
        (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
    }
    if axes == Axes::DataRange {
        // room on both sides, and a visible range for a flat curve
        let (wx, wy) = ((x1 - x0).max(1e-9 * x0.abs().max(1.0)), (y1 - y0).max(1e-3 * y0.abs().max(1e-12)));
        (x0, x1, y0, y1) = (x0 - 0.05 * wx, x1 + 0.0 * wx, y0 - 0.25 * wy, y1 + 0.25 * wy);
    }
    let (dx, dy) = (0.05 * (x1 - x0), 0.08 * (y1 - y0));
    let size = (1200, 800);
    let mut pixels = vec![0u8; 3 * size.0 as usize * size.1 as usize];
    {
        let root = BitMapBackend::with_buffer(&mut pixels, size).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(&e))?;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 28))
            .margin(20)
            .x_label_area_size(60)
            .y_label_area_size(90)
            .build_cartesian_2d(x0..x1 + dx, y0 - if y0 < 0.0 { dy } else { 0.0 }..y1 + dy)
            .map_err(|e| err(&e))?;
        chart
            .configure_mesh()
            .x_desc(x_label)
            .y_desc(y_label)
            .label_style(("sans-serif", 18))
            .axis_desc_style(("sans-serif", 20))
            .draw()
            .map_err(|e| err(&e))?;
        let palette = [RGBColor(31, 119, 180), RGBColor(214, 39, 40), RGBColor(44, 160, 44), RGBColor(148, 103, 189)];
        for b in boundaries {
            let series = chart.draw_series(LineSeries::new(b.points.iter().copied(), BLACK.stroke_width(2))).map_err(|e| err(&e))?;
            if !b.label.is_empty() {
                series.label(b.label.as_str()).legend(|(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], BLACK.stroke_width(2)));
            }
        }
        for r in regions {
            chart.draw_series(std::iter::once(Text::new(r.label.clone(), r.at, ("sans-serif", 28)))).map_err(|e| err(&e))?;
        }
        for (k, c) in curves.iter().enumerate() {
            let colour = palette[k % palette.len()];
            if dots {
                let finite = c.points.iter().copied().filter(|p| p.0.is_finite() && p.1.is_finite());
                chart
                    .draw_series(finite.map(|p| Circle::new(p, 7, colour.filled())))
                    .map_err(|e| err(&e))?
                    .label(c.label.as_str())
                    .legend(move |(x, y)| Circle::new((x + 12, y), 6, colour.filled()));
                continue;
            }
            chart
                .draw_series(LineSeries::new(c.points.iter().copied(), colour.stroke_width(3)))
                .map_err(|e| err(&e))?
                .label(c.label.as_str())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], colour.stroke_width(3)));
        }
        for m in markers {
            chart
                .draw_series(std::iter::once(Cross::new(m.at, 10, BLACK.stroke_width(3))))
                .map_err(|e| err(&e))?
                .label(m.label.as_str())
                .legend(|(x, y)| Cross::new((x + 12, y), 7, BLACK.stroke_width(2)));
        }
        // a diagram's regions start at the origin: its legend goes where a curve would not
        let upper_left = axes == Axes::FromOrigin && boundaries.is_empty();
        draw_legend(&mut chart, if upper_left { SeriesLabelPosition::UpperLeft } else { SeriesLabelPosition::UpperRight }).map_err(|e| err(&e))?;
        root.present().map_err(|e| err(&e))?;
    }
    write_png(path, size, &pixels)
}

/// Line segments ((r, z) ends) of one kind in an outline picture, with their legend label.
pub struct SegmentLayer {
    pub label: String,
    pub segments: Vec<[[f64; 2]; 2]>,
    pub width: u32,
}

/// One meridian view of an outline picture: its caption (none for a single view) and layers.
pub struct Panel {
    pub caption: Option<String>,
    pub layers: Vec<SegmentLayer>,
}

/// (r, z) outlines drawn to scale, z across and r up (meridian sections), one panel above the
/// other on a common z range, each cropped to its own r range: each layer's segments in its own
/// colour (grey first, then the palette), with a legend.
pub fn outline_picture(path: &Path, title: &str, panels: &[Panel]) -> Result<()> {
    use_bundled_font();
    let err = draw_err(path);
    let range = |layers: &[SegmentLayer]| {
        layers
            .iter()
            .flat_map(|l| l.segments.iter().flatten())
            .fold((f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY), |(r0, r1, z0, z1), p| {
                (r0.min(p[0]), r1.max(p[0]), z0.min(p[1]), z1.max(p[1]))
            })
    };
    let ranges: Vec<_> = panels.iter().map(|p| range(&p.layers)).collect();
    let (z0, z1) = ranges.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), r| (a.min(r.2), b.max(r.3)));
    let pad = 0.03 * (z1 - z0).max(ranges.iter().fold(0.0f64, |m, r| m.max(r.1 - r.0)));
    let (z0, z1) = (z0 - pad, z1 + pad);
    // to scale: each panel's height follows from the common width and its section's proportions
    let width = 1800u32;
    let plot_width = f64::from(width - 150);
    let heights: Vec<u32> = ranges
        .iter()
        .zip(panels)
        .map(|(r, p)| (plot_width * (r.1 - r.0 + 2.0 * pad) / (z1 - z0)).round() as u32 + 110 + if p.caption.is_some() { 30 } else { 0 })
        .collect();
    let size = (width, heights.iter().sum::<u32>() + 50);
    let mut pixels = vec![0u8; 3 * size.0 as usize * size.1 as usize];
    {
        let root = BitMapBackend::with_buffer(&mut pixels, size).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(&e))?;
        let mut area = root.titled(title, ("sans-serif", 26)).map_err(|e| err(&e))?;
        for ((panel, r), &height) in panels.iter().zip(&ranges).zip(&heights) {
            let (here, rest) = area.split_vertically(height);
            area = rest;
            let mut builder = ChartBuilder::on(&here);
            builder.margin(20).x_label_area_size(50).y_label_area_size(80);
            if let Some(caption) = &panel.caption {
                builder.caption(caption, ("sans-serif", 20));
            }
            let mut chart = builder.build_cartesian_2d(z0..z1, r.0 - pad..r.1 + pad).map_err(|e| err(&e))?;
            chart.configure_mesh().disable_mesh().x_desc("z, mm").y_desc("r, mm").label_style(("sans-serif", 16)).draw().map_err(|e| err(&e))?;
            let palette = [RGBColor(150, 150, 150), RGBColor(31, 119, 180), RGBColor(214, 39, 40), RGBColor(44, 160, 44)];
            for (k, layer) in panel.layers.iter().enumerate() {
                let style = palette[k % palette.len()].stroke_width(layer.width);
                chart
                    .draw_series(layer.segments.iter().map(|[a, b]| PathElement::new(vec![(a[1], a[0]), (b[1], b[0])], style)))
                    .map_err(|e| err(&e))?
                    .label(layer.label.as_str())
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], style));
            }
            draw_legend(&mut chart, SeriesLabelPosition::UpperLeft).map_err(|e| err(&e))?;
        }
        root.present().map_err(|e| err(&e))?;
    }
    write_png(path, size, &pixels)
}

/// The series' legend, boxed, at `position`.
fn draw_legend<'a, CT: CoordTranslate>(chart: &mut ChartContext<'a, BitMapBackend<'a>, CT>, position: SeriesLabelPosition) -> DrawResult {
    chart.configure_series_labels().position(position).label_font(("sans-serif", 18)).background_style(WHITE.mix(0.9)).border_style(BLACK).draw()
}

/// A Q8 mesh in its deformed configuration with one value per element.
pub struct FieldPicture<'a> {
    pub coordinates: &'a [[f64; 2]],
    pub connectivity: &'a [[usize; 8]],
    pub displacement: &'a [[f64; 2]],
    /// One value per element (same order as `connectivity`).
    pub values: &'a [f64],
    pub title: String,
    /// Name and unit of the value, for the colour bar.
    pub value_label: String,
}

/// Rainbow colour scale (blue - cyan - green - yellow - red), as FE post-processors use.
pub fn rainbow(t: f64) -> RGBColor {
    let stops = [(0.0, [0.0, 0.0, 1.0]), (0.25, [0.0, 1.0, 1.0]), (0.5, [0.0, 1.0, 0.0]), (0.75, [1.0, 1.0, 0.0]), (1.0, [1.0, 0.0, 0.0])];
    let t = if t.is_finite() { t.clamp(0.0, 1.0) } else { 0.0 };
    let k = stops.iter().rposition(|s| s.0 <= t).unwrap_or(0).min(stops.len() - 2);
    let (a, b) = (stops[k], stops[k + 1]);
    let f = (t - a.0) / (b.0 - a.0);
    let c: [u8; 3] = std::array::from_fn(|i| ((a.1[i] + f * (b.1[i] - a.1[i])) * 255.0).round() as u8);
    RGBColor(c[0], c[1], c[2])
}

/// A picture window: (z range, r range), mm.
pub type Window = ((f64, f64), (f64, f64));

/// Draws the deformed mesh (axial coordinate z across, radius r up, equal scales) in one panel
/// per window ((z0, z1), (r0, r1)); None as a window means the whole deformed mesh. Colour
/// scale from the smallest to the largest value of all elements, with a colour bar.
pub fn deformed_field(path: &Path, picture: &FieldPicture<'_>, windows: &[Option<Window>]) -> Result<()> {
    use_bundled_font();
    let err = draw_err(path);
    let x = |n: usize| [picture.coordinates[n][0] + picture.displacement[n][0], picture.coordinates[n][1] + picture.displacement[n][1]];
    let lo = picture.values.iter().copied().filter(|v| v.is_finite()).fold(f64::INFINITY, f64::min);
    let hi = picture.values.iter().copied().filter(|v| v.is_finite()).fold(f64::NEG_INFINITY, f64::max);
    let span = if hi > lo { hi - lo } else { 1.0 };
    let (width, panel_height) = (1800u32, 520u32);
    let size = (width, 70 + panel_height * windows.len() as u32);
    let mut pixels = vec![0u8; 3 * size.0 as usize * size.1 as usize];
    {
        let root = BitMapBackend::with_buffer(&mut pixels, size).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(&e))?;
        let (head, body) = root.split_vertically(70);
        head.titled(&picture.title, ("sans-serif", 26)).map_err(|e| err(&e))?;
        let (panels, bar) = body.split_horizontally(width - 170);
        for (area, window) in panels.split_evenly((windows.len(), 1)).iter().zip(windows) {
            let ((z0, z1), (r0, r1)) = window.unwrap_or_else(|| {
                let (mut b, mut t) = ((f64::INFINITY, f64::NEG_INFINITY), (f64::INFINITY, f64::NEG_INFINITY));
                for n in 0..picture.coordinates.len() {
                    let p = x(n);
                    (b, t) = ((b.0.min(p[1]), b.1.max(p[1])), (t.0.min(p[0]), t.1.max(p[0])));
                }
                (b, t)
            });
            draw_panel(area, &x, picture, (z0, z1), (r0, r1), |v| rainbow((v - lo) / span)).map_err(|e| err(&e))?;
        }
        draw_colour_bar(&bar, &picture.value_label, lo, hi).map_err(|e| err(&e))?;
        root.present().map_err(|e| err(&e))?;
    }
    write_png(path, size, &pixels)
}

type DrawResult = std::result::Result<(), DrawingAreaErrorKind<<BitMapBackend<'static> as DrawingBackend>::ErrorType>>;

fn draw_panel(
    area: &DrawingArea<BitMapBackend<'_>, Shift>,
    x: &impl Fn(usize) -> [f64; 2],
    picture: &FieldPicture<'_>,
    z: (f64, f64),
    r: (f64, f64),
    colour: impl Fn(f64) -> RGBColor,
) -> std::result::Result<(), String> {
    let (w, h) = area.dim_in_pixel();
    let (label_x, label_y, margin) = (45.0, 70.0, 15.0);
    // equal scales: widen whichever range is short for the panel's shape
    let (pw, ph) = (w as f64 - label_y - 2.0 * margin, h as f64 - label_x - 2.0 * margin);
    let scale = (pw / (z.1 - z.0)).min(ph / (r.1 - r.0));
    let (zc, rc) = (0.5 * (z.0 + z.1), 0.5 * (r.0 + r.1));
    let (hz, hr) = (0.5 * pw / scale, 0.5 * ph / scale);
    let mut chart = ChartBuilder::on(area)
        .margin(margin as u32)
        .x_label_area_size(label_x as u32)
        .y_label_area_size(label_y as u32)
        .build_cartesian_2d(zc - hz..zc + hz, rc - hr..rc + hr)
        .map_err(|e| e.to_string())?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc("z (mm)")
        .y_desc("r (mm)")
        .label_style(("sans-serif", 16))
        .axis_desc_style(("sans-serif", 18))
        .draw()
        .map_err(|e| e.to_string())?;
    let visible = |p: [f64; 2]| (p[1] - zc).abs() <= hz + 5.0 && (p[0] - rc).abs() <= hr + 5.0;
    let polygons = picture.connectivity.iter().zip(picture.values).filter_map(|(conn, &v)| {
        let pts: Vec<(f64, f64)> = Shape::of(conn).outline().iter().map(|&k| x(conn[k])).map(|p| (p[1], p[0])).collect();
        pts.iter().any(|&(zz, rr)| visible([rr, zz])).then(|| Polygon::new(pts, colour(v).filled()))
    });
    chart.draw_series(polygons).map_err(|e| e.to_string())?;
    // element edges, thin, where the elements are large enough on screen to show them
    let edges = picture.connectivity.iter().filter_map(|conn| {
        let mut pts: Vec<(f64, f64)> = Shape::of(conn).outline().iter().map(|&k| x(conn[k])).map(|p| (p[1], p[0])).collect();
        // corner to the opposite corner (Q8) or mid-side (T6)
        let size = (pts[0].0 - pts[pts.len() / 2].0).hypot(pts[0].1 - pts[pts.len() / 2].1) * scale;
        pts.push(pts[0]);
        (size > 12.0 && pts.iter().any(|&(zz, rr)| visible([rr, zz]))).then(|| PathElement::new(pts, BLACK.mix(0.25).stroke_width(1)))
    });
    chart.draw_series(edges).map_err(|e| e.to_string())?;
    Ok(())
}

fn draw_colour_bar(area: &DrawingArea<BitMapBackend<'_>, Shift>, label: &str, lo: f64, hi: f64) -> DrawResult {
    let (_, h) = area.dim_in_pixel();
    let (top, bottom, left, right) = (40i32, h as i32 - 40, 20i32, 50i32);
    let steps = 200;
    for k in 0..steps {
        let t = k as f64 / (steps - 1) as f64;
        let y1 = bottom - ((bottom - top) as f64 * (k as f64 / steps as f64)) as i32;
        let y0 = bottom - ((bottom - top) as f64 * ((k + 1) as f64 / steps as f64)) as i32;
        area.draw(&Rectangle::new([(left, y0), (right, y1)], rainbow(t).filled()))?;
    }
    area.draw(&Rectangle::new([(left, top), (right, bottom)], BLACK.stroke_width(1)))?;
    let style = ("sans-serif", 16).into_font();
    for k in 0..=5 {
        let t = k as f64 / 5.0;
        let y = bottom - ((bottom - top) as f64 * t) as i32;
        let digits = if (hi - lo).abs() >= 10.0 { 1 } else { 4 };
        area.draw(&Text::new(format!("{:.*}", digits, lo + t * (hi - lo)), (right + 6, y - 8), style.clone()))?;
    }
    area.draw(&Text::new(label.to_string(), (left - 10, top - 30), style))?;
    Ok(())
}
