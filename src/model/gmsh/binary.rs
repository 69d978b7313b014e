//! Binary .msh 4.1 (Gmsh's `Mesh.Binary = 1`): the same sections as the text format, their
//! numbers as little-endian machine words (ints 4 bytes, size_t as the header says, doubles
//! 8), each section's data followed by a newline and its `$End` line; `$PhysicalNames` stays
//! text. Layout: Gmsh reference manual, "MSH file format" (version 4.1).

use super::{RawElement, RawMesh};
use crate::error::{Error, Result};

/// Whether `bytes` is a binary .msh 4.1 (its format line says file type 1).
pub(super) fn is_binary(bytes: &[u8]) -> bool {
    let mut lines = bytes.split(|&b| b == b'\n').map(|l| l.trim_ascii());
    lines.next() == Some(b"$MeshFormat") && lines.next().is_some_and(|l| l.split(|&b| b == b' ').nth(1) == Some(b"1"))
}

struct Cursor<'a> {
    bytes: &'a [u8],
    at: usize,
    size_t: usize,
    name: &'a str,
    /// The section being read, for messages.
    section: &'static str,
}

impl<'a> Cursor<'a> {
    fn error(&self, message: impl std::fmt::Display) -> Error {
        Error::input(format!("{}: {} (binary, byte {}): {message}", self.name, self.section, self.at))
    }

    fn take(&mut self, n: usize) -> Result<&'a [u8]> {
        let end = self.at.checked_add(n).filter(|&e| e <= self.bytes.len()).ok_or_else(|| self.error("the file ends inside the section"))?;
        let out = &self.bytes[self.at..end];
        self.at = end;
        Ok(out)
    }

    fn int(&mut self) -> Result<i32> {
        Ok(i32::from_le_bytes(self.take(4)?.try_into().expect("4 bytes")))
    }

    fn size(&mut self) -> Result<u64> {
        let b = self.take(self.size_t)?;
        Ok(match self.size_t {
            4 => u32::from_le_bytes(b.try_into().expect("4 bytes")) as u64,
            _ => u64::from_le_bytes(b.try_into().expect("8 bytes")),
        })
    }

    /// A count, checked against what the rest of the file could hold (`each` bytes apiece), so
    /// a corrupt count gives a message rather than an allocation of terabytes.
    fn count(&mut self, each: usize) -> Result<usize> {
        let n = self.size()?;
        let left = (self.bytes.len() - self.at) as u64;
        if n.saturating_mul(each.max(1) as u64) > left {
            return Err(self.error(format!("a count of {n} is more than the file holds")));
        }
        Ok(n as usize)
    }

    fn double(&mut self) -> Result<f64> {
        Ok(f64::from_le_bytes(self.take(8)?.try_into().expect("8 bytes")))
    }

    /// The next line as text (without its newline).
    fn line(&mut self) -> Result<&'a str> {
        let rest = &self.bytes[self.at..];
        let end = rest.iter().position(|&b| b == b'\n').unwrap_or(rest.len());
        self.at += (end + 1).min(rest.len());
        std::str::from_utf8(&rest[..end]).map(str::trim).map_err(|_| self.error("expected a line of text"))
    }

    /// Skips blank lines; the next non-blank line.
    fn next_line(&mut self) -> Result<Option<&'a str>> {
        while self.at < self.bytes.len() {
            let l = self.line()?;
            if !l.is_empty() {
                return Ok(Some(l));
            }
        }
        Ok(None)
    }

    fn expect(&mut self, tag: &str) -> Result<()> {
        match self.next_line()? {
            Some(l) if l == tag => Ok(()),
            other => Err(self.error(format!("expected {tag}, found {:?}", other.unwrap_or("the end of the file")))),
        }
    }
}

/// Nodes of a Gmsh element type (those a 2-D mesh may hold), None for others.
fn nodes_of(ty: i32) -> Option<usize> {
    Some(match ty {
        15 => 1,
        1 => 2,
        8 | 2 => 3,
        26 | 3 => 4,
        27 => 5,
        9 | 28 => 6,
        16 => 8,
        10 | 20 => 9,
        21 => 10,
        22 => 12,
        23 | 24 => 15,
        25 => 21,
        4 => 4,
        5 => 8,
        6 => 6,
        7 => 5,
        11 => 10,
        _ => return None,
    })
}

