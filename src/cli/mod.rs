//! The command line's grammar: subcommands and their flags, with the help text users read.

pub mod check;
pub mod outcome;
pub mod post;
pub mod study;
pub use study::{StudyArgs, SweepArgs};

use clap::{Parser, Subcommand};
use slideline::bellows::spec::DesignSpec;
use slideline::Error;
use std::path::PathBuf;

/// Parallel nonlinear finite-element solver for axisymmetric solids in contact, on PETSc.
///
/// Units throughout: mm, N, MPa, degC. Run in parallel with `mpirun -n 2 slideline run DECK`.
#[derive(Parser)]
#[command(name = "slideline", version, propagate_version = true)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand)]
pub enum Command {
    /// Analyse an axial bellows expansion joint (the seed paper's DN300 case by default).
    ///
    /// Geometry, material and loads default to the paper's values; every one can be changed
    /// by a flag. Step 1 heats to --temperature with --pressure inside, step 2 compresses the
    /// joint by --displacement in --increments increments.
    Bellows(BellowsArgs),
    /// Run the analysis described by a TOML deck and write results to HDF5 (+ XDMF for ParaView).
    ///
    /// PETSc options go after `--`, e.g.
    /// `slideline run cylinder.toml -- -snes_monitor -ksp_type gmres -pc_type gamg -log_view`.
    /// The PETSC_OPTIONS environment variable is honoured too.
    Run(RunArgs),
    /// The design-by-analysis checks of ASME VIII-2 Part 5 that a deck's `[design_by_analysis]`
    /// table names (plastic collapse by the limit-load method, buckling, ratcheting), each by an
    /// analysis of its own, and their verdict table.
    Check(check::CheckArgs),
    /// Read a results file: the run's summary and history, a field at an increment, a node's
    /// or set's time series, two runs side by side, the force-displacement picture. No MPI.
    Post(PostArgs),
    /// Run one model for a range of penalty values (and with the augmented Lagrangian) and
    /// compare iterations, penetration and reaction: the bellows (default) or a deck.
    PenaltyStudy(StudyArgs),
    /// Variants of a bellows design specification (every combination of the values given to
    /// its keys), each through the code check and the analyses asked, the runs shared out to
    /// groups of ranks: one study file and CSV, a table sorted by a figure, a picture of the
    /// trade-off.
    BellowsSweep(SweepArgs),
    /// The bellows codes' chart coefficients Cp, Cf, Cd (EJMA, ASME VIII-1 App. 26) computed
    /// by elastic analyses of the idealised U-shaped convolution at each (C1, C2) given.
    Coefficients {
        /// C1 = 2 rm / w, one or more (comma-separated).
        #[arg(long, value_delimiter = ',', required = true)]
        c1: Vec<f64>,
        /// C2 = 1.82 rm / sqrt(Dm tp), one or more (comma-separated); every C1 with every C2.
        #[arg(long, value_delimiter = ',', required = true)]
        c2: Vec<f64>,
        /// Elements through the ply (4 by default) and per ply thickness along the meridian (4).
        #[arg(long, default_value_t = 4)]
        through: usize,
        #[arg(long, default_value_t = 4.0)]
        per_thickness: f64,
        /// Draw each coefficient against C2, a curve per C1, as the codes' charts do:
        /// PREFIX_cp.png, PREFIX_cf.png, PREFIX_cd.png.
        #[arg(long, value_name = "PREFIX")]
        plot: Option<PathBuf>,
        /// PETSc options (after `--`).
        #[arg(last = true, allow_hyphen_values = true)]
        petsc: Vec<String>,
    },
}

