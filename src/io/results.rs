//! The HDF5 results file: the deck, the mesh and its sets, the fields of each converged
//! increment (`nodal/` by `io::nodal`), the restart state (`io::restart`) and the history. Its
//! layout, dataset by dataset, is in docs/results.md; every dataset carries its units and a
//! description (`io::describe`).
//!
//! Metadata operations are collective (every rank calls them with the same arguments); bulk
//! data is written by each rank for its own contiguous slab. The file is flushed after every
//! converged increment, so a run that dies keeps everything converged before.

use super::h5::{describe_dataset, gauss_rows, group_in, h5err, write_field, write_rows, COMPLETE, COMPLETION_MARKED, OUTPUT_EVERY, PLANE};
use super::history::HistoryRow;
use super::nodal::NodalWriter;
use super::state::{write_state, CommittedState};
use super::xdmf;
use crate::decomposition::Partition;
use crate::element::solid::QUADRATURE_POINTS;
use crate::error::{Error, Result};
use crate::fe::axisymmetric::von_mises;
use crate::model::{Model, OutputFields, Precision};
use crate::petsc::PetscSession;
use crate::records::contact::PassOutput;
use crate::records::increment_fields::IncrementFields;
use hdf5::types::VarLenUnicode;
use mpi::traits::{AsRaw, Communicator, CommunicatorCollectives};
use std::path::{Path, PathBuf};

/// Increments whose links `/increments` holds in one piece of metadata (h5ffi::create_group_for_links).
const INCREMENTS_AT_ONCE: u16 = 2048;

pub struct ResultsFile {
    pub(super) file: hdf5::File,
    pub(super) path: PathBuf,
    rank: usize,
    elements: usize,
    element_slab: (usize, usize),
    /// Converged increments written so far.
    increments: usize,
    /// The XDMF sidecar, on rank 0 (which writes it).
    sidecar: Option<xdmf::Sidecar>,
    /// How the sidecars give the cells.
    pub(super) topology: xdmf::Topology,
    contact_mesh_written: bool,
    /// Reactions also per segment of this angle (degrees), CalculiX's convention for .inp runs.
    reaction_segment_degrees: Option<f64>,
    /// Whether the model is axisymmetric (has an axisymmetric element): its forces are per
    /// radian and get full-ring columns; a plane model's are for its thickness.
    axisymmetric: bool,
    pub(super) nodal: NodalWriter,
    /// How many of each local element's Gauss slots are integration points (9, or a reduced
    /// Q8's 4, a reduced T6's 3): the datasets hold NaN in the others.
    pub(super) gauss_points: Vec<usize>,
    /// The fields written beside the displacement.
    fields: OutputFields,
    precision: Precision,
    world: mpi::topology::SimpleCommunicator,
}

