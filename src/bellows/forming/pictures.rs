//! The formed bellows pictured from the forming's file (its last increment, after the
//! springback): the pack's thickness along the tube beside EJMA's n tp and n t, and the plies'
//! equivalent plastic strain (the cold work) and residual hoop stress on the formed shape.

use super::FormingGeometry;
use crate::bellows::spec::DesignSpec;
use crate::error::{Error, Result};
use crate::io::plots::{deformed_field, line_plot, Axes, Curve, FieldPicture};
use crate::io::reader::ResultsReader;
use std::path::PathBuf;

/// The three pictures, `formed_thickness`, `formed_plastic_strain` and `formed_hoop_stress`
/// (at `picture(name)`), each with what it shows.
pub fn draw(p: &DesignSpec, reader: &ResultsReader, picture: impl Fn(&str) -> PathBuf) -> Result<Vec<(PathBuf, String)>> {
    let last = reader.increments()?.pop().ok_or_else(|| Error::input(format!("{}: no increment: nothing was formed", reader.path().display())))?;
    let (x0, u, conn) = (reader.coordinates()?, reader.displacement(&last)?, reader.connectivity()?);
    let x: Vec<[f64; 2]> = x0.iter().zip(&u).map(|(a, b)| [a[0] + b[0], a[1] + b[1]]).collect();
    let n = p.bellows.plies;
    let mut out = Vec::new();

    // the pack's thickness at each inside node of the convolutions: its distance to the
    // outside face (the plies slide on each other: the outside node that stood beside it has
    // moved along the meridian), the face a polyline of its nodes in their order along the tube
    let (inside, mut outside) = (reader.node_set("ply1_inner")?, reader.node_set(&format!("ply{n}_outer"))?);
    outside.sort_by(|&a, &b| x0[a][1].total_cmp(&x0[b][1]));
    let [z0, z1] = FormingGeometry::of(p).convoluted();
    let mut points: Vec<(f64, f64)> = inside
        .iter()
        .filter(|&&i| x0[i][1] >= z0 - 1e-9 && x0[i][1] <= z1 + 1e-9)
        .map(|&i| {
            let near = outside.windows(2).filter(|s| (x0[s[0]][1] - x0[i][1]).abs() < 10.0 * p.pack_thickness() + 5.0);
            (x0[i][1] - z0, near.map(|s| to_segment(x[i], x[s[0]], x[s[1]])).fold(f64::INFINITY, f64::min))
        })
        .collect();
    points.sort_by(|a, b| a.0.total_cmp(&b.0));
    let length = z1 - z0;
    let level = |label: String, value: f64| Curve { label, points: vec![(0.0, value), (length, value)] };
    let (pack, tp) = (n as f64 * p.bellows.ply_thickness, n as f64 * p.geometry().ejma_formed_thickness());
    let curves = [
        Curve { label: "formed (finite elements): the crests thinnest, the roots thickened a little".into(), points },
        level(format!("nominal n t {pack:.3} mm"), pack),
        level(format!("EJMA's n tp = n t sqrt(Db / Dm) {tp:.4} mm"), tp),
    ];
    let path = picture("formed_thickness");
    line_plot(
        &path,
        "The formed pack's thickness along the convolutions",
        "position along the tube before forming, mm",
        "pack thickness, mm",
        &curves,
        &[],
        Axes::DataRange,
    )?;
    out.push((path, "the formed pack's thickness along the convolutions".to_string()));

    // the plies' elements alone (the dies are drawn out), their nodal fields' element means
    let mut plies = Vec::new();
    for k in 1..=n {
        plies.extend(reader.element_set(&format!("ply{k}"))?);
    }
    let connectivity: Vec<[usize; 8]> = plies.iter().map(|&e| conn[e]).collect();
    let (mut r, mut z) = ((f64::INFINITY, f64::NEG_INFINITY), (f64::INFINITY, f64::NEG_INFINITY));
    for c in &connectivity {
        for &k in c {
            (r, z) = ((r.0.min(x[k][0]), r.1.max(x[k][0])), (z.0.min(x[k][1]), z.1.max(x[k][1])));
        }
    }
    let window = Some(((z.0 - 2.0, z.1 + 2.0), (r.0 - 4.0, r.1 + 2.0)));
    for (field, scale, name, title, unit) in [
        ("nodal/equivalent_plastic_strain", 100.0, "formed_plastic_strain", "equivalent plastic strain after forming (the cold work), element means", "%"),
        ("nodal/stress_tt", 1.0, "formed_hoop_stress", "residual hoop stress after forming and springback, element means", "MPa"),
    ] {
        let nodal = reader.field(&last, field)?;
        let values: Vec<f64> = connectivity.iter().map(|c| scale * c.iter().map(|&k| nodal[k]).sum::<f64>() / 8.0).collect();
        let (lo, hi) = values.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
        let path = picture(name);
        let picture = FieldPicture {
            coordinates: &x0,
            connectivity: &connectivity,
            displacement: &u,
            values: &values,
            title: format!("The formed bellows: {title}, {lo:.1} to {hi:.1} {unit}"),
            value_label: unit.into(),
        };
        deformed_field(&path, &picture, &[window])?;
        out.push((path, title.to_string()));
    }
    Ok(out)
}

/// The distance from point `p` to the segment from `a` to `b`.
fn to_segment(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (d, v) = ([b[0] - a[0], b[1] - a[1]], [p[0] - a[0], p[1] - a[1]]);
    let s = ((v[0] * d[0] + v[1] * d[1]) / (d[0] * d[0] + d[1] * d[1]).max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
    (v[0] - s * d[0]).hypot(v[1] - s * d[1])
}