#[derive(clap::Args)]
pub struct PostArgs {
    /// The results file (HDF5) of a run.
    pub file: PathBuf,
    /// Write the history table as CSV to this file (all columns, full precision).
    #[arg(long)]
    pub csv: Option<PathBuf>,
    /// Field to report, at the Gauss points (von_mises, stress, equivalent_plastic_strain, ...)
    /// or the nodes (contact_pressure, temperature, strain_zz, ...): min/max and where; an
    /// unknown name lists the file's fields.
    #[arg(long)]
    pub field: Option<String>,
    /// Increment for --field and --linearize: its number (the run's #N, the file's
    /// /increments/NNNNNN) or `last` (the default).
    #[arg(long)]
    pub increment: Option<String>,
    /// Time series of the node with this external number.
    #[arg(long)]
    pub node: Option<u64>,
    /// Time series of this node set (its reaction if constrained, else its mean displacement).
    #[arg(long)]
    pub set: Option<String>,
    /// Another results file of the same model: the two histories side by side.
    #[arg(long)]
    pub compare: Option<PathBuf>,
    /// With --compare: compare the histories of different models anyway.
    #[arg(long)]
    pub force: bool,
    /// Draw the axial reactions against the prescribed displacement (PNG; default FILE_force.png).
    #[arg(long, value_name = "PNG", num_args = 0..=1)]
    pub plot: Option<Option<PathBuf>>,
    /// Print the deck text stored in the file.
    #[arg(long)]
    pub deck: bool,
    /// Print the bellows code check stored in the file (`slideline bellows` writes it).
    #[arg(long)]
    pub assessment: bool,
    /// Write a bellows run's design report again (self-contained HTML), from the file alone.
    #[arg(long, value_name = "FILE.html")]
    pub report: Option<std::path::PathBuf>,
    /// The history's long lines (every reaction, the contact, the residual norm).
    #[arg(long)]
    pub verbose: bool,
    /// Linearise the stress along straight sections through a wall (ASME VIII-2 Annex 5-A):
    /// membrane and bending parts in the section's axes, at --increment; each section
    /// R1,Z1:R2,Z2 in mm (reference coordinates); repeat for more sections.
    #[arg(long, value_name = "R1,Z1:R2,Z2")]
    pub linearize: Vec<String>,
}

/// Flags of `slideline run`.
#[derive(clap::Args)]
pub struct RunArgs {
    /// The input deck: TOML (docs/deck.md), or an Abaqus/CalculiX deck (.inp; the subset in
    /// docs/inp.md).
    pub deck: PathBuf,
    /// Results file (HDF5). Default: the deck's name with extension .h5, in the current directory.
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// No progress lines.
    #[arg(short, long)]
    pub quiet: bool,
    /// The long progress line: every reaction, the contact, the residual norm.
    #[arg(long, conflicts_with = "quiet")]
    pub verbose: bool,
    /// A line per Newton iteration: the convergence test's largest residual force and
    /// correction against their bounds.
    #[arg(long)]
    pub monitor: bool,
    /// Continue the run that wrote this results file (from its last complete increment, or
    /// --increment), with this deck: the same model, possibly more increments or further steps.
    #[arg(long, value_name = "FILE.h5")]
    pub restart: Option<PathBuf>,
    /// The increment (#N, as the run printed it) to continue from.
    #[arg(long, value_name = "N", requires = "restart")]
    pub increment: Option<usize>,
    /// Newton's convergence test, over the deck's `[stepping] convergence`: `field`
    /// (CalculiX's and Abaqus's) or `residual` (||F|| down by 1e-10, or to round-off).
    #[arg(long, value_enum)]
    pub convergence: Option<ConvergenceArg>,
    /// The visualisation fields as 64-bit (`double`) or 32-bit (`single`) floats, over the
    /// deck's `[output] precision`; the displacement, restart state, history and mesh stay 64-bit.
    #[arg(long, value_enum)]
    pub output_precision: Option<PrecisionArg>,
    /// PETSc options (after `--`).
    #[arg(last = true, allow_hyphen_values = true)]
    pub petsc: Vec<String>,
}

