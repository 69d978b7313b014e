//! The mesh cards of a deck: *NODE, *ELEMENT (CAX4 and CAX3 elements get shared mid-side nodes),
//! *NSET / *ELSET, *SURFACE.

use super::cards::{error_at, Card, DataLine, Location};
use super::{face_side, Builder};
use crate::error::Result;
use crate::fe::quadrature::Integration;
use crate::fe::section::Section;
use crate::fe::shape::Shape;
use crate::model::mesh::Edge;
use std::collections::BTreeSet;

impl Builder {
    pub(super) fn nodes(&mut self, card: &Card) -> Result<()> {
        card.only(&["NSET"])?;
        let mut ids = Vec::new();
        for d in &card.data {
            let id = d.id("NODE", 0, "node number")?;
            let r = d.number("NODE", 1, "r (first coordinate)", Some(0.0))?;
            let z = d.number("NODE", 2, "z (second coordinate)", Some(0.0))?;
            if d.fields.len() > 3 && d.number("NODE", 3, "third coordinate", Some(0.0))? != 0.0 {
                return Err(error_at(
                    &d.at,
                    "NODE",
                    format!("node {id} has a third coordinate: slideline's models are two-dimensional (the r-z plane, or x-y for a plane model)"),
                ));
            }
            if self.node_index.contains_key(&id) {
                return Err(error_at(&d.at, "NODE", format!("node {id} is defined twice (or clashes with a mid-side node added to a CAX4 element)")));
            }
            self.node_index.insert(id, self.mesh.coords.len());
            ids.push(self.mesh.coords.len());
            self.mesh.coords.push([r, z]);
            self.mesh.node_ids.push(id);
        }
        if let Some(name) = card.param("NSET") {
            self.node_sets.entry(name.to_uppercase()).or_default().extend(ids);
        }
        Ok(())
    }

    pub(super) fn node(&self, d: &DataLine, keyword: &str, k: usize) -> Result<usize> {
        let id = d.id(keyword, k, "node number")?;
        self.node_index.get(&id).copied().ok_or_else(|| error_at(&d.at, keyword, format!("node {id} is not defined")))
    }

    /// Point masses (type MASS, one node each): not elements of slideline's mesh; their nodes
    /// are kept by set, for the *MASS card and a GRAV or CENTRIF load on the set.
    fn point_masses(&mut self, card: &Card) -> Result<()> {
        let set = card.param("ELSET").map(|s| s.to_uppercase()).ok_or_else(|| card.error("point masses (TYPE=MASS) need an ELSET for their *MASS card"))?;
        let mut nodes = Vec::new();
        for d in &card.data {
            nodes.push(self.node(d, "ELEMENT", 1)?);
        }
        self.point_masses.entry(set).or_insert((Vec::new(), None)).0.extend(nodes);
        Ok(())
    }

