//! A perturbation step in the results file, `/perturbations/NAME` (collective): the mode, the
//! harmonic amplitudes of every node, the displacement at theta = 0 as a 3-D vector, the
//! stress amplitudes at the Gauss points, and
//! `reactions/SET` with each set's summed nodal forces (per radian) and full-ring resultants
//! as attributes.

use super::h5::{gauss_rows, group_in, h5err, write_rows};
use super::results::ResultsFile;
use crate::decomposition::Partition;
use crate::element::solid::QUADRATURE_POINTS;
use crate::error::Result;
use crate::model::perturbation::{Analysis, Perturbation};
use crate::records::perturbation::frequency_hz;
use crate::records::perturbation::PerturbationAnswer;

impl ResultsFile {
    /// Writes perturbation step `p`'s answer (collective; every rank holds the whole answer),
    /// and rank 0 its XDMF sidecar, with the base state's displacement from increment group
    /// `base` (its fields in the file).
    pub fn write_perturbation(&mut self, p: &Perturbation, answer: &PerturbationAnswer, partition: &Partition, base: Option<&str>) -> Result<()> {
        let path = self.path.clone();
        let err = h5err(&path);
        let top = group_in(&self.file, "perturbations", &path)?;
        let g = top.create_group(&p.name).map_err(&err)?;
        g.new_attr::<u32>().create("mode").map_err(&err)?.write_scalar(&p.mode).map_err(&err)?;
        let procedure: hdf5::types::VarLenUnicode = p.analysis.procedure().parse().expect("no NUL");
        g.new_attr::<hdf5::types::VarLenUnicode>().create("procedure").map_err(&err)?.write_scalar(&procedure).map_err(&err)?;
        let slab = (partition.node_offsets[partition.rank], partition.node_offsets[partition.rank + 1]);
        let owned = partition.owned_nodes();
        let field = |name: &str, amplitudes: &[[f64; 3]]| -> Result<()> {
            let nn = amplitudes.len();
            write_rows(&g, name, &[nn, 3], slab, &owned.iter().flat_map(|&n| amplitudes[n]).collect::<Vec<f64>>(), &path)
        };
        // the field a response step gives, or an eigenvalue step's first mode
        let first = answer.modes.first().map_or(&answer.amplitudes, |m| &m.amplitudes);
        let nn = first.len();
        field("amplitudes", first)?;
        // at theta = 0: cos = 1, sin = 0 (n = 0: u_theta = U_t)
        let hoop = if p.mode == 0 { 1.0 } else { 0.0 };
        field("displacement", &first.iter().map(|a| [a[0], a[1], hoop * a[2]]).collect::<Vec<_>>())?;
        if answer.modes.is_empty() {
            let ne = partition.element_offsets[partition.size];
            let element_slab = (partition.element_offsets[partition.rank], partition.element_offsets[partition.rank + 1]);
            let stress = gauss_rows(&answer.stress, &self.gauss_points);
            write_rows(&g, "stress", &[ne, QUADRATURE_POINTS, 6], element_slab, &stress, &path)?;
            // and at the nodes, for ParaView to colour the deformed shape by
            self.nodal.write_amplitudes(&g, &answer.stress, &path)?;
        } else {
            // the eigenvalues (rank 0 writes the short lists) and every mode's amplitudes
            let k = answer.modes.len();
            let list = |name: &str, values: Vec<f64>| -> Result<()> {
                let rows = if partition.rank == 0 { (0, k) } else { (k, k) };
                write_rows(&g, name, &[k], rows, &values[rows.0..rows.1], &path)
            };
            list("eigenvalues", answer.modes.iter().map(|m| m.eigenvalue).collect())?;
            if let Analysis::Frequency { .. } = p.analysis {
                list("frequencies", answer.modes.iter().map(|m| frequency_hz(m.eigenvalue)).collect())?;
                if answer.modes.iter().all(|m| m.effective_mass.is_some()) {
                    list("effective_mass_ring", answer.modes.iter().map(|m| m.effective_mass.unwrap_or(f64::NAN)).collect())?;
                }
            }
            for (i, mode) in answer.modes.iter().enumerate() {
                field(&format!("mode_{}", i + 1), &mode.amplitudes)?;
            }
            // buckle steps: each mode's critical pressure on each surface the step loads
            for (k, (surface, _)) in answer.modes.first().map_or(&[][..], |m| m.critical_pressures.as_slice()).iter().enumerate() {
                list(&format!("critical_pressure_{surface}"), answer.modes.iter().map(|m| m.critical_pressures[k].1).collect())?;
            }
        }
        let reactions = g.create_group("reactions").map_err(&err)?;
        for r in &answer.reactions {
            let s = reactions.create_group(&r.set).map_err(&err)?;
            s.new_attr::<f64>().shape(3).create("force").map_err(&err)?.write(&r.force).map_err(&err)?;
            for (name, value, _) in &r.resultants {
                s.new_attr::<f64>().create(*name).map_err(&err)?.write_scalar(value).map_err(&err)?;
            }
        }
        self.file.flush().map_err(&err)?;
        if partition.rank == 0 {
            let elements = partition.element_offsets[partition.size];
            super::xdmf::write_perturbation_sidecar(&path, &p.name, base, (nn, elements, self.topology), answer.modes.len(), answer.modes.is_empty())?;
        }
        Ok(())
    }
}