impl ResultsFile {
    /// Creates the file (collective) and writes the attributes and the mesh.
    pub fn create(path: &Path, session: &PetscSession, model: &Model, partition: &Partition) -> Result<Self> {
        let err = h5err(path);
        let world = session.world();
        let file = hdf5::File::with_options().with_fapl(|p| p.mpio(world.as_raw(), None)).create(path).map_err(&err)?;
        let rank = partition.rank;
        let text = |s: &str| s.parse::<VarLenUnicode>().map_err(|e| Error::Output { path: path.to_path_buf(), message: e.to_string() });
        let units = if model.is_axisymmetric() {
            "length mm, force N, stress MPa, temperature degC, time s; forces and reactions per radian unless named _ring (full 360 degrees)"
        } else {
            "length mm, force N, stress MPa, temperature degC, time s; a plane model (x, y stored as r, z; tt the out-of-plane component): forces and reactions over the sections' thickness"
        };
        let geometry = match (model.is_axisymmetric(), model.element_section.iter().any(|s| s.is_axisymmetric())) {
            (true, _) => "axisymmetric",
            (false, true) => "axisymmetric and plane",
            (false, false) => PLANE,
        };
        for (name, value) in [
            ("deck", model.source_text.as_str()),
            ("units", units),
            ("geometry", geometry),
            ("petsc_options", &session.options().join(" ")),
            ("slideline_version", env!("CARGO_PKG_VERSION")),
            ("step_names", &model.general_steps().map(|s| s.name.as_str()).collect::<Vec<_>>().join("\n")),
            ("fingerprints", &crate::model::fingerprint::text(model)),
        ] {
            file.new_attr::<VarLenUnicode>().create(name).map_err(&err)?.write_scalar(&text(value)?).map_err(&err)?;
        }
        file.new_attr::<u32>().create("ranks").map_err(&err)?.write_scalar(&(partition.size as u32)).map_err(&err)?;
        // readers trust only increments marked complete (a run that dies mid-write leaves one unmarked)
        file.new_attr::<u8>().create(COMPLETION_MARKED).map_err(&err)?.write_scalar(&1u8).map_err(&err)?;
        file.new_attr::<u32>().create("steps").map_err(&err)?.write_scalar(&(model.general_step_count() as u32)).map_err(&err)?;
        // which increments have fields, so that a reader can tell one that went missing
        file.new_attr::<u32>().create(OUTPUT_EVERY).map_err(&err)?.write_scalar(&(model.output.every as u32)).map_err(&err)?;

        let mesh = &model.mesh;
        let (nn, ne) = (mesh.coords.len(), mesh.elements.len());
        let node_slab = (partition.node_offsets[rank], partition.node_offsets[rank + 1]);
        let element_slab = (partition.element_offsets[rank], partition.element_offsets[rank + 1]);
        let (topology, gauss_points) = write_mesh(&file, model, partition, path)?;
        // the t = 0 frame of the sidecar: zero vectors, scalars and element values, the
        // reference temperature
        let initial = file.create_group(xdmf::INITIAL.trim_start_matches('/')).map_err(&err)?;
        let owned_count = node_slab.1 - node_slab.0;
        write_rows(&initial, "vector", &[nn, 3], node_slab, &vec![0.0f64; 3 * owned_count], path)?;
        write_rows(&initial, "scalar", &[nn], node_slab, &vec![0.0f64; owned_count], path)?;
        // and per element, for the element fields: ParaView keeps one array list over time
        write_rows(&initial, "cell", &[ne], element_slab, &vec![0.0f64; element_slab.1 - element_slab.0], path)?;
        let initial_temperature: Vec<f64> = partition.owned_nodes().iter().map(|&n| model.reference_temperature.at(n)).collect();
        write_rows(&initial, "temperature", &[nn], node_slab, &initial_temperature, path)?;
        // a writer killed while flushing cannot leave the increments' links half-written
        super::h5ffi::create_group_for_links(&file, "increments", INCREMENTS_AT_ONCE, 6)
            .map_err(|message| Error::Output { path: path.to_path_buf(), message })?;
        file.create_group("history").map_err(&err)?;
        file.flush().map_err(&err)?;
        let what = xdmf::GridFields {
            fields: model.output.fields,
            precision: model.output.precision,
            contact: !model.contacts.is_empty(),
            friction: (0..model.contacts.len()).any(|p| model.pair_has_friction(p)),
            kinematic: model.has_kinematic_hardening(),
            topology,
            plane: geometry == PLANE,
        };
        let sidecar = (rank == 0).then(|| xdmf::Sidecar::new(path, nn, ne, what)).transpose();
        // rank 0 alone writes the sidecar: every rank learns whether it could
        let mut failed = 0u8;
        world.all_reduce_into(&u8::from(sidecar.is_err()), &mut failed, mpi::collective::SystemOperation::max());
        let sidecar = match (sidecar, failed) {
            (Ok(s), 0) => s,
            (Err(e), _) => return Err(e),
            (Ok(_), _) => {
                return Err(Error::Output { path: xdmf::sidecar_path(path), message: "rank 0 could not write the XDMF sidecar".into() });
            }
        };
        Ok(ResultsFile {
            file,
            path: path.to_path_buf(),
            rank,
            elements: ne,
            element_slab,
            increments: 0,
            sidecar,
            topology,
            contact_mesh_written: false,
            reaction_segment_degrees: model.reaction_segment_degrees,
            axisymmetric: model.is_axisymmetric(),
            nodal: NodalWriter::new(world.duplicate(), model, partition),
            gauss_points,
            fields: model.output.fields,
            precision: model.output.precision,
            world: session.world().duplicate(),
        })
    }

    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Continues the history of the run a restart continues: its rows up to the restart
    /// increment (so that the numbering and the history go on from there), and the file it
    /// came from as the root attribute `restarted_from` (collective).
    pub fn continue_history(&mut self, from: &Path, rows: &[(String, HistoryRow)]) -> Result<()> {
        let err = h5err(&self.path);
        let text: VarLenUnicode = format!("{} increment {}", from.display(), rows.len())
            .parse()
            .map_err(|_| Error::Output { path: self.path.clone(), message: "restart file name".into() })?;
        self.file.new_attr::<VarLenUnicode>().create("restarted_from").map_err(&err)?.write_scalar(&text).map_err(&err)?;
        let decks: VarLenUnicode = format!(
            "increments 1 to {n}: the deck of {} (its attribute deck; a restart may add or change only the steps after increment {n}'s); from {}: this file's deck",
            from.display(),
            rows.len() + 1,
            n = rows.len()
        )
        .parse()
        .map_err(|_| Error::Output { path: self.path.clone(), message: "restart file name".into() })?;
        self.file.new_attr::<VarLenUnicode>().create("deck_of_increments").map_err(&err)?.write_scalar(&decks).map_err(&err)?;
        for (_, row) in rows {
            self.append_history(row)?;
            self.increments += 1;
        }
        self.file.flush().map_err(&err)
    }

