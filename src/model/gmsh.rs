//! Reader for Gmsh .msh meshes: format 4.1 (ASCII and binary) and 2.2 (ASCII).
//!
//! Physical groups become sets: a 2D group becomes an element set (and a node set of its
//! nodes), a 1D group a surface of 3-node edges (and the node set of its nodes), a 0D group a
//! node set. Every name is the group's physical name (or `physical_<tag>` if it has none).
//! Elements must be quadratic: 8-node quadrilaterals (Gmsh type 16: `Mesh.ElementOrder = 2`,
//! `Mesh.SecondOrderIncomplete = 1`, recombined) or 6-node triangles (type 9, what
//! `Mesh.ElementOrder = 2` gives without recombination), mixed as they come. Errors name the
//! file and line (the element block in a binary file).
//!
//! (The `mshio` crate was considered: it drops node tags of densely numbered files and ignores
//! `$PhysicalNames`, which is where set names come from.)

use super::mesh::{Edge, Mesh, MeshSets};
use crate::error::{Error, Result};
use crate::fe::shape::Shape;
use std::collections::{BTreeMap, HashMap};
use std::path::Path;

const QUAD8: u32 = 16;
const TRI6: u32 = 9;
const LINE3: u32 = 8;
const POINT: u32 = 15;

mod binary;
mod write;
pub use write::{to_msh, write};

pub fn read(path: &Path) -> Result<(Mesh, MeshSets)> {
    if path.extension().is_some_and(|e| e.eq_ignore_ascii_case("geo")) {
        return Err(Error::input(format!(
            "{}: a Gmsh geometry, not a mesh: mesh it first (gmsh -2 -order 2 -format msh41 {}) and give the .msh",
            path.display(),
            path.display()
        )));
    }
    let bytes = std::fs::read(path).map_err(|source| Error::Read { path: path.to_path_buf(), source })?;
    let name = path.display().to_string();
    if binary::is_binary(&bytes) {
        return assemble(binary::parse(&bytes, &name)?, &name);
    }
    let text = String::from_utf8(bytes)
        .map_err(|_| Error::input(format!("{name}: neither a text .msh nor a binary .msh 4.1 (Gmsh: -format msh41, or msh22 for text)")))?;
    parse(&text, &name)
}

/// What a .msh file says, before it becomes a mesh: physical names, the entities' physical
/// groups, node coordinates and elements of every dimension.
#[derive(Default)]
struct RawMesh {
    physical_names: HashMap<(i32, i32), String>,
    /// (dim, entity tag) -> physical tags
    entity_physicals: HashMap<(i32, i32), Vec<i32>>,
    node_coords: HashMap<u64, [f64; 2]>,
    elements: Vec<RawElement>,
}

struct RawElement {
    dim: i32,
    entity: i32,
    ty: u32,
    tag: u64,
    nodes: Vec<u64>,
    /// Where it is, for messages: "FILE:LINE" (text) or "FILE, element block K" (binary).
    at: String,
}

struct Lines<'a> {
    name: &'a str,
    lines: std::iter::Enumerate<std::str::Lines<'a>>,
    line: usize,
}

impl<'a> Lines<'a> {
    fn next(&mut self) -> Result<&'a str> {
        for (i, l) in self.lines.by_ref() {
            self.line = i + 1;
            if !l.trim().is_empty() {
                return Ok(l.trim());
            }
        }
        Err(self.error("unexpected end of file"))
    }

    fn error(&self, msg: impl std::fmt::Display) -> Error {
        Error::input(format!("{}:{}: {msg}", self.name, self.line))
    }

    /// Next line parsed as whitespace-separated numbers.
    fn numbers<T: std::str::FromStr>(&mut self, what: &str) -> Result<Vec<T>> {
        let l = self.next()?;
        l.split_whitespace().map(|t| t.parse::<T>().map_err(|_| self.error(format!("bad number {t:?} in {what}")))).collect()
    }

    fn expect(&mut self, tag: &str) -> Result<()> {
        let l = self.next()?;
        if l != tag {
            return Err(self.error(format!("expected {tag}, found {l:?}")));
        }
        Ok(())
    }
}

