//! Closest-segment search: a uniform grid of segment bounding boxes (inflated by the capture
//! distance), rebuilt on the current configuration at every evaluation. Building is linear in
//! the number of segments and each query looks at one cell, so the search is linear, not
//! quadratic, in the surface sizes.

use super::slideline::{project, Projection};
use super::surface::ContactSurface;
use std::collections::HashMap;

pub struct SegmentGrid {
    cell: f64,
    cells: HashMap<(i64, i64), Vec<usize>>,
}

impl SegmentGrid {
    /// Grid over the segments of `surface` at positions `x`, boxes inflated by `capture`.
    pub fn new(surface: &ContactSurface, x: &impl Fn(usize) -> [f64; 2], capture: f64) -> Self {
        let n = surface.segments.len().max(1);
        let mean: f64 = surface.segments.iter().map(|s| dist(x(s[0]), x(s[1]))).sum::<f64>() / n as f64;
        let cell = (mean + 2.0 * capture).max(f64::MIN_POSITIVE);
        let mut cells: HashMap<(i64, i64), Vec<usize>> = HashMap::with_capacity(2 * n);
        for (k, s) in surface.segments.iter().enumerate() {
            let (a, b) = (x(s[0]), x(s[1]));
            let lo = [a[0].min(b[0]) - capture, a[1].min(b[1]) - capture];
            let hi = [a[0].max(b[0]) + capture, a[1].max(b[1]) + capture];
            let (i0, j0) = (cell_of(lo[0], cell), cell_of(lo[1], cell));
            let (i1, j1) = (cell_of(hi[0], cell), cell_of(hi[1], cell));
            for i in i0..=i1 {
                for j in j0..=j1 {
                    cells.entry((i, j)).or_default().push(k);
                }
            }
        }
        SegmentGrid { cell, cells }
    }

    /// Segments whose inflated box may contain `p`.
    pub fn candidates(&self, p: [f64; 2]) -> &[usize] {
        self.cells.get(&(cell_of(p[0], self.cell), cell_of(p[1], self.cell))).map(|v| v.as_slice()).unwrap_or(&[])
    }
}

fn cell_of(v: f64, cell: f64) -> i64 {
    (v / cell).floor() as i64
}

fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// The master segment a slave node at `xs` bears on, among `candidates` (minus `excluded`):
/// the segment whose closest point is nearest, within `capture`. A projection beyond a
/// segment end is kept only where a neighbouring segment continues the surface (the blind
/// spot of a convex corner, with the surface coordinate extrapolated); beyond a free end of
/// the surface the node has slid off. At a concave corner the nearer segment wins, so a node
/// is never counted twice.
pub fn closest_segment(surface: &ContactSurface, x: &impl Fn(usize) -> [f64; 2], xs: [f64; 2], candidates: &[usize], excluded: &[usize], capture: f64) -> Option<(usize, Projection)> {
    let mut best: Option<(usize, Projection, f64)> = None;
    for &k in candidates {
        if excluded.contains(&k) {
            continue;
        }
        let [n1, n2] = surface.segments[k];
        let Some(p) = project(xs, x(n1), x(n2)) else { continue };
        let a = p.a.clamp(0.0, 1.0);
        let closest = [x(n1)[0] + a * (x(n2)[0] - x(n1)[0]), x(n1)[1] + a * (x(n2)[1] - x(n1)[1])];
        let d = dist(xs, closest);
        if d > capture {
            continue;
        }
        let better = match &best {
            None => true,
            Some((bk, bp, bd)) => d < *bd - 1e-12 * capture || (d <= *bd + 1e-12 * capture && (inside(&p) && !inside(bp) || (inside(&p) == inside(bp) && k < *bk))),
        };
        if better {
            best = Some((k, p, d));
        }
    }
    let (k, p, _) = best?;
    let off_start = p.a < 0.0 && surface.neighbours[k][0].is_none();
    let off_end = p.a > 1.0 && surface.neighbours[k][1].is_none();
    if off_start || off_end {
        return None;
    }
    Some((k, p))
}

fn inside(p: &Projection) -> bool {
    (0.0..=1.0).contains(&p.a)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::mesh::rectangle;

    #[test]
    fn finds_the_segment_under_a_node_and_loses_it_past_the_free_end() {
        let (mesh, sets) = rectangle([1.0, 5.0], [0.0, 1.0], [4, 1]).unwrap();
        let s = ContactSurface::new(&mesh, &sets.surfaces["top"]);
        let x = |n: usize| mesh.coords[n];
        let grid = SegmentGrid::new(&s, &x, 0.5);
        // a node slightly inside the top face at r = 2.3
        let xs = [2.3, 0.99];
        let (k, p) = closest_segment(&s, &x, xs, grid.candidates(xs), &[], 0.5).unwrap();
        let [a, b] = s.segments[k];
        assert!(x(a)[0].min(x(b)[0]) <= 2.3 && 2.3 <= x(a)[0].max(x(b)[0]));
        assert!((p.gap + 0.01).abs() < 1e-12, "{p:?}");
        // on a shared vertex (r = 2.5): exactly one segment, projection at its end
        let xs = [2.5, 0.99];
        assert!(closest_segment(&s, &x, xs, grid.candidates(xs), &[], 0.5).is_some());
        // beyond the free end r = 5
        let xs = [5.2, 0.99];
        assert!(closest_segment(&s, &x, xs, grid.candidates(xs), &[], 0.5).is_none());
    }

    #[test]
    fn the_grid_returns_every_segment_within_capture() {
        let (mesh, sets) = rectangle([0.0, 40.0], [0.0, 1.0], [40, 1]).unwrap();
        let s = ContactSurface::new(&mesh, &sets.surfaces["top"]);
        let x = |n: usize| mesh.coords[n];
        let grid = SegmentGrid::new(&s, &x, 0.3);
        for i in 0..400 {
            let p = [i as f64 * 0.1 + 0.05, 1.1];
            let brute: Vec<usize> = (0..s.segments.len())
                .filter(|&k| {
                    let [a, b] = s.segments[k];
                    x(a)[0].min(x(b)[0]) - 0.3 <= p[0] && p[0] <= x(a)[0].max(x(b)[0]) + 0.3
                })
                .collect();
            let c = grid.candidates(p);
            assert!(brute.iter().all(|k| c.contains(k)), "at {p:?}: {brute:?} not all in {c:?}");
        }
    }
}
