//! The plies' meridional membrane stress from the elements' nodal forces.
//!
//! Why not the mean of the stress across the ply: S3 and S5 are a few percent of the bending
//! stress beside them, and the displacement elements' stress, not in equilibrium point by
//! point, carries an error of about 0.5 % of the bending stress into its mean across a ply; the
//! mean moved by 9 and 23 % when the ply mesh was refined. The elements' nodal forces are in
//! equilibrium with the loads exactly (the way Abaqus's section forces, *SECTION PRINT, are
//! read), so the force one column of a ply's elements passes to the next through the mesh
//! line between them is the meridional force there to the solver's tolerance.
//!
//! At the line between columns A and B (A nearer tube A) the force on A from B is A's internal
//! force at the line's nodes less A's share of the loads applied there; taking half the
//! difference of A's and B's internal forces, (f_A - f_B) / 2, splits those loads (pressure,
//! contact) evenly between the sides, so they cancel. Where the line's nodes are shared with
//! another body (the pack merged with a tube where a tangent begins), that body's forces on
//! them are no load to split: the line is read from the convolution's side alone. Its component along the meridian over
//! the line's area (per radian: the ply thickness times the radius at the line's middle, the
//! exact integral of r ds over a straight line) is the membrane stress: force over area, the
//! codes' own definition (S3 = P w / (2 tp) is the pressure's force over the metal).

use crate::bellows::joint::{ply_columns, ConvolutionPiece};
use crate::bellows::spec::DesignSpec;
use crate::element::solid::{compute_solid, SolidInput, NODES};
use crate::error::{Error, Result};
use crate::io::reader::ResultsReader;
use crate::material::{PointState, SurfaceBranch};
use crate::model::Model;
use crate::solve::problem::material_kernel;
use std::collections::HashMap;

/// The element nodes on the line where a column starts (towards tube A) and where it ends: a
/// mapped block's element is [(i, j), (i+2, j), (i+2, j+2), (i, j+2), mid-sides...], j along.
const START: [usize; 3] = [0, 4, 1];
const END: [usize; 3] = [3, 6, 2];

/// The meridional membrane stress of every ply at every element line across it, on the
/// convolutions' pieces: `[ply][piece][line]`, lines 0..=n of a piece of n columns.
#[derive(Clone, Debug)]
pub struct PlyMembrane {
    lines: Vec<Vec<Vec<f64>>>,
}

impl PlyMembrane {
    /// From increment `increment` of the results file `r`, a run of `model` (the file's nodes
    /// are in the partition's order: matched to the model's by their numbers and positions).
    pub fn from_file(r: &ResultsReader, increment: &str, model: &Model, p: &DesignSpec, pieces: &[ConvolutionPiece], scale: f64) -> Result<Self> {
        let failed = |message: String| Error::Output { path: r.path().to_path_buf(), message };
        let (coords, ids, file_u) = (r.coordinates()?, r.node_ids()?, r.field(increment, "nodal/displacement")?);
        let index: HashMap<u64, usize> = model.mesh.node_ids.iter().enumerate().map(|(n, &id)| (id, n)).collect();
        let mut u = vec![[f64::NAN; 2]; model.mesh.coords.len()];
        for (row, id) in ids.iter().enumerate() {
            match index.get(id) {
                Some(&n) if coords[row] == model.mesh.coords[n] => u[n] = [file_u[3 * row], file_u[3 * row + 1]],
                _ => return Err(failed(format!("node {id} of the file is not the model's"))),
            }
        }
        Self::new(model, &u, p, pieces, scale).map_err(failed)
    }