/// Adds a node; a tag given again is accepted at the same place only.
fn insert_node(node_coords: &mut HashMap<u64, [f64; 2]>, tag: u64, at: [f64; 2], lines: &Lines) -> Result<()> {
    match node_coords.insert(tag, at) {
        Some(before) if before != at => Err(lines.error(format!("node {tag} is given twice, at ({}, {}) and at ({}, {})", before[0], before[1], at[0], at[1]))),
        _ => Ok(()),
    }
}

fn need<T: Copy>(v: &[T], n: usize, lines: &Lines, what: &str) -> Result<()> {
    if v.len() < n {
        return Err(lines.error(format!("{what}: expected at least {n} values, found {}", v.len())));
    }
    Ok(())
}

/// Dimension of a Gmsh element type (points 0, lines 1, surfaces 2, volumes 3).
fn type_dimension(ty: u32) -> i32 {
    match ty {
        15 => 0,
        1 | 8 | 26 | 27 | 28 => 1,
        2 | 3 | 9 | 10 | 16 | 20 | 21 | 22 | 23 | 24 | 25 => 2,
        _ => 3,
    }
}

/// A text .msh (4.1 or 2.2) as a mesh and its sets.
pub fn parse(text: &str, name: &str) -> Result<(Mesh, MeshSets)> {
    assemble(parse_text(text, name)?, name)
}

/// A format 4.1 $Nodes section (after its header line): every block's tags, then their
/// coordinates, the counts checked against the header.
fn nodes_41(lines: &mut Lines<'_>, node_coords: &mut HashMap<u64, [f64; 2]>) -> Result<()> {
    let h: Vec<u64> = lines.numbers("$Nodes header")?;
    need(&h, 4, lines, "$Nodes header")?;
    let mut read = 0u64;
    for _ in 0..h[0] {
        let b: Vec<i64> = lines.numbers("node block header")?;
        need(&b, 4, lines, "node block header")?;
        if b[2] != 0 {
            return Err(lines.error("parametric node coordinates are not supported"));
        }
        if b[3] < 0 || b[3] as u64 > h[1] - read.min(h[1]) {
            return Err(lines.error(format!("a node block of {} nodes, past the {} the $Nodes header gives", b[3], h[1])));
        }
        let n = b[3] as usize;
        read += n as u64;
        // the count comes from the file: reserve no more than a line can hold
        let mut tags = Vec::with_capacity(n.min(1 << 16));
        for _ in 0..n {
            let t: Vec<u64> = lines.numbers("node tag")?;
            need(&t, 1, lines, "node tag")?;
            tags.push(t[0]);
        }
        for tag in tags {
            let c: Vec<f64> = lines.numbers("node coordinates")?;
            need(&c, 3, lines, "node coordinates")?;
            if c[2] != 0.0 {
                return Err(lines.error(format!("node {tag} has z = {}: the mesh must lie in the x-y plane (x = r, y = z)", c[2])));
            }
            insert_node(node_coords, tag, [c[0], c[1]], lines)?;
        }
    }
    if read != h[1] {
        return Err(lines.error(format!("the $Nodes header gives {} nodes, its blocks hold {read}", h[1])));
    }
    lines.expect("$EndNodes")?;
    Ok(())
}

