//! What the forming made, read from its results file: the formed convolutions' height and
//! pitch beside the target's, the pack's thickness at each crest and root beside EJMA's
//! t sqrt(Db / Dm), each ply's volume before and after (plasticity keeps it), the plastic
//! strain forming left; and the table that prints them.

use super::FormingGeometry;
use crate::bellows::spec::DesignSpec;
use crate::error::{Error, Result};
use crate::fe::quadrature::Integration;
use crate::fe::section::Section;
use crate::io::reader::ResultsReader;

/// The name of the forming's table in the results file (`slideline post` prints it).
pub const TABLE: &str = "forming";

/// The formed bellows' figures (mm, fractions).
#[derive(Clone, Debug, PartialEq)]
pub struct Formed {
    /// Each convolution's height: its crest's mid-surface top above the tangents' mid-surface.
    pub heights: Vec<f64>,
    /// The convoluted length over the convolutions: the mean pitch.
    pub pitch: f64,
    /// Crest to crest, each pair of neighbours.
    pub crest_spacings: Vec<f64>,
    /// The pack's thickness at each crest top and at each root between two convolutions.
    pub crest_thickness: Vec<f64>,
    pub root_thickness: Vec<f64>,
    /// Each ply's thickness at the crest tops (the inside ply first), the mean over the
    /// convolutions.
    pub crest_ply_thickness: Vec<f64>,
    /// Each ply's volume after forming over its volume before, less one.
    pub volume_change: Vec<f64>,
    /// The largest equivalent plastic strain, and its mean through the pack at the crest tops
    /// and at the roots (every ply node within [`STRAIN_WINDOW`] of them along the tube).
    pub max_plastic_strain: f64,
    pub crest_plastic_strain: f64,
    pub root_plastic_strain: f64,
}

/// Half the length of tube (mm, along the straight tube) whose ply nodes give the mean plastic
/// strain at a crest top or a root: a fixed length, so that the mean does not follow the mesh.
/// Measured on two of the seed's convolutions, quick / default / fine mesh (1 x 2, 2 x 1, 4 x
/// 0.5 mm elements): the crest tops' mean 16.4, 15.1, 15.0 %, where the two surface nodes'
/// mean went 4.7, 8.7, 7.3 %.
pub const STRAIN_WINDOW: f64 = 1.0;

/// How far the formed w and q may miss the target's, a fraction, before a tryout forms again.
pub const TOLERANCE: f64 = 0.02;

/// A convolution's height gained per mm of tube: its two sidewalls share the tube (the seed's
/// 53.70 mm formed w 18.78, 56.12 mm 20.04: 0.52).
const HEIGHT_PER_LENGTH: f64 = 0.5;

fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len() as f64
}

impl Formed {
    pub fn height(&self) -> f64 {
        mean(&self.heights)
    }

    /// Crest and root thickness, means over the convolutions.
    pub fn crest(&self) -> f64 {
        mean(&self.crest_thickness)
    }

    pub fn root(&self) -> f64 {
        mean(&self.root_thickness)
    }

    /// The joint to form again where this forming's w or q misses the target's by more than
    /// [`TOLERANCE`]: the developed length longer by the height missed over
    /// [`HEIGHT_PER_LENGTH`], the dies closing shorter by the pitch missed.
    pub fn corrected(&self, p: &DesignSpec) -> Option<DesignSpec> {
        let (w, q) = (p.bellows.convolution_height, p.bellows.pitch);
        if (self.height() / w - 1.0).abs() <= TOLERANCE && (self.pitch / q - 1.0).abs() <= TOLERANCE {
            return None;
        }
        let mut next = p.clone();
        next.forming.developed_length = Some(p.developed_length() + (w - self.height()) / HEIGHT_PER_LENGTH);
        next.forming.overclose = Some((p.overclose() + self.pitch - q).max(0.0));
        next.validate_forming().ok().map(|_| next)
    }

    /// The line a tryout prints: what was formed, what is formed next.
    pub fn tryout_line(&self, p: &DesignSpec, next: &DesignSpec) -> String {
        format!(
            "forming: w {:.3} mm for {}, q {:.3} mm for {}: formed again from {:.2} mm of tube a convolution (was {:.2}), the dies closed {:.2} mm short of the pitch (was {:.2})",
            self.height(),
            p.bellows.convolution_height,
            self.pitch,
            p.bellows.pitch,
            next.developed_length(),
            p.developed_length(),
            next.overclose(),
            p.overclose()
        )
    }

