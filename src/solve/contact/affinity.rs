//! How contact weighs in the partition: from the reference configuration, each slave edge
//! adds its contact work to its element, and each element is linked to the elements of the
//! master edges its slave edges face, so facing surfaces are cut at the same place and their
//! couplings stay on one rank.

use crate::contact::search::EdgeGrid;
use crate::decomposition::Affinity;
use crate::model::{ContactIntegration, Model};
use crate::solve::contact::surfaces::{edge_neighbourhood, surfaces_and_directions};

/// Relative work per Newton iteration of one element (1.3 residuals with the dual-number
/// material update and one tangent: about 6 us, `cargo bench --bench kernels`) and of one
/// slave edge of a pass: segment-integrated and facing a master (two slave nodes' search,
/// gaps, gradients and Hessians), node-to-segment, or with no master within reach (it only
/// searches). With these the default bellows' ranks spend the same time in each stage to
/// within about 2 % (-log_view per rank).
const ELEMENT_WORK: u32 = 8;
const SEGMENT_EDGE_WORK: u32 = 11;
const NODAL_EDGE_WORK: u32 = 2;
const SEARCH_ONLY_WORK: u32 = 1;

/// The partitioner's view of contact, from the reference configuration: each slave edge adds
/// its contact work to its element, and each element is linked to the elements of the master
/// edges its slave edges face within the capture distance, so that facing plies are cut at the
/// same place and their couplings stay on one rank.
pub fn partition_affinity(model: &Model) -> Affinity {
    let mut work = vec![ELEMENT_WORK; model.mesh.elements.len()];
    let mut links = Vec::new();
    let (surfaces, directions) = surfaces_and_directions(model);
    let x = |n: usize| model.mesh.coords[n];
    for d in directions {
        let (slave, master, c) = (&surfaces[d.slave], &surfaces[d.master], &model.contacts[d.pair]);
        let grid = EdgeGrid::new(master, &x, c.capture_distance);
        for (e, nodes) in slave.edges.iter().enumerate() {
            let excluded = if d.slave == d.master { edge_neighbourhood(slave, e, c.exclude_neighbours) } else { Vec::new() };
            let before = links.len();
            for p in nodes.map(x) {
                if let Some((m, _)) = grid.closest_edge(master, &x, p, &excluded, c.capture_distance, None) {
                    links.push([slave.element[e], master.element[m]]);
                }
            }
            work[slave.element[e]] += match (links.len() > before, c.integration) {
                (false, _) => SEARCH_ONLY_WORK,
                (true, ContactIntegration::Segment) => SEGMENT_EDGE_WORK,
                (true, ContactIntegration::NodeToSegment) => NODAL_EDGE_WORK,
            };
        }
    }
    links.sort_unstable();
    links.dedup();
    Affinity { work, links }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::deck;
    use std::path::Path;

    /// Two stacked blocks, the upper one's bottom (4 elements) resting on the lower one's top
    /// (2 elements), a third block far away.
    const DECK: &str = r#"
[[mesh.block]]
name = "lower"
r = [0.0, 4.0]
z = [0.0, 1.0]
divisions = [2, 1]
[[mesh.block]]
name = "upper"
r = [0.0, 4.0]
z = [1.0, 2.0]
divisions = [4, 1]
[[mesh.block]]
name = "far"
r = [0.0, 4.0]
z = [50.0, 51.0]
divisions = [2, 1]
[[material]]
name = "steel"
youngs_modulus = 200000.0
poissons_ratio = 0.3
[[contact]]
name = "stack"
slave = "upper_bottom"
master = "lower_top"
penalty = 1.0e4
capture_distance = 0.5
[[step]]
boundary = [ { set = "lower_bottom", uz = 0.0 }, { set = "far_bottom", uz = 0.0 } ]
"#;

    #[test]
    fn the_partition_sees_facing_elements_linked_and_slave_elements_heavier() {
        let model = deck::parse(DECK, Path::new("stack.toml")).unwrap();
        let block = |name: &str| -> Vec<usize> {
            let mut e: Vec<usize> = model.element_sets[name].clone();
            e.sort_by(|&a, &b| model.mesh.coords[model.mesh.elements[a][0]][0].total_cmp(&model.mesh.coords[model.mesh.elements[b][0]][0]));
            e
        };
        let (lower, upper, far) = (block("lower"), block("upper"), block("far"));
        let affinity = partition_affinity(&model);
        // each upper element (r in [i, i + 1]) is linked to the lower element under it, and
        // to lower elements only (a node over the lower elements' shared corner links to both)
        for (i, &u) in upper.iter().enumerate() {
            let linked: Vec<usize> = affinity.links.iter().filter(|l| l[0] == u).map(|l| l[1]).collect();
            assert!(linked.contains(&lower[i / 2]), "upper element {i} not linked to the lower element under it: {linked:?}");
            assert!(linked.iter().all(|l| lower.contains(l)));
        }
        assert!(affinity.links.iter().all(|l| !far.contains(&l[0]) && !far.contains(&l[1])), "nothing faces the far block");
        // work: slave-edge elements carry the contact integration on top of their own
        assert!(upper.iter().all(|&u| affinity.work[u] == ELEMENT_WORK + SEGMENT_EDGE_WORK));
        assert!(lower.iter().chain(&far).all(|&e| affinity.work[e] == ELEMENT_WORK));
    }
}
