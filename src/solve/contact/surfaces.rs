//! Which surfaces and nodes take part in contact: the model's contact surfaces (each once,
//! however many pairs name it), the directions (passes) of every pair over them, and the
//! self-contact exclusions. Shared by the contact assembly and the partition's weights.

use crate::contact::surface::ContactSurface;
use crate::model::Model;

/// Mesh nodes of every contact surface of the model (sorted).
pub fn contact_nodes(model: &Model) -> Vec<usize> {
    let mut nodes: Vec<usize> = model
        .contacts
        .iter()
        .flat_map(|c| [&c.slave, &c.master])
        .flat_map(|s| model.contact_edges(s).into_iter().flat_map(|e| model.mesh.edge_nodes(e)))
        .collect();
    nodes.sort_unstable();
    nodes.dedup();
    nodes
}

/// One direction of a pair, by surface index: its slave nodes bear on its master's edges and
/// carry `weight` of the pair's force (one half each in a two-pass pair). `slave_nodes`: the
/// pair's node-based slave (its first direction only), those nodes bearing with the master
/// face's area.
pub(in crate::solve) struct Direction<'a> {
    pub pair: usize,
    pub slave: usize,
    pub master: usize,
    pub weight: f64,
    pub slave_nodes: Option<&'a [usize]>,
}

/// The model's contact surfaces (each once, however many pairs name it) and the directions of
/// every pair over them.
pub(in crate::solve) fn surfaces_and_directions(model: &Model) -> (Vec<ContactSurface>, Vec<Direction<'_>>) {
    let mut names: Vec<&str> = Vec::new();
    for c in &model.contacts {
        for s in [c.slave.as_str(), c.master.as_str()] {
            if !names.contains(&s) {
                names.push(s);
            }
        }
    }
    let surfaces = names.iter().map(|n| ContactSurface::of_model(model, n)).collect();
    let index = |n: &str| names.iter().position(|m| *m == n).expect("surface listed");
    let mut directions = Vec::new();
    for (pair, c) in model.contacts.iter().enumerate() {
        let (s, m) = (index(&c.slave), index(&c.master));
        let two = c.two_pass && s != m;
        let weight = if two { 0.5 } else { 1.0 };
        directions.push(Direction { pair, slave: s, master: m, weight, slave_nodes: c.slave_nodes.as_deref() });
        if two {
            directions.push(Direction { pair, slave: m, master: s, weight, slave_nodes: None });
        }
    }
    (surfaces, directions)
}

/// Self-contact: the edges a slave edge may not bear on, those within `hops` of its nodes.
pub(in crate::solve) fn edge_neighbourhood(surface: &ContactSurface, edge: usize, hops: usize) -> Vec<usize> {
    let mut near: Vec<usize> = surface.edges[edge].iter().flat_map(|&n| surface.neighbourhood(n, hops)).collect();
    near.sort_unstable();
    near.dedup();
    near
}
