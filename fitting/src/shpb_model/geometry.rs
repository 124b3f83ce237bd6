//! The specimen cylinder as material points at each model level ("levels,
//! cheapest first"), the bar axis along the last coordinate:
//! - `Axisymmetric`: the r-z half section [0, R] × [0, L], a lattice of spacing s = L / n
//!   (n the layers along the length), the axis r = 0 held radially;
//! - `Quarter3d`: the quarter x, y > 0 of the cylinder, symmetry planes x = 0 and y = 0,
//!   the model's face forces × 4;
//! - `Full3d`: the whole cylinder.
//!
//! In 3D the cross-section is the lattice of spacing s_r = R / round(R / s) clipped to the
//! circle (cut cells keep their area, `mpm_core::discretize`), so that the lattice is
//! symmetric about both planes and a quarter holds whole cells; the layers along the
//! axis are round(L / s_r). The grid cell is two radial spacings, so x = 0 and y = 0 are
//! node planes.

use super::Cylinder;
use mpm_core::discretize::{fill, Geometry};
use mpm_core::{Kinematics, VelocityBc};
use nalgebra::SVector;

/// The model levels of the MPM model of the SHPB test.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ModelLevel {
    Axisymmetric,
    Quarter3d,
    Full3d,
}

impl ModelLevel {
    /// Grid dimension.
    pub fn dimension(self) -> usize {
        match self {
            ModelLevel::Axisymmetric => 2,
            ModelLevel::Quarter3d | ModelLevel::Full3d => 3,
        }
    }

    /// The level's name in scene and set files.
    pub fn name(self) -> &'static str {
        match self {
            ModelLevel::Axisymmetric => "mpm-axisymmetric",
            ModelLevel::Quarter3d => "mpm-3d-quarter",
            ModelLevel::Full3d => "mpm-3d",
        }
    }

    /// What the level models, for reports.
    pub fn description(self) -> &'static str {
        match self {
            ModelLevel::Axisymmetric => "axisymmetric MPM SHPB specimen",
            ModelLevel::Quarter3d => "3D quarter MPM SHPB specimen",
            ModelLevel::Full3d => "3D MPM SHPB specimen",
        }
    }
}

impl std::str::FromStr for ModelLevel {
    type Err = String;

    fn from_str(name: &str) -> Result<ModelLevel, String> {
        let levels = [
            ModelLevel::Axisymmetric,
            ModelLevel::Quarter3d,
            ModelLevel::Full3d,
        ];
        levels
            .into_iter()
            .find(|l| l.name() == name)
            .ok_or_else(|| {
                format!(
                    "\"{name}\", expected \"mpm-axisymmetric\", \"mpm-3d-quarter\" or \"mpm-3d\""
                )
            })
    }
}

/// A model level at a point count along the specimen: `20` (the scene's level) or
/// `mpm-3d-quarter:40` on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Discretization {
    pub level: ModelLevel,
    pub layers: usize,
}

impl Discretization {
    /// Read `text`; a bare count takes `default_level`.
    pub fn parse(text: &str, default_level: ModelLevel) -> Result<Self, String> {
        let (level, layers) = match text.split_once(':') {
            Some((level, layers)) => (level.trim().parse()?, layers),
            None => (default_level, text),
        };
        let layers = layers.trim().parse().map_err(|_| {
            format!("\"{text}\": expected a point count along the specimen, e.g. 20 or mpm-3d-quarter:20")
        })?;
        Ok(Discretization { level, layers })
    }
}

impl std::fmt::Display for Discretization {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}:{}", self.level.name(), self.layers)
    }
}

/// Unit vector along the bars (the last coordinate).
pub fn bar_axis<const D: usize>() -> SVector<f64, D> {
    SVector::from_fn(|i, _| if i == D - 1 { 1.0 } else { 0.0 })
}

/// A level's points of the specimen and what comes with them.
pub struct Specimen<const D: usize> {
    pub kinematics: Kinematics,
    /// Position and volume (axisymmetric: of its ring) of each point [m, m³].
    pub points: Vec<(SVector<f64, D>, f64)>,
    /// Lattice spacing per direction: each point's domain [m].
    pub spacing: SVector<f64, D>,
    /// Grid cell size [m].
    pub cell: f64,
    /// The axis condition or the symmetry planes.
    pub conditions: Vec<VelocityBc<D>>,
    /// How many copies of the model make the specimen (its face forces are the model's
    /// times this) [-].
    pub copies: f64,
}