/// Flags of `slideline bellows` (mm, MPa, degC).
#[derive(clap::Args)]
#[command(allow_negative_numbers = true)]
pub struct BellowsArgs {
    /// A joint file: any key of a design specification (docs/bellows-spec.md), each missing one
    /// the seed joint's (e.g. examples/bellows.toml); flags given on the command line override it.
    #[arg(long)]
    pub params: Option<PathBuf>,
    /// A design specification in a data sheet's terms (docs/bellows-spec.md): the bellows, its
    /// material at the design temperature, the design conditions and the code's choices. Prints
    /// the code's verdict, then runs the joint it describes (flags given override it).
    #[arg(long, value_name = "FILE.toml", conflicts_with_all = ["params", "restart"])]
    pub spec: Option<PathBuf>,
    /// With --spec: print the code's verdict and stop (no finite-element analysis).
    #[arg(long, requires = "spec")]
    pub check_only: bool,
    /// With --spec: instead of the stroke's run, the design-by-analysis checks of ASME VIII-2
    /// Part 5 on the joint (docs/design-by-analysis.md): plastic collapse under the design
    /// pressure by the limit-load method (at 1.5 S, the pressure x 1.5, the ends held), and
    /// ratcheting over three cycles of the stroke under the pressure, elastic-perfectly plastic.
    /// With --report, the design report has the specification, the code's verdict and these
    /// checks.
    #[arg(long, requires = "spec", conflicts_with_all = ["check_only", "restart", "joint.cycle"])]
    pub dba: bool,
    /// Instead of the joint's run, hydroform its bellows from a straight tube (the `[forming]`
    /// table, docs/bellows.md "Forming"): pressure between die plates, the dies closed to the
    /// pitch, the pressure let out and the dies drawn out; then the formed bellows under the
    /// design pressure and stroke (OUTPUT_service.h5, continuing the forming's file). Prints
    /// the formed bellows beside its target (height, pitch, crest and root thickness, volume,
    /// plastic strain), what the service did to it and the code's figures with the formed
    /// thickness beside EJMA's tp. With --squirm and --frequencies, their
    /// analyses of the formed bellows at rest and at the service's end beside the idealised
    /// joint's at rest.
    #[arg(long, conflicts_with_all = ["check_only", "dba", "joint.cycle", "assess", "lateral", "angular", "report"])]
    pub form: bool,
    /// After the run, write the design report: one self-contained HTML file (the
    /// specification, the code's verdict, the finite-element tables, the mesh, the pictures).
    #[arg(long, value_name = "FILE.html", conflicts_with = "check_only")]
    pub report: Option<PathBuf>,
    /// Number of plies in the pack (the tori's inside radii stay, as a forming die's: more plies
    /// widen their mid-surface radii, and need a pitch of 4 of those).
    #[arg(long = "plies", id = "bellows.plies", default_value_t = 2, value_name = "PLIES")]
    pub plies: usize,
    /// Thickness of each ply, mm.
    #[arg(allow_hyphen_values = true, long = "ply-thickness", id = "bellows.ply_thickness", default_value_t = 1.0, value_name = "PLY_THICKNESS")]
    pub ply_thickness: f64,
    /// Number of convolutions.
    #[arg(long = "convolutions", id = "bellows.convolutions", default_value_t = 6, value_name = "CONVOLUTIONS")]
    pub convolutions: usize,
    /// Convolution pitch, mm (4 x torus radius for U shapes).
    #[arg(allow_hyphen_values = true, long = "pitch", id = "bellows.pitch", default_value_t = 24.0, value_name = "PITCH")]
    pub pitch: f64,
    /// Convolution height w (mid-surface, root to crest), mm.
    #[arg(allow_hyphen_values = true, long = "height", id = "bellows.convolution_height", default_value_t = 20.0, value_name = "HEIGHT")]
    pub height: f64,
    /// Mean radius of the root and crest tori, mm.
    #[arg(allow_hyphen_values = true, long, default_value_t = 6.0)]
    pub torus_radius: f64,
    /// Axial compression of the joint, mm.
    #[arg(allow_hyphen_values = true, long = "displacement", id = "design.axial_compression", default_value_t = 70.0, value_name = "DISPLACEMENT")]
    pub displacement: f64,
    /// Increments of the compression step.
    #[arg(long = "increments", id = "joint.increments", default_value_t = 240, value_name = "INCREMENTS")]
    pub increments: usize,
    /// Contact penalty, N/mm^3 (MPa per mm of penetration).
    #[arg(allow_hyphen_values = true, long = "penalty", id = "joint.penalty", default_value_t = 1.0e4, value_name = "PENALTY")]
    pub penalty: f64,
    /// Operating temperature, degC (from 20).
    #[arg(allow_hyphen_values = true, long = "temperature", id = "design.temperature", default_value_t = 200.0, value_name = "TEMPERATURE")]
    pub temperature: f64,
    /// Internal pressure, MPa (0.6 = 6 bar).
    #[arg(allow_hyphen_values = true, long = "pressure", id = "design.pressure", default_value_t = 0.6, value_name = "PRESSURE")]
    pub pressure: f64,
    /// Initial yield stress, MPa.
    #[arg(allow_hyphen_values = true, long = "yield-stress", id = "material.yield_stress", default_value_t = 300.0, value_name = "YIELD_STRESS")]
    pub yield_stress: f64,
    /// Linear isotropic hardening modulus, MPa.
    #[arg(allow_hyphen_values = true, long = "hardening", id = "material.hardening_modulus", default_value_t = 1000.0, value_name = "HARDENING")]
    pub hardening: f64,
    /// Mass density of the plies, tubes and sleeve, t/mm^3 (AISI 304: 8.0e-9), for
    /// --frequencies.
    #[arg(allow_hyphen_values = true, long = "density", id = "material.density", default_value_t = 8.0e-9, value_name = "DENSITY")]
    pub density: f64,
    /// Element length along the plies, mm.
    #[arg(allow_hyphen_values = true, long = "ply-element-length", id = "joint.ply_element_length", default_value_t = 1.0, value_name = "PLY_ELEMENT_LENGTH")]
    pub ply_element_length: f64,
    /// Elements through each ply.
    #[arg(long = "ply-elements", id = "joint.ply_elements", default_value_t = 2, value_name = "PLY_ELEMENTS")]
    pub ply_elements: usize,
    /// Coulomb friction coefficient between the plies (and where a ply's folds touch).
    #[arg(allow_hyphen_values = true, long = "friction-plies", id = "joint.friction_plies", default_value_t = 0.0, value_name = "MU")]
    pub friction_plies: f64,
    /// Coulomb friction coefficient between the sleeve and tube B's bore.
    #[arg(allow_hyphen_values = true, long = "friction-sleeve", id = "joint.friction_sleeve", default_value_t = 0.0, value_name = "MU")]
    pub friction_sleeve: f64,
    /// Tangential penalty of the friction, MPa/mm of elastic slip.
    #[arg(allow_hyphen_values = true, long = "tangential-penalty", id = "joint.tangential_penalty", default_value_t = 300.0, value_name = "MPA_PER_MM")]
    pub tangential_penalty: f64,
    /// Instead of --tangential-penalty, the elastic slip at the Coulomb limit (mm): the
    /// stiffness follows the pressure, eps_T = mu p / slip (Abaqus's form).
    #[arg(allow_hyphen_values = true, long = "elastic-slip", id = "joint.elastic_slip", value_name = "MM", conflicts_with = "joint.tangential_penalty")]
    pub elastic_slip: Option<f64>,
    /// The code check's chart coefficients Cp,Cf,Cd read off the code's charts (EJMA, ASME
    /// VIII-1 App. 26); without them slideline computes them from the idealised convolution.
    #[arg(allow_hyphen_values = true, long = "coefficients", id = "bellows.coefficients", value_name = "CP,CF,CD", value_delimiter = ',')]
    pub coefficients: Option<Vec<f64>>,
    #[command(flatten)]
    pub analyses: JointAnalyses,
    /// A load cycle: after the compression, a further step takes tube B's end back to where it
    /// started (the force-displacement picture then shows the loop).
    #[arg(long = "cycle", id = "joint.cycle")]
    pub cycle: bool,
    /// Newton's convergence test: `field` (CalculiX's and Abaqus's: residual forces within
    /// 0.5 % of the time-averaged force, corrections within 2 % of the increment) or
    /// `residual` (the residual norm down by 1e-10, or to round-off).
    #[arg(long = "convergence", id = "joint.convergence", value_enum, default_value_t = ConvergenceArg::Field, value_name = "CONVERGENCE")]
    pub convergence: ConvergenceArg,
    /// Write the fields of every N-th increment (and of the last of each step); the history
    /// keeps every increment.
    #[arg(long = "output-every", id = "joint.output_every", default_value_t = 1, value_name = "N")]
    pub output_every: usize,
    /// The visualisation fields as 32-bit (`single`, 7 significant digits) or 64-bit
    /// (`double`, as computed) floats, or each to its stated resolution; the displacement,
    /// restart state, history and mesh stay 64-bit.
    #[arg(long = "output-precision", id = "joint.output_precision", value_enum, default_value_t = PrecisionArg::Single, value_name = "OUTPUT_PRECISION")]
    pub output_precision: PrecisionArg,
    /// A coarse, quick version of the same case (about 5 s on 2 ranks).
    #[arg(long)]
    pub quick: bool,
    /// Write the mesh (Gmsh .msh next to --output) and stop.
    #[arg(long)]
    pub mesh_only: bool,
    /// Write the model as a CalculiX/Abaqus deck (`slideline run` and `ccx` both run it) and stop.
    #[arg(long, value_name = "FILE.inp")]
    pub export_inp: Option<PathBuf>,
    /// Results file (HDF5).
    #[arg(short, long, default_value = "bellows.h5")]
    pub output: PathBuf,
    /// Continue the run that wrote this results file (its parameters, unless --params or flags
    /// change them: more increments, say) from its last complete increment or --increment.
    #[arg(long, value_name = "FILE.h5")]
    pub restart: Option<PathBuf>,
    /// The increment (#N, as the run printed it) to continue from.
    #[arg(long, value_name = "N", requires = "restart")]
    pub increment: Option<usize>,
    /// No progress lines.
    #[arg(short, long)]
    pub quiet: bool,
    /// The long progress line: every reaction, the contact, the residual norm.
    #[arg(long, conflicts_with = "quiet")]
    pub verbose: bool,
    /// A line per Newton iteration: the convergence test's largest residual force and
    /// correction against their bounds.
    #[arg(long)]
    pub monitor: bool,
    /// PETSc options (after `--`).
    #[arg(last = true, allow_hyphen_values = true)]
    pub petsc: Vec<String>,
}

