//! The vertical cut (thesis §12.2, fig. 12.1): a sheet of thickness l_y and length
//! l_x = 3 l_y lies on a die over its left two thirds; a rigid punch whose edge stands a
//! clearance g_x right of the die edge moves down at constant speed and shears the right
//! strip off. Relative feed = punch travel / l_y; 100 % after 20 µs, so v = l_y / 20 µs.
//!
//! Chosen here (fig. 12.1 gives them only as a drawing): l_y = 3 mm, so that set S0 (60
//! points over the thickness at dx = 0.1 mm) has two points per cell as the thesis's
//! baseline; l_x = 9 mm (n_x = 3 n_y at isotropic point spacing); g_x = 0.15 mm (5 % of
//! the thickness, a usual blanking clearance); a rectangular punch 2 mm high reaching
//! 1 mm past the sheet's right end; punch penalty κ_pen = 1e13 kg/s² (the orthogonal
//! cut's, §12.3) and no friction (§12.1: lubricated, sharp tools); v = 150 m/s.
//!
//! Boundary conditions. G sets (grid shift): springs eq. 12.1,
//! f = κ_BC ((X_MP)_i − (x_MP)_i) with κ_BC = 1e7 kg/s², on Γ1 = the points with
//! X_y ≤ 4e-5 m and X_x ≤ 2/3 l_x (the thesis prints ∨; ∧ is meant: the bottom layer over
//! the die) in x and y, and on Γ2 = the points with X_x ≤ 4e-5 m in y (for point spacings
//! above the thesis's 50 µm the layers reach 0.6 of a spacing, to hold the first row). S sets (no shift):
//! the same regions as grid conditions, v_x = v_y = 0 on the nodes with y ≤ 0 and
//! x ≤ 2/3 l_x, v_y = 0 on the nodes with x ≤ 0 (the thesis's grid-condition text swaps
//! Γ1 and Γ2 and would hold the strip too; its spring text is followed for both).
//!
//! Time step: the thesis uses 5e-10 s (1e-10 s for n_y = 200), 1-5 % of the CFL limit,
//! without a reason; here the solver's own limit (CFL and the stability of the stiffest
//! penalty or spring on the lightest point) unless `RunOptions::dt` is given.

use crate::workpiece::{self, RunOptions, Workpiece};
use mpm_core::scene::spec::{
    BoxSpec, NodeSetSpec, RigidShapeSpec, RigidSpec, SceneFile, SpringSpec, VelocityBcSpec,
};

/// The material file of the shipped scenes (relative to `data/scenes/cutting/`).
pub const MATERIAL: &str = "../../materials/al7075_t6.toml";

/// One discretization of table 12.2: grid spacing dx = dy [m], points over the thickness
/// n_y (n_x = 3 n_y), and whether the grid shifts (by dx/2, with spring conditions).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Discretization {
    pub name: &'static str,
    pub spacing: f64,
    pub points_y: usize,
    pub shift: bool,
}

const fn set(name: &'static str, spacing: f64, points_y: usize, shift: bool) -> Discretization {
    Discretization {
        name,
        spacing,
        points_y,
        shift,
    }
}

/// Table 12.2.
pub const SETS: [Discretization; 10] = [
    set("S0", 1e-4, 60, false),
    set("S1", 6.25e-5, 100, false),
    set("S2", 5e-5, 200, false),
    set("G0", 1e-4, 60, true),
    set("G1", 6.25e-5, 100, true),
    set("G2", 5e-5, 200, true),
    set("G0_100", 1e-4, 100, true),
    set("G0_200", 1e-4, 200, true),
    set("G1_60", 6.25e-5, 60, true),
    set("G1_200", 6.25e-5, 200, true),
];

/// The set named `name` (`S0`, ..., `G1_200`; `G0 100` may be written with a space).
pub fn discretization(name: &str) -> Option<Discretization> {
    let name = name.replace(' ', "_");
    SETS.iter()
        .copied()
        .find(|s| s.name.eq_ignore_ascii_case(&name))
}

/// The geometry, tool and conditions (module docs for the choices). SI units.
#[derive(Debug, Clone, PartialEq)]
pub struct VerticalCut {
    /// Sheet thickness l_y and length l_x [m].
    pub thickness: f64,
    pub length: f64,
    /// Horizontal gap between die edge and punch edge [m].
    pub clearance: f64,
    /// Time to 100 % relative feed [s].
    pub full_feed_time: f64,
    /// Punch penalty κ_pen [kg/s²] and Coulomb friction μ [-].
    pub penalty: f64,
    pub friction: f64,
    /// Spring conditions: κ_BC [kg/s²] and the depth of the layers Γ1, Γ2 [m].
    pub spring_stiffness: f64,
    pub spring_layer: f64,
}

impl Default for VerticalCut {
    fn default() -> Self {
        VerticalCut {
            thickness: 3e-3,
            length: 9e-3,
            clearance: 0.15e-3,
            full_feed_time: 20e-6,
            penalty: 1e13,
            friction: 0.0,
            spring_stiffness: 1e7,
            spring_layer: 4e-5,
        }
    }
}

