//! The picture of an eigenmode over its base state, drawn at a stated scale small enough that
//! no two faces cross: a mode's amplitudes have no size of their own, so the drawing picks
//! one, and one too large shows plies running through each other that the mode does not mean.

use crate::error::{Error, Result};
use crate::io::plots::{outline_picture, Panel, SegmentLayer};
use crate::io::reader::ResultsReader;
use crate::model::mesh::Mesh;
use std::path::Path;

/// A picture of an eigenmode of perturbation step `step` (mode `mode` of the harmonic `n`), to
/// scale: the meridian section at theta = 0 and at theta = 180 degrees, one above the other, each
/// the base state (the run's last increment) in grey and the mode over it, drawn at the scale
/// [`clear_scale`] picks (at most 2.5 % of the model's length for the largest amplitude), which
/// the legend states.
pub fn mode_picture(reader: &ResultsReader, path: &Path, step: &str, n: u32, mode: usize, title: &str) -> Result<()> {
    let increments = reader.increments()?;
    let last = increments.last().ok_or_else(|| Error::input("no increment: no base state to draw the mode on"))?;
    let (x0, u) = (reader.coordinates()?, reader.displacement(last)?);
    let amplitudes = reader.perturbation_field(step, &format!("mode_{mode}"))?;
    let base: Vec<[f64; 2]> = x0.iter().zip(&u).map(|(x, u)| [x[0] + u[0], x[1] + u[1]]).collect();
    let mesh = Mesh { coords: base, elements: reader.connectivity()?, ..Default::default() };
    let shape: Vec<[f64; 2]> = amplitudes.chunks_exact(3).map(|a| [a[0], a[1]]).collect();
    let (z0, z1) = mesh.coords.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| (a.min(x[1]), b.max(x[1])));
    let scale = clear_scale(&mesh, &shape, 0.025 * (z1 - z0));
    // theta = 180 degrees: cos n theta = (-1)^n
    let sign = if n.is_multiple_of(2) { 1.0 } else { -1.0 };
    let edges = mesh.free_edges();
    let outline = |factor: f64| {
        let moved = mesh.coords.iter().zip(&shape).map(|(x, a)| [x[0] + factor * a[0], x[1] + factor * a[1]]).collect();
        Mesh { coords: moved, elements: mesh.elements.clone(), ..Default::default() }.edge_segments(&edges)
    };
    let state = outline(0.0);
    let panel = |caption: &str, factor: f64| Panel {
        caption: Some(caption.to_string()),
        layers: vec![
            SegmentLayer { label: "base state".into(), segments: state.clone(), width: 1 },
            SegmentLayer { label: format!("mode {mode} of n = {n}, drawn with its largest amplitude {scale:.2} mm"), segments: outline(factor), width: 2 },
        ],
    };
    outline_picture(path, title, &[panel("theta = 0", scale), panel("theta = 180 degrees", sign * scale)])
}

