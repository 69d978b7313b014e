//! XDMF 3 sidecar describing the HDF5 results as a time series of Q8 meshes, so that ParaView
//! (its default Xdmf3 reader and the legacy one) and meshio open `results.xmf` directly. Every
//! data item is a plain HDF5 dataset (no functions or hyperslabs, which Xdmf3 and meshio skip):
//! the displacement as a 3-component vector (u_r, u_z, 0) for Warp By Vector, the stress
//! components, von Mises stress, equivalent plastic strain and temperature at the nodes
//! (carried there from the Gauss points, see `io::nodal`), and per element the mean von Mises
//! stress, the largest plastic strain and the rank.

use super::nodal::{nodal_scalar_kept, NODAL_SCALARS};
use crate::error::{Error, Result};
use crate::model::OutputFields;
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};

/// Path of the sidecar of results file `h5`: same name with extension `.xmf`.
pub fn sidecar_path(h5: &Path) -> PathBuf {
    h5.with_extension("xmf")
}

/// The sidecar of one results file, grown by one grid per converged increment. Each grid is
/// formatted once and kept: formatting every increment's grid again at each write made the
/// sidecar quadratic in the number of increments (a 2400-increment run formatted 2.9 million
/// grids). The file itself is still written whole each time, so that a reader never finds it
/// half-written (about 1.4 kB a grid).
pub struct Sidecar {
    target: PathBuf,
    /// The results file's name, as the data items reference it (relative: the two files move
    /// together).
    file: String,
    nodes: usize,
    elements: usize,
    /// The grids written so far, one per increment.
    grids: String,
    /// The fields written beside the displacement.
    fields: OutputFields,
    /// The model has contact pairs: the nodal contact fields are written.
    contact: bool,
}

impl Sidecar {
    pub fn new(h5: &Path, nodes: usize, elements: usize, fields: OutputFields, contact: bool) -> Self {
        let file = h5.file_name().map(|f| f.to_string_lossy().into_owned()).unwrap_or_default();
        Sidecar { target: sidecar_path(h5), file, nodes, elements, grids: String::new(), fields, contact }
    }

    /// Adds the grid of the increment stored in group `/increments/{group}` at `time`, and
    /// rewrites the sidecar (atomically: temporary file, then rename).
    pub fn add_increment(&mut self, group: &str, time: f64) -> Result<()> {
        self.push_grid(group, time);
        const HEADER: &str =
            "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\"><Domain><Grid Name=\"slideline\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
        const FOOTER: &str = "</Grid></Domain></Xdmf>\n";
        let tmp = self.target.with_extension("xmf.tmp");
        let io = |source| Error::Output { path: self.target.clone(), message: format!("{source}") };
        let mut out = std::fs::File::create(&tmp).map_err(io)?;
        for part in [HEADER, &self.grids, FOOTER] {
            out.write_all(part.as_bytes()).map_err(io)?;
        }
        std::fs::rename(&tmp, &self.target).map_err(io)
    }

    fn push_grid(&mut self, group: &str, time: f64) {
        let (nodes, elements, file) = (self.nodes, self.elements, &self.file);
        let item = |path: &str, dims: &str, ty: &str, precision: u32| {
            format!(r#"<DataItem Dimensions="{dims}" NumberType="{ty}" Precision="{precision}" Format="HDF">{file}:{path}</DataItem>"#)
        };
        let g = format!("/increments/{group}");
        let x = &mut self.grids;
        let _ = writeln!(x, r#"<Grid Name="increment {group}" GridType="Uniform"><Time Value="{time}"/>"#);
        let _ = writeln!(
            x,
            r#"<Topology TopologyType="Quadrilateral_8" NumberOfElements="{elements}">{}</Topology>"#,
            item("/mesh/connectivity", &format!("{elements} 8"), "Int", 8)
        );
        let _ = writeln!(x, r#"<Geometry GeometryType="XY">{}</Geometry>"#, item("/mesh/coordinates", &format!("{nodes} 2"), "Float", 8));
        let _ = writeln!(
            x,
            r#"<Attribute Name="displacement" AttributeType="Vector" Center="Node">{}</Attribute>"#,
            item(&format!("{g}/nodal/displacement"), &format!("{nodes} 3"), "Float", 8)
        );
        let f = self.fields;
        let contact: &[&str] = if self.contact && f.contact { &["contact_pressure", "contact_status", "contact_gap"] } else { &[] };
        let temperature: &[&str] = if f.temperature { &["temperature"] } else { &[] };
        let scalars = NODAL_SCALARS.iter().filter(|name| nodal_scalar_kept(name, f));
        for name in scalars.chain(temperature).chain(contact) {
            let _ = writeln!(
                x,
                r#"<Attribute Name="{name}" AttributeType="Scalar" Center="Node">{}</Attribute>"#,
                item(&format!("{g}/nodal/{name}"), &nodes.to_string(), "Float", 8)
            );
        }
        let element: Vec<&str> =
            [("von_mises_mean", f.von_mises), ("equivalent_plastic_strain_max", f.plastic_strain)].into_iter().filter(|e| e.1).map(|e| e.0).collect();
        for name in element {
            let _ = writeln!(
                x,
                r#"<Attribute Name="{name}" AttributeType="Scalar" Center="Cell">{}</Attribute>"#,
                item(&format!("{g}/{name}"), &elements.to_string(), "Float", 8)
            );
        }
        let _ = writeln!(
            x,
            r#"<Attribute Name="rank" AttributeType="Scalar" Center="Cell">{}</Attribute>"#,
            item("/mesh/element_rank", &elements.to_string(), "UInt", 4)
        );
        let _ = writeln!(x, "</Grid>");
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_write_holds_every_increment_so_far_and_closes_the_document() {
        let dir = std::env::temp_dir().join(format!("slideline-xdmf-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let h5 = dir.join("run.h5");
        let mut sidecar = Sidecar::new(&h5, 10, 2, OutputFields::ALL, false);
        for (k, time) in [0.5, 1.0, 1.25].into_iter().enumerate() {
            sidecar.add_increment(&format!("{:06}", k + 1), time).unwrap();
            let text = std::fs::read_to_string(sidecar_path(&h5)).unwrap();
            assert_eq!(text.matches("<Grid Name=\"increment").count(), k + 1);
            assert!(text.contains(&format!("<Time Value=\"{time}\"/>")) && text.contains(&format!("run.h5:/increments/{:06}/nodal/displacement", k + 1)));
            assert_eq!(text.matches("<Grid").count(), text.matches("</Grid>").count(), "every grid closed, the collection too");
            assert!(text.trim_end().ends_with("</Grid></Domain></Xdmf>"));
            assert!(!h5.with_extension("xmf.tmp").exists(), "the temporary file is renamed into place");
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
