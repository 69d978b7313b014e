//! The joint as the finite elements see it: the pipes' and sleeve's dimensions (the `[joint]`
//! keys, or the seed's scaled with the bellows' inside diameter), the tori's mid-surface radii,
//! the material at the design temperature, the stroke; the quick mesh, the seed's test, the
//! title and the deck text a results file keeps; and the finite-element joint's own rules.

use super::DesignSpec;
use crate::error::{Error, Result};

/// The seed joint's bellows inside diameter, mm: the unset pipe and sleeve lengths scale with it.
const SEED_INSIDE_DIAMETER: f64 = 320.0;
/// The seed joint's pipe wall and sleeve thickness, pipe length and sleeve overlap, mm.
const SEED_WALL: f64 = 10.0;
const SEED_TUBE_LENGTH: f64 = 128.0;
const SEED_SLEEVE_OVERLAP: f64 = 40.0;
/// The joint's mass density where the material gives none (the seed's AISI 304), t/mm^3.
const SEED_DENSITY: f64 = 8.0e-9;

impl DesignSpec {
    fn scale(&self) -> f64 {
        self.bellows.inside_diameter / SEED_INSIDE_DIAMETER
    }

    pub fn tube_thickness(&self) -> f64 {
        self.joint.tube_thickness.unwrap_or(SEED_WALL * self.scale())
    }

    /// Radius of the tubes' outside surface, where the ply pack's inside sits on the tangents.
    pub fn tube_outer_radius(&self) -> f64 {
        self.bellows.inside_diameter / 2.0
    }

    pub fn tube_inner_radius(&self) -> f64 {
        self.tube_outer_radius() - self.tube_thickness()
    }

    /// Axial length of tube A (tube B is as long, at the other end): room for the tangent and
    /// the sleeve's overlap.
    pub fn tube_length(&self) -> f64 {
        let scale = self.scale();
        self.joint.tube_length.unwrap_or((SEED_TUBE_LENGTH * scale).max(self.bellows.tangent_length + SEED_SLEEVE_OVERLAP * scale))
    }

    /// The whole joint's length: both tubes and the convolutions between them.
    pub fn length(&self) -> f64 {
        2.0 * self.tube_length() + self.bellows.convolutions as f64 * self.bellows.pitch
    }

    pub fn sleeve_thickness(&self) -> f64 {
        self.joint.sleeve_thickness.unwrap_or(SEED_WALL * self.scale())
    }

    pub fn sleeve_overlap(&self) -> f64 {
        self.joint.sleeve_overlap.unwrap_or(SEED_SLEEVE_OVERLAP * self.scale())
    }

    /// Mid-surface radius of the root tori.
    pub fn torus_radius(&self) -> f64 {
        self.mid_surface_radii().1
    }

    /// Mid-surface radius of the crest tori.
    pub fn crest(&self) -> f64 {
        self.mid_surface_radii().0
    }

    /// The radial distance between the root's and the crest's torus centres: a radial
    /// sidewall's length.
    pub fn sidewall(&self) -> f64 {
        self.bellows.convolution_height - self.torus_radius() - self.crest()
    }

    /// The length of a sidewall, radial or tapered: the common tangent of the root and crest
    /// tori, whose centres lie q / 2 apart axially.
    pub fn sidewall_length(&self) -> f64 {
        let d2 = (self.bellows.pitch / 2.0).powi(2) + self.sidewall().powi(2);
        (d2 - (self.torus_radius() + self.crest()).powi(2)).max(0.0).sqrt()
    }

    /// The material's properties at the design temperature (NaN where a table does not reach
    /// it: the data sheet's rules refuse that first).
    pub fn youngs_modulus(&self) -> f64 {
        self.material.youngs_modulus.at(self.design.temperature, "youngs_modulus").unwrap_or(f64::NAN)
    }

    pub fn yield_stress(&self) -> f64 {
        self.material.yield_stress.at(self.design.temperature, "yield_stress").unwrap_or(f64::NAN)
    }

    pub fn thermal_expansion(&self) -> f64 {
        self.material.thermal_expansion.at(self.design.temperature, "thermal_expansion").unwrap_or(f64::NAN)
    }

