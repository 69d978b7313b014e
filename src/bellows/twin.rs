//! Where the finite-element joint departs from the joint the code's formulas assume: the
//! plies' material (the formulas take them as formed and thinned by forming), plies that yield
//! under the design pressure alone, and a stroke that the convolutions do not share evenly (the
//! formulas share it evenly). The closing table's last section, made again from the file.

use super::spec::DesignSpec;
use crate::error::Result;
use crate::io::reader::ResultsReader;
use crate::io::HistoryRow;

/// A convolution taking more than this times the mean movement is named: the stroke localises.
pub const UNEVEN_SHARE: f64 = 1.5;

/// The plastic strain above which the joint is said to yield: a point just touching the yield
/// surface is not (the DN400 joint with 15 % cold work reached 2.9e-6 under its pressure).
pub const YIELDED: f64 = 1e-4;

/// The section from the run's history and fields in `reader`.
pub fn section(p: &DesignSpec, reader: &ResultsReader) -> Result<String> {
    let rows = reader.history_rows()?;
    let mut out = format!("the finite-element joint beside the code's:\n  plies: {}\n", p.plies_label());
    let thinned = p.geometry().formed_thickness();
    out += &format!(
        "  the code's formulas take the plies as formed (cold-worked: its in-plane limit on 2.3 Sy, Km {})\n  \
         and thinned by forming (tp {:.4} mm; the finite-element plies {} mm)\n",
        crate::error::shown(p.bellows.forming.meridional_factor()),
        thinned,
        crate::error::shown(p.bellows.ply_thickness)
    );
    if let Some(note) = yield_under_pressure(p, &rows) {
        out += &format!("  note: {note}\n");
    }
    if let Some(shares) = stroke_shares(p, reader, &rows)? {
        out += &shares;
    }
    if p.joint.ply_elements == 1 {
        out += "  note: one element through each ply (the quick mesh) does not see a convolution collapse: on the DN400\n  \
                joint of docs/bellows-spec.md it shared a 25 mm stroke 3 to 13 % a convolution where two elements (the\n  \
                default mesh) saw two take 25 % each; its stresses, strains and life are not for a design\n";
    }
    Ok(out)
}

/// Whether the joint yields under the design pressure alone (the first step's pressure and
/// temperature), and by what pressure: the first increment of that step with plastic strain.
fn yield_under_pressure(p: &DesignSpec, rows: &[(String, HistoryRow)]) -> Option<String> {
    let pressure_step: Vec<&HistoryRow> = rows.iter().map(|(_, r)| r).filter(|r| r.step == 1).collect();
    let k = pressure_step.iter().position(|r| r.max_plastic_strain > YIELDED)?;
    let below = if k == 0 { 0.0 } else { pressure_step[k - 1].load_factor };
    let at = |lambda: f64| crate::error::shown(lambda * p.design.pressure);
    Some(format!(
        "the joint yields under the design pressure alone (more than {} % plastic strain): first between {} and {} MPa\n  \
         (the design pressure {} MPa), {:.3} % at the pressure step's end; the code's formulas assume plies that do not\n  \
         (as formed: give [material] formed_curve or cold_work)",
        100.0 * YIELDED,
        at(below),
        at(pressure_step[k].load_factor),
        crate::error::shown(p.design.pressure),
        100.0 * pressure_step.last()?.max_plastic_strain
    ))
}