impl BellowsArgs {
    /// The job these flags ask for, with the joint and movements they give.
    pub fn job(&self, params: DesignSpec, movements: Option<slideline::bellows::flexibility::Movements>) -> slideline::bellows::workflow::BellowsJob {
        slideline::bellows::workflow::BellowsJob {
            params,
            report: self.report.clone(),
            movements,
            output: self.output.clone(),
            quiet: self.quiet,
            verbose: self.verbose,
            monitor: self.monitor,
            restart: self.restart.clone().map(|file| slideline::io::restart::RestartFrom { file, increment: self.increment }),
            squirm: self.analyses.squirm,
            assess: self.analyses.assess,
            frequencies: self.analyses.frequencies,
        }
    }

    /// The movements of the flexibility perturbations (`--lateral`, `--angular`), if any, for
    /// joint `p`.
    pub fn movements(&self, p: &DesignSpec) -> Result<Option<slideline::bellows::flexibility::Movements>, Error> {
        slideline::bellows::flexibility::Movements::checked(self.analyses.lateral, self.analyses.angular, p)
    }

    /// The joint: the `--spec` specification, the `--params` file over the seed's joint, a
    /// restarted file's own joint, or the seed's; then `--quick`; then each key a flag given on
    /// the command line sets (`matches`: a flag's id is its key, `section.key`), and
    /// `--torus-radius` (both tori's mid-surface radius). Checked: a joint with a design
    /// specification's data by the data sheet's rules and the finite-element joint's, any
    /// other by the finite-element joint's.
    pub fn joint(&self, matches: Option<&clap::ArgMatches>) -> Result<DesignSpec, Error> {
        use slideline::bellows::spec::keys;
        let given = |id: &str| matches.and_then(|m| m.value_source(id)) == Some(clap::parser::ValueSource::CommandLine);
        if let Some(c) = self.coefficients.as_ref().filter(|c| c.len() != 3) {
            return Err(Error::input(format!("bellows: --coefficients takes three values, Cp,Cf,Cd; got {}", c.len())));
        }
        if given("torus_radius") && self.spec.is_some() {
            return Err(Error::input(
                "bellows: --torus-radius with --spec: give the crest and root radii in the specification ([bellows] crest_radius, root_radius)",
            ));
        }
        let mut joint = match (&self.spec, &self.params, &self.restart) {
            (Some(path), _, _) => DesignSpec::from_file(path)?,
            (None, Some(path), _) => DesignSpec::joint_file(path)?,
            // a restart continues the file's own joint (with its specification's text)
            (None, None, Some(file)) => restarted_joint(file)?,
            (None, None, None) => DesignSpec::seed(),
        };
        if self.quick {
            joint = joint.quick();
        }
        let settings = matches.map(flag_keys).unwrap_or_default();
        if !settings.is_empty() {
            joint = keys::with_keys(&joint, &settings)?;
        }
        if given("torus_radius") {
            let half = joint.pack_thickness() / 2.0;
            if self.torus_radius <= half {
                return Err(Error::input(format!(
                    "bellows: torus radius {} must exceed half the ply pack ({half}): the inner ply would fold onto itself",
                    self.torus_radius
                )));
            }
            (joint.bellows.root_radius, joint.bellows.crest_radius) = (self.torus_radius - half, self.torus_radius - half);
        }
        match joint.has_design_data() {
            true => joint.validate()?,
            false => joint.validate_joint()?,
        }
        Ok(joint)
    }
}