    /// Converged increments written so far (history rows).
    pub fn increments_written(&self) -> usize {
        self.increments
    }

    /// Writes one converged increment (collective): its history row, and with `fields` its
    /// group /increments/NNNNNN (NNNNNN the run-wide number): this rank's displacement slab
    /// (owned nodes, partition order) and stress slab (local elements), the nodal and contact
    /// fields, marked complete last; then flushes and rewrites the XDMF sidecar.
    pub fn write_increment(
        &mut self,
        step_name: &str,
        row: &HistoryRow,
        fields: Option<(&IncrementFields<'_>, &CommittedState<'_>)>,
        partition: &Partition,
    ) -> Result<()> {
        let name = format!("{:06}", row.number);
        let group = fields.map(|(f, _)| self.write_fields(&name, step_name, row, f, partition)).transpose()?;
        if let (Some(g), Some((_, state))) = (&group, fields) {
            write_state(&self.file, g, &self.world, row.number, state, &self.path)?;
        }
        self.append_history(row)?;
        if let Some(g) = &group {
            // last: the mark that every dataset and the history row of the increment are on
            // disk, from every rank (flushed first, so a rank killed before the mark is
            // written never leaves a mark over data that is not there)
            self.file.flush().map_err(h5err(&self.path))?;
            g.new_attr::<u8>().create(COMPLETE).map_err(h5err(&self.path))?.write_scalar(&1u8).map_err(h5err(&self.path))?;
        }
        self.file.flush().map_err(h5err(&self.path))?;
        self.increments += 1;
        if group.is_none() {
            return Ok(());
        }
        if let Some(sidecar) = self.sidecar.as_mut() {
            sidecar.add_increment(&name, row.time)?;
        }
        Ok(())
    }