    pub(super) fn elements(&mut self, card: &Card) -> Result<()> {
        card.only(&["TYPE", "ELSET"])?;
        let kind = card.required("TYPE")?.to_uppercase();
        // (shape, nodes listed): the linear CAX4 and CAX3 get mid-side nodes
        // the section family (its thickness comes with *SOLID SECTION): CAX, CPE, CPS
        let family = match kind.get(..3) {
            Some("CPE") => Section::PlaneStrain { thickness: 1.0 },
            Some("CPS") => Section::PlaneStress { thickness: 1.0 },
            _ => Section::Axisymmetric,
        };
        let (shape, per_element) = match kind.get(3..).filter(|_| ["CAX", "CPE", "CPS"].contains(&&kind[..3])) {
            Some("8" | "8R") => (Shape::Quad8, 8),
            Some("4" | "4R") => (Shape::Quad8, 4),
            Some("6") => (Shape::Tri6, 6),
            Some("3") => (Shape::Tri6, 3),
            _ if kind == "MASS" => return self.point_masses(card),
            _ => {
                let why = match kind.as_str() {
                    "D" => "fluid network elements: slideline has no fluid networks",
                    _ => "outside the subset (slideline reads the axisymmetric CAX8, CAX8R, CAX6, CAX4, CAX4R, CAX3 and the plane CPE.., CPS.. of the same shapes)",
                };
                return Err(card.error(format!("element type {kind}: {why}")));
            }
        };
        // CalculiX's and Abaqus's CAX8R integrate 2 x 2; a CAX4R, read as a Q8, is not that
        // element (one point with hourglass control) whichever way it is integrated
        let integration = if kind.ends_with("8R") || kind.ends_with('6') { Integration::Reduced } else { Integration::Full };
        let corners_only = per_element == shape.corners();
        // an element's node list may continue on following lines
        let mut pending: Vec<(String, Location)> = Vec::new();
        let mut ids = Vec::new();
        for d in &card.data {
            pending.extend(d.fields.iter().filter(|f| !f.is_empty()).map(|f| (f.clone(), d.at.clone())));
            if pending.len() < per_element + 1 {
                // a line continues on the next only where it ends with a comma (Abaqus's rule;
                // CalculiX's elements fit on one line): a short line is its own error
                if d.continues {
                    continue;
                }
                return Err(error_at(
                    &pending[0].1,
                    "ELEMENT",
                    format!("{kind} takes {per_element} nodes after the element number, this line has {} (a line continues on the next only where it ends with a comma)", pending.len() - 1),
                ));
            }
            if pending.len() > per_element + 1 {
                return Err(error_at(&d.at, "ELEMENT", format!("{kind} takes {per_element} nodes, got {}", pending.len() - 1)));
            }
            let line = DataLine { fields: pending.iter().map(|p| p.0.clone()).collect(), at: pending[0].1.clone(), continues: false };
            pending.clear();
            let id = line.id("ELEMENT", 0, "element number")?;
            if self.element_index.contains_key(&id) {
                return Err(error_at(&line.at, "ELEMENT", format!("element {id} is defined twice")));
            }
            let mut conn = [0usize; 8];
            for (k, slot) in conn.iter_mut().take(per_element).enumerate() {
                *slot = self.node(&line, "ELEMENT", k + 1)?;
            }
            let c = shape.corners();
            if corners_only {
                for s in 0..c {
                    conn[c + s] = self.midside(conn[s], conn[(s + 1) % c]);
                }
            }
            if shape == Shape::Tri6 {
                conn = Shape::tri6_slots([conn[0], conn[1], conn[2], conn[3], conn[4], conn[5]]);
            }
            self.element_index.insert(id, self.mesh.elements.len());
            ids.push(self.mesh.elements.len());
            self.mesh.elements.push(conn);
            self.mesh.element_ids.push(id);
            self.element_family.push(family);
            self.element_integration.push(integration);
        }
        if let Some((_, at)) = pending.first() {
            return Err(error_at(at, "ELEMENT", format!("{kind} takes {per_element} nodes, the last element has {}", pending.len() - 1)));
        }
        *self.element_types.entry(kind).or_default() += ids.len();
        if let Some(name) = card.param("ELSET") {
            self.element_sets.entry(name.to_uppercase()).or_default().extend(ids);
        }
        Ok(())
    }

