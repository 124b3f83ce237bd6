//! Bodies from quadrilateral (2D) and hexahedral (3D) meshes, one material point per
//! element, as the thesis's CPDI takes hexahedral meshes as input (§10.1): the point sits
//! at the element's centroid, carries its volume and its corners as the CPDI domain
//! (`shape::Hex`, kernel `cpdi-hex`).
//!
//! The file format is the Abaqus input file (`.inp`), flattened: `*Node` lines
//! `id, x, y[, z]` [m] and `*Element, type=…` lines `id, n1, …, n4` (CPE4, CPS4, CAX4 and
//! their R/H/I variants) or `id, n1, …, n8` (C3D8, C3D8R, C3D8H, C3D8I), corners in the
//! Abaqus order (counter-clockwise, then the top face), a line ending in a comma continued
//! on the next. `**` starts a comment. The data lines of every other keyword (sets,
//! materials, steps) are skipped; an `*Instance` that moves its part (data lines) and a
//! second `*Part` are errors, since the nodes would not be where the file lists them.
//!
//! Volume of a point: the element's area per metre (plane strain), 2π r_c A (axisymmetric,
//! Pappus, r_c the centroid's radius), its volume (3D).

use crate::kinematics::Kinematics;
use crate::shape::{corners, Hex};
use nalgebra::SVector;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// A mesh read from a file: node coordinates and, per element, its corners in the vertex
/// order of `shape::hex` with the line it was read from.
#[derive(Debug, Clone)]
pub struct Mesh<const D: usize> {
    pub nodes: HashMap<u64, SVector<f64, D>>,
    pub elements: Vec<(usize, Vec<u64>)>,
    pub file: PathBuf,
}

/// A mesh that cannot be used, with the file and line.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}:{line}: {message}", file.display())]
pub struct MeshError {
    pub file: PathBuf,
    pub line: usize,
    pub message: String,
}

/// Abaqus corner k (1-based order, counter-clockwise) → vertex index of `shape::hex`.
const QUAD_ORDER: [usize; 4] = [0, 1, 3, 2];
const HEX_ORDER: [usize; 8] = [0, 1, 3, 2, 4, 5, 7, 6];

/// Element types with `D`-dimensional 2ᴰ-corner elements.
fn element_type_fits(name: &str, d: usize) -> bool {
    let base = name.trim_end_matches(['R', 'H', 'I']);
    match d {
        2 => matches!(base, "CPE4" | "CPS4" | "CAX4"),
        _ => base == "C3D8",
    }
}

/// Read the mesh of `path` (module docs).
pub fn read<const D: usize>(path: &Path) -> Result<Mesh<D>, MeshError> {
    let text = std::fs::read_to_string(path).map_err(|e| MeshError {
        file: path.into(),
        line: 0,
        message: format!("cannot read: {e}"),
    })?;
    parse(&text, path)
}