    /// The plies' hardening as the finite elements take it: as formed (the `formed_curve`, or the
    /// annealed curve from the `cold_work` on), None where the plies are annealed (the tubes'
    /// curve).
    pub fn formed_plies(&self) -> Result<Option<crate::model::Plasticity>> {
        let m = &self.material;
        let bad = |key: &str, why: String| Error::input(format!("bellows: material.{key}: {why}"));
        match (&m.formed_curve, m.cold_work) {
            (None, None) => Ok(None),
            (Some(_), Some(_)) => Err(bad("cold_work", "give one of formed_curve and cold_work".into())),
            (Some(curve), None) => {
                let points: Vec<(f64, f64)> = curve.iter().map(|&[ep, s]| (ep, s)).collect();
                crate::model::Plasticity::table(&points).map(Some).map_err(|why| bad("formed_curve", why))
            }
            (None, Some(ep)) => {
                if !(ep > 0.0 && ep.is_finite()) {
                    return Err(bad("cold_work", format!("a plastic strain > 0, got {}", crate::error::shown(ep))));
                }
                if m.hardening_modulus <= 0.0 {
                    return Err(bad(
                        "cold_work",
                        "the annealed curve has no hardening (hardening_modulus 0): cold work raises nothing; give the plies' formed_curve".into(),
                    ));
                }
                Ok(Some(crate::model::Plasticity::linear(self.yield_stress() + m.hardening_modulus * ep, m.hardening_modulus)))
            }
        }
    }

    /// What the finite-element plies are made of, for a table: annealed or as formed.
    pub fn plies_label(&self) -> String {
        let m = &self.material;
        match (&m.formed_curve, m.cold_work) {
            (Some(c), _) => format!("as formed: the given curve, yield {} MPa", crate::error::shown(c.first().map_or(f64::NAN, |p| p[1]))),
            (None, Some(ep)) => format!(
                "as formed: the annealed curve from {} % cold work on, yield {} MPa",
                crate::error::shown(100.0 * ep),
                crate::error::shown(self.yield_stress() + m.hardening_modulus * ep)
            ),
            (None, None) => format!(
                "annealed: yield {} MPa, hardening {} MPa, nominal thickness",
                crate::error::shown(self.yield_stress()),
                crate::error::shown(m.hardening_modulus)
            ),
        }
    }

    pub fn density(&self) -> f64 {
        self.material.density.unwrap_or(SEED_DENSITY)
    }

    /// The axial compression of tube B's end, mm (negative: an extension).
    pub fn displacement(&self) -> f64 {
        self.design.axial_compression.unwrap_or(0.0) - self.design.axial_extension.unwrap_or(0.0)
    }

    /// The coarse version of the same joint (`--quick`): one element through each ply, 2 mm
    /// along the meridian, 8 mm along the walls, at most 40 requested increments.
    pub fn quick(mut self) -> Self {
        let j = &mut self.joint;
        (j.ply_elements, j.ply_element_length, j.wall_element_length, j.wall_elements) = (1, 2.0, 8.0, 2);
        j.increments = j.increments.min(40);
        self
    }

    /// Whether this is the seed paper's joint: its geometry and material, whatever the loads,
    /// mesh, stepping, contact, friction and output (a shorter stroke, a penalty study or a
    /// quick mesh of the seed is still the seed, and its table keeps the paper's column, each
    /// row saying where it is read).
    pub fn is_seed_joint(&self) -> bool {
        let dimensions = |s: &DesignSpec| {
            [
                s.tube_inner_radius(),
                s.tube_thickness(),
                s.tube_length(),
                s.sleeve_thickness(),
                s.sleeve_overlap(),
                s.youngs_modulus(),
                s.material.poissons_ratio,
                s.thermal_expansion(),
                s.yield_stress(),
                s.material.hardening_modulus,
            ]
        };
        let seed = DesignSpec::seed();
        let bellows = |s: &DesignSpec| super::BellowsSpec { coefficients: None, formed_ply_thickness: None, ..s.bellows.clone() };
        bellows(self) == bellows(&seed) && dimensions(self) == dimensions(&seed)
    }

    /// One line naming the joint (an exported deck's heading).
    pub fn fe_title(&self) -> String {
        let b = &self.bellows;
        format!(
            "slideline bellows: {} plies x {} mm, {} convolutions, pitch {}, height {}; {} MPa at {} degC, {} mm compression in {} increments, penalty {} N/mm^3",
            b.plies,
            b.ply_thickness,
            b.convolutions,
            b.pitch,
            b.convolution_height,
            self.design.pressure,
            self.design.temperature,
            self.displacement(),
            self.joint.increments,
            self.joint.penalty
        )
    }

