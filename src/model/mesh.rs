//! Axisymmetric mesh of quadratic elements (8-node quadrilaterals, 6-node triangles) in (r, z),
//! and a structured block generator.

use crate::error::{Error, Result};
use crate::fe::axisymmetric::{jacobian, map_point};
use crate::fe::section::Section;
use crate::fe::shape::Shape;
use std::collections::BTreeMap;

pub const NODES_PER_ELEMENT: usize = 8;

#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// (r, z) of each node, mm.
    pub coords: Vec<[f64; 2]>,
    /// External node numbers (Gmsh tags), for messages and output.
    pub node_ids: Vec<u64>,
    /// Connectivity in internal node indices (order of `fe::shape`), 8 slots per element: a
    /// Q8's nodes, or a T6's six and its first node twice (`Shape::of`).
    pub elements: Vec<[usize; NODES_PER_ELEMENT]>,
    /// External element numbers.
    pub element_ids: Vec<u64>,
}

/// Side `side` (0..4 of a Q8, 0..3 of a T6) of element `element`: a 3-node edge, part of a
/// surface.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub struct Edge {
    pub element: usize,
    pub side: usize,
}

impl Mesh {
    /// Appends `other` as a separate body (no node shared), numbering its nodes and elements
    /// on from this mesh's; returns the offsets (first node, first element) of its entities.
    pub fn append(&mut self, other: &Mesh) -> (usize, usize) {
        let (n0, e0) = (self.coords.len(), self.elements.len());
        self.coords.extend(&other.coords);
        self.node_ids.extend((0..other.coords.len()).map(|k| (n0 + k + 1) as u64));
        self.elements.extend(other.elements.iter().map(|c| c.map(|n| n + n0)));
        self.element_ids.extend((0..other.elements.len()).map(|k| (e0 + k + 1) as u64));
        (n0, e0)
    }