    /// The fields of one increment in a new group `name` (collective).
    fn write_fields(&mut self, name: &str, step_name: &str, row: &HistoryRow, fields: &IncrementFields<'_>, partition: &Partition) -> Result<hdf5::Group> {
        let IncrementFields { stress: local_stress, plastic_strain: local_plastic_strain, contact, .. } = *fields;
        let err = h5err(&self.path);
        let g = self.file.group("increments").map_err(&err)?.create_group(name).map_err(&err)?;
        // one number: the uniform temperature, or the field's largest value (the nodal field
        // is for ParaView and meshio)
        let temperature = ("temperature", fields.temperature.range()[1]);
        for (attr, value) in [("step", row.step as f64), ("increment", row.increment as f64), ("load_factor", row.load_factor), ("time", row.time), temperature]
        {
            g.new_attr::<f64>().create(attr).map_err(&err)?.write_scalar(&value).map_err(&err)?;
        }
        let step_name_v: VarLenUnicode = step_name.parse().map_err(|_| Error::Output { path: self.path.clone(), message: "step name".into() })?;
        g.new_attr::<VarLenUnicode>().create("step_name").map_err(&err)?.write_scalar(&step_name_v).map_err(&err)?;
        let f = self.fields;
        let used = &self.gauss_points;
        if f.stress {
            let s = gauss_rows(local_stress, used);
            write_field(&g, "stress", &[self.elements, QUADRATURE_POINTS, 4], self.element_slab, &s, self.precision, &self.world, &self.path)?;
        }
        if f.von_mises {
            let vm: Vec<[[f64; 1]; QUADRATURE_POINTS]> = local_stress.iter().map(|e| e.map(|s| [von_mises(&s)])).collect();
            write_field(
                &g,
                "von_mises",
                &[self.elements, QUADRATURE_POINTS],
                self.element_slab,
                &gauss_rows(&vm, used),
                self.precision,
                &self.world,
                &self.path,
            )?;
            let mean: Vec<f64> = vm.iter().zip(used).map(|(e, &n)| e[..n].iter().map(|v| v[0]).sum::<f64>() / n as f64).collect();
            write_field(&g, "von_mises_mean", &[self.elements], self.element_slab, &mean, self.precision, &self.world, &self.path)?;
        }
        if let (true, Some(back)) = (f.plastic_strain, fields.backstress) {
            write_field(
                &g,
                "backstress",
                &[self.elements, QUADRATURE_POINTS, 4],
                self.element_slab,
                &gauss_rows(back, used),
                self.precision,
                &self.world,
                &self.path,
            )?;
        }
        if f.plastic_strain {
            let ep: Vec<[[f64; 1]; QUADRATURE_POINTS]> = local_plastic_strain.iter().map(|e| e.map(|v| [v])).collect();
            write_field(
                &g,
                "equivalent_plastic_strain",
                &[self.elements, QUADRATURE_POINTS],
                self.element_slab,
                &gauss_rows(&ep, used),
                self.precision,
                &self.world,
                &self.path,
            )?;
            let ep_max: Vec<f64> = local_plastic_strain.iter().zip(used).map(|(c, &n)| c[..n].iter().fold(0.0f64, |m, &v| m.max(v))).collect();
            write_field(&g, "equivalent_plastic_strain_max", &[self.elements], self.element_slab, &ep_max, self.precision, &self.world, &self.path)?;
        }
        self.nodal.write(&g, fields, &self.path)?;
        // Newton history of the increment: identical on all ranks, written by rank 0.
        let norms = &row.residual_norms;
        let (slab, data): ((usize, usize), &[f64]) = if self.rank == 0 { ((0, norms.len()), norms) } else { ((0, 0), &[]) };
        write_rows(&g, "residual_norms", &[norms.len()], slab, data, &self.path)?;
        drop(err);
        if !contact.is_empty() && f.contact {
            self.write_contact(&g, row, contact, partition)?;
        }
        Ok(g)
    }

    /// Per pass of each pair: gap, pressure and active flag of every slave node (this rank's
    /// slab); the slave nodes and their areas once, under /mesh/contact.
    fn write_contact(&mut self, g: &hdf5::Group, row: &HistoryRow, passes: &[PassOutput<'_>], partition: &Partition) -> Result<()> {
        let err = h5err(&self.path);
        let group_of = |base: &hdf5::Group, p: &PassOutput<'_>| -> Result<hdf5::Group> {
            let pair = &row.contacts[p.pair].name;
            let pg = group_in(base, pair, &self.path)?;
            pg.create_group(&format!("pass{}", p.pass)).map_err(&err)
        };
        if !self.contact_mesh_written {
            let mg = self.file.group("mesh").map_err(&err)?.create_group("contact").map_err(&err)?;
            for p in passes {
                let pg = group_of(&mg, p)?;
                let slab = (p.offset, p.offset + p.nodes.len());
                let rows: Vec<u64> = p.nodes.iter().map(|&n| partition.node_position[n] as u64).collect();
                write_rows(&pg, "nodes", &[p.total], slab, &rows, &self.path)?;
                write_rows(&pg, "areas", &[p.total], slab, &p.areas, &self.path)?;
            }
            self.contact_mesh_written = true;
        }
        let cg = g.create_group("contact").map_err(&err)?;
        for p in passes {
            let pg = group_of(&cg, p)?;
            let slab = (p.offset, p.offset + p.nodes.len());
            let gap: Vec<f64> = p.states.iter().map(|s| s.gap).collect();
            let pressure: Vec<f64> = p.states.iter().map(|s| s.pressure).collect();
            let active: Vec<u8> = p.states.iter().map(|s| u8::from(s.pressure > 0.0)).collect();
            let traction: Vec<f64> = p.states.iter().map(|s| s.traction).collect();
            write_field(&pg, "traction", &[p.total], slab, &traction, self.precision, &self.world, &self.path)?;
            write_field(&pg, "gap", &[p.total], slab, &gap, self.precision, &self.world, &self.path)?;
            write_field(&pg, "pressure", &[p.total], slab, &pressure, self.precision, &self.world, &self.path)?;
            write_rows(&pg, "active", &[p.total], slab, &active, &self.path)?;
            if let Some(area) = &p.bearing_areas {
                write_field(&pg, "area", &[p.total], slab, area, self.precision, &self.world, &self.path)?;
            }
            if p.friction {
                let shear: Vec<f64> = p.states.iter().map(|s| s.shear).collect();
                let sliding: Vec<u8> = p.states.iter().map(|s| u8::from(s.sliding)).collect();
                write_field(&pg, "shear", &[p.total], slab, &shear, self.precision, &self.world, &self.path)?;
                write_rows(&pg, "sliding", &[p.total], slab, &sliding, &self.path)?;
            }
        }
        Ok(())
    }