    /// The figures of the file's last increment (the forming's end).
    pub fn read(p: &DesignSpec, reader: &ResultsReader) -> Result<Formed> {
        let g = FormingGeometry::of(p);
        let last = reader.increments()?.pop().ok_or_else(|| Error::input(format!("{}: no increment: nothing was formed", reader.path().display())))?;
        let x0 = reader.coordinates()?;
        let u = reader.displacement(&last)?;
        let x: Vec<[f64; 2]> = x0.iter().zip(&u).map(|(a, b)| [a[0] + b[0], a[1] + b[1]]).collect();
        let n = p.bellows.plies;
        let inside = reader.node_set("ply1_inner")?;
        let outside = reader.node_set(&format!("ply{n}_outer"))?;
        let [z0, _] = g.convoluted();
        // the nodes of a surface first within [a, b) of the straight tube
        let within = |nodes: &[usize], a: f64, b: f64| -> Vec<usize> { nodes.iter().copied().filter(|&k| x0[k][1] >= a && x0[k][1] < b).collect() };
        let extreme = |nodes: &[usize], top: bool| -> usize {
            let key = |k: &usize| if top { x[*k][0] } else { -x[*k][0] };
            *nodes.iter().max_by(|a, b| key(a).total_cmp(&key(b))).expect("a surface's nodes in a convolution")
        };
        // the nodal field (the Gauss points' carried to the nodes) for the means, the Gauss
        // points' own for the largest
        let ep = reader.field(&last, "nodal/equivalent_plastic_strain").ok();
        let mut plies = Vec::new();
        for k in 1..=n {
            plies.extend(reader.node_set(&format!("ply{k}"))?);
        }
        // the mean plastic strain through the pack about the node `at`
        let pack_mean = |ep: &[f64], at: usize| -> f64 {
            let near: Vec<f64> = plies.iter().filter(|&&k| (x0[k][1] - x0[at][1]).abs() <= STRAIN_WINDOW).map(|&k| ep[k]).collect();
            mean(&near)
        };
        let r_mid = g.bore + g.pack / 2.0;
        let (mut heights, mut crest_z, mut crest_thickness, mut root_thickness, mut crest_ep, mut root_ep) = (vec![], vec![], vec![], vec![], vec![], vec![]);
        for k in 0..g.convolutions {
            let (a, b) = (z0 + k as f64 * g.developed, z0 + (k + 1) as f64 * g.developed);
            let (i, o) = (extreme(&within(&inside, a, b), true), extreme(&within(&outside, a, b), true));
            heights.push((x[i][0] + x[o][0]) / 2.0 - r_mid);
            crest_thickness.push(x[o][0] - x[i][0]);
            crest_z.push(x[o][1]);
            if let Some(ep) = &ep {
                crest_ep.push(pack_mean(ep, i));
            }
            if k > 0 {
                let half = g.developed / 2.0;
                let (i, o) = (extreme(&within(&inside, a - half, a + half), false), extreme(&within(&outside, a - half, a + half), false));
                root_thickness.push(x[o][0] - x[i][0]);
                if let Some(ep) = &ep {
                    root_ep.push(pack_mean(ep, i));
                }
            }
        }
        // each ply's own, between its faces' tops in each convolution
        let mut crest_ply_thickness = Vec::new();
        for k in 1..=n {
            let (i_nodes, o_nodes) = (reader.node_set(&format!("ply{k}_inner"))?, reader.node_set(&format!("ply{k}_outer"))?);
            let per: Vec<f64> = (0..g.convolutions)
                .map(|c| {
                    let (a, b) = (z0 + c as f64 * g.developed, z0 + (c + 1) as f64 * g.developed);
                    x[extreme(&within(&o_nodes, a, b), true)][0] - x[extreme(&within(&i_nodes, a, b), true)][0]
                })
                .collect();
            crest_ply_thickness.push(mean(&per));
        }
        // the convoluted length: from the first tangent's end to the second's start
        let tangent_b = reader.node_set("tangent_b")?;
        let start_b = tangent_b.iter().map(|&k| x[k][1]).fold(f64::INFINITY, f64::min);
        let pitch = (start_b - z0) / g.convolutions as f64;
        let volume_change = (1..=n).map(|k| ply_volume_change(reader, &x0, &x, &format!("ply{k}"))).collect::<Result<Vec<f64>>>()?;
        let mut max_ep = f64::NAN;
        if let Ok(gauss) = reader.field(&last, "equivalent_plastic_strain") {
            let points = gauss.len() / reader.connectivity()?.len().max(1);
            max_ep = 0.0;
            for k in 1..=n {
                for e in reader.element_set(&format!("ply{k}"))? {
                    max_ep = gauss[e * points..(e + 1) * points].iter().copied().fold(max_ep, f64::max);
                }
            }
        }
        Ok(Formed {
            heights,
            pitch,
            crest_spacings: crest_z.windows(2).map(|w| w[1] - w[0]).collect(),
            crest_thickness,
            root_thickness,
            crest_ply_thickness,
            volume_change,
            max_plastic_strain: max_ep,
            crest_plastic_strain: if crest_ep.is_empty() { f64::NAN } else { mean(&crest_ep) },
            root_plastic_strain: if root_ep.is_empty() { f64::NAN } else { mean(&root_ep) },
        })
    }
}

