//! Writer for Gmsh .msh 4.1 ASCII meshes: the inverse of the reader, so a generated mesh (the
//! bellows, a block mesh) can be looked at in Gmsh and read back as a deck's mesh.

use super::{LINE3, POINT, QUAD8, TRI6};
use crate::error::{Error, Result};
use crate::fe::shape::Shape;
use crate::model::mesh::{Edge, Mesh, MeshSets};
use std::collections::BTreeMap;
use std::path::Path;

/// Writes `mesh` with its sets as a Gmsh .msh 4.1 ASCII file that [`read`](super::read) reads back to the
/// same model: element sets become physical surfaces, surfaces physical curves (3-node
/// lines), and node sets that are neither (nor `all`) physical points. Entities group the
/// items that share the same set memberships.
pub fn write(mesh: &Mesh, sets: &MeshSets, path: &Path) -> Result<()> {
    let text = to_msh(mesh, sets);
    std::fs::write(path, text).map_err(|e| Error::Output { path: path.to_path_buf(), message: e.to_string() })
}

pub fn to_msh(mesh: &Mesh, sets: &MeshSets) -> String {
    use std::fmt::Write as _;
    let mut out = String::new();
    let mut names: Vec<(i32, i32, &str)> = Vec::new();
    // membership signature -> entity
    let element_groups: Vec<(&String, &Vec<usize>)> = sets.element_sets.iter().filter(|(n, _)| n.as_str() != "all").collect();
    let surface_groups: Vec<(&String, &Vec<Edge>)> = sets.surfaces.iter().collect();
    let derived = |n: &String| sets.surfaces.contains_key(n) || sets.element_sets.contains_key(n) || n.as_str() == "all";
    let point_groups: Vec<(&String, &Vec<usize>)> = sets.node_sets.iter().filter(|(n, _)| !derived(n)).collect();
    let mut tag = 1;
    for (n, _) in &element_groups {
        names.push((2, tag, n.as_str()));
        tag += 1;
    }
    let first_curve_tag = tag;
    for (n, _) in &surface_groups {
        names.push((1, tag, n.as_str()));
        tag += 1;
    }
    let first_point_tag = tag;
    for (n, _) in &point_groups {
        names.push((0, tag, n.as_str()));
        tag += 1;
    }
    // surfaces: one entity per signature of element-set membership and shape (a block of
    // elements has one type)
    let mut surface_entities: BTreeMap<(Vec<i32>, u32), Vec<usize>> = BTreeMap::new();
    for e in 0..mesh.elements.len() {
        let sig: Vec<i32> = element_groups.iter().enumerate().filter(|(_, (_, m))| m.contains(&e)).map(|(k, _)| k as i32 + 1).collect();
        let ty = match mesh.shape(e) {
            Shape::Quad8 => QUAD8,
            Shape::Tri6 => TRI6,
        };
        surface_entities.entry((sig, ty)).or_default().push(e);
    }
    let curve_entities = by_membership(&surface_groups, first_curve_tag);
    let point_entities = by_membership(&point_groups, first_point_tag);
    // a point entity holds one node: split groups
    let point_list: Vec<(Vec<i32>, usize)> = point_entities.into_iter().flat_map(|(sig, nodes)| nodes.into_iter().map(move |n| (sig.clone(), n))).collect();

    let _ = writeln!(out, "$MeshFormat\n4.1 0 8\n$EndMeshFormat");
    let _ = writeln!(out, "$PhysicalNames\n{}", names.len());
    for (d, t, n) in &names {
        let _ = writeln!(out, "{d} {t} \"{n}\"");
    }
    let _ = writeln!(out, "$EndPhysicalNames");
    let _ = writeln!(out, "$Entities\n{} {} {} 0", point_list.len(), curve_entities.len(), surface_entities.len());
    let tags = |sig: &Vec<i32>| sig.iter().map(|t| t.to_string()).collect::<Vec<_>>().join(" ");
    for (k, (sig, n)) in point_list.iter().enumerate() {
        let c = mesh.coords[*n];
        let _ = writeln!(out, "{} {} {} 0 {} {}", k + 1, c[0], c[1], sig.len(), tags(sig));
    }
    for (k, sig) in curve_entities.keys().enumerate() {
        let _ = writeln!(out, "{} 0 0 0 0 0 0 {} {} 0", k + 1, sig.len(), tags(sig));
    }
    for (k, (sig, _)) in surface_entities.keys().enumerate() {
        let _ = writeln!(out, "{} 0 0 0 0 0 0 {} {} 0", k + 1, sig.len(), tags(sig));
    }
    let _ = writeln!(out, "$EndEntities");
    let nn = mesh.coords.len();
    let _ = writeln!(out, "$Nodes\n1 {nn} 1 {nn}\n2 1 0 {nn}");
    for k in 0..nn {
        let _ = writeln!(out, "{}", k + 1);
    }
    for c in &mesh.coords {
        let _ = writeln!(out, "{:?} {:?} 0", c[0], c[1]);
    }
    let _ = writeln!(out, "$EndNodes");
    let blocks = point_list.len() + curve_entities.len() + surface_entities.len();
    let count = point_list.len() + curve_entities.values().map(|v| v.len()).sum::<usize>() + mesh.elements.len();
    let _ = writeln!(out, "$Elements\n{blocks} {count} 1 {count}");
    let mut id = 1;
    for (k, (_, n)) in point_list.iter().enumerate() {
        let _ = writeln!(out, "0 {} {POINT} 1\n{id} {}", k + 1, n + 1);
        id += 1;
    }
    for (k, list) in curve_entities.values().enumerate() {
        let _ = writeln!(out, "1 {} {LINE3} {}", k + 1, list.len());
        for &e in list {
            let [a, b, m] = mesh.edge_nodes(e);
            let _ = writeln!(out, "{id} {} {} {}", a + 1, b + 1, m + 1);
            id += 1;
        }
    }
    for (k, ((_, ty), list)) in surface_entities.iter().enumerate() {
        let _ = writeln!(out, "2 {} {ty} {}", k + 1, list.len());
        for &e in list {
            let conn: Vec<String> = mesh.element_nodes(e).iter().map(|n| (n + 1).to_string()).collect();
            let _ = writeln!(out, "{id} {}", conn.join(" "));
            id += 1;
        }
    }
    let _ = writeln!(out, "$EndElements");
    out
}

/// The members of `groups` (physical tags `first_tag + k`), one entity per signature: the
/// tags of the groups an item belongs to.
fn by_membership<T: Copy + Ord>(groups: &[(&String, &Vec<T>)], first_tag: i32) -> BTreeMap<Vec<i32>, Vec<T>> {
    let mut items: Vec<T> = groups.iter().flat_map(|(_, m)| m.iter().copied()).collect();
    items.sort_unstable();
    items.dedup();
    let mut entities: BTreeMap<Vec<i32>, Vec<T>> = BTreeMap::new();
    for item in items {
        let signature = groups.iter().enumerate().filter(|(_, (_, m))| m.contains(&item)).map(|(k, _)| first_tag + k as i32).collect();
        entities.entry(signature).or_default().push(item);
    }
    entities
}