    /// The joint as a TOML file (`slideline bellows --params FILE` runs the same model again),
    /// headed by a comment saying so: the deck text a results file keeps.
    pub fn to_toml(&self) -> String {
        let body = toml::to_string(self).unwrap_or_else(|e| format!("# (the joint is not writable as TOML: {e})\n"));
        format!("# {}\n# slideline bellows --params THIS_FILE runs this model again\n{body}", self.fe_title())
    }

    /// The joint a results file's deck text describes; `origin` names it in an error.
    pub fn from_deck(text: &str, origin: &str) -> Result<Self> {
        toml::from_str(text).map_err(|e| Error::input(format!("{origin}: {}", e.message())))
    }

    /// The finite-element joint's own rules: a joint that can be built, each offending value
    /// named as the flags name it.
    pub fn validate_joint(&self) -> Result<()> {
        let (b, j) = (&self.bellows, &self.joint);
        let positive = [
            ("tube inner radius", self.tube_inner_radius()),
            ("tube thickness", self.tube_thickness()),
            ("length", self.length()),
            ("tube length", self.tube_length()),
            ("pitch", b.pitch),
            ("convolution height", b.convolution_height),
            ("torus radius", self.torus_radius()),
            ("crest radius", self.crest()),
            ("ply thickness", b.ply_thickness),
            ("tangent length", b.tangent_length),
            ("sleeve thickness", self.sleeve_thickness()),
            ("ply element length", j.ply_element_length),
            ("wall element length", j.wall_element_length),
            ("penalty", j.penalty),
            ("tangential penalty", j.tangential_penalty),
            ("Young's modulus", self.youngs_modulus()),
            ("yield stress", self.yield_stress()),
            ("density", self.density()),
        ];
        let coefficients = b.coefficients.into_iter().flat_map(|c| [("coefficient Cp", c[0]), ("coefficient Cf", c[1]), ("coefficient Cd", c[2])]);
        let positive = positive.into_iter().chain(j.elastic_slip.map(|g| ("elastic slip", g))).chain(coefficients);
        for (name, v) in positive {
            if !(v > 0.0 && v.is_finite()) {
                return Err(Error::input(format!("bellows: {name} must be > 0, got {}", crate::error::shown(v))));
            }
        }
        if let Some(rule) = b.coefficients.and_then(|c| super::off_the_charts(&c)) {
            return Err(Error::input(format!("bellows: {rule}")));
        }
        for (name, v) in [
            ("temperature", self.design.temperature),
            ("pressure", self.design.pressure),
            ("thermal expansion", self.thermal_expansion()),
            ("hardening modulus", self.material.hardening_modulus),
            ("sleeve overlap", self.sleeve_overlap()),
            ("sleeve crown", j.sleeve_crown),
        ] {
            if !v.is_finite() {
                return Err(Error::input(format!("bellows: {name} must be a finite number, got {v}")));
            }
        }
        for (name, mu) in [("friction between the plies", j.friction_plies), ("friction of the sleeve", j.friction_sleeve)] {
            if !(mu >= 0.0 && mu.is_finite()) {
                return Err(Error::input(format!("bellows: {name} must be a coefficient >= 0, got {mu}")));
            }
        }
        for (name, n) in [
            ("plies", b.plies),
            ("convolutions", b.convolutions),
            ("increments", j.increments),
            ("heat increments", j.heat_increments),
            ("ply elements", j.ply_elements),
            ("wall elements", j.wall_elements),
            ("output every", j.output_every),
        ] {
            if n == 0 {
                return Err(Error::input(format!("bellows: {name} must be at least 1")));
            }
        }
        self.validate_convolution()?;
        self.formed_plies()?;
        self.validate_walls()
    }

