//! XDMF 3 sidecar describing the HDF5 results as a time series of meshes (Q8, or Q8 and T6
//! through XDMF's mixed topology), so that ParaView
//! (its default Xdmf3 reader and the legacy one) and meshio open `results.xmf` directly. Every
//! data item is a plain HDF5 dataset (no functions or hyperslabs, which Xdmf3 and meshio skip):
//! the displacement and reaction force as 3-component vectors (r, z, 0) for Warp By Vector and
//! glyphs, the stress and strain components, their invariants, equivalent plastic strain,
//! temperature and contact state at the nodes (carried there from the Gauss points, see
//! `io::nodal`), and per element the mean von Mises stress, the largest plastic strain and the
//! rank. An `Information` element names each attribute's units (ParaView shows the names; the
//! units are also the datasets' `units` attributes). The first grid is the undeformed,
//! unloaded state at t = 0 (`/initial`), so that a reader opened at its default time shows the
//! mesh.

use super::describe::{describe, plane_units};
use super::nodal::{nodal_scalar_kept, BACKSTRESS_SCALARS, CONTACT_SCALARS, NODAL_SCALARS, NODAL_TAIL};
use crate::error::{Error, Result};
use crate::fe::shape::Shape;
use crate::model::{Mesh, OutputFields, Precision};
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};

/// Path of the sidecar of results file `h5`: same name with extension `.xmf`.
pub fn sidecar_path(h5: &Path) -> PathBuf {
    h5.with_extension("xmf")
}

/// The group holding the t = 0 frame's data: zero vectors and scalars, the reference
/// temperature.
pub const INITIAL: &str = "/initial";

/// The dataset of the cells of a mesh with triangles, in XDMF's form.
pub const CELLS: &str = "/mesh/topology";

/// How the grids give their cells: the Q8 rows of `/mesh/connectivity`; in a mesh of T6 only,
/// their 6 nodes per row in [`CELLS`]; in a mesh of both, XDMF's mixed list there (each cell's
/// type number, then its nodes) of `values` numbers. The padded rows of `/mesh/connectivity`
/// stay slideline's own format (`fe::shape`). meshio 5 reads the first two; its reader of mixed
/// lists knows no quadratic quadrilateral, so a mixed mesh opens in ParaView, and in Python
/// through h5py.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Topology {
    Quad8,
    Tri6,
    Mixed { values: usize },
}

impl Topology {
    pub fn of(mesh: &Mesh) -> Topology {
        let shapes = |s: Shape| (0..mesh.elements.len()).filter(|&e| mesh.shape(e) == s).count();
        match (shapes(Shape::Quad8), shapes(Shape::Tri6)) {
            (_, 0) => Topology::Quad8,
            (0, _) => Topology::Tri6,
            (q, t) => Topology::Mixed { values: 9 * q + 7 * t },
        }
    }

    /// The `Topology` element of a grid of `elements` cells in results file `file`.
    fn xml(self, file: &str, elements: usize) -> String {
        let (kind, path, dims) = match self {
            Topology::Quad8 => ("Quadrilateral_8", "/mesh/connectivity", format!("{elements} 8")),
            Topology::Tri6 => ("Triangle_6", CELLS, format!("{elements} 6")),
            Topology::Mixed { values } => ("Mixed", CELLS, values.to_string()),
        };
        format!(
            r#"<Topology TopologyType="{kind}" NumberOfElements="{elements}"><DataItem Dimensions="{dims}" NumberType="Int" Precision="8" Format="HDF">{file}:{path}</DataItem></Topology>"#
        )
    }
}

/// XDMF's number for a cell of shape `shape` in a mixed topology (XdmfTopologyType:
/// Triangle_6 0x24, Quadrilateral_8 0x25).
pub const fn xdmf_cell_type(shape: Shape) -> i64 {
    match shape {
        Shape::Tri6 => 0x24,
        Shape::Quad8 => 0x25,
    }
}

/// What the sidecar's grids hold beside the displacement.
#[derive(Clone, Copy, Debug)]
pub struct GridFields {
    pub fields: OutputFields,
    /// The width of the fields' floats but the displacement's (always 64-bit).
    pub precision: Precision,
    /// The model has contact pairs: the nodal contact fields are written.
    pub contact: bool,
    /// Some pair has friction: the nodal shear and sliding are written.
    pub friction: bool,
    /// Some material has kinematic hardening: the nodal backstress is written (with the
    /// plastic strain).
    pub kinematic: bool,
    pub topology: Topology,
    /// A model of plane sections only: forces over the thickness, not per radian.
    pub plane: bool,
}