/// The keys that the flags given on the command line set: each flag whose id is a key
/// (`section.key`), its value as TOML (a choice by its canonical name, a switch `true`, a list
/// an array).
fn flag_keys(matches: &clap::ArgMatches) -> Vec<(String, toml::Value)> {
    use clap::Args;
    let command = BellowsArgs::augment_args(clap::Command::new("bellows"));
    let mut settings = Vec::new();
    for arg in command.get_arguments().filter(|a| a.get_id().as_str().contains('.')) {
        let id = arg.get_id().as_str();
        if matches.value_source(id) != Some(clap::parser::ValueSource::CommandLine) {
            continue;
        }
        let raw: Vec<String> = matches.get_raw(id).map(|v| v.map(|s| s.to_string_lossy().into_owned()).collect()).unwrap_or_default();
        let choice = |text: &str| arg.get_possible_values().into_iter().find(|v| v.matches(text, false)).map(|v| v.get_name().to_string());
        let value = match (arg.get_action(), raw.as_slice()) {
            (clap::ArgAction::SetTrue, _) => toml::Value::Boolean(true),
            (_, [one]) if !arg.get_possible_values().is_empty() => toml::Value::String(choice(one).unwrap_or_else(|| one.clone())),
            (_, [one]) if arg.get_value_delimiter().is_none() => slideline::bellows::spec::keys::value_of(one),
            (_, many) => toml::Value::Array(many.iter().map(|v| slideline::bellows::spec::keys::value_of(v)).collect()),
        };
        settings.push((id.to_string(), value));
    }
    settings
}