/// A format 4.1 $Elements section: every block's elements, no tag twice, the counts checked
/// against the header.
fn elements_41(lines: &mut Lines<'_>, elements: &mut Vec<RawElement>, element_tags: &mut std::collections::HashSet<u64>) -> Result<()> {
    let h: Vec<u64> = lines.numbers("$Elements header")?;
    need(&h, 4, lines, "$Elements header")?;
    let mut read = 0u64;
    for _ in 0..h[0] {
        let b: Vec<i64> = lines.numbers("element block header")?;
        need(&b, 4, lines, "element block header")?;
        let (dim, entity, ty) = (b[0] as i32, b[1] as i32, b[2] as u32);
        if b[3] < 0 || b[3] as u64 > h[1] - read.min(h[1]) {
            return Err(lines.error(format!("an element block of {} elements, past the {} the $Elements header gives", b[3], h[1])));
        }
        read += b[3] as u64;
        for _ in 0..b[3] {
            let v: Vec<u64> = lines.numbers("element")?;
            need(&v, 2, lines, "element")?;
            if !element_tags.insert(v[0]) {
                return Err(lines.error(format!("element {} is given twice", v[0])));
            }
            elements.push(RawElement { dim, entity, ty, tag: v[0], nodes: v[1..].to_vec(), at: format!("{}:{}", lines.name, lines.line) });
        }
    }
    if read != h[1] {
        return Err(lines.error(format!("the $Elements header gives {} elements, its blocks hold {read}", h[1])));
    }
    lines.expect("$EndElements")?;
    Ok(())
}