    fn append_history(&self, row: &HistoryRow) -> Result<()> {
        let ring = 2.0 * std::f64::consts::PI;
        let mut columns: Vec<(String, f64)> = vec![
            ("step".into(), row.step as f64),
            ("increment".into(), row.increment as f64),
            ("load_factor".into(), row.load_factor),
            ("time".into(), row.time),
            ("newton_iterations".into(), row.newton_iterations as f64),
            ("linear_iterations".into(), row.linear_iterations as f64),
            ("residual_norm".into(), row.residual_norm),
            ("average_force".into(), row.average_force),
            ("cutbacks".into(), row.cutbacks as f64),
            ("augmentations".into(), row.augmentations as f64),
            ("max_equivalent_plastic_strain".into(), row.max_plastic_strain),
            ("wall_time".into(), row.wall_time),
        ];
        for c in &row.contacts {
            columns.push((format!("contact_{}_active_nodes", c.name), c.active_nodes as f64));
            columns.push((format!("contact_{}_max_penetration", c.name), c.max_penetration));
            // the full ring's force first, as the reactions
            if self.axisymmetric {
                columns.push((format!("contact_{}_force_ring", c.name), c.normal_force * ring));
            }
            columns.push((format!("contact_{}_force", c.name), c.normal_force));
        }
        for (name, value) in row.energy.map(|e| e.columns()).into_iter().flatten() {
            columns.push((name.to_string(), value));
        }
        for (set, f) in &row.reactions {
            // the full ring's first (as Abaqus and ANSYS report an axisymmetric model), per
            // radian beside it
            if self.axisymmetric {
                columns.push((format!("reaction_{set}_r_ring"), f[0] * ring));
                columns.push((format!("reaction_{set}_z_ring"), f[1] * ring));
            }
            columns.push((format!("reaction_{set}_r"), f[0]));
            columns.push((format!("reaction_{set}_z"), f[1]));
            if let Some(deg) = self.reaction_segment_degrees {
                let seg = deg.to_radians();
                columns.push((format!("reaction_{set}_r_{deg}deg"), f[0] * seg));
                columns.push((format!("reaction_{set}_z_{deg}deg"), f[1] * seg));
            }
        }
        for (set, u) in &row.set_displacements {
            columns.push((format!("displacement_{set}_r"), u[0]));
            columns.push((format!("displacement_{set}_z"), u[1]));
        }
        let err = h5err(&self.path);
        let history = self.file.group("history").map_err(&err)?;
        // rows already written
        let n = self.increments;
        // the columns in the order the run prints them (HDF5 lists members alphabetically)
        let order: Vec<&str> = columns.iter().map(|(name, _)| name.as_str()).collect();
        if !order.iter().all(|c| history.link_exists(c)) {
            if history.attr_names().map_err(&err)?.iter().any(|a| a == "columns") {
                history.delete_attr("columns").map_err(&err)?;
            }
            let text: VarLenUnicode = order.join(",").parse().map_err(|_| Error::Output { path: self.path.clone(), message: "column names".into() })?;
            history.new_attr::<VarLenUnicode>().create("columns").map_err(&err)?.write_scalar(&text).map_err(&err)?;
        }
        for (name, value) in columns {
            let ds = if history.link_exists(&name) {
                history.dataset(&name).map_err(&err)?
            } else {
                // A column that appears later (a set constrained from step 2 on) starts with NaN rows.
                let ds = history.new_dataset::<f64>().chunk(256).shape(0..).create(name.as_str()).map_err(&err)?;
                let (units, description) = super::describe::describe_column(&name);
                describe_dataset(&ds, units, &description, &self.path)?;
                ds.resize(n).map_err(&err)?;
                if n > 0 && self.rank == 0 {
                    ds.write_slice(&vec![f64::NAN; n], 0..n).map_err(&err)?;
                }
                ds
            };
            ds.resize(n + 1).map_err(&err)?;
            if self.rank == 0 {
                ds.write_slice(&[value], n..n + 1).map_err(&err)?;
            }
        }
        Ok(())
    }
}