/// `cylinder` at `level` with `layers` points along its length.
pub fn specimen<const D: usize>(
    cylinder: &Cylinder,
    layers: usize,
    level: ModelLevel,
) -> Specimen<D> {
    assert_eq!(
        level.dimension(),
        D,
        "{} is a {}D model",
        level.name(),
        level.dimension()
    );
    let radius = 0.5 * cylinder.diameter;
    let s = cylinder.length / layers as f64;
    if level == ModelLevel::Axisymmetric {
        let box_ = Geometry::Box {
            min: SVector::zeros(),
            max: SVector::from_fn(|i, _| if i == 0 { radius } else { cylinder.length }),
        };
        let spacing = SVector::repeat(s);
        return Specimen {
            kinematics: Kinematics::Axisymmetric,
            points: fill(&box_, spacing, Kinematics::Axisymmetric),
            spacing,
            cell: 2.0 * s,
            conditions: vec![VelocityBc::axis()],
            copies: 1.0,
        };
    }
    let s_r = radius / (radius / s).round().max(1.0);
    let dz = cylinder.length / (cylinder.length / s_r).round().max(1.0);
    let cylinder_shape = Geometry::Cylinder {
        start: SVector::zeros(),
        end: bar_axis::<D>() * cylinder.length,
        radius,
    };
    let mut points = fill(&cylinder_shape, SVector::repeat(s_r), Kinematics::Solid);
    let (conditions, copies) = if level == ModelLevel::Quarter3d {
        points.retain(|(x, _)| x[0] > 0.0 && x[1] > 0.0);
        let planes = (0..2).map(|axis| VelocityBc::symmetry(axis, 0.0)).collect();
        (planes, 4.0)
    } else {
        (Vec::new(), 1.0)
    };
    Specimen {
        kinematics: Kinematics::Solid,
        points,
        spacing: SVector::from_fn(|i, _| if i == D - 1 { dz } else { s_r }),
        cell: 2.0 * s_r,
        conditions,
        copies,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every level holds the cylinder's volume (cut cells keep their area; an
    /// axisymmetric point's volume is its ring's), the quarter a quarter of the full
    /// model's points, none on a symmetry plane.
    #[test]
    fn every_level_holds_the_specimen() {
        let c = Cylinder {
            diameter: 8e-3,
            length: 4e-3,
        };
        let v = c.area() * c.length;
        let axi = specimen::<2>(&c, 20, ModelLevel::Axisymmetric);
        let axi_v: f64 = axi.points.iter().map(|p| p.1).sum();
        assert!((axi_v / v - 1.0).abs() < 1e-12, "{axi_v} {v}");
        let full = specimen::<3>(&c, 20, ModelLevel::Full3d);
        let quarter = specimen::<3>(&c, 20, ModelLevel::Quarter3d);
        assert_eq!(4 * quarter.points.len(), full.points.len());
        assert!(quarter
            .points
            .iter()
            .all(|(x, _)| x[0] > 1e-5 && x[1] > 1e-5));
        for (m, copies) in [(&full, 1.0), (&quarter, 4.0)] {
            let volume: f64 = m.points.iter().map(|p| p.1).sum::<f64>() * copies;
            // the clipping polygon has the circle's area: n/2 ρ² sin(2π/n) = π R²
            assert!((volume / v - 1.0).abs() < 1e-12, "{volume} {v}");
            assert_eq!(m.copies, copies);
        }
        assert_eq!(full.spacing, SVector::<f64, 3>::repeat(2e-4));
    }

    #[test]
    fn discretizations_read_back() {
        let quarter = Discretization {
            level: ModelLevel::Quarter3d,
            layers: 40,
        };
        assert_eq!(
            Discretization::parse("mpm-3d-quarter:40", ModelLevel::Full3d),
            Ok(quarter)
        );
        assert_eq!(quarter.to_string(), "mpm-3d-quarter:40");
        let bare = Discretization::parse(" 20", ModelLevel::Full3d).unwrap();
        assert_eq!((bare.level, bare.layers), (ModelLevel::Full3d, 20));
        assert!(Discretization::parse("mpm-3d:x", ModelLevel::Full3d)
            .unwrap_err()
            .contains("point count"));
        assert!(Discretization::parse("3d:20", ModelLevel::Full3d)
            .unwrap_err()
            .contains("mpm-3d-quarter"));
    }

    #[test]
    fn level_names_read_back() {
        for l in [
            ModelLevel::Axisymmetric,
            ModelLevel::Quarter3d,
            ModelLevel::Full3d,
        ] {
            assert_eq!(l.name().parse::<ModelLevel>(), Ok(l));
        }
        assert!("mpm-2d"
            .parse::<ModelLevel>()
            .unwrap_err()
            .contains("mpm-3d-quarter"));
    }
}