fn parse_text(text: &str, name: &str) -> Result<RawMesh> {
    let mut lines = Lines { name, lines: text.lines().enumerate(), line: 0 };
    let mut raw = RawMesh::default();
    let RawMesh { physical_names, entity_physicals, node_coords, elements } = &mut raw;
    let mut seen_format = false;
    // format 2.2: each element names its physical group itself (its first tag)
    let mut legacy = false;

    // a section given twice, a count its blocks do not hold, a tag given twice: refused by name
    let (mut nodes_seen, mut elements_seen) = (false, false);
    let mut element_tags: std::collections::HashSet<u64> = std::collections::HashSet::new();
    while let Ok(header) = lines.next() {
        if header == "$Nodes" && std::mem::replace(&mut nodes_seen, true) || header == "$Elements" && std::mem::replace(&mut elements_seen, true) {
            return Err(lines.error(format!("a second {header} section: a mesh has one")));
        }
        match header {
            "$MeshFormat" => {
                let l = lines.next()?;
                let f: Vec<&str> = l.split_whitespace().collect();
                legacy = f.first() == Some(&"2.2");
                if f.first() != Some(&"4.1") && !legacy {
                    return Err(lines
                        .error(format!("unsupported .msh version {:?}: slideline reads formats 4.1 and 2.2 (Gmsh: -format msh41)", f.first().unwrap_or(&""))));
                }
                if f.get(1) != Some(&"0") {
                    return Err(lines.error("a binary .msh 2.2: slideline reads binary files in format 4.1 (Gmsh: -format msh41) and 2.2 as text"));
                }
                lines.expect("$EndMeshFormat")?;
                seen_format = true;
            }
            "$PhysicalNames" => {
                let n: Vec<usize> = lines.numbers("$PhysicalNames count")?;
                need(&n, 1, &lines, "$PhysicalNames")?;
                for _ in 0..n[0] {
                    let l = lines.next()?;
                    let mut it = l.splitn(3, char::is_whitespace);
                    let dim = it.next().and_then(|t| t.parse().ok());
                    let tag = it.next().and_then(|t| t.parse().ok());
                    let nm = it.next().map(|t| t.trim().trim_matches('"').to_string());
                    match (dim, tag, nm) {
                        (Some(d), Some(t), Some(nm)) if !nm.is_empty() => {
                            physical_names.insert((d, t), nm);
                        }
                        _ => return Err(lines.error(format!("bad physical name line {l:?}"))),
                    }
                }
                lines.expect("$EndPhysicalNames")?;
            }
            "$Entities" => {
                let counts: Vec<usize> = lines.numbers("$Entities counts")?;
                need(&counts, 4, &lines, "$Entities")?;
                for (dim, &count) in counts.iter().take(4).enumerate() {
                    for _ in 0..count {
                        let v: Vec<f64> = lines.numbers("entity")?;
                        // point: tag x y z nphys phys...; others: tag 6 bbox values nphys phys... nbound ...
                        let at = if dim == 0 { 4 } else { 7 };
                        need(&v, at + 1, &lines, "entity")?;
                        let np = v[at] as usize;
                        need(&v, at + 1 + np, &lines, "entity physical tags")?;
                        let phys = v[at + 1..at + 1 + np].iter().map(|&p| p as i32).collect();
                        entity_physicals.insert((dim as i32, v[0] as i32), phys);
                    }
                }
                lines.expect("$EndEntities")?;
            }
            "$Nodes" if legacy => {
                let n: Vec<u64> = lines.numbers("$Nodes count")?;
                need(&n, 1, &lines, "$Nodes count")?;
                for _ in 0..n[0] {
                    let v: Vec<f64> = lines.numbers("node")?;
                    need(&v, 4, &lines, "node (tag x y z)")?;
                    let tag = v[0] as u64;
                    if v[3] != 0.0 {
                        return Err(lines.error(format!("node {tag} has z = {}: the mesh must lie in the x-y plane (x = r, y = z)", v[3])));
                    }
                    insert_node(node_coords, tag, [v[1], v[2]], &lines)?;
                }
                lines.expect("$EndNodes")?;
            }
            "$Elements" if legacy => {
                let n: Vec<u64> = lines.numbers("$Elements count")?;
                need(&n, 1, &lines, "$Elements count")?;
                for _ in 0..n[0] {
                    // tag type ntags tags... nodes...; the first tag is the physical group
                    let v: Vec<u64> = lines.numbers("element")?;
                    need(&v, 3, &lines, "element")?;
                    let (tag, ty, ntags) = (v[0], v[1] as u32, v[2] as usize);
                    need(&v, 3 + ntags, &lines, "element tags")?;
                    let dim = type_dimension(ty);
                    // one entity per physical group, so the 4.1 path's lookups serve
                    let entity = if ntags > 0 { v[3] as i32 } else { -1 };
                    if ntags > 0 {
                        entity_physicals.insert((dim, entity), vec![entity]);
                    }
                    if !element_tags.insert(tag) {
                        return Err(lines.error(format!("element {tag} is given twice")));
                    }
                    elements.push(RawElement { dim, entity, ty, tag, nodes: v[3 + ntags..].to_vec(), at: format!("{name}:{}", lines.line) });
                }
                lines.expect("$EndElements")?;
            }
            "$Nodes" => nodes_41(&mut lines, node_coords)?,
            "$Elements" => elements_41(&mut lines, elements, &mut element_tags)?,
            other if other.starts_with("$End") => return Err(lines.error(format!("unexpected {other}"))),
            other if other.starts_with('$') => {
                // A section slideline does not use ($Periodic, $NodeData, ...): skip it whole.
                let end = format!("$End{}", &other[1..]);
                while lines.next()? != end {}
            }
            other => return Err(lines.error(format!("expected a section header, found {other:?}"))),
        }
    }
    if !seen_format {
        return Err(Error::input(format!("{name}: not a Gmsh mesh (no $MeshFormat section)")));
    }
    Ok(raw)
}