/// The results file's `/mesh` group: the coordinates, connectivity (and the XDMF topology where
/// it differs), the ids, ranks and Gauss point counts, the sets; each rank its slab (collective).
/// Gives the topology and the local elements' integration point counts.
fn write_mesh(file: &hdf5::File, model: &Model, partition: &Partition, path: &Path) -> Result<(xdmf::Topology, Vec<usize>)> {
    let err = h5err(path);
    let rank = partition.rank;
    let mesh = &model.mesh;
    let (nn, ne) = (mesh.coords.len(), mesh.elements.len());
    let node_slab = (partition.node_offsets[rank], partition.node_offsets[rank + 1]);
    let element_slab = (partition.element_offsets[rank], partition.element_offsets[rank + 1]);
    let g = file.create_group("mesh").map_err(&err)?;
    let owned = partition.owned_nodes();
    let local = partition.local_elements();
    let coords: Vec<f64> = owned.iter().flat_map(|&n| mesh.coords[n]).collect();
    write_rows(&g, "coordinates", &[nn, 2], node_slab, &coords, path)?;
    let conn: Vec<i64> = local.iter().flat_map(|&e| mesh.elements[e].map(|n| partition.node_position[n] as i64)).collect();
    write_rows(&g, "connectivity", &[ne, 8], element_slab, &conn, path)?;
    let topology = xdmf::Topology::of(mesh);
    let nodes_of = |e: usize| mesh.element_nodes(e).iter().map(|&n| partition.node_position[n] as i64);
    match topology {
        xdmf::Topology::Quad8 => {}
        xdmf::Topology::Tri6 => {
            let cells: Vec<i64> = local.iter().flat_map(|&e| nodes_of(e)).collect();
            write_rows(&g, "topology", &[ne, 6], element_slab, &cells, path)?;
        }
        xdmf::Topology::Mixed { values } => {
            // each rank's cells follow those of the ranks before it
            let length = |e: usize| 1 + mesh.shape(e).nodes();
            let start: usize = (0..ne).filter(|&e| partition.element_rank[e] < rank).map(length).sum();
            let cells: Vec<i64> = local.iter().flat_map(|&e| std::iter::once(xdmf::xdmf_cell_type(mesh.shape(e))).chain(nodes_of(e))).collect();
            write_rows(&g, "topology", &[values], (start, start + cells.len()), &cells, path)?;
        }
    }
    let ids: Vec<u64> = owned.iter().map(|&n| mesh.node_ids[n]).collect();
    write_rows(&g, "node_ids", &[nn], node_slab, &ids, path)?;
    let ids: Vec<u64> = local.iter().map(|&e| mesh.element_ids[e]).collect();
    write_rows(&g, "element_ids", &[ne], element_slab, &ids, path)?;
    let ranks: Vec<u32> = local.iter().map(|&e| partition.element_rank[e] as u32).collect();
    write_rows(&g, "element_rank", &[ne], element_slab, &ranks, path)?;
    let gauss_points: Vec<usize> = local.iter().map(|&e| model.mesh.shape(e).points(model.element_integration[e])).collect();
    let counts: Vec<u32> = gauss_points.iter().map(|&n| n as u32).collect();
    write_rows(&g, "gauss_points", &[ne], element_slab, &counts, path)?;
    // Sets are small and identical on every rank: rank 0 writes them.
    for (group, sets, position) in
        [("node_sets", &model.node_sets, &partition.node_position), ("element_sets", &model.element_sets, &partition.element_position)]
    {
        let sg = g.create_group(group).map_err(&err)?;
        for (name, members) in sets.iter() {
            let mut pos: Vec<u64> = members.iter().map(|&m| position[m] as u64).collect();
            pos.sort_unstable();
            let slab = if rank == 0 { (0, pos.len()) } else { (0, 0) };
            write_rows(&sg, name, &[pos.len()], slab, if rank == 0 { &pos } else { &[] }, path)?;
        }
    }
    Ok((topology, gauss_points))
}
