//! A heat step in the results file, `/heat/NAME` (collective): every node's temperature, the
//! heat flux at the Gauss points and each element's mean, and `flows/SET` with the heat flowing
//! in through each held set as attributes; rank 0 writes its XDMF sidecar (`STEM_NAME.xmf`).

use super::h5::{gauss_rows, group_in, h5err, write_rows};
use super::results::ResultsFile;
use crate::decomposition::Partition;
use crate::element::solid::QUADRATURE_POINTS;
use crate::error::Result;
use crate::model::heat::HeatStep;
use crate::records::heat::HeatAnswer;

impl ResultsFile {
    /// Writes heat step `step`'s answer (collective; every rank holds every temperature, and
    /// the flux of its own elements). `axisymmetric`: the flows are per radian, and the
    /// full ring's are written beside them.
    pub fn write_heat(&mut self, step: &HeatStep, answer: &HeatAnswer, partition: &Partition, axisymmetric: bool) -> Result<()> {
        let path = self.path.clone();
        let err = h5err(&path);
        let top = group_in(&self.file, "heat", &path)?;
        let g = top.create_group(&step.name).map_err(&err)?;
        let nodes = answer.temperature.len();
        let slab = (partition.node_offsets[partition.rank], partition.node_offsets[partition.rank + 1]);
        let owned: Vec<f64> = partition.owned_nodes().iter().map(|&n| answer.temperature[n]).collect();
        write_rows(&g, "temperature", &[nodes], slab, &owned, &path)?;
        let elements = partition.element_offsets[partition.size];
        let element_slab = (partition.element_offsets[partition.rank], partition.element_offsets[partition.rank + 1]);
        let flux = gauss_rows(&answer.flux, &self.gauss_points);
        write_rows(&g, "flux", &[elements, QUADRATURE_POINTS, 2], element_slab, &flux, &path)?;
        // each element's mean as a 3-vector, for ParaView's glyphs (q_theta = 0)
        let mean: Vec<f64> = answer
            .flux
            .iter()
            .zip(&self.gauss_points)
            .flat_map(|(points, &n)| {
                let m = [0, 1].map(|i| points[..n].iter().map(|q| q[i]).sum::<f64>() / n as f64);
                [m[0], m[1], 0.0]
            })
            .collect();
        write_rows(&g, "element_flux", &[elements, 3], element_slab, &mean, &path)?;
        let flows = g.create_group("flows").map_err(&err)?;
        for f in &answer.flows {
            let s = flows.create_group(&f.set).map_err(&err)?;
            let (key, ring) = if axisymmetric { ("flow_per_radian", Some(std::f64::consts::TAU * f.flow)) } else { ("flow", None) };
            s.new_attr::<f64>().create(key).map_err(&err)?.write_scalar(&f.flow).map_err(&err)?;
            if let Some(ring) = ring {
                s.new_attr::<f64>().create("flow_ring").map_err(&err)?.write_scalar(&ring).map_err(&err)?;
            }
            let units: hdf5::types::VarLenUnicode = "mW, heat flowing into the body through the set's nodes".parse().expect("no NUL");
            s.new_attr::<hdf5::types::VarLenUnicode>().create("units").map_err(&err)?.write_scalar(&units).map_err(&err)?;
        }
        self.file.flush().map_err(&err)?;
        if partition.rank == 0 {
            super::xdmf::write_heat_sidecar(&path, &step.name, (nodes, elements, self.topology))?;
        }
        Ok(())
    }
}