/// The mesh of a file's quadratic elements and the sets of its physical groups.
fn assemble(raw: RawMesh, name: &str) -> Result<(Mesh, MeshSets)> {
    let RawMesh { physical_names, entity_physicals, node_coords, elements } = raw;
    // one name, one group of a dimension: two would merge into one set without a word
    let mut named: BTreeMap<(i32, &str), i32> = BTreeMap::new();
    let mut groups: Vec<(&(i32, i32), &String)> = physical_names.iter().collect();
    groups.sort();
    for ((dim, tag), group) in groups {
        if let Some(first) = named.insert((*dim, group.as_str()), *tag) {
            return Err(Error::input(format!(
                "{name}: the physical name \"{group}\" is given to two groups of dimension {dim} (tags {first} and {tag}): give each its own name"
            )));
        }
    }

    // the 2D elements define the mesh; only their nodes are kept
    let mut mesh = Mesh::default();
    let mut node_index: HashMap<u64, usize> = HashMap::new();
    let mut entity_elements: BTreeMap<i32, Vec<usize>> = BTreeMap::new();
    for RawElement { dim, entity, ty, tag, nodes, at } in &elements {
        if *dim != 2 {
            continue;
        }
        let (count, what) = match *ty {
            QUAD8 => (8, "an 8-node quadrilateral"),
            TRI6 => (6, "a 6-node triangle"),
            _ => return Err(Error::input(format!("{at}: element {tag} is {}; slideline uses quadratic elements: 8-node quadrilaterals (Gmsh type 16: Mesh.ElementOrder = 2, Mesh.SecondOrderIncomplete = 1, recombined) or 6-node triangles (type 9: Mesh.ElementOrder = 2)", type_name(*ty)))),
        };
        if nodes.len() != count {
            return Err(Error::input(format!("{at}: element {tag} lists {} nodes, {what} needs {count}", nodes.len())));
        }
        let mut conn = [0usize; 8];
        for (k, t) in nodes.iter().enumerate() {
            let c = *node_coords.get(t).ok_or_else(|| Error::input(format!("{at}: element {tag} uses node {t}, which is not in $Nodes")))?;
            conn[k] = *node_index.entry(*t).or_insert_with(|| {
                mesh.coords.push(c);
                mesh.node_ids.push(*t);
                mesh.coords.len() - 1
            });
        }
        if count == 6 {
            conn = Shape::tri6_slots([conn[0], conn[1], conn[2], conn[3], conn[4], conn[5]]);
        }
        entity_elements.entry(*entity).or_default().push(mesh.elements.len());
        mesh.elements.push(conn);
        mesh.element_ids.push(*tag);
    }

    if mesh.elements.is_empty() {
        return Err(Error::input(format!(
            "{name}: the mesh has no elements (slideline needs 8-node quadrilaterals, Gmsh type 16, or 6-node triangles, type 9)"
        )));
    }
    let mut sets = MeshSets::default();
    sets.element_sets.insert("all".into(), (0..mesh.elements.len()).collect());
    sets.node_sets.insert("all".into(), (0..mesh.coords.len()).collect());
    let group_name = |dim: i32, tag: i32| physical_names.get(&(dim, tag)).cloned().unwrap_or_else(|| format!("physical_{tag}"));

    // 2D groups: element sets.
    for (entity, elems) in &entity_elements {
        for &p in entity_physicals.get(&(2, *entity)).map(|v| v.as_slice()).unwrap_or(&[]) {
            sets.element_sets.entry(group_name(2, p)).or_default().extend(elems);
        }
    }
    // 1D groups: surfaces made of element sides; 0D groups: node sets.
    let mut side_of: HashMap<(usize, usize), Edge> = HashMap::new();
    for e in 0..mesh.elements.len() {
        for edge in mesh.sides(e) {
            let [a, b, _] = mesh.edge_nodes(edge);
            side_of.insert((a.min(b), a.max(b)), edge);
        }
    }
    let mut surfaces: BTreeMap<String, Vec<Edge>> = BTreeMap::new();
    for RawElement { dim, entity, ty, tag, nodes, at } in &elements {
        let phys = entity_physicals.get(&(*dim, *entity)).map(|v| v.as_slice()).unwrap_or(&[]);
        if phys.is_empty() || *dim > 1 {
            continue;
        }
        let index = |t: &u64| {
            node_index.get(t).copied().ok_or_else(|| Error::input(format!("{at}: element {tag} uses node {t}, which belongs to no 8-node quadrilateral")))
        };
        match (*dim, *ty) {
            (1, LINE3) if nodes.len() == 3 => {
                let (a, b) = (index(&nodes[0])?, index(&nodes[1])?);
                let edge =
                    *side_of.get(&(a.min(b), a.max(b))).ok_or_else(|| Error::input(format!("{at}: line element {tag} is not a side of any quadrilateral")))?;
                for &p in phys {
                    surfaces.entry(group_name(1, p)).or_default().push(edge);
                }
            }
            (1, _) => return Err(Error::input(format!("{at}: element {tag} in a physical curve is {}; surfaces need 3-node lines (type 8)", type_name(*ty)))),
            (0, POINT) => {
                let n = index(&nodes[0])?;
                for &p in phys {
                    sets.node_sets.entry(group_name(0, p)).or_default().push(n);
                }
            }
            _ => return Err(Error::input(format!("{at}: element {tag} of type {ty} in a physical point group is not a point"))),
        }
    }
    for (nm, mut edges) in surfaces {
        edges.sort_unstable();
        edges.dedup();
        sets.add_surface(&mesh, &nm, edges);
    }
    // Element sets also name their nodes, so boundary conditions can use them.
    for (nm, elems) in sets.element_sets.clone() {
        if nm == "all" {
            continue;
        }
        let mut nodes: Vec<usize> = elems.iter().flat_map(|&e| mesh.element_nodes(e).to_vec()).collect();
        nodes.sort_unstable();
        nodes.dedup();
        sets.node_sets.entry(nm).or_insert(nodes);
    }
    for v in sets.node_sets.values_mut() {
        v.sort_unstable();
        v.dedup();
    }
    Ok((mesh, sets))
}