/// The joint a results file's run was made for (its deck), with the text of its specification
/// where the run had one (its verdict holds it).
fn restarted_joint(file: &std::path::Path) -> Result<DesignSpec, Error> {
    let reader = slideline::io::reader::ResultsReader::open(file)?;
    let mut joint = DesignSpec::from_deck(&reader.text_attr("deck")?, &format!("{}: its deck (not a bellows run?)", file.display()))?;
    if let Some((_, text, _)) = reader.verdict()? {
        joint.text = text;
    }
    Ok(joint)
}

/// The analyses of the joint beside its run, for `bellows` and each variant of `bellows-sweep`.
#[derive(clap::Args)]
pub struct JointAnalyses {
    /// The design assessment by finite elements beside the code check: linear elastic analyses
    /// of the design pressure alone and of the stroke alone, linearised across the plies, and
    /// the life from the run's own strain range.
    #[arg(long)]
    pub assess: bool,
    /// The lateral spring rate: tube B's end offset sideways by MM, its rotation held, by a
    /// harmonic perturbation (mode 1) of the joint at rest and of the run's end state, beside
    /// the code's beam analogy (the guide sleeve's contact left out).
    #[arg(allow_hyphen_values = true, long, value_name = "MM")]
    pub lateral: Option<f64>,
    /// The angular spring rate: tube B's end rotated by DEG about a diameter through the
    /// bellows' centre, as --lateral.
    #[arg(allow_hyphen_values = true, long, value_name = "DEG")]
    pub angular: Option<f64>,
    /// The instability pressures by buckling analyses of the joint at rest and of the run's end
    /// state, both tubes' ends held: the column instability (squirm, mode 1) beside EJMA's
    /// column formula, and the in-plane instability (mode 0) beside the code's.
    #[arg(long)]
    pub squirm: bool,
    /// The natural frequencies by frequency steps of the joint at rest and of the run's end
    /// state, both tubes' ends held: the first axial (mode 0) and lateral (mode 1) modes beside
    /// the spring and beam analogies of EJMA's formulas (the fluid's mass left out).
    #[arg(long)]
    pub frequencies: bool,
}

