//! XDMF (version 2) sidecar describing the HDF5 results as a time series of Q8 meshes, so
//! ParaView opens `results.xmf` directly (Xdmf reader). Displacement is exposed as a
//! 3-component vector (u_r, u_z, 0) for Warp By Vector; stresses are per element (mean von
//! Mises) since XDMF has no quadrature-point centring.

use crate::error::{Error, Result};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

pub struct IncrementEntry {
    pub group: String,
    pub time: f64,
}

/// Path of the sidecar of results file `h5`: same name with extension `.xmf`.
pub fn sidecar_path(h5: &Path) -> PathBuf {
    h5.with_extension("xmf")
}

/// Rewrites the whole sidecar (atomically: temporary file, then rename).
pub fn write(h5: &Path, nodes: usize, elements: usize, increments: &[IncrementEntry]) -> Result<()> {
    let file = h5.file_name().map(|f| f.to_string_lossy().into_owned()).unwrap_or_default();
    let item = |path: &str, dims: &str, ty: &str, precision: u32| {
        format!(r#"<DataItem Dimensions="{dims}" NumberType="{ty}" Precision="{precision}" Format="HDF">{file}:{path}</DataItem>"#)
    };
    let column = |path: &str, c: usize| {
        format!(
            r#"<DataItem ItemType="HyperSlab" Dimensions="{nodes} 1"><DataItem Dimensions="3 2" Format="XML">0 {c} 1 1 {nodes} 1</DataItem>{}</DataItem>"#,
            item(path, &format!("{nodes} 2"), "Float", 8)
        )
    };
    let mut x = String::new();
    let _ = writeln!(x, r#"<?xml version="1.0" ?>"#);
    let _ = writeln!(x, r#"<Xdmf Version="2.0"><Domain><Grid Name="slideline" GridType="Collection" CollectionType="Temporal">"#);
    for inc in increments {
        let g = format!("/increments/{}", inc.group);
        let _ = writeln!(x, r#"<Grid Name="increment {}" GridType="Uniform"><Time Value="{}"/>"#, inc.group, inc.time);
        let _ = writeln!(
            x,
            r#"<Topology TopologyType="Quadrilateral_8" NumberOfElements="{elements}">{}</Topology>"#,
            item("/mesh/connectivity", &format!("{elements} 8"), "Int", 8)
        );
        let _ = writeln!(x, r#"<Geometry GeometryType="XY">{}</Geometry>"#, item("/mesh/coordinates", &format!("{nodes} 2"), "Float", 8));
        let _ = writeln!(
            x,
            r#"<Attribute Name="displacement" AttributeType="Vector" Center="Node"><DataItem ItemType="Function" Function="JOIN($0, $1, 0.0 * $0)" Dimensions="{nodes} 3">{}{}</DataItem></Attribute>"#,
            column(&format!("{g}/displacement"), 0),
            column(&format!("{g}/displacement"), 1)
        );
        let _ = writeln!(
            x,
            r#"<Attribute Name="von_mises_mean" AttributeType="Scalar" Center="Cell">{}</Attribute>"#,
            item(&format!("{g}/von_mises_mean"), &elements.to_string(), "Float", 8)
        );
        let _ = writeln!(
            x,
            r#"<Attribute Name="rank" AttributeType="Scalar" Center="Cell">{}</Attribute>"#,
            item("/mesh/element_rank", &elements.to_string(), "UInt", 4)
        );
        let _ = writeln!(x, "</Grid>");
    }
    let _ = writeln!(x, "</Grid></Domain></Xdmf>");
    let target = sidecar_path(h5);
    let tmp = target.with_extension("xmf.tmp");
    let io = |source| Error::Output { path: target.clone(), message: format!("{source}") };
    std::fs::write(&tmp, x).map_err(io)?;
    std::fs::rename(&tmp, &target).map_err(io)
}