/// Parse the text of a mesh file; `path` names it in errors.
pub fn parse<const D: usize>(text: &str, path: &Path) -> Result<Mesh<D>, MeshError> {
    let mut reader = Reader {
        mesh: Mesh {
            nodes: HashMap::new(),
            elements: Vec::new(),
            file: path.into(),
        },
        section: Section::Skipped,
        parts: 0,
    };
    let mut pending = String::new();
    let mut first_line = 0;
    for (k, raw) in text.lines().enumerate() {
        let line = raw.trim();
        if line.is_empty() || line.starts_with("**") {
            continue;
        }
        if pending.is_empty() {
            first_line = k + 1;
        }
        pending.push_str(line);
        if line.ends_with(',') && !line.starts_with('*') {
            continue; // continued on the next line
        }
        reader.line(&std::mem::take(&mut pending), first_line)?;
    }
    if reader.mesh.elements.is_empty() {
        return Err(reader.err(
            0,
            format!("no {D}-D elements (*Element, type=…) in the file"),
        ));
    }
    for (line, corners) in &reader.mesh.elements {
        if let Some(id) = corners
            .iter()
            .find(|id| !reader.mesh.nodes.contains_key(id))
        {
            return Err(reader.err(*line, format!("node {id} is not defined by any *Node line")));
        }
    }
    Ok(reader.mesh)
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Section {
    Nodes,
    Elements,
    Instance,
    Skipped,
}

struct Reader<const D: usize> {
    mesh: Mesh<D>,
    section: Section,
    parts: usize,
}

impl<const D: usize> Reader<D> {
    fn err(&self, line: usize, message: impl Into<String>) -> MeshError {
        MeshError {
            file: self.mesh.file.clone(),
            line,
            message: message.into(),
        }
    }

    fn line(&mut self, text: &str, line: usize) -> Result<(), MeshError> {
        if let Some(keyword) = text.strip_prefix('*') {
            return self.keyword(keyword, line);
        }
        let fields: Vec<&str> = text
            .split(',')
            .map(str::trim)
            .filter(|f| !f.is_empty())
            .collect();
        match self.section {
            Section::Nodes => self.node(&fields, line),
            Section::Elements => self.element(&fields, line),
            Section::Instance => Err(self.err(
                line,
                "the *Instance moves its part (translation or rotation lines): write the input \
                 file flattened (Abaqus/CAE: Model > Edit Attributes > Do not use parts and \
                 assemblies in input files)",
            )),
            Section::Skipped => Ok(()),
        }
    }

    fn keyword(&mut self, keyword: &str, line: usize) -> Result<(), MeshError> {
        let name = keyword
            .split(',')
            .next()
            .unwrap_or("")
            .trim()
            .to_ascii_lowercase();
        let option = |key: &str| {
            keyword.split(',').skip(1).find_map(|p| {
                let (k, v) = p.split_once('=')?;
                (k.trim().eq_ignore_ascii_case(key)).then(|| v.trim().to_ascii_uppercase())
            })
        };
        self.section = match name.as_str() {
            "node" => Section::Nodes,
            "element" => {
                let Some(kind) = option("type") else {
                    return Err(self.err(line, "*Element without type="));
                };
                if !element_type_fits(&kind, D) {
                    return Err(self.err(
                        line,
                        format!(
                            "element type {kind}: a {D}-D scene takes {}",
                            if D == 2 {
                                "4-node quadrilaterals (CPE4, CPS4, CAX4 and their R/H/I variants)"
                            } else {
                                "8-node hexahedra (C3D8, C3D8R, C3D8H, C3D8I)"
                            }
                        ),
                    ));
                }
                Section::Elements
            }
            "part" => {
                self.parts += 1;
                if self.parts > 1 {
                    return Err(self.err(line, "a second *Part: one body per mesh file"));
                }
                Section::Skipped
            }
            "instance" => Section::Instance,
            _ => Section::Skipped,
        };
        Ok(())
    }

    /// The error of a data line that does not have the `form` it should.
    fn malformed(&self, line: usize, form: &str, fields: &[&str]) -> MeshError {
        self.err(line, format!("{form}, got `{}`", fields.join(", ")))
    }

    fn node(&mut self, fields: &[&str], line: usize) -> Result<(), MeshError> {
        let form = "a *Node line is `id, x, y[, z]` (integer id)";
        let bad = || self.malformed(line, form, fields);
        let id: u64 = fields
            .first()
            .and_then(|f| f.parse().ok())
            .ok_or_else(bad)?;
        let x: Vec<f64> = fields[1..]
            .iter()
            .map(|f| f.parse().ok())
            .collect::<Option<_>>()
            .ok_or_else(bad)?;
        let extra_zero = D == 2 && x.len() == 3 && x[2] == 0.0;
        if x.len() != D && !extra_zero {
            return Err(self.err(
                line,
                format!(
                    "a *Node line of a {D}-D mesh has {} numbers (id and {D} coordinates), got {}",
                    D + 1,
                    fields.len()
                ),
            ));
        }
        let position = SVector::<f64, D>::from_fn(|k, _| x[k]);
        if self.mesh.nodes.insert(id, position).is_some() {
            return Err(self.err(line, format!("node {id} defined twice")));
        }
        Ok(())
    }

    fn element(&mut self, fields: &[&str], line: usize) -> Result<(), MeshError> {
        let form = "an *Element line is `id, node, …` (integers)";
        let ids: Vec<u64> = fields
            .iter()
            .map(|f| f.parse().ok())
            .collect::<Option<_>>()
            .ok_or_else(|| self.malformed(line, form, fields))?;
        if ids.len() != corners(D) + 1 {
            return Err(self.err(
                line,
                format!(
                    "a {D}-D element has {} nodes, got {}",
                    corners(D),
                    ids.len().saturating_sub(1)
                ),
            ));
        }
        let order: &[usize] = if D == 2 { &QUAD_ORDER } else { &HEX_ORDER };
        let mut vertices = vec![0; corners(D)];
        for (k, &j) in order.iter().enumerate() {
            vertices[j] = ids[k + 1];
        }
        self.mesh.elements.push((line, vertices));
        Ok(())
    }
}

/// The material point of one element: position [m], volume [m³, or m³ per m in plane
/// strain] and domain.
pub type MeshPoint<const D: usize> = (SVector<f64, D>, f64, Hex<D>);

/// One material point per element of `mesh`.
pub fn points<const D: usize>(
    mesh: &Mesh<D>,
    kinematics: Kinematics,
) -> Result<Vec<MeshPoint<D>>, MeshError> {
    mesh.elements
        .iter()
        .map(|(line, ids)| {
            let vertices: Vec<_> = ids.iter().map(|id| mesh.nodes[id]).collect();
            let (centre, hex) = Hex::new(&vertices).map_err(|e| MeshError {
                file: mesh.file.clone(),
                line: *line,
                message: format!("element: {e}"),
            })?;
            let volume = match kinematics {
                Kinematics::Axisymmetric => 2.0 * std::f64::consts::PI * centre[0] * hex.volume,
                _ => hex.volume,
            };
            Ok((centre, volume, hex))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector2;

    fn parse2(text: &str) -> Result<Mesh<2>, MeshError> {
        parse(text, Path::new("test.inp"))
    }

    /// Two unit squares side by side, with what real files carry around the mesh.
    const TWO_SQUARES: &str = "*Heading
 two squares
** a comment
*Node
1, 1.0, 0.0
2, 2.0, 0.0, 0.0
3, 3.0, 0.0
4, 1.0, 1.0
5, 2.0, 1.0
6, 3.0,
 1.0
*Element, type=CPE4R, elset=all
10, 1, 2, 5, 4
11, 2, 3, 6, 5
*Nset, nset=left
1, 4
*Material, name=steel
*Elastic
200e9, 0.3
";

    #[test]
    fn a_quad_mesh_gives_one_point_per_element_at_its_centroid() {
        let mesh = parse2(TWO_SQUARES).unwrap();
        assert_eq!(mesh.elements.len(), 2);
        // Abaqus' counter-clockwise corners 1 2 5 4 in the lexicographic vertex order
        assert_eq!(mesh.elements[0].1, vec![1, 2, 4, 5]);
        let plane = points(&mesh, Kinematics::PlaneStrain).unwrap();
        assert!((plane[0].0 - Vector2::new(1.5, 0.5)).norm() < 1e-15);
        assert!((plane[1].1 - 1.0).abs() < 1e-15);
        // axisymmetric: the ring volume π (r2² − r1²) h exactly (Pappus)
        let ring = points(&mesh, Kinematics::Axisymmetric).unwrap();
        let pi = std::f64::consts::PI;
        assert!((ring[0].1 - pi * 3.0).abs() < 1e-12 && (ring[1].1 - pi * 5.0).abs() < 1e-12);
    }

    #[test]
    fn a_trapezoid_point_sits_at_the_area_centroid() {
        let text =
            "*Node\n1, 0, 0\n2, 2, 0\n3, 2, 2\n4, 0, 1\n*Element, type=CPS4\n1, 1, 2, 3, 4\n";
        let mesh = parse2(text).unwrap();
        let (x, v, _) = points(&mesh, Kinematics::PlaneStrain).unwrap()[0];
        // area 3; centroid of the trapezoid: x = 10/9, y = 7/9
        assert!((v - 3.0).abs() < 1e-14, "{v}");
        assert!(
            (x - Vector2::new(10.0 / 9.0, 7.0 / 9.0)).norm() < 1e-14,
            "{x}"
        );
    }

    #[test]
    fn bad_meshes_are_refused_with_file_and_line() {
        let cases = [
            (
                "*Node\n1, 0, 0\n*Element, type=CPE4\n1, 1, 2, 3, 4\n",
                4,
                "node 2 is not defined",
            ),
            (
                "*Node\n1, 0, 0, 0\n*Element, type=C3D8\n",
                3,
                "a 2-D scene takes 4-node",
            ),
            ("*Node\n1, 0, 0, 0.5\n", 2, "has 3 numbers"),
            ("*Node\n1, 0, 0\n1, 1, 0\n", 3, "node 1 defined twice"),
            ("*Node\n1, 0, x\n", 2, "`id, x, y[, z]`"),
            ("*Node\n1.5, 0, 0\n", 2, "(integer id), got `1.5, 0, 0`"),
            ("*Element, type=CPE4\n1, 1, 2, 3\n", 2, "has 4 nodes, got 3"),
            (
                "*Instance, name=a, part=p\n 1.0, 0.0, 0.0\n",
                2,
                "flattened",
            ),
            ("*Part, name=a\n*Part, name=b\n", 2, "a second *Part"),
            ("*Node\n1, 0, 0\n", 0, "no 2-D elements"),
        ];
        for (text, line, expected) in cases {
            let e = parse2(text).unwrap_err();
            assert_eq!(e.line, line, "{e}");
            assert!(e.to_string().contains(expected), "{e}");
            assert!(e.to_string().starts_with("test.inp:"), "{e}");
        }
        // clockwise corners fold the element's map
        let text =
            "*Node\n1, 0, 0\n2, 1, 0\n3, 1, 1\n4, 0, 1\n*Element, type=CPE4\n7, 1, 4, 3, 2\n";
        let e = points(&parse2(text).unwrap(), Kinematics::PlaneStrain).unwrap_err();
        assert_eq!(e.line, 7, "{e}");
        assert!(e.message.contains("wrong order"), "{e}");
    }
}