    /// The mesh's size: the larger side of the box around its nodes (mm).
    pub fn largest_extent(&self) -> f64 {
        (0..2)
            .map(|c| {
                let (lo, hi) = self.coords.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| (lo.min(x[c]), hi.max(x[c])));
                hi - lo
            })
            .fold(0.0, f64::max)
    }

    pub fn element_coords(&self, e: usize) -> [[f64; 2]; NODES_PER_ELEMENT] {
        self.elements[e].map(|n| self.coords[n])
    }

    /// The shape of element `e`.
    pub fn shape(&self, e: usize) -> Shape {
        Shape::of(&self.elements[e])
    }

    /// The nodes of element `e`: 8 or 6 (without a T6's unused slots).
    pub fn element_nodes(&self, e: usize) -> &[usize] {
        &self.elements[e][..self.shape(e).nodes()]
    }

    /// The sides of element `e`.
    pub fn sides(&self, e: usize) -> impl Iterator<Item = Edge> + Clone {
        (0..self.shape(e).corners()).map(move |side| Edge { element: e, side })
    }

    /// Global nodes (start, end, middle) of an edge.
    pub fn edge_nodes(&self, edge: Edge) -> [usize; 3] {
        let conn = &self.elements[edge.element];
        Shape::of(conn).edge_nodes(edge.side).map(|a| conn[a])
    }

    /// Chord length of a (quadratic) edge: start to middle to end.
    pub fn edge_length(&self, edge: Edge) -> f64 {
        let [a, b, m] = self.edge_nodes(edge).map(|n| self.coords[n]);
        (m[0] - a[0]).hypot(m[1] - a[1]) + (b[0] - m[0]).hypot(b[1] - m[1])
    }

    /// The element sides on no other element: the boundary of every body.
    pub fn free_edges(&self) -> Vec<Edge> {
        let mut count: std::collections::HashMap<(usize, usize), usize> = std::collections::HashMap::new();
        let key = |e: Edge| {
            let [a, b, _] = self.edge_nodes(e);
            (a.min(b), a.max(b))
        };
        let all = (0..self.elements.len()).flat_map(|e| self.sides(e));
        for e in all.clone() {
            *count.entry(key(e)).or_default() += 1;
        }
        all.filter(|&e| count[&key(e)] == 1).collect()
    }

    /// The straight pieces (start to middle, middle to end) of `edges`, as (r, z) pairs.
    pub fn edge_segments(&self, edges: &[Edge]) -> Vec<[[f64; 2]; 2]> {
        edges
            .iter()
            .flat_map(|&e| {
                let [a, b, m] = self.edge_nodes(e).map(|n| self.coords[n]);
                [[a, m], [m, b]]
            })
            .collect()
    }

    /// The connected bodies (node lists, each sorted), nodes joined through shared elements.
    pub fn bodies(&self) -> Vec<Vec<usize>> {
        let mut parent: Vec<usize> = (0..self.coords.len()).collect();
        fn root(parent: &mut [usize], mut n: usize) -> usize {
            while parent[n] != n {
                parent[n] = parent[parent[n]];
                n = parent[n];
            }
            n
        }
        for conn in &self.elements {
            for &n in &conn[1..Shape::of(conn).nodes()] {
                let (a, b) = (root(&mut parent, conn[0]), root(&mut parent, n));
                parent[a.max(b)] = a.min(b);
            }
        }
        let mut groups: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
        let used: std::collections::HashSet<usize> = self.elements.iter().flatten().copied().collect();
        for n in (0..self.coords.len()).filter(|n| used.contains(n)) {
            groups.entry(root(&mut parent, n)).or_default().push(n);
        }
        groups.into_values().collect()
    }

    /// Checks an axisymmetric mesh (`validate_sections` with every element axisymmetric).
    pub fn validate(&self) -> Result<()> {
        self.validate_sections(&vec![Section::Axisymmetric; self.elements.len()])
    }

    /// Checks the mesh has elements, finite coordinates, its axisymmetric elements (by
    /// `sections`) at r >= 0, and no inverted or degenerate element.
    pub fn validate_sections(&self, sections: &[Section]) -> Result<()> {
        /// The largest coordinate accepted, mm.
        const MAX_COORDINATE: f64 = 1e9;
        if self.elements.is_empty() {
            return Err(Error::input("the mesh has no elements (slideline needs 8-node quadrilaterals or 6-node triangles)"));
        }
        let size = self.coords.iter().fold(0.0f64, |m, c| m.max(c[0].abs()).max(c[1].abs())).max(1.0);
        if let Some((i, c)) = self.coords.iter().enumerate().find(|(_, c)| !c[0].is_finite() || !c[1].is_finite()) {
            return Err(Error::input(format!("node {} at ({}, {}): coordinates must be finite", self.node_ids[i], c[0], c[1])));
        }
        // beyond 1e9 mm (1000 km) the element's products overflow or lose every digit: a typo
        // or other units, named at its node rather than as an element's odd Jacobian
        if let Some((i, c)) = self.coords.iter().enumerate().find(|(_, c)| c[0].abs() > MAX_COORDINATE || c[1].abs() > MAX_COORDINATE) {
            return Err(Error::input(format!(
                "node {} at ({:e}, {:e}): coordinates beyond {MAX_COORDINATE:e} mm (lengths are in mm)",
                self.node_ids[i], c[0], c[1]
            )));
        }
        let axisymmetric_nodes = (0..self.elements.len()).filter(|&e| sections[e].is_axisymmetric()).flat_map(|e| self.element_nodes(e).to_vec());
        if let Some(i) = axisymmetric_nodes.into_iter().find(|&n| self.coords[n][0] < -1e-9 * size) {
            let c = self.coords[i];
            return Err(Error::input(format!("node {} at (r, z) = ({}, {}): axisymmetric nodes need a finite r >= 0", self.node_ids[i], c[0], c[1])));
        }
        for e in 0..self.elements.len() {
            let (shape, x) = (self.shape(e), self.element_coords(e));
            let nodes = || self.element_nodes(e).iter().map(|&n| self.node_ids[n]).collect::<Vec<u64>>();
            let mut distinct = self.element_nodes(e).to_vec();
            distinct.sort_unstable();
            distinct.dedup();
            if distinct.len() < shape.nodes() {
                return Err(Error::input(format!(
                    "element {} (nodes {:?}): a node appears twice (collapsed elements are not supported)",
                    self.element_ids[e],
                    nodes()
                )));
            }
            // Gauss points (also checks r > 0 there) and corners (a collapsed side or corner
            // has det J = 0 exactly at the corner).
            let reference = shape.reference_nodes();
            let positive = |r: f64| {
                if sections[e].is_axisymmetric() && r <= 0.0 {
                    Err(format!("radius {r:.3e} <= 0 at an integration point: an axisymmetric mesh must lie at r >= 0"))
                } else {
                    Ok(())
                }
            };
            let gauss = shape.rule().map(|q| map_point(shape, &x, q.0).and_then(|g| positive(g.r)));
            let corners = reference[..shape.corners()].iter().map(|&c| jacobian(&x, &shape.functions(c).1, c).map(|_| ()));
            for check in gauss.into_iter().chain(corners) {
                if let Err(msg) = check {
                    return Err(Error::input(format!("element {} (nodes {:?}): {msg}", self.element_ids[e], nodes())));
                }
            }
        }
        Ok(())
    }
}

