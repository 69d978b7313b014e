//! The linearised stresses across each ply at the stations along every piece of every
//! convolution (crest, root, both sidewalls): what the finite-element assessment and the
//! flexibility's stresses read of a run.

use crate::bellows::joint::ConvolutionPiece;
use crate::bellows::spec::DesignSpec;
use crate::error::{Error, Result};
use crate::fe::linearize::{linearize, Linearized, StressSampler};
use crate::io::reader::ResultsReader;

/// Stations per piece of the meridian (odd: the middle one is the apex or the mid-sidewall).
pub(super) const STATIONS: usize = 9;
/// The linearised meridional and hoop stresses at one station of one ply.
#[derive(Clone, Copy, Debug)]
pub(super) struct Station {
    pub membrane: f64,
    pub bending: f64,
    pub hoop: f64,
}

impl From<&Linearized> for Station {
    fn from(l: &Linearized) -> Self {
        Station { membrane: l.membrane[1], bending: l.bending[1], hoop: l.membrane[2] }
    }
}

/// The linearised stresses of one piece: [station][k], each with the ply it was found in.
pub(super) type PieceStations = Vec<Vec<(usize, Station)>>;

/// The linearised stresses of `stress` (the Gauss points' [rr, zz, tt, rz] of every element of
/// the file `r`, in its order) at every station of every piece, ply by ply (indexed [piece][station][k], with the ply's number from 0), the membrane as linearised (`finite_element` replaces it by the ply's force over its area).
pub(super) fn stations_of(r: &ResultsReader, stress: &[[[f64; 4]; 9]], p: &DesignSpec, pieces: &[ConvolutionPiece]) -> Result<Vec<PieceStations>> {
    let file = r.path();
    let (coords, conn) = (r.coordinates()?, r.connectivity()?);
    // a sampler per ply: a section ends on the ply's surfaces, where the next ply begins
    let sets: Vec<Vec<usize>> = (1..=p.bellows.plies).map(|k| r.element_set(&format!("ply{k}"))).collect::<Result<_>>()?;
    let ply_conn: Vec<Vec<[usize; 8]>> = sets.iter().map(|set| set.iter().map(|&e| conn[e]).collect()).collect();
    let samplers: Vec<StressSampler> = sets
        .iter()
        .zip(&ply_conn)
        .map(|(set, c)| StressSampler::new(&coords, c, &set.iter().map(|&e| stress[e]).collect::<Vec<_>>()).with_slack(1e-2))
        .collect();
    let (t, pack) = (p.bellows.ply_thickness, p.pack_thickness());
    pieces
        .iter()
        .map(|piece| {
            (0..STATIONS)
                .map(|j| {
                    let (x, tan) = piece.piece.at((j as f64 + 0.5) / STATIONS as f64);
                    let normal = [-tan[1], tan[0]];
                    (0..p.bellows.plies)
                        .map(|k| {
                            // the k-th ply from the pack's side at -pack / 2 along the normal
                            let (lo, hi) = (-pack / 2.0 + k as f64 * t, -pack / 2.0 + (k + 1) as f64 * t);
                            let at = |d: f64| [x[0] + d * normal[0], x[1] + d * normal[1]];
                            let ply = (0..p.bellows.plies).find(|&j| samplers[j].at(at(0.5 * (lo + hi))).is_some());
                            let ply = ply.ok_or_else(|| Error::Output {
                                path: file.to_path_buf(),
                                message: format!("{}: no ply at {:?}", piece.label, at(0.5 * (lo + hi))),
                            })?;
                            linearize(at(lo), at(hi), 40, |q, d| samplers[ply].entering(q, d))
                                .map(|l| Station::from(&l))
                                .map(|s| (ply, s))
                                .map_err(|m| Error::Output { path: file.to_path_buf(), message: format!("{}, ply {}: {m}", piece.label, ply + 1) })
                        })
                        .collect()
                })
                .collect()
        })
        .collect()
}