/// The sidecar of one results file, grown by one grid per converged increment. Each grid is
/// formatted once and kept: formatting every increment's grid again at each write made the
/// sidecar quadratic in the number of increments (a 2400-increment run formatted 2.9 million
/// grids). The file itself is still written whole each time, so that a reader never finds it
/// half-written (about 2 kB a grid).
pub struct Sidecar {
    target: PathBuf,
    /// The results file's name, as the data items reference it (relative: the two files move
    /// together).
    file: String,
    nodes: usize,
    elements: usize,
    /// The grids written so far: the t = 0 frame, then one per increment.
    grids: String,
    what: GridFields,
    /// Each attribute's units, for the document's `Information` element.
    units: Vec<(String, &'static str)>,
}

impl Sidecar {
    /// The sidecar of `h5`, written at once with its t = 0 frame.
    pub fn new(h5: &Path, nodes: usize, elements: usize, what: GridFields) -> Result<Self> {
        let file = h5.file_name().map(|f| f.to_string_lossy().into_owned()).unwrap_or_default();
        let mut sidecar = Sidecar { target: sidecar_path(h5), file, nodes, elements, grids: String::new(), what, units: Vec::new() };
        sidecar.push_grid("000000", 0.0, None);
        sidecar.write()?;
        Ok(sidecar)
    }

    /// Adds the grid of the increment stored in group `/increments/{group}` at `time`, and
    /// rewrites the sidecar.
    pub fn add_increment(&mut self, group: &str, time: f64) -> Result<()> {
        self.push_grid(group, time, Some(&format!("/increments/{group}")));
        self.write()
    }

    /// Writes the whole sidecar atomically: temporary file, then rename.
    fn write(&self) -> Result<()> {
        // the units beside the collection (inside it, meshio would count them as a time step;
        // inside an Attribute, meshio refuses it)
        let units: Vec<String> = self.units.iter().map(|(name, units)| format!("{name}: {units}")).collect();
        let header = format!(
            "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\"><Domain><Information Name=\"units\" Value=\"{}\"/>\n<Grid Name=\"slideline\" GridType=\"Collection\" CollectionType=\"Temporal\">\n",
            units.join("; ")
        );
        const FOOTER: &str = "</Grid></Domain></Xdmf>\n";
        let tmp = self.target.with_extension("xmf.tmp");
        let io = |source| Error::Output { path: self.target.clone(), message: format!("{source}") };
        let mut out = std::fs::File::create(&tmp).map_err(io)?;
        for part in [header.as_str(), &self.grids, FOOTER] {
            out.write_all(part.as_bytes()).map_err(io)?;
        }
        std::fs::rename(&tmp, &self.target).map_err(io)
    }