/// The volume of element set `set` at `x` over its volume at `x0`, less one (axisymmetric:
/// 2 pi r dA, the Gauss rule of the elements).
fn ply_volume_change(reader: &ResultsReader, x0: &[[f64; 2]], x: &[[f64; 2]], set: &str) -> Result<f64> {
    let connectivity = reader.connectivity()?;
    let volume = |at: &[[f64; 2]]| -> Result<f64> {
        let mut v = 0.0;
        for e in reader.element_set(set)? {
            let c = connectivity[e].map(|k| at[k]);
            let geo = crate::element::solid::ElementGeometry::new(crate::fe::shape::Shape::Quad8, Integration::Full, Section::Axisymmetric, &c)
                .map_err(|why| Error::input(format!("{set}: element {}: {why}", e + 1)))?;
            v += geo.volume();
        }
        Ok(v)
    };
    Ok(volume(x)? / volume(x0)? - 1.0)
}

/// The forming's table: the formed bellows beside its target.
pub fn table(p: &DesignSpec, f: &Formed) -> String {
    let g = FormingGeometry::of(p);
    let range = |v: &[f64]| {
        let (lo, hi) = v.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &x| (lo.min(x), hi.max(x)));
        format!("{lo:.3} to {hi:.3}")
    };
    let tp = p.geometry().ejma_formed_thickness() * p.bellows.plies as f64;
    let pct = |x: f64| 100.0 * x;
    let signed = |x: f64| format!("{:+.2} %", 100.0 * x);
    let mut out = format!(
        "the bellows as formed (hydroformed at {:.3} MPa from {:.2} mm of tube a convolution, the dies closed to a pitch of {:.2} mm, then\n  \
         the pressure let out and the dies drawn out):                       target     formed\n",
        p.forming_pressure().unwrap_or(f64::NAN),
        g.developed,
        g.closed_pitch
    );
    let row = |label: &str, target: String, formed: String| format!("  {label:<62} {target:>9}  {formed}\n");
    let w = f.height();
    out += &row(
        "convolution height w (mid-surface), mm",
        format!("{:.3}", p.bellows.convolution_height),
        format!("{w:.3} ({}: {})", signed(w / p.bellows.convolution_height - 1.0), range(&f.heights)),
    );
    out += &row(
        "pitch q (the convoluted length over N), mm",
        format!("{:.3}", p.bellows.pitch),
        format!("{:.3} ({})", f.pitch, signed(f.pitch / p.bellows.pitch - 1.0)),
    );
    out += &row("  crest to crest, mm", String::new(), range(&f.crest_spacings));
    out += &row("pack thickness at the crests, mm (EJMA's n tp)", format!("{tp:.4}"), format!("{:.4} ({})", f.crest(), range(&f.crest_thickness)));
    out += &row("pack thickness at the roots, mm (nominal n t)", format!("{:.4}", g.pack), format!("{:.4} ({})", f.root(), range(&f.root_thickness)));
    let plies: Vec<String> = f.crest_ply_thickness.iter().map(|t| format!("{t:.4}")).collect();
    out += &row("each ply at the crests, inside first, mm (EJMA's tp)", format!("{:.4}", tp / p.bellows.plies as f64), plies.join(", "));
    let volumes: Vec<String> = f.volume_change.iter().map(|v| format!("{:+.3}", pct(*v))).collect();
    out += &row("each ply's volume change, %", "0".into(), volumes.join(", "));
    out += &row(
        "plastic strain, %: largest; through the pack at crests, roots",
        String::new(),
        format!("{:.2}; {:.2}, {:.2}", pct(f.max_plastic_strain), pct(f.crest_plastic_strain), pct(f.root_plastic_strain)),
    );
    out
}