/// Named sets that come with a generated or imported mesh.
#[derive(Clone, Debug, Default)]
pub struct MeshSets {
    pub node_sets: BTreeMap<String, Vec<usize>>,
    pub element_sets: BTreeMap<String, Vec<usize>>,
    pub surfaces: BTreeMap<String, Vec<Edge>>,
}

impl MeshSets {
    /// Adds a surface and the node set of its nodes under the same name.
    pub fn add_surface(&mut self, mesh: &Mesh, name: &str, edges: Vec<Edge>) {
        let mut nodes: Vec<usize> = edges.iter().flat_map(|&e| mesh.edge_nodes(e)).collect();
        nodes.sort_unstable();
        nodes.dedup();
        self.node_sets.insert(name.to_string(), nodes);
        self.surfaces.insert(name.to_string(), edges);
    }
}

/// Most elements a generated mesh may have (about 2 GB of mesh and matrix on a workstation).
pub const MAX_GENERATED_ELEMENTS: usize = 5_000_000;

/// Refuses a generated mesh of more than [`MAX_GENERATED_ELEMENTS`] elements before any of it
/// is allocated.
pub fn check_element_count(count: Option<usize>, divisions: [usize; 2]) -> Result<()> {
    match count {
        Some(n) if n <= MAX_GENERATED_ELEMENTS => Ok(()),
        _ => Err(Error::input(format!(
            "mesh divisions {} x {}: {} elements is more than slideline generates ({MAX_GENERATED_ELEMENTS})",
            divisions[0],
            divisions[1],
            divisions[0] as f64 * divisions[1] as f64
        ))),
    }
}

/// Structured block of `nr x nz` Q8 elements on [r0, r1] x [z0, z1]. Sets: element set `all`,
/// node set `all`, and surfaces with node sets `inner` (r = r0), `outer` (r = r1),
/// `bottom` (z = z0), `top` (z = z1).
pub fn rectangle(r: [f64; 2], z: [f64; 2], divisions: [usize; 2]) -> Result<(Mesh, MeshSets)> {
    graded_rectangle(r, z, divisions, [1.0, 1.0])
}

