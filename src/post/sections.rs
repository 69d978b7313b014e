//! `slideline post --linearize`: the stress linearised across sections of a results file's
//! mesh (ASME VIII-2 5.A), each section's membrane and bending stresses.

use super::increment_name;
use crate::error::{Error, Result};
use crate::io::reader::ResultsReader;

/// A section `R1,Z1:R2,Z2` (mm; X1,Y1:X2,Y2 in a plane model) as its two ends; bad input
/// naming it otherwise.
pub fn parse_section(text: &str) -> Result<([f64; 2], [f64; 2])> {
    let bad = || Error::input(format!("--linearize {text:?}: give a section as R1,Z1:R2,Z2 (mm; X1,Y1:X2,Y2 in a plane model), e.g. 100,5:130,5"));
    let (a, b) = text.split_once(':').ok_or_else(bad)?;
    let point = |s: &str| -> Result<[f64; 2]> {
        let (r, z) = s.split_once(',').ok_or_else(bad)?;
        let v = [r.trim().parse::<f64>().map_err(|_| bad())?, z.trim().parse::<f64>().map_err(|_| bad())?];
        v.iter().all(|x| x.is_finite()).then_some(v).ok_or_else(bad)
    };
    Ok((point(a)?, point(b)?))
}

/// The linearised stresses of each section at increment `number` (reference coordinates).
pub fn linearize(r: &ResultsReader, sections: &[String], number: usize) -> Result<String> {
    use crate::fe::linearize::{linearize, StressSampler};
    use crate::fe::recover::Rule;
    let sections: Vec<([f64; 2], [f64; 2])> = sections.iter().map(|s| parse_section(s)).collect::<Result<_>>()?;
    let name = increment_name(r, number)?;
    let (coords, elements) = (r.coordinates()?, r.connectivity()?);
    let flat = r
        .field(&name, "stress")
        .map_err(|_| Error::input(format!("{}: increment {number} holds no stress (the run's [output] fields)", r.path().display())))?;
    let stress: Vec<[[f64; 4]; 9]> = flat.chunks_exact(36).map(|e| std::array::from_fn(|q| std::array::from_fn(|c| e[4 * q + c]))).collect();
    // the nodal output's rule in each element: its nearest Gauss point's value where it has
    // yielded (a file without the plastic strain is taken as elastic, and says so below)
    let plastic = r.field(&name, "equivalent_plastic_strain").ok();
    let rules: Vec<Rule> = match &plastic {
        Some(ep) => ep.chunks_exact(9).map(|e| Rule::for_element(&std::array::from_fn(|q| e[q]))).collect(),
        None => vec![Rule::Extrapolate; elements.len()],
    };
    let sampler = StressSampler::integrated(&coords, &elements, &r.integration()?, &rules, &stress);
    // a plane model's third component is the out-of-plane stress, its coordinates x, y
    let (third, across) = if r.is_plane() { ("out-of-plane", "in-plane across it") } else { ("hoop", "meridional across it") };
    let mut out = format!("stress linearisation at increment #{number} (MPa; section axes: normal along the section, {across}, {third}, shear)\n");
    let yielded = rules.iter().filter(|&&r| r == Rule::Copy).count();
    out += &match plastic {
        Some(_) if yielded > 0 => format!("  the stress along a section: fitted through the Gauss points in elastic elements, held within them in the {yielded} yielded ones (never extrapolated past a yielded point)\n"),
        Some(_) => String::new(),
        None => "  note: the file holds no plastic strain at this increment: the stress is extrapolated from the Gauss points in every element, also where it may have yielded\n".to_string(),
    };
    for (a, b) in sections {
        let l = linearize(a, b, 200, |p, d| sampler.entering(p, d))
            .map_err(|m| Error::input(format!("{}: section ({}, {}):({}, {}): {m}", r.path().display(), a[0], a[1], b[0], b[1])))?;
        out.push_str(&format!("section ({}, {}) -> ({}, {}), t = {:.4} mm\n", a[0], a[1], b[0], b[1], l.thickness));
        let walls = sampler.walls_crossed(a, b);
        if walls > 1 {
            out.push_str(&format!(
                "  note: the section crosses {walls} walls (the plies of a pack, say, meshed apart), linearised here as one; each has a membrane and bending stress of its own: linearise across each\n"
            ));
        }
        out.push_str(&format!("  {:<26} {:>12} {:>12} {:>12} {:>12}\n", "", "normal", across.split(' ').next().unwrap_or_default(), third, "shear"));
        let row = |what: &str, v: &[f64; 4]| format!("  {what:<26} {:>12.4} {:>12.4} {:>12.4} {:>12.4}\n", v[0], v[1], v[2], v[3]);
        out.push_str(&row("membrane", &l.membrane));
        out.push_str(&row("bending (at the start)", &l.bending));
        out.push_str(&row("total at the start", &l.total[0]));
        out.push_str(&row("total at the end", &l.total[1]));
        out.push_str(&format!(
            "  von Mises: membrane {:.4}, membrane + bending {:.4} (start) / {:.4} (end)\n",
            l.membrane_equivalent, l.membrane_plus_bending_equivalent[0], l.membrane_plus_bending_equivalent[1]
        ));
    }
    Ok(out)
}