    /// From the displacements `u` (model node order) of a linear analysis of joint `p`'s model
    /// `model`, multiplied by `scale`; `pieces` are `convolution_pieces(p)`.
    pub fn new(model: &Model, u: &[[f64; 2]], p: &DesignSpec, pieces: &[ConvolutionPiece], scale: f64) -> std::result::Result<Self, String> {
        let columns = ply_columns(p);
        // convolution piece i is mid-surface piece i + 1: its first column follows tangent A's
        let first: Vec<usize> = (0..pieces.len()).map(|i| columns[..=i].iter().sum()).collect();
        let mesh = &model.mesh;
        let mut lines = Vec::with_capacity(p.bellows.plies);
        for ply in 0..p.bellows.plies {
            let name = format!("ply{}", ply + 1);
            let set = model.element_sets.get(&name).ok_or_else(|| format!("the model has no element set {name}"))?;
            let per_column = p.joint.ply_elements;
            // the nodes of elements outside this ply
            let mut elsewhere = vec![false; mesh.coords.len()];
            let inside: std::collections::HashSet<usize> = set.iter().copied().collect();
            for (_, conn) in mesh.elements.iter().enumerate().filter(|(e, _)| !inside.contains(e)) {
                for &node in conn {
                    elsewhere[node] = true;
                }
            }
            if set.len() != columns.iter().sum::<usize>() * per_column {
                return Err(format!("{name} has {} elements, not a mapped block of {} columns", set.len(), columns.iter().sum::<usize>()));
            }
            // per column, its elements' internal force summed at the nodes of its start and
            // of its end line
            let column_forces = (0..set.len() / per_column)
                .map(|c| {
                    let mut sums = [[0.0; 2]; 2];
                    for &e in &set[c * per_column..(c + 1) * per_column] {
                        let force = internal_force(model, e, u)?;
                        for (sum, line) in sums.iter_mut().zip([START, END]) {
                            for a in line {
                                sum[0] += force[2 * a];
                                sum[1] += force[2 * a + 1];
                            }
                        }
                    }
                    Ok(sums)
                })
                .collect::<std::result::Result<Vec<_>, String>>()?;
            let mut of_ply = Vec::with_capacity(pieces.len());
            for (i, piece) in pieces.iter().enumerate() {
                let n = columns[i + 1];
                let mut values = Vec::with_capacity(n + 1);
                for m in 0..=n {
                    let c = first[i] + m; // the column after the line
                    let (before, after) = (&set[(c - 1) * per_column..c * per_column], &set[c * per_column..(c + 1) * per_column]);
                    // the blocks' numbering, checked: the line's nodes are shared
                    for (&a, &b) in before.iter().zip(after) {
                        if END.map(|k| mesh.elements[a][k]) != START.map(|k| mesh.elements[b][k]) {
                            return Err(format!("{name}: elements {} and {} do not meet on a line across the ply", mesh.element_ids[a], mesh.element_ids[b]));
                        }
                    }
                    let (fa, fb) = (column_forces[c - 1][1], column_forces[c][0]);
                    // a line bonded to another body (the tangents, where the pack is merged
                    // with the tube) carries that body's forces on its nodes: read it from the
                    // piece's own side alone
                    let bonded = START.iter().any(|&k| after.iter().any(|&e| elsewhere[mesh.elements[e][k]]));
                    let force = match (bonded, m) {
                        (true, 0) => [-fb[0], -fb[1]],
                        (true, _) if m == n => fa,
                        _ => [0.5 * (fa[0] - fb[0]), 0.5 * (fa[1] - fb[1])],
                    };
                    let (_, tangent) = piece.piece.at(m as f64 / n as f64);
                    // the line runs from the ply's inside to its outside: its ends' corner nodes
                    let ends = [mesh.coords[mesh.elements[after[0]][0]], mesh.coords[mesh.elements[after[per_column - 1]][1]]];
                    let thickness = (ends[1][0] - ends[0][0]).hypot(ends[1][1] - ends[0][1]);
                    let area = thickness * model.element_section[after[0]].measure(0.5 * (ends[0][0] + ends[1][0]));
                    values.push(scale * (force[0] * tangent[0] + force[1] * tangent[1]) / area);
                }
                of_ply.push(values);
            }
            lines.push(of_ply);
        }
        Ok(PlyMembrane { lines })
    }

    /// The membrane stress of ply `ply` (from 0) at fraction `s` in [0, 1] along convolution
    /// piece `piece`, linear between the element lines.
    pub fn at(&self, ply: usize, piece: usize, s: f64) -> f64 {
        let values = &self.lines[ply][piece];
        let n = values.len() - 1;
        let x = s.clamp(0.0, 1.0) * n as f64;
        let m = (x.floor() as usize).min(n - 1);
        let w = x - m as f64;
        (1.0 - w) * values[m] + w * values[m + 1]
    }
}

/// The internal force per radian of element `e` of `model` at displacements `u`, from its
/// reference state (the linear analyses' elastic material, no temperature change).
fn internal_force(model: &Model, e: usize, u: &[[f64; 2]]) -> std::result::Result<[f64; 2 * NODES], String> {
    let conn = model.mesh.elements[e];
    let x = conn.map(|n| model.mesh.coords[n]);
    let geometry = model.element_geometry(e, &x)?;
    let material = material_kernel(&model.materials[model.element_material[e]]);
    let committed = [PointState::initial(model.kinematics); crate::element::solid::QUADRATURE_POINTS];
    let input = SolidInput {
        geometry: &geometry,
        material: &material,
        kinematics: model.kinematics,
        temperature_change: [0.0; NODES],
        committed: &committed,
        surface: SurfaceBranch::Elastic,
    };
    let response = compute_solid(&input, &conn.map(|n| u[n]), None)?;
    Ok(std::array::from_fn(|i| response.internal_force[i]))
}