pub(super) fn parse(bytes: &[u8], name: &str) -> Result<RawMesh> {
    let mut c = Cursor { bytes, at: 0, size_t: 8, name, section: "$MeshFormat" };
    c.expect("$MeshFormat")?;
    let format: Vec<&str> = c.line()?.split_whitespace().collect();
    if format.first() != Some(&"4.1") {
        return Err(c.error(format!("a binary .msh {}: slideline reads binary files in format 4.1 (Gmsh: -format msh41)", format.first().unwrap_or(&"?"))));
    }
    c.size_t = match format.get(2).and_then(|s| s.parse::<usize>().ok()) {
        Some(s @ (4 | 8)) => s,
        other => return Err(c.error(format!("data size {other:?}: expected 4 or 8"))),
    };
    if c.int()? != 1 {
        return Err(c.error("the file is big-endian (written on another kind of machine): save it as text (Mesh.Binary = 0)"));
    }
    c.expect("$EndMeshFormat")?;
    let mut raw = RawMesh::default();
    while let Some(header) = c.next_line()? {
        match header {
            "$PhysicalNames" => {
                c.section = "$PhysicalNames";
                let n: usize = c.line()?.parse().map_err(|_| c.error("bad count"))?;
                for _ in 0..n {
                    let l = c.line()?;
                    let mut it = l.splitn(3, char::is_whitespace);
                    match (it.next().and_then(|t| t.parse().ok()), it.next().and_then(|t| t.parse().ok()), it.next().map(|t| t.trim().trim_matches('"'))) {
                        (Some(d), Some(t), Some(nm)) if !nm.is_empty() => {
                            raw.physical_names.insert((d, t), nm.to_string());
                        }
                        _ => return Err(c.error(format!("bad physical name line {l:?}"))),
                    }
                }
                c.expect("$EndPhysicalNames")?;
            }
            "$Entities" => {
                c.section = "$Entities";
                let counts = [c.count(4)?, c.count(4)?, c.count(4)?, c.count(4)?];
                for (dim, &count) in counts.iter().enumerate() {
                    for _ in 0..count {
                        let tag = c.int()?;
                        for _ in 0..if dim == 0 { 3 } else { 6 } {
                            c.double()?;
                        }
                        let n = c.count(4)?;
                        let physicals = (0..n).map(|_| c.int()).collect::<Result<Vec<i32>>>()?;
                        if dim > 0 {
                            let bounding = c.count(4)?;
                            c.take(4 * bounding)?;
                        }
                        raw.entity_physicals.insert((dim as i32, tag), physicals);
                    }
                }
                c.expect("$EndEntities")?;
            }
            "$Nodes" => {
                c.section = "$Nodes";
                let blocks = c.count(16)?;
                let (total, _min, _max) = (c.size()?, c.size()?, c.size()?);
                let before = raw.node_coords.len();
                for _ in 0..blocks {
                    let (_dim, _entity, parametric) = (c.int()?, c.int()?, c.int()?);
                    if parametric != 0 {
                        return Err(c.error("parametric node coordinates are not supported"));
                    }
                    let n = c.count(c.size_t + 24)?;
                    let tags = (0..n).map(|_| c.size()).collect::<Result<Vec<u64>>>()?;
                    for tag in tags {
                        let (x, y, z) = (c.double()?, c.double()?, c.double()?);
                        if z != 0.0 {
                            return Err(c.error(format!("node {tag} has z = {z}: the mesh must lie in the x-y plane (x = r, y = z)")));
                        }
                        raw.node_coords.insert(tag, [x, y]);
                    }
                }
                // the header's total must be what the blocks hold (a corrupt one is named)
                if total != (raw.node_coords.len() - before) as u64 {
                    return Err(c.error(format!("the header claims {total} nodes, its blocks hold {}", raw.node_coords.len() - before)));
                }
                c.expect("$EndNodes")?;
            }
            "$Elements" => {
                c.section = "$Elements";
                let blocks = c.count(16)?;
                let (total, _min, _max) = (c.size()?, c.size()?, c.size()?);
                let before = raw.elements.len();
                for block in 0..blocks {
                    let (dim, entity, ty) = (c.int()?, c.int()?, c.int()?);
                    let per = nodes_of(ty).ok_or_else(|| c.error(format!("element type {ty} (block {}) is not one a 2-D mesh holds", block + 1)))?;
                    let n = c.count(c.size_t * (per + 1))?;
                    for _ in 0..n {
                        let tag = c.size()?;
                        let nodes = (0..per).map(|_| c.size()).collect::<Result<Vec<u64>>>()?;
                        let at = format!("{name}, $Elements block {}", block + 1);
                        raw.elements.push(RawElement { dim, entity, ty: ty as u32, tag, nodes, at });
                    }
                }
                if total != (raw.elements.len() - before) as u64 {
                    return Err(c.error(format!("the header claims {total} elements, its blocks hold {}", raw.elements.len() - before)));
                }
                c.expect("$EndElements")?;
            }
            other if other.starts_with("$End") => return Err(c.error(format!("unexpected {other}"))),
            other if other.starts_with('$') => {
                // a section slideline does not use: skip to its end line
                let end = format!("\n$End{}", &other[1..]);
                let rest = &bytes[c.at..];
                let skip = rest.windows(end.len()).position(|w| w == end.as_bytes()).ok_or_else(|| c.error(format!("no {} after {other}", &end[1..])))?;
                c.at += skip + end.len();
            }
            other => return Err(c.error(format!("expected a section header, found {other:?}"))),
        }
    }
    Ok(raw)
}