fn type_name(ty: u32) -> String {
    match ty {
        1 => "a 2-node line (type 1)".into(),
        2 => "a 3-node triangle (type 2)".into(),
        3 => "a 4-node quadrilateral (type 3)".into(),
        9 => "a 6-node triangle (type 9)".into(),
        10 => "a 9-node quadrilateral (type 10)".into(),
        other => format!("Gmsh element type {other}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::mesh::{blocks, Block};

    /// A format 2.2 file: one Q8 (physical surface "plate"), its bottom side as a 3-node line
    /// (physical curve "bottom") and a corner point (physical point "corner").
    const MSH22: &str = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n3\n0 3 \"corner\"\n1 2 \"bottom\"\n2 1 \"plate\"\n$EndPhysicalNames\n\
$Nodes\n8\n1 10 0 0\n2 12 0 0\n3 12 2 0\n4 10 2 0\n5 11 0 0\n6 12 1 0\n7 11 2 0\n8 10 1 0\n$EndNodes\n\
$Elements\n3\n1 15 2 3 1 1\n2 8 2 2 1 1 2 5\n3 16 2 1 1 1 2 3 4 5 6 7 8\n$EndElements\n";

    #[test]
    fn a_format_2_2_mesh_reads_with_its_physical_groups() {
        let (mesh, sets) = parse(MSH22, "t.msh").unwrap();
        assert_eq!((mesh.coords.len(), mesh.elements.len()), (8, 1));
        assert_eq!(mesh.coords[mesh.elements[0][2]], [12.0, 2.0]);
        assert_eq!(sets.element_sets["plate"], vec![0]);
        assert_eq!(sets.surfaces["bottom"], vec![Edge { element: 0, side: 0 }]);
        assert_eq!(sets.node_sets["corner"].iter().map(|&n| mesh.node_ids[n]).collect::<Vec<_>>(), vec![1]);
    }

    #[test]
    fn a_binary_msh_4_1_reads_as_its_text_twin() {
        // both written by Gmsh 4 itself (tests/data/make_binary_msh.py)
        let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
        let (text, text_sets) = read(&data.join("plate_text.msh")).unwrap();
        let (bin, bin_sets) = read(&data.join("plate_binary.msh")).unwrap();
        assert_eq!((bin.elements.len(), bin.coords.len()), (8, 37), "4 x 2 Q8 elements");
        assert_eq!((&bin.elements, &bin.node_ids, &bin.element_ids), (&text.elements, &text.node_ids, &text.element_ids));
        // the text file prints 16 digits, the binary one holds every bit
        assert!(bin.coords.iter().flatten().zip(text.coords.iter().flatten()).all(|(a, b)| (a - b).abs() < 1e-13));
        assert_eq!(bin_sets.surfaces, text_sets.surfaces);
        assert_eq!(bin_sets.node_sets, text_sets.node_sets);
        assert_eq!(bin_sets.element_sets, text_sets.element_sets);
        assert_eq!(bin_sets.surfaces["bottom"].len(), 4);
        assert_eq!(bin_sets.node_sets["corner"].iter().map(|&n| bin.coords[n]).collect::<Vec<_>>(), vec![[10.0, 0.0]]);
        // cut short: a message naming the section, not a panic
        let bytes = std::fs::read(data.join("plate_binary.msh")).unwrap();
        let cut = bytes.len() * 2 / 3;
        let message = binary::parse(&bytes[..cut], "cut.msh").err().expect("refused").to_string();
        assert!(message.contains("cut.msh: $"), "{message}");
        // a header claiming 2^62 nodes (its blocks hold 37): named, not run
        let mut claimed = bytes.clone();
        let at = claimed.windows(7).position(|w| w == b"$Nodes\n").unwrap() + 7 + 8;
        claimed[at..at + 8].copy_from_slice(&(1u64 << 62).to_le_bytes());
        let message = binary::parse(&claimed, "claimed.msh").err().expect("refused").to_string();
        assert!(message.contains("$Nodes") && message.contains("the header claims 4611686018427387904 nodes, its blocks hold 37"), "{message}");
    }

    #[test]
    fn a_physical_name_given_to_two_groups_is_named() {
        let twice = MSH22.replace("0 3 \"corner\"", "1 3 \"bottom\"");
        let message = parse(&twice, "t.msh").expect_err("refused").to_string();
        assert!(message.contains("the physical name \"bottom\" is given to two groups of dimension 1 (tags 2 and 3)"), "{message}");
    }

    #[test]
    fn written_meshes_read_back_with_their_sets() {
        let specs = [
            Block { name: "a".into(), r: [0.0, 2.0], z: [0.0, 1.0], divisions: [2, 1], grading: [1.0, 1.0], triangles: false },
            Block { name: "b".into(), r: [0.0, 2.0], z: [1.0, 3.0], divisions: [3, 2], grading: [1.0, 0.5], triangles: true },
        ];
        let (mesh, mut sets) = blocks(&specs).unwrap();
        sets.node_sets.insert("corner".into(), vec![0]);
        let text = to_msh(&mesh, &sets);
        let (back, back_sets) = parse(&text, "roundtrip.msh").unwrap();
        assert_eq!(back.elements.len(), mesh.elements.len());
        assert_eq!(back.coords.len(), mesh.coords.len());
        for (name, edges) in &sets.surfaces {
            assert_eq!(back_sets.surfaces[name].len(), edges.len(), "surface {name}");
        }
        for name in ["a", "b", "corner", "b_top", "all"] {
            assert_eq!(back_sets.node_sets[name].len(), sets.node_sets[name].len(), "node set {name}");
        }
        // block b is 12 triangles (type 9), read back as such
        assert_eq!(back_sets.element_sets["b"].len(), 12);
        assert!(back_sets.element_sets["b"].iter().all(|&e| back.shape(e) == Shape::Tri6));
        assert!(back_sets.element_sets["a"].iter().all(|&e| back.shape(e) == Shape::Quad8));
        back.validate().unwrap();
    }
}
