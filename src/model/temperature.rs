//! Temperatures over the mesh, degC: one value at every node, or one per node (a field given
//! on node sets). The solver interpolates nodal temperatures to the Gauss points with the
//! element's shape functions, so thermal strain follows the field inside each element.

/// A temperature at every node of the mesh, degC.
#[derive(Clone, Debug, PartialEq)]
pub enum Temperature {
    Uniform(f64),
    /// One value per mesh node (internal node order).
    Nodal(Vec<f64>),
}

impl Temperature {
    /// The field of these nodal values: `Uniform` when they are all equal.
    pub fn from_nodal(values: Vec<f64>) -> Self {
        let t = Temperature::Nodal(values);
        match t.uniform() {
            Some(u) => Temperature::Uniform(u),
            None => t,
        }
    }

    /// The temperature of `node`.
    pub fn at(&self, node: usize) -> f64 {
        match self {
            Temperature::Uniform(t) => *t,
            Temperature::Nodal(v) => v[node],
        }
    }

    /// The value at every one of `nodes` nodes.
    pub fn nodal(&self, nodes: usize) -> Vec<f64> {
        match self {
            Temperature::Uniform(t) => vec![*t; nodes],
            Temperature::Nodal(v) => v.clone(),
        }
    }

    /// The single value, where the temperature is uniform.
    pub fn uniform(&self) -> Option<f64> {
        match self {
            Temperature::Uniform(t) => Some(*t),
            Temperature::Nodal(v) => v.first().copied().filter(|&t| v.iter().all(|&x| x == t)),
        }
    }

    /// The first value that is not finite, if any.
    pub fn non_finite(&self) -> Option<f64> {
        match self {
            Temperature::Uniform(t) => Some(*t).filter(|t| !t.is_finite()),
            Temperature::Nodal(v) => v.iter().copied().find(|t| !t.is_finite()),
        }
    }

    /// The field `a + lambda (b - a)` over `nodes` nodes (uniform when both ends are).
    pub fn lerp(a: &Temperature, b: &Temperature, lambda: f64, nodes: usize) -> Temperature {
        match (a, b) {
            (Temperature::Uniform(x), Temperature::Uniform(y)) => Temperature::Uniform(x + lambda * (y - x)),
            _ => Temperature::Nodal((0..nodes).map(|n| a.at(n) + lambda * (b.at(n) - a.at(n))).collect()),
        }
    }

    /// The field's values in [min, max].
    pub fn range(&self) -> [f64; 2] {
        match self {
            Temperature::Uniform(t) => [*t, *t],
            Temperature::Nodal(v) => v.iter().fold([f64::INFINITY, f64::NEG_INFINITY], |[a, b], &t| [a.min(t), b.max(t)]),
        }
    }
}

/// The value of each of `nodes` nodes after setting `values` (node, degC) in order over
/// `before` (None: no value yet): a later value wins on a node set twice.
pub fn apply(nodes: usize, before: Option<&Temperature>, values: impl IntoIterator<Item = (usize, f64)>) -> Vec<Option<f64>> {
    let mut field: Vec<Option<f64>> = (0..nodes).map(|n| before.map(|t| t.at(n))).collect();
    for (n, value) in values {
        field[n] = Some(value);
    }
    field
}

/// Builds a nodal field by assignments in order (a later one wins on the nodes two share),
/// starting from `before` (None: every node must be assigned); returns the field, uniform when
/// every node ends with the same value. `Err` names how many nodes no assignment reached.
pub fn assign(nodes: usize, before: Option<&Temperature>, assignments: &[(&[usize], f64)]) -> Result<Temperature, usize> {
    let field = apply(nodes, before, assignments.iter().flat_map(|&(set, value)| set.iter().map(move |&n| (n, value))));
    let missing = field.iter().filter(|t| t.is_none()).count();
    if missing > 0 {
        return Err(missing);
    }
    Ok(Temperature::from_nodal(field.into_iter().flatten().collect()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn assignments_apply_in_order_and_collapse_to_uniform() {
        let all: Vec<usize> = (0..4).collect();
        let t = assign(4, None, &[(&all, 20.0), (&[1, 2], 100.0), (&[2], 50.0)]).unwrap();
        assert_eq!(t, Temperature::Nodal(vec![20.0, 100.0, 50.0, 20.0]));
        assert_eq!(t.range(), [20.0, 100.0]);
        assert_eq!(assign(4, Some(&t), &[(&all, 7.0)]).unwrap(), Temperature::Uniform(7.0));
        // a later step changes only the nodes it names
        assert_eq!(assign(4, Some(&Temperature::Uniform(1.0)), &[(&[3], 2.0)]).unwrap().at(0), 1.0);
        // an initial field must reach every node
        assert_eq!(assign(4, None, &[(&[0, 1], 5.0)]), Err(2));
    }
}