    /// One grid: an increment's (`group` its HDF5 group) or, with None, the t = 0 frame.
    fn push_grid(&mut self, name: &str, time: f64, group: Option<&str>) {
        let (nodes, elements, file) = (self.nodes, self.elements, &self.file);
        let mut names = Vec::new();
        let self_units = &mut names;
        let item = |path: &str, dims: &str, ty: &str, precision: u32| {
            format!(r#"<DataItem Dimensions="{dims}" NumberType="{ty}" Precision="{precision}" Format="HDF">{file}:{path}</DataItem>"#)
        };
        let mut attribute = |name: &str, kind: &str, center: &str, data: String| {
            self_units.push(name.to_string());
            format!(r#"<Attribute Name="{name}" AttributeType="{kind}" Center="{center}">{data}</Attribute>"#)
        };
        let x = &mut self.grids;
        let label = if group.is_some() { format!("increment {name}") } else { "initial state".to_string() };
        let _ = writeln!(x, r#"<Grid Name="{label}" GridType="Uniform"><Time Value="{time}"/>"#);
        let _ = writeln!(x, "{}", self.what.topology.xml(file, elements));
        let _ = writeln!(x, r#"<Geometry GeometryType="XY">{}</Geometry>"#, item("/mesh/coordinates", &format!("{nodes} 2"), "Float", 8));
        let vector_path = |name: &str| group.map_or(format!("{INITIAL}/vector"), |g| format!("{g}/nodal/{name}"));
        let scalar_path = |name: &str| match (group, name) {
            (Some(g), _) => format!("{g}/nodal/{name}"),
            (None, "temperature") => format!("{INITIAL}/temperature"),
            (None, _) => format!("{INITIAL}/scalar"),
        };
        let GridFields { fields: f, precision, contact, friction, kinematic, .. } = self.what;
        // the t = 0 frame's zeros are 64-bit
        let width = if group.is_some() && precision == Precision::Single { 4 } else { 8 };
        for (name, width) in [("displacement", 8), ("reaction_force", width)] {
            let _ = writeln!(x, "{}", attribute(name, "Vector", "Node", item(&vector_path(name), &format!("{nodes} 3"), "Float", width)));
        }
        // every frame carries the same arrays (ParaView keeps one list over time): the t = 0
        // frame's contact and element fields are zeros
        let contact_count = match (contact && f.contact, friction) {
            (false, _) => 0,
            (true, false) => 3,
            (true, true) => 5,
        };
        let scalars = NODAL_SCALARS.iter().chain(&NODAL_TAIL).filter(|name| nodal_scalar_kept(name, f));
        let backstress = if kinematic && f.plastic_strain { &BACKSTRESS_SCALARS[..] } else { &[] };
        for name in scalars.chain(backstress).chain(&CONTACT_SCALARS[..contact_count]) {
            let _ = writeln!(x, "{}", attribute(name, "Scalar", "Node", item(&scalar_path(name), &nodes.to_string(), "Float", width)));
        }
        let element = [("von_mises_mean", f.von_mises), ("equivalent_plastic_strain_max", f.plastic_strain)].into_iter().filter(|e| e.1).map(|e| e.0);
        for name in element {
            let path = group.map_or(format!("{INITIAL}/cell"), |g| format!("{g}/{name}"));
            let _ = writeln!(x, "{}", attribute(name, "Scalar", "Cell", item(&path, &elements.to_string(), "Float", width)));
        }
        let _ = writeln!(x, "{}", attribute("rank", "Scalar", "Cell", item("/mesh/element_rank", &elements.to_string(), "UInt", 4)));
        let _ = writeln!(x, "</Grid>");
        for name in names {
            if !self.units.iter().any(|(n, _)| *n == name) {
                let (units, _) = describe("/increments/000001/nodal", &name);
                self.units.push((name, if self.what.plane { plane_units(units) } else { units }));
            }
        }
    }
}

/// The sidecar of perturbation step `name` beside results file `h5`: `STEM_NAME.xmf`, one grid
/// on the undeformed mesh with the base state's displacement (`base`, an increment's group, when
/// its fields are in the file) and the perturbation's field at theta = 0 and its amplitudes, each
/// a 3-component vector: warp by the first, then by the second with a scale. Written by one
/// process; returns its path.
pub fn write_perturbation_sidecar(
    h5: &Path,
    name: &str,
    base: Option<&str>,
    (nodes, elements, topology): (usize, usize, Topology),
    modes: usize,
    nodal_stress: bool,
) -> Result<PathBuf> {
    let file = h5.file_name().map(|f| f.to_string_lossy().into_owned()).unwrap_or_default();
    let stem = h5.file_stem().map(|f| f.to_string_lossy().into_owned()).unwrap_or_default();
    let target = h5.with_file_name(format!("{stem}_{name}.xmf"));
    let item = |path: &str, dims: &str| format!(r#"<DataItem Dimensions="{dims}" NumberType="Float" Precision="8" Format="HDF">{file}:{path}</DataItem>"#);
    let vector = |label: &str, path: &str| {
        format!(r#"<Attribute Name="{label}" AttributeType="Vector" Center="Node">{}</Attribute>"#, item(path, &format!("{nodes} 3")))
    };
    // one grid alone in the domain (meshio reads no other element there); units: mm
    let mut x = String::from("<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\"><Domain>\n");
    let _ = writeln!(x, r#"<Grid Name="perturbation {name}" GridType="Uniform">"#);
    let _ = writeln!(x, "{}", topology.xml(&file, elements));
    let _ = writeln!(x, r#"<Geometry GeometryType="XY">{}</Geometry>"#, item("/mesh/coordinates", &format!("{nodes} 2")));
    if let Some(g) = base {
        let _ = writeln!(x, "{}", vector("base_displacement", &format!("/increments/{g}/nodal/displacement")));
    }
    let _ = writeln!(x, "{}", vector("displacement", &format!("/perturbations/{name}/displacement")));
    let _ = writeln!(x, "{}", vector("amplitudes", &format!("/perturbations/{name}/amplitudes")));
    for k in 1..=modes {
        let _ = writeln!(x, "{}", vector(&format!("mode_{k}"), &format!("/perturbations/{name}/mode_{k}")));
    }
    // a response step's stress amplitudes at the nodes
    for component in super::nodal::AMPLITUDE_STRESS.iter().filter(|_| nodal_stress) {
        let data = item(&format!("/perturbations/{name}/nodal/{component}"), &nodes.to_string());
        let _ = writeln!(x, r#"<Attribute Name="{component}" AttributeType="Scalar" Center="Node">{data}</Attribute>"#);
    }
    x.push_str("</Grid></Domain></Xdmf>\n");
    std::fs::write(&target, x).map_err(|e| Error::Output { path: target.clone(), message: e.to_string() })?;
    Ok(target)
}

/// The sidecar of heat step `name` beside results file `h5`: `STEM_NAME.xmf`, one grid on the
/// mesh with the temperature at the nodes and each element's mean heat flux. Written by one
/// process; returns its path.
pub fn write_heat_sidecar(h5: &Path, name: &str, (nodes, elements, topology): (usize, usize, Topology)) -> Result<PathBuf> {
    let file = h5.file_name().map(|f| f.to_string_lossy().into_owned()).unwrap_or_default();
    let stem = h5.file_stem().map(|f| f.to_string_lossy().into_owned()).unwrap_or_default();
    let target = h5.with_file_name(format!("{stem}_{name}.xmf"));
    let item = |path: &str, dims: &str| format!(r#"<DataItem Dimensions="{dims}" NumberType="Float" Precision="8" Format="HDF">{file}:{path}</DataItem>"#);
    let mut x = String::from("<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\"><Domain>\n");
    let _ = writeln!(x, r#"<Grid Name="heat {name}" GridType="Uniform">"#);
    let _ = writeln!(x, "{}", topology.xml(&file, elements));
    let _ = writeln!(x, r#"<Geometry GeometryType="XY">{}</Geometry>"#, item("/mesh/coordinates", &format!("{nodes} 2")));
    let _ = writeln!(
        x,
        r#"<Attribute Name="temperature" AttributeType="Scalar" Center="Node">{}</Attribute>"#,
        item(&format!("/heat/{name}/temperature"), &nodes.to_string())
    );
    let _ = writeln!(
        x,
        r#"<Attribute Name="heat_flux" AttributeType="Vector" Center="Cell">{}</Attribute>"#,
        item(&format!("/heat/{name}/element_flux"), &format!("{elements} 3"))
    );
    x.push_str("</Grid></Domain></Xdmf>\n");
    std::fs::write(&target, x).map_err(|e| Error::Output { path: target.clone(), message: e.to_string() })?;
    Ok(target)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_write_holds_every_increment_so_far_and_closes_the_document() {
        let dir = std::env::temp_dir().join(format!("slideline-xdmf-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let h5 = dir.join("run.h5");
        let mut sidecar = Sidecar::new(
            &h5,
            10,
            2,
            GridFields {
                fields: OutputFields::DEFAULT,
                precision: Precision::Double,
                contact: false,
                friction: false,
                kinematic: false,
                topology: Topology::Quad8,
                plane: false,
            },
        )
        .unwrap();
        let text = std::fs::read_to_string(sidecar_path(&h5)).unwrap();
        assert!(text.contains("<Time Value=\"0\"/>") && text.contains("run.h5:/initial/vector"), "the t = 0 frame is there from the start");
        for (k, time) in [0.5, 1.0, 1.25].into_iter().enumerate() {
            sidecar.add_increment(&format!("{:06}", k + 1), time).unwrap();
            let text = std::fs::read_to_string(sidecar_path(&h5)).unwrap();
            assert_eq!(text.matches("<Grid Name=\"increment").count(), k + 1);
            assert_eq!(text.matches("<Grid Name=\"initial state").count(), 1);
            assert!(text.contains(&format!("<Time Value=\"{time}\"/>")) && text.contains(&format!("run.h5:/increments/{:06}/nodal/displacement", k + 1)));
            assert_eq!(text.matches("<Grid").count(), text.matches("</Grid>").count(), "every grid closed, the collection too");
            assert!(text.trim_end().ends_with("</Grid></Domain></Xdmf>"));
            assert!(!h5.with_extension("xmf.tmp").exists(), "the temporary file is renamed into place");
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