/// The largest drawing scale, at most `cap`, at which the mode `shape` (per node, its largest
/// component 1) moves no free-edge node through a face it stands in front of by more than a
/// tenth of the mesh's smallest free-edge piece: for each such node and face piece (of another
/// body, or of its own body across a gap), the scaled closing -(U_node - U_face) . n must stay
/// within the node's height above the piece plus that allowance.
pub fn clear_scale(mesh: &Mesh, shape: &[[f64; 2]], cap: f64) -> f64 {
    let body_of = {
        let mut body = vec![usize::MAX; mesh.coords.len()];
        for (b, nodes) in mesh.bodies().iter().enumerate() {
            nodes.iter().for_each(|&n| body[n] = b);
        }
        body
    };
    // the free faces' straight pieces, each with its outward unit normal (away from its element)
    let mut pieces: Vec<([usize; 2], [f64; 2])> = Vec::new();
    for edge in mesh.free_edges() {
        let [a, b, m] = mesh.edge_nodes(edge);
        let centre = mesh.element_coords(edge.element).iter().fold([0.0; 2], |c, x| [c[0] + x[0], c[1] + x[1]]);
        let count = mesh.element_nodes(edge.element).len() as f64;
        let centre = [centre[0] / count, centre[1] / count];
        for [i, j] in [[a, m], [m, b]] {
            let (p, q) = (mesh.coords[i], mesh.coords[j]);
            let length = (q[0] - p[0]).hypot(q[1] - p[1]);
            if length == 0.0 {
                continue;
            }
            let mut normal = [(q[1] - p[1]) / length, -(q[0] - p[0]) / length];
            if normal[0] * (p[0] - centre[0]) + normal[1] * (p[1] - centre[1]) < 0.0 {
                normal = [-normal[0], -normal[1]];
            }
            pieces.push(([i, j], normal));
        }
    }
    let length = |[i, j]: [usize; 2]| (mesh.coords[j][0] - mesh.coords[i][0]).hypot(mesh.coords[j][1] - mesh.coords[i][1]);
    let allowance = 0.1 * pieces.iter().map(|(ends, _)| length(*ends)).fold(f64::INFINITY, f64::min);
    if pieces.is_empty() || cap <= 0.0 {
        return cap.max(0.0);
    }
    let free: std::collections::BTreeSet<usize> = pieces.iter().flat_map(|(ends, _)| *ends).collect();
    // pieces bucketed on a grid as wide as the farthest two faces can close at the cap
    let reach = 2.0 * cap + allowance;
    let cell = |x: [f64; 2]| ((x[0] / reach).floor() as i64, (x[1] / reach).floor() as i64);
    let mut grid: std::collections::HashMap<(i64, i64), Vec<usize>> = std::collections::HashMap::new();
    for (k, (ends, _)) in pieces.iter().enumerate() {
        let cells: std::collections::BTreeSet<(i64, i64)> = ends.iter().map(|&n| cell(mesh.coords[n])).collect();
        let (r0, r1) = (cells.iter().map(|c| c.0).min().unwrap_or(0), cells.iter().map(|c| c.0).max().unwrap_or(0));
        let (z0, z1) = (cells.iter().map(|c| c.1).min().unwrap_or(0), cells.iter().map(|c| c.1).max().unwrap_or(0));
        for r in r0..=r1 {
            for z in z0..=z1 {
                grid.entry((r, z)).or_default().push(k);
            }
        }
    }
    let mut scale = cap;
    for &node in &free {
        let x = mesh.coords[node];
        let (cr, cz) = cell(x);
        for k in (cr - 1..=cr + 1).flat_map(|r| (cz - 1..=cz + 1).map(move |z| (r, z))).filter_map(|c| grid.get(&c)).flatten() {
            let ([i, j], normal) = pieces[*k];
            if i == node || j == node {
                continue;
            }
            // the piece's point closest to the node, the node's height above the piece, the mode there
            let (p, q) = (mesh.coords[i], mesh.coords[j]);
            let d = [q[0] - p[0], q[1] - p[1]];
            let t = (((x[0] - p[0]) * d[0] + (x[1] - p[1]) * d[1]) / (d[0] * d[0] + d[1] * d[1])).clamp(0.0, 1.0);
            let apart = [x[0] - p[0] - t * d[0], x[1] - p[1] - t * d[1]];
            let gap = apart[0] * normal[0] + apart[1] * normal[1];
            let distance = apart[0].hypot(apart[1]);
            let in_front = if body_of[i] == body_of[node] { distance > allowance && gap >= 0.5 * distance } else { gap >= -allowance };
            if !in_front || distance > reach {
                continue;
            }
            let at = |c: usize| (1.0 - t) * shape[i][c] + t * shape[j][c];
            let closing = -((shape[node][0] - at(0)) * normal[0] + (shape[node][1] - at(1)) * normal[1]);
            if closing > 0.0 {
                scale = scale.min((gap + allowance) / closing);
            }
        }
    }
    scale.max(0.0)
}

#[cfg(test)]
mod tests {
    use super::clear_scale;
    use crate::model::mesh::{rectangle, Mesh};

    /// Two 1 mm plies, one above the other, touching at r = 11 mm (ply A below from r 10 to 11,
    /// ply B above from 11 to 12), 20 mm long; each meshed 1 x 4.
    fn plies() -> Mesh {
        let (mut a, _) = rectangle([10.0, 11.0], [0.0, 20.0], [1, 4]).unwrap();
        let (b, _) = rectangle([11.0, 12.0], [0.0, 20.0], [1, 4]).unwrap();
        a.append(&b);
        a
    }

    #[test]
    fn a_rigid_shift_of_both_plies_is_drawn_at_the_cap() {
        let mesh = plies();
        let shape = vec![[1.0, 0.0]; mesh.coords.len()];
        assert_eq!(clear_scale(&mesh, &shape, 7.0), 7.0);
    }

    #[test]
    fn a_ply_moving_into_the_other_is_drawn_so_it_crosses_no_more_than_the_allowance() {
        let mesh = plies();
        // ply A (r < 11) moves out by 1 per unit, ply B stays: the faces close 1 per unit
        let shape: Vec<[f64; 2]> = mesh.coords.iter().enumerate().map(|(k, _)| if k < mesh.coords.len() / 2 { [1.0, 0.0] } else { [0.0, 0.0] }).collect();
        // the smallest free piece is half of a 1 mm side: allowance 0.05 mm
        let scale = clear_scale(&mesh, &shape, 7.0);
        assert!((scale - 0.05).abs() < 1e-12, "{scale}");
        // moving apart crosses nothing: the cap
        let apart: Vec<[f64; 2]> = shape.iter().map(|a| [-a[0], 0.0]).collect();
        assert_eq!(clear_scale(&mesh, &apart, 7.0), 7.0);
    }

    #[test]
    fn faces_across_a_gap_may_close_by_the_gap() {
        // the plies 3 mm apart (B from 14 to 15): A moving out by 1 per unit may be drawn at 3.05
        let (mut mesh, _) = rectangle([10.0, 11.0], [0.0, 20.0], [1, 4]).unwrap();
        let (b, _) = rectangle([14.0, 15.0], [0.0, 20.0], [1, 4]).unwrap();
        let first = mesh.append(&b).0;
        let shape: Vec<[f64; 2]> = (0..mesh.coords.len()).map(|k| if k < first { [1.0, 0.0] } else { [0.0, 0.0] }).collect();
        let scale = clear_scale(&mesh, &shape, 7.0);
        assert!((scale - 3.05).abs() < 1e-9, "{scale}");
    }
}