fn boxed(min: [f64; 2], max: [f64; 2]) -> BoxSpec {
    BoxSpec {
        min: min.to_vec(),
        max: max.to_vec(),
    }
}

impl VerticalCut {
    /// Punch speed v = l_y / t_100 [m/s].
    pub fn punch_speed(&self) -> f64 {
        self.thickness / self.full_feed_time
    }

    /// x of the die edge: the sheet rests on the die for x ≤ 2/3 l_x [m].
    pub fn die_edge(&self) -> f64 {
        2.0 / 3.0 * self.length
    }

    /// The scene of `set` run to the relative feed `end_feed` with `options`.
    pub fn scene(&self, set: &Discretization, end_feed: f64, options: &RunOptions) -> SceneFile {
        let (lx, ly) = (self.length, self.thickness);
        let end = end_feed * self.full_feed_time;
        let edge = self.die_edge() + self.clearance;
        let (far, top) = (lx + 1e-3, ly + 2e-3);
        let far_below = -1.0;
        let sheet = Workpiece {
            material: "al7075",
            body: "sheet",
            size: [lx, ly],
            points: [3 * set.points_y, set.points_y],
        };
        let mut scene = workpiece::scene(&sheet, set.spacing, set.shift, end, options);
        scene.rigid_bodies = vec![RigidSpec {
            name: "punch".into(),
            shape: RigidShapeSpec::Polygon {
                vertices: vec![
                    vec![edge, ly],
                    vec![far, ly],
                    vec![far, top],
                    vec![edge, top],
                ],
            },
            penalty: self.penalty,
            friction: self.friction,
            search_interval: None,
            translation: Some(vec![
                vec![0.0, 0.0, 0.0],
                vec![end, 0.0, -self.punch_speed() * end],
            ]),
            rotation: None,
        }];
        let nodes = |below: Option<&str>, at: Option<f64>, inside: Option<BoxSpec>| NodeSetSpec {
            plane: None,
            below: below.map(Into::into),
            above: None,
            at,
            inside,
        };
        let fixed = |nodes: NodeSetSpec, axes: &[&str]| VelocityBcSpec {
            nodes,
            fixed: axes.iter().map(|a| a.to_string()).collect(),
            value: None,
            one_sided: false,
            history: None,
        };
        // the thesis's layer holds the first row of its point spacings (≤ 50 µm); a coarser
        // spacing needs a layer down to 0.6 of a spacing to hold its first row
        let layer = self.spring_layer.max(0.6 * ly / set.points_y as f64);
        let spring = |max: [f64; 2], axes: &[&str]| SpringSpec {
            region: boxed([far_below, far_below], max),
            directions: axes.iter().map(|a| a.to_string()).collect(),
            stiffness: self.spring_stiffness,
        };
        match set.shift {
            true => {
                scene.springs = vec![
                    spring([self.die_edge(), layer], &["x", "y"]),
                    spring([layer, top], &["y"]),
                ]
            }
            false => {
                let support = boxed([far_below, far_below], [self.die_edge(), 0.0]);
                scene.velocity_bcs = vec![
                    fixed(nodes(None, None, Some(support)), &["x", "y"]),
                    fixed(nodes(Some("x"), Some(0.0), None), &["y"]),
                ]
            }
        }
        scene
    }

    /// Relative feed at time `t` [s]: punch travel over the thickness [-].
    pub fn feed_at(&self, t: f64) -> f64 {
        t / self.full_feed_time
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    /// Every set of table 12.2 builds: n_x × n_y points (the thesis's NoMP), the right
    /// conditions for its kind, the punch edge at the clearance right of the die edge.
    #[test]
    fn every_set_of_table_12_2_builds_with_its_point_count() {
        let cut = VerticalCut::default();
        let scenes = Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/scenes/cutting/x.toml");
        let nomp = [
            10800, 30000, 120000, 10800, 30000, 120000, 30000, 120000, 10800, 120000,
        ];
        for (set, nomp) in SETS.iter().zip(nomp) {
            let spec = cut.scene(set, 1.2, &RunOptions::new(MATERIAL));
            let scene = mpm_core::scene::from_description(&spec, &scenes).unwrap();
            let mpm_core::scene::Simulation::Planar(s) = scene.simulation else {
                panic!("plane strain")
            };
            assert_eq!(s.particles.len(), nomp, "{}", set.name);
            assert_eq!(
                s.conditions.len(),
                if set.shift { 2 } else { 0 },
                "{}",
                set.name
            );
            assert_eq!(
                s.velocity_bcs.len(),
                if set.shift { 0 } else { 2 },
                "{}",
                set.name
            );
        }
        assert!((cut.punch_speed() - 150.0).abs() < 1e-9);
        assert_eq!(discretization("g0 100").unwrap().points_y, 100);
        assert!(discretization("G3").is_none());
    }
}