/// The `--output-precision` choices.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum PrecisionArg {
    /// The values as computed (64-bit; `full` is the same).
    #[value(alias = "full")]
    Double,
    /// 32-bit floats: each value to 2^-24 of itself (the default).
    Single,
    /// Each field to its stated resolution (docs/results.md).
    Resolution,
}

impl From<PrecisionArg> for crate::model::Precision {
    fn from(p: PrecisionArg) -> Self {
        match p {
            PrecisionArg::Double => crate::model::Precision::Double,
            PrecisionArg::Single => crate::model::Precision::Single,
            PrecisionArg::Resolution => crate::model::Precision::Resolution,
        }
    }
}

/// The `--convergence` choices.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum ConvergenceArg {
    Field,
    Residual,
}

impl From<ConvergenceArg> for crate::model::Convergence {
    fn from(c: ConvergenceArg) -> Self {
        match c {
            ConvergenceArg::Field => crate::model::Convergence::Field,
            ConvergenceArg::Residual => crate::model::Convergence::Residual,
        }
    }
}

/// `bellows --spec FILE --check-only`: the code's verdict on the specification, printed (rank
/// 0); PETSc starts only to compute chart coefficients the file does not give.
pub fn check_only(spec: &DesignSpec, petsc: &[String]) -> std::process::ExitCode {
    use mpi::traits::Communicator;
    let session = match slideline::petsc::PetscSession::initialize(petsc) {
        Ok(s) => s,
        Err(e) => return outcome::fail(&e, outcome::launched_as_rank_zero()),
    };
    let root = session.world().rank() == 0;
    match slideline::bellows::workflow::code_verdict(&session, spec) {
        Ok((_, _, table)) => {
            if root {
                print!("{table}");
            }
            std::process::ExitCode::SUCCESS
        }
        Err(e) => outcome::fail(&e, root),
    }
}