    /// The pipes, the sleeve, the material's Poisson's ratio, the stroke, friction and the
    /// mesh's size.
    fn validate_walls(&self) -> Result<()> {
        let j = &self.joint;
        let convoluted = self.bellows.convolutions as f64 * self.bellows.pitch;
        if j.sleeve_crown < 0.0 || j.sleeve_crown >= self.sleeve_thickness() / 2.0 {
            return Err(Error::input(format!(
                "bellows: sleeve crown must be >= 0 and below half the sleeve thickness ({} mm), got {}",
                self.sleeve_thickness() / 2.0,
                j.sleeve_crown
            )));
        }
        if !(j.sleeve_crown_length > 0.0 && j.sleeve_crown_length <= self.sleeve_overlap()) {
            return Err(Error::input(format!(
                "bellows: sleeve crown length must be > 0 and within the sleeve's overlap with tube B ({} mm), got {}",
                self.sleeve_overlap(),
                j.sleeve_crown_length
            )));
        }
        if self.bellows.tangent_length > self.tube_length() || self.sleeve_overlap() > self.tube_length() {
            return Err(Error::input("bellows: the tangents and the sleeve overlap must fit on the tubes"));
        }
        if self.sleeve_thickness() >= self.tube_inner_radius() {
            return Err(Error::input("bellows: the sleeve is thicker than the tube bore"));
        }
        if !(self.material.poissons_ratio > -1.0 && self.material.poissons_ratio < 0.5) {
            return Err(Error::input(format!("bellows: Poisson's ratio must lie in (-1, 0.5), got {}", self.material.poissons_ratio)));
        }
        let displacement = self.displacement();
        if displacement.is_nan() || displacement.abs() >= convoluted {
            return Err(Error::input(format!("bellows: a displacement of {displacement} mm exceeds the convoluted length {convoluted} mm")));
        }
        if j.elastic_slip.is_some() && j.friction_plies == 0.0 && j.friction_sleeve == 0.0 {
            return Err(Error::input(
                "bellows: --elastic-slip sets friction's stick stiffness, and no pair has friction (give --friction-plies or --friction-sleeve)",
            ));
        }
        // counted before anything is allocated: an absurd mesh is refused, not a memory failure
        let elements = self.element_estimate();
        if elements > crate::model::mesh::MAX_GENERATED_ELEMENTS as f64 {
            return Err(Error::input(format!(
                "bellows: the mesh would have about {elements:.3e} elements, more than {} (coarsen --ply-elements, --ply-element-length, --wall-elements or --wall-element-length)",
                crate::model::mesh::MAX_GENERATED_ELEMENTS
            )));
        }
        Ok(())
    }

    /// The U-shaped convolution's own checks: tori that hold the ply pack, sidewalls that do not
    /// fold back, a height that holds both tori; named as one torus radius where the root's and
    /// crest's are one.
    fn validate_convolution(&self) -> Result<()> {
        let (rr, rc) = (self.torus_radius(), self.crest());
        let one_radius = self.bellows.root_radius == self.bellows.crest_radius;
        let pack = self.pack_thickness();
        for (name, r) in [("torus radius", rr), ("crest radius", rc)] {
            if r <= pack / 2.0 {
                return Err(Error::input(format!("bellows: {name} {r} must exceed half the ply pack ({}): the inner ply would fold onto itself", pack / 2.0)));
            }
        }
        // radial sidewalls at q = 2 (rr + rc), tapered ones wider; narrower would fold them back
        if self.bellows.pitch < 2.0 * (rr + rc) - 1e-9 {
            let radii = if one_radius { "4 x the torus radius" } else { "2 (root radius + crest radius)" };
            return Err(Error::input(format!(
                "bellows: a pitch of {} is less than {radii} = {}: U-shaped convolutions' sidewalls would fold back over each other (a torus's mid-surface radius is its inside radius plus half the ply pack: {} + {} mm at the root)",
                crate::error::shown(self.bellows.pitch),
                crate::error::shown(2.0 * (rr + rc)),
                crate::error::shown(self.bellows.root_radius),
                crate::error::shown(pack / 2.0)
            )));
        }
        if self.sidewall() < 0.0 {
            let torus = if one_radius { "two torus radii" } else { "the root and crest radii" };
            return Err(Error::input(format!("bellows: convolution height {} is less than {torus} ({})", self.bellows.convolution_height, rr + rc)));
        }
        Ok(())
    }

    /// About how many elements the joint's mesh has: the plies along their developed meridian
    /// (tangents, tori and sidewalls) and the three walls (tubes and sleeve) along the joint.
    fn element_estimate(&self) -> f64 {
        let (b, j) = (&self.bellows, &self.joint);
        let tori = std::f64::consts::PI * (self.torus_radius() + self.crest());
        let meridian = 2.0 * b.tangent_length + b.convolutions as f64 * (tori + 2.0 * self.sidewall_length());
        let plies = (b.plies * j.ply_elements) as f64 * (meridian / j.ply_element_length).ceil();
        let walls = 3.0 * j.wall_elements as f64 * (self.length() / j.wall_element_length).ceil();
        plies + walls
    }
}