/// Each convolution's share of the stroke at the stroke step's end: the axial movement between
/// the roots that bound it (the ply pack's mid-surface at the root bottoms), as a table, with a
/// note where one takes more than [`UNEVEN_SHARE`] times the mean. None without a stroke or
/// without that increment's fields.
fn stroke_shares(p: &DesignSpec, reader: &ResultsReader, rows: &[(String, HistoryRow)]) -> Result<Option<String>> {
    let Some(end) = rows.iter().rev().map(|(_, r)| r).find(|r| r.step == 2) else { return Ok(None) };
    let group = format!("{:06}", end.number);
    if p.displacement() == 0.0 || !reader.has_displacement(&group) {
        return Ok(None);
    }
    let (coordinates, displacement) = (reader.coordinates()?, reader.displacement(&group)?);
    let movements = convolution_movements(p, &coordinates, &displacement);
    let total: f64 = movements.iter().sum();
    let mut out = format!(
        "  the convolutions' axial movement at the stroke's end (#{}): {:.2} mm in all (the stroke with the pipes'\n  \
         growth), each convolution's, mm (share):\n   ",
        end.number, -total
    );
    for (k, m) in movements.iter().enumerate() {
        out += &format!(" {}: {:.3} ({:.0} %)", k + 1, -m, 100.0 * m / total);
    }
    out.push('\n');
    if let Some((k, times)) = localised(&movements) {
        out += &format!(
            "  note: convolution {} takes {times:.2} times the mean movement: the stroke localises there, where the code's formulas share it evenly\n",
            k + 1
        );
    }
    Ok(Some(out))
}

/// The convolution (0-based) that takes the most of the movement, and how many times the mean,
/// where that is more than [`UNEVEN_SHARE`].
pub fn localised(movements: &[f64]) -> Option<(usize, f64)> {
    let mean = movements.iter().sum::<f64>() / movements.len() as f64;
    let (k, m) = movements.iter().enumerate().max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))?;
    (m / mean > UNEVEN_SHARE).then_some((k, m / mean))
}

/// The axial movement of each convolution (mm, compression negative): that of the root
/// bottom after it less that of the root bottom before it, each the mesh node nearest the ply
/// pack's mid-surface there.
pub fn convolution_movements(p: &DesignSpec, coordinates: &[[f64; 2]], displacement: &[[f64; 2]]) -> Vec<f64> {
    let r0 = p.tube_outer_radius() + p.pack_thickness() / 2.0;
    let nearest = |z: f64| {
        (0..coordinates.len()).min_by(|&a, &b| {
            let d = |n: usize| (coordinates[n][0] - r0).hypot(coordinates[n][1] - z);
            d(a).total_cmp(&d(b))
        })
    };
    let roots: Vec<f64> =
        (0..=p.bellows.convolutions).map(|k| nearest(p.tube_length() + k as f64 * p.bellows.pitch).map_or(f64::NAN, |n| displacement[n][1])).collect();
    roots.windows(2).map(|w| w[1] - w[0]).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The seed joint's roots at z = 128 + 24 k on the mid-surface r = 161; a field that moves
    /// every root but the third's neighbours evenly, and compresses the third convolution three
    /// times as much as each other one: its movement is found, and named.
    #[test]
    fn each_convolution_moves_as_its_roots_and_a_localised_one_is_named() {
        let p = DesignSpec::seed();
        let roots: Vec<[f64; 2]> = (0..=6).map(|k| [161.0, 128.0 + 24.0 * k as f64]).collect();
        // nodes off the roots too: the nearest is the root's
        let coordinates: Vec<[f64; 2]> = roots.iter().flat_map(|&[r, z]| [[r, z], [r + 3.0, z + 1.0]]).collect();
        let movement = [-1.0, -1.0, -3.0, -1.0, -1.0, -1.0];
        let mut uz = vec![0.0];
        for m in movement {
            uz.push(uz.last().unwrap() + m);
        }
        let displacement: Vec<[f64; 2]> = uz.iter().flat_map(|&u| [[0.0, u], [0.0, 99.0]]).collect();
        let found = convolution_movements(&p, &coordinates, &displacement);
        assert_eq!(found, movement);
        let (k, times) = localised(&found).unwrap();
        assert_eq!(k, 2);
        assert!((times - 3.0 / (8.0 / 6.0)).abs() < 1e-12, "{times}");
        assert_eq!(localised(&[-1.0, -1.2, -1.1]), None);
    }
}
