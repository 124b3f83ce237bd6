//! The orthogonal cut (thesis §12.3, fig. 12.10): a 42CrMo4 workpiece l_x = 6 mm long and
//! l_y = 2 mm high (n_y points over the height, n_x = 3 n_y), held by springs (eq. 12.1,
//! κ_BC = 1e8 kg/s²) on Γ1 = the points with X_y ≤ 80 µm in x and y and on Γ2 = the points
//! with X_x ≤ 80 µm in y; a rigid tool with an ideally sharp tip at depth f_y below the top
//! surface moves to −x at constant speed (κ_pen = 1e13 kg/s²) and lifts a chip off the
//! top; grid shift dx/2 every step; 80 µs.
//!
//! Chosen here (fig. 12.10 gives them only as a drawing): rake angle 5°, clearance angle
//! 7° (a usual turning tool), a tool 3 mm high and 2 mm long; cutting speed 40 m/s, so
//! that the tool travels 3.2 mm in 80 µs and the chip does not reach the workpiece's left
//! end; the tip starts 50 µm right of the workpiece; no friction unless asked (§12.1).

use crate::workpiece::{self, RunOptions, Workpiece};
use mpm_core::scene::spec::{BoxSpec, RigidShapeSpec, RigidSpec, SceneFile, SpringSpec};

/// The material file as a scene in `data/scenes/cutting/` names it.
pub const MATERIAL: &str = "../../materials/42crmo4_qt660.toml";

/// The workpiece, tool and conditions (module docs for the choices). SI units, angles in
/// degrees.
#[derive(Debug, Clone, PartialEq)]
pub struct OrthogonalCut {
    pub length: f64,
    pub height: f64,
    /// Depth of cut f_y [m].
    pub feed: f64,
    pub speed: f64,
    pub rake_deg: f64,
    pub clearance_deg: f64,
    pub penalty: f64,
    pub friction: f64,
    pub spring_stiffness: f64,
    pub spring_layer: f64,
    /// Run time [s].
    pub end: f64,
}

impl Default for OrthogonalCut {
    fn default() -> Self {
        OrthogonalCut {
            length: 6e-3,
            height: 2e-3,
            feed: 0.3e-3,
            speed: 40.0,
            rake_deg: 5.0,
            clearance_deg: 7.0,
            penalty: 1e13,
            friction: 0.0,
            spring_stiffness: 1e8,
            spring_layer: 8e-5,
            end: 80e-6,
        }
    }
}

/// One discretization of the sensitivity matrix: grid spacing [m] and points over the
/// height n_y (n_x = 3 n_y).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Resolution {
    pub spacing: f64,
    pub points_y: usize,
}

impl OrthogonalCut {
    /// The tool tip at t = 0 [m].
    pub fn tip(&self) -> [f64; 2] {
        [self.length + 50e-6, self.height - self.feed]
    }

    /// The tool tip at time `t` [s].
    pub fn tip_at(&self, t: f64) -> [f64; 2] {
        let [x, y] = self.tip();
        [x - self.speed * t, y]
    }

    /// The tool: tip, clearance face rising to the right, rake face leaning back (to +x)
    /// by the rake angle (a convex quadrilateral, counter-clockwise).
    fn tool_vertices(&self) -> Vec<Vec<f64>> {
        let [x, y] = self.tip();
        let (w, h) = (2e-3, 3e-3);
        let (rake, clearance) = (self.rake_deg.to_radians(), self.clearance_deg.to_radians());
        vec![
            vec![x, y],
            vec![x + w, y + w * clearance.tan()],
            vec![x + w, y + h],
            vec![x + h * rake.tan(), y + h],
        ]
    }

    /// The scene at `resolution` run with `options`.
    pub fn scene(&self, resolution: &Resolution, options: &RunOptions) -> SceneFile {
        let n = resolution.points_y;
        let region = |max: [f64; 2]| BoxSpec {
            min: vec![-1.0, -1.0],
            max: max.to_vec(),
        };
        let spring = |max: [f64; 2], axes: &[&str]| SpringSpec {
            region: region(max),
            directions: axes.iter().map(|a| a.to_string()).collect(),
            stiffness: self.spring_stiffness,
        };
        let body = Workpiece {
            material: "42crmo4",
            body: "workpiece",
            size: [self.length, self.height],
            points: [3 * n, n],
        };
        let mut scene = workpiece::scene(&body, resolution.spacing, true, self.end, options);
        scene.rigid_bodies = vec![RigidSpec {
            name: "tool".into(),
            shape: RigidShapeSpec::Polygon {
                vertices: self.tool_vertices(),
            },
            penalty: self.penalty,
            friction: self.friction,
            search_interval: None,
            translation: Some(vec![
                vec![0.0, 0.0, 0.0],
                vec![self.end, -self.speed * self.end, 0.0],
            ]),
            rotation: None,
        }];
        scene.springs = vec![
            spring([self.length + 1.0, self.spring_layer], &["x", "y"]),
            spring([self.spring_layer, self.height + 1.0], &["y"]),
        ];
        scene
    }
}

/// The sensitivity matrix of §12.3: n_y ∈ {80, 100, 150} × dx ∈ {2e-4, 1e-4, 8e-5} m.
pub fn sensitivity_matrix() -> Vec<Resolution> {
    let mut out = Vec::new();
    for points_y in [80, 100, 150] {
        for spacing in [2e-4, 1e-4, 8e-5] {
            out.push(Resolution { spacing, points_y });
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    /// The scene builds with 3 n_y × n_y points, two spring sets, the tool tip at the
    /// depth of cut, and the tool convex (its vertices counter-clockwise).
    #[test]
    fn the_orthogonal_cut_builds() {
        let cut = OrthogonalCut::default();
        let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/scenes/cutting/x.toml");
        let spec = cut.scene(
            &Resolution {
                spacing: 2e-4,
                points_y: 80,
            },
            &RunOptions::new(MATERIAL),
        );
        let scene = mpm_core::scene::from_description(&spec, &file).unwrap();
        let mpm_core::scene::Simulation::Planar(s) = scene.simulation else {
            panic!("plane strain")
        };
        assert_eq!(s.particles.len(), 19200);
        assert_eq!(s.conditions.len(), 2);
        assert!((cut.tip()[1] - 1.7e-3).abs() < 1e-15);
        let v = cut.tool_vertices();
        for k in 0..v.len() {
            let (a, b, c) = (&v[k], &v[(k + 1) % v.len()], &v[(k + 2) % v.len()]);
            let cross = (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0]);
            assert!(cross > 0.0, "vertex {k}");
        }
        assert_eq!(sensitivity_matrix().len(), 9);
    }
}