/// Like [`rectangle`], with element sizes in geometric progression: in each direction the last
/// element is `ratio` times the first (ratio < 1 refines towards r1 or z1).
pub fn graded_rectangle(r: [f64; 2], z: [f64; 2], divisions: [usize; 2], ratio: [f64; 2]) -> Result<(Mesh, MeshSets)> {
    let [nr, nz] = divisions;
    if nr == 0 || nz == 0 {
        return Err(Error::input(format!("mesh.rectangle: divisions must be at least 1, got {divisions:?}")));
    }
    check_element_count(nr.checked_mul(nz), divisions)?;
    if !(r[1] > r[0] && z[1] > z[0] && r[0] >= 0.0) {
        return Err(Error::input(format!("mesh.rectangle: need 0 <= r0 < r1 and z0 < z1, got r = {r:?}, z = {z:?}")));
    }
    if !(ratio[0] > 0.0 && ratio[1] > 0.0) {
        return Err(Error::input(format!("mesh block: grading ratios must be > 0, got {ratio:?}")));
    }
    // element boundaries in geometric progression; mid-side nodes halfway
    let stations = |lo: f64, hi: f64, n: usize, q: f64| -> Vec<f64> {
        let growth = if n > 1 { q.powf(1.0 / (n - 1) as f64) } else { 1.0 };
        let sizes: Vec<f64> = (0..n).map(|k| growth.powi(k as i32)).collect();
        let total: f64 = sizes.iter().sum();
        let mut out = vec![lo];
        for s in sizes {
            let last = *out.last().unwrap();
            let next = last + (hi - lo) * s / total;
            out.push(0.5 * (last + next));
            out.push(next);
        }
        *out.last_mut().unwrap() = hi;
        out
    };
    let (rs, zs) = (stations(r[0], r[1], nr, ratio[0]), stations(z[0], z[1], nz, ratio[1]));
    Ok(mapped_block([nr, nz], |i, j| [rs[i], zs[j]]))
}

/// Structured block of `ni x nj` Q8 elements whose node (i, j) (i in 0..=2 ni along the first
/// direction, j in 0..=2 nj along the second, odd i and j together skipped: serendipity) lies
/// at `position(i, j)`. The map must keep (i, j) counter-clockwise in (r, z). Sets: element
/// set and node set `all`, surfaces with node sets `inner` (i = 0), `outer` (i = 2 ni),
/// `bottom` (j = 0), `top` (j = 2 nj).
pub fn mapped_block(divisions: [usize; 2], position: impl Fn(usize, usize) -> [f64; 2]) -> (Mesh, MeshSets) {
    let [nr, nz] = divisions;
    let (gi, gj) = (2 * nr + 1, 2 * nz + 1);
    let mut index = vec![usize::MAX; gi * gj];
    let mut mesh = Mesh::default();
    for j in 0..gj {
        for i in 0..gi {
            if i % 2 == 1 && j % 2 == 1 {
                continue; // no centre node in the serendipity element
            }
            index[j * gi + i] = mesh.coords.len();
            mesh.coords.push(position(i, j));
            mesh.node_ids.push(mesh.coords.len() as u64);
        }
    }
    let at = |i: usize, j: usize| index[j * gi + i];
    let (mut inner, mut outer, mut bottom, mut top) = (vec![], vec![], vec![], vec![]);
    for ej in 0..nz {
        for ei in 0..nr {
            let (i, j) = (2 * ei, 2 * ej);
            let e = mesh.elements.len();
            mesh.elements.push([at(i, j), at(i + 2, j), at(i + 2, j + 2), at(i, j + 2), at(i + 1, j), at(i + 2, j + 1), at(i + 1, j + 2), at(i, j + 1)]);
            mesh.element_ids.push(e as u64 + 1);
            if ej == 0 {
                bottom.push(Edge { element: e, side: 0 });
            }
            if ei == nr - 1 {
                outer.push(Edge { element: e, side: 1 });
            }
            if ej == nz - 1 {
                top.push(Edge { element: e, side: 2 });
            }
            if ei == 0 {
                inner.push(Edge { element: e, side: 3 });
            }
        }
    }
    let mut sets = MeshSets::default();
    sets.element_sets.insert("all".into(), (0..mesh.elements.len()).collect());
    sets.node_sets.insert("all".into(), (0..mesh.coords.len()).collect());
    for (name, edges) in [("inner", inner), ("outer", outer), ("bottom", bottom), ("top", top)] {
        sets.add_surface(&mesh, name, edges);
    }
    (mesh, sets)
}