    /// The mid-side node between corners `a` and `b` of a CAX4 element (shared by both
    /// elements on the edge), at the middle of the straight edge.
    pub(super) fn midside(&mut self, a: usize, b: usize) -> usize {
        let key = (a.min(b), a.max(b));
        if let Some(&n) = self.added_midside.get(&key) {
            return n;
        }
        let (pa, pb) = (self.mesh.coords[a], self.mesh.coords[b]);
        let id = self.node_index.keys().max().copied().unwrap_or(0) + 1;
        let n = self.mesh.coords.len();
        self.mesh.coords.push([0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1])]);
        self.mesh.node_ids.push(id);
        self.node_index.insert(id, n);
        self.added_midside.insert(key, n);
        n
    }

    /// An added mid-side node joins every node set that holds both corners of its edge, so that
    /// a constraint on the set holds the whole (quadratic) edge, as it holds CalculiX's linear
    /// edge between the two corners.
    pub(super) fn join_midside_nodes_to_sets(&mut self) {
        if self.added_midside.is_empty() {
            return;
        }
        for set in self.node_sets.values_mut() {
            set.sort_unstable();
            set.dedup();
            let holds = |n: &usize| set.binary_search(n).is_ok();
            let mut joined: Vec<usize> = self.added_midside.iter().filter(|((a, b), _)| holds(a) && holds(b)).map(|(_, &m)| m).collect();
            if !joined.is_empty() {
                set.append(&mut joined);
                set.sort_unstable();
            }
        }
    }

    /// The nodes of data field `k`: a node number or a node set name.
    pub(super) fn node_items(&self, d: &DataLine, keyword: &str, k: usize) -> Result<Vec<usize>> {
        let f = d.fields.get(k).map(|s| s.as_str()).unwrap_or("");
        if f.chars().all(|c| c.is_ascii_digit()) && !f.is_empty() {
            return Ok(vec![self.node(d, keyword, k)?]);
        }
        self.node_sets
            .get(&f.to_uppercase())
            .cloned()
            .ok_or_else(|| error_at(&d.at, keyword, format!("node set '{f}' is not defined (define it before its use)")))
    }

    /// The elements of data field `k`: an element number or an element set name.
    pub(super) fn element_items(&self, d: &DataLine, keyword: &str, k: usize) -> Result<Vec<usize>> {
        let f = d.fields.get(k).map(|s| s.as_str()).unwrap_or("");
        if f.chars().all(|c| c.is_ascii_digit()) && !f.is_empty() {
            let id = d.id(keyword, k, "element number")?;
            return self.element_index.get(&id).map(|&e| vec![e]).ok_or_else(|| error_at(&d.at, keyword, format!("element {id} is not defined")));
        }
        self.element_sets
            .get(&f.to_uppercase())
            .cloned()
            .ok_or_else(|| error_at(&d.at, keyword, format!("element set '{f}' is not defined (define it before its use)")))
    }

    pub(super) fn set(&mut self, card: &Card) -> Result<()> {
        let nodes = card.keyword == "NSET";
        let kw = card.keyword.as_str();
        let param = if nodes { "NSET" } else { "ELSET" };
        card.only(&[param, "GENERATE"])?;
        let name = card.required(param)?.to_uppercase();
        let mut members = Vec::new();
        for d in &card.data {
            if card.has("GENERATE") {
                let (first, last) = (d.id(kw, 0, "first number")?, d.id(kw, 1, "last number")?);
                let step = if d.fields.len() > 2 { d.id(kw, 2, "increment")? } else { 1 };
                if last < first {
                    return Err(error_at(&d.at, kw, format!("GENERATE from {first} to {last}: the last number is smaller")));
                }
                for id in (first..=last).step_by(step as usize) {
                    let index = if nodes { self.node_index.get(&id) } else { self.element_index.get(&id) };
                    let what = if nodes { "node" } else { "element" };
                    members.push(*index.ok_or_else(|| error_at(&d.at, kw, format!("{what} {id} (generated) is not defined")))?);
                }
            } else {
                for k in (0..d.fields.len()).filter(|&k| !d.fields[k].is_empty()) {
                    members.extend(if nodes { self.node_items(d, kw, k)? } else { self.element_items(d, kw, k)? });
                }
            }
        }
        let set = if nodes { self.node_sets.entry(name).or_default() } else { self.element_sets.entry(name).or_default() };
        set.extend(members);
        set.sort_unstable();
        set.dedup();
        Ok(())
    }

    pub(super) fn surface(&mut self, card: &Card) -> Result<()> {
        card.only(&["NAME", "TYPE"])?;
        let name = card.required("NAME")?.to_uppercase();
        let mut edges = Vec::new();
        match card.param("TYPE").map(|t| t.to_uppercase()).as_deref() {
            None | Some("ELEMENT") => {
                for d in &card.data {
                    let face = d.fields.get(1).map(|s| s.to_uppercase()).unwrap_or_default();
                    let side = face_side(&face, 'S').ok_or_else(|| {
                        error_at(&d.at, "SURFACE", format!("face '{face}': axisymmetric quadrilaterals have faces S1 to S4, triangles S1 to S3"))
                    })?;
                    for element in self.element_items(d, "SURFACE", 0)? {
                        if side >= self.mesh.shape(element).corners() {
                            let id = self.mesh.element_ids[element];
                            return Err(error_at(&d.at, "SURFACE", format!("face '{face}' of element {id}: a triangle has faces S1 to S3")));
                        }
                        edges.push(Edge { element, side });
                    }
                }
            }
            Some("NODE") => {
                let mut nodes = BTreeSet::new();
                for d in &card.data {
                    nodes.extend(self.node_items(d, "SURFACE", 0)?);
                }
                // Abaqus's optional area beside each node: CalculiX does not read it either
                if let Some(d) = card.data.iter().find(|d| d.fields.iter().skip(1).any(|f| !f.is_empty())) {
                    self.notes.push(format!(
                        "surface {name}: the area given beside a node ({}) is not used: a node-based slave bears with the area of the master face it meets (CalculiX's rule)",
                        d.at
                    ));
                }
                // the free faces whose two corners belong to the set (CAX4 faces have no mid-side node in it)
                edges.extend(self.mesh.free_edges().into_iter().filter(|&e| {
                    let [a, b, _] = self.mesh.edge_nodes(e);
                    nodes.contains(&a) && nodes.contains(&b)
                }));
                if edges.is_empty() {
                    return Err(card.error(format!("node-based surface {name}: no free element face has both corners in the set")));
                }
                // a node of the set on none of these faces (a mid-side node of a face with one
                // corner outside) has no area of its own there
                let on_faces: BTreeSet<usize> = edges.iter().flat_map(|&e| self.mesh.edge_nodes(e)).collect();
                let left: Vec<u64> = nodes.difference(&on_faces).map(|&n| self.mesh.node_ids[n]).collect();
                let left = match left.len() {
                    0 => String::new(),
                    k => format!(" ({k} of its nodes, {}, lie on none of them)", crate::error::first_ten(&left)),
                };
                self.notes.push(format!(
                    "surface {name} ({}) is node-based: as the slave of a NODE TO SURFACE pair each of its {} nodes bears on the master with the area of the master face it meets, as in CalculiX; elsewhere slideline uses the {} free element faces whose corners belong to it{left}",
                    card.at,
                    nodes.len(),
                    edges.len()
                ));
                self.node_surfaces.entry(name.clone()).or_default().extend(nodes);
            }
            Some(other) => return Err(card.error(format!("TYPE={other} is not supported (ELEMENT or NODE)"))),
        }
        edges.sort();
        edges.dedup();
        self.surfaces.entry(name).or_default().extend(edges);
        Ok(())
    }
}