/// Splits every Q8 of a generated mesh into two T6 along its diagonal from corner 0 to corner
/// 2, through a new node at the Q8's centre (its reference point (0, 0), on the diagonal): a
/// structured triangle mesh of the same region and sets. Element e becomes 2e and 2e + 1; node
/// set `all` takes the new nodes.
pub fn split_into_triangles(mesh: &Mesh, sets: &MeshSets) -> (Mesh, MeshSets) {
    let mut out = Mesh { coords: mesh.coords.clone(), node_ids: mesh.node_ids.clone(), ..Mesh::default() };
    let (n, _) = Shape::Quad8.functions([0.0, 0.0]);
    let first_id = mesh.node_ids.iter().max().copied().unwrap_or(0) + 1;
    for (e, c) in mesh.elements.iter().enumerate() {
        let x = mesh.element_coords(e);
        out.coords.push([0, 1].map(|k| (0..8).map(|a| n[a] * x[a][k]).sum()));
        out.node_ids.push(first_id + e as u64);
        let centre = out.coords.len() - 1;
        out.elements.push(Shape::tri6_slots([c[0], c[1], c[2], c[4], c[5], centre]));
        out.elements.push(Shape::tri6_slots([c[0], c[2], c[3], centre, c[6], c[7]]));
        out.element_ids.extend([2 * e as u64 + 1, 2 * e as u64 + 2]);
    }
    // a Q8 side -> (which triangle, its side)
    let side_of = |edge: Edge| match edge.side {
        0 => Edge { element: 2 * edge.element, side: 0 },
        1 => Edge { element: 2 * edge.element, side: 1 },
        2 => Edge { element: 2 * edge.element + 1, side: 1 },
        _ => Edge { element: 2 * edge.element + 1, side: 2 },
    };
    let mut split = sets.clone();
    for members in split.element_sets.values_mut() {
        *members = members.iter().flat_map(|&e| [2 * e, 2 * e + 1]).collect();
    }
    for edges in split.surfaces.values_mut() {
        *edges = edges.iter().map(|&e| side_of(e)).collect();
    }
    if let Some(all) = split.node_sets.get_mut("all") {
        all.extend(mesh.coords.len()..out.coords.len());
    }
    (out, split)
}

/// One structured block of a multi-block mesh.
#[derive(Clone, Debug)]
pub struct Block {
    pub name: String,
    pub r: [f64; 2],
    pub z: [f64; 2],
    pub divisions: [usize; 2],
    pub grading: [f64; 2],
    /// Each quadrilateral split into two 6-node triangles.
    pub triangles: bool,
}

/// Separate bodies, one per block (nodes are not shared). Each block's sets carry its name:
/// element set `NAME`, node set `NAME`, surfaces and node sets `NAME_inner`, `NAME_outer`,
/// `NAME_bottom`, `NAME_top`; `all` names everything.
pub fn blocks(specs: &[Block]) -> Result<(Mesh, MeshSets)> {
    let mut mesh = Mesh::default();
    let mut sets = MeshSets::default();
    for b in specs {
        let (m, s) = graded_rectangle(b.r, b.z, b.divisions, b.grading).map_err(|e| Error::input(format!("mesh block '{}': {e}", b.name)))?;
        let (m, s) = if b.triangles { split_into_triangles(&m, &s) } else { (m, s) };
        let (n0, e0) = mesh.append(&m);
        if sets.element_sets.contains_key(&b.name) {
            return Err(Error::input(format!("mesh block '{}' is defined twice", b.name)));
        }
        sets.element_sets.insert(b.name.clone(), (e0..e0 + m.elements.len()).collect());
        sets.node_sets.insert(b.name.clone(), (n0..n0 + m.coords.len()).collect());
        for side in ["inner", "outer", "bottom", "top"] {
            let name = format!("{}_{side}", b.name);
            sets.node_sets.insert(name.clone(), s.node_sets[side].iter().map(|n| n + n0).collect());
            sets.surfaces.insert(name, s.surfaces[side].iter().map(|e| Edge { element: e.element + e0, side: e.side }).collect());
        }
    }
    sets.element_sets.insert("all".into(), (0..mesh.elements.len()).collect());
    sets.node_sets.insert("all".into(), (0..mesh.coords.len()).collect());
    Ok((mesh, sets))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_block_split_into_triangles_keeps_its_area_boundary_and_sets() {
        let (q, qs) = mapped_block([3, 2], |i, j| [10.0 + i as f64 + 0.1 * j as f64, j as f64 * 0.7]);
        let (t, ts) = split_into_triangles(&q, &qs);
        t.validate().unwrap();
        assert_eq!(t.elements.len(), 12);
        assert!((0..12).all(|e| t.shape(e) == Shape::Tri6));
        // the same area (sum of det J w over the rule) and the same boundary length
        let area = |m: &Mesh| -> f64 {
            (0..m.elements.len())
                .map(|e| {
                    let (s, x) = (m.shape(e), m.element_coords(e));
                    s.rule().iter().map(|(p, w)| w * jacobian(&x, &s.functions(*p).1, *p).unwrap().1).sum::<f64>()
                })
                .sum()
        };
        assert!((area(&q) - area(&t)).abs() < 1e-12 * area(&q));
        let boundary = |m: &Mesh| m.free_edges().iter().map(|&e| m.edge_length(e)).sum::<f64>();
        assert!((boundary(&q) - boundary(&t)).abs() < 1e-12);
        for name in ["inner", "outer", "bottom", "top"] {
            let nodes = |m: &Mesh, s: &MeshSets| {
                let mut n: Vec<usize> = s.surfaces[name].iter().flat_map(|&e| m.edge_nodes(e)).collect();
                n.sort_unstable();
                n.dedup();
                n
            };
            assert_eq!(nodes(&q, &qs), nodes(&t, &ts), "surface {name}");
        }
        assert_eq!(ts.node_sets["all"].len(), t.coords.len());
        assert_eq!(ts.element_sets["all"].len(), 12);
        assert_eq!(t.bodies().len(), 1);
    }

    #[test]
    fn grading_refines_towards_the_far_end_and_blocks_are_separate_bodies() {
        let (mesh, _) = graded_rectangle([0.0, 10.0], [0.0, 1.0], [4, 1], [0.25, 1.0]).unwrap();
        let mut r: Vec<f64> = mesh.coords.iter().map(|c| c[0]).collect();
        r.sort_by(f64::total_cmp);
        r.dedup();
        let first = r[2] - r[0];
        let last = r[r.len() - 1] - r[r.len() - 3];
        assert!((last / first - 0.25).abs() < 1e-12, "{first} {last}");
        mesh.validate().unwrap();
        let specs = [
            Block { name: "a".into(), r: [0.0, 1.0], z: [0.0, 1.0], divisions: [1, 1], grading: [1.0, 1.0], triangles: false },
            Block { name: "b".into(), r: [0.0, 1.0], z: [1.0, 2.0], divisions: [2, 1], grading: [1.0, 1.0], triangles: false },
        ];
        let (mesh, sets) = blocks(&specs).unwrap();
        assert_eq!(mesh.elements.len(), 3);
        assert_eq!(mesh.coords.len(), 8 + 13);
        assert_eq!(sets.surfaces["b_bottom"].len(), 2);
        assert!(sets.node_sets["a_top"].iter().all(|n| !sets.node_sets["b_bottom"].contains(n)));
    }

    #[test]
    fn rectangle_has_expected_counts_and_valid_elements() {
        let (mesh, sets) = rectangle([1.0, 3.0], [0.0, 1.0], [4, 2]).unwrap();
        assert_eq!(mesh.elements.len(), 8);
        assert_eq!(mesh.coords.len(), 9 * 5 - 4 * 2);
        mesh.validate().unwrap();
        assert_eq!(sets.node_sets["inner"].len(), 5);
        assert_eq!(sets.surfaces["top"].len(), 4);
        for &n in &sets.node_sets["outer"] {
            assert_eq!(mesh.coords[n][0], 3.0);
        }
    }

    #[test]
    fn empty_mesh_is_rejected() {
        let err = Mesh::default().validate().unwrap_err().to_string();
        assert!(err.contains("no elements"), "{err}");
    }
}
