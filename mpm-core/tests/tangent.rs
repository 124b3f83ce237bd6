//! The derivative pass (`solver::Tangent`) against central differences of whole runs: a
//! small Johnson-Cook copper bar hits a one-sided rigid wall (axisymmetric MUSL, plane
//! strain USF and USL, with bulk viscosity; linear, CPDI and cpGIMP shape functions), a
//! rigid half-space with penalty contact and friction, or the face of an elastic bar,
//! which the contact force moves, and the derivatives of a few
//! observed quantities with respect to A, B, N, C and M are compared with
//! (q(p + h) − q(p − h)) / 2h at three relative steps, h/p = 1e-5, 1e-6 and 1e-7, the
//! range where truncation and round-off are both below the tolerance (the full step
//! sweep is in `mpw verify`). The closest counts: a branch event within ±h (a point
//! crossing a cell face, a node passing the mass cutoff, first yield, a contact point
//! starting to slide) makes the quotient average two one-sided slopes; in the USF run one
//! sits 5e-7 p from A, and the quotient at 1e-5 is off by 1.8e-5 while the one at 1e-7
//! agrees to 1e-8; in the contact run one sits between 3e-6 and 1e-5 p above A, and σ_yy
//! of the bottom point is off by 3e-4 at 1e-5, by 5e-6 at 1e-6 and, from round-off, by
//! 5e-5 at 1e-7.

use materials::seeded::seeded;
use materials::{load_elasto_plastic, ElastoPlastic, Model};
use mpm_core::bar::BarEnd;
use mpm_core::discretize::{fill, Geometry};
use mpm_core::kinematics::Kinematics;
use mpm_core::shape::ShapeFunction;
use mpm_core::solver::{Scheme, Settings, Solver, Tangent};
use mpm_core::{RigidBody, SpringBc, VelocityBc};
use nalgebra::Vector2;
use std::sync::Arc;

const FREE: [&str; 5] = ["A", "B", "N", "C", "M"];

fn copper() -> ElastoPlastic {
    load_elasto_plastic(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../data/materials/ofhc_copper.toml"
    ))
    .unwrap()
}

/// What the bar lands on: a one-sided wall (a velocity condition on the grid), a rigid
/// half-space with penalty contact and Coulomb friction μ, or nothing: its bottom layer
/// of points is tied to where it started by springs of stiffness κ [N/m per m] along x
/// and y (eq. 12.1, as the cutting workpiece's base).
#[derive(Debug, Clone, Copy)]
enum Floor {
    Wall,
    Rigid {
        friction: f64,
    },
    Springs {
        stiffness: f64,
    },
    /// The half-space is the face of an elastic bar (a transmitter bar, module `bar`) of
    /// impedance Z [N s/m], which the contact force pushes down.
    Bar {
        friction: f64,
        impedance: f64,
    },
}

/// How a check runs: kinematics, scheme, shape functions and floor.
#[derive(Debug, Clone, Copy)]
struct Case {
    kinematics: Kinematics,
    scheme: Scheme,
    kernel: ShapeFunction,
    floor: Floor,
    /// Fraction of PIC in the velocity update.
    pic_fraction: f64,
}

impl Case {
    fn new(kinematics: Kinematics, scheme: Scheme) -> Case {
        Case {
            kinematics,
            scheme,
            kernel: ShapeFunction::Linear,
            floor: Floor::Wall,
            pic_fraction: 0.0,
        }
    }
}

/// A 2 mm by 6 mm bar at 150 m/s onto the floor y = 0, 0.5 mm cells, 2×2 points per cell.
fn bar(model: &ElastoPlastic, case: Case) -> Solver<2> {
    let h = 0.5e-3;
    let mut settings = Settings::<2>::new(case.kinematics, h);
    settings.scheme = case.scheme;
    settings.shape_function = case.kernel;
    settings.pic_fraction = case.pic_fraction;
    let mut s = Solver::new(settings);
    let points = fill(
        &Geometry::Box {
            min: Vector2::zeros(),
            max: Vector2::new(2e-3, 6e-3),
        },
        Vector2::repeat(h / 2.0),
        case.kinematics,
    );
    let block = s.add_body("bar", Arc::new(*model), &points, Vector2::new(0.0, -150.0));
    s.set_half_size(block, Vector2::repeat(h / 4.0));
    match case.floor {
        Floor::Wall => s.velocity_bcs.push(VelocityBc::wall(1, 0.0, true)),
        Floor::Rigid { friction } => s.add_rigid_body(rigid_floor(h, friction)),
        Floor::Bar {
            friction,
            impedance,
        } => {
            let mut floor = rigid_floor(h, friction);
            // a steel bar's wave speed, E_b A_b = Z c0
            let c0 = 5.0e3;
            let axis = Vector2::new(0.0, 1.0);
            floor.motion.bar = Some(BarEnd::new(axis, impedance * c0, c0, None));
            s.add_rigid_body(floor);
        }
        Floor::Springs { stiffness } => {
            let x0 = &s.particles.reference_position;
            let bottom = (0..x0.len()).filter(|&i| x0[i][1] < h / 2.0).collect();
            s.add_condition(Arc::new(SpringBc {
                particles: bottom,
                directions: [true, true],
                stiffness,
            }));
        }
    }
    s.initialize();
    s
}

/// The rigid half-space y < 0 with penalty contact and Coulomb friction μ = `friction`,
/// for points spaced h/2: κ = ω² m with ω = c / (h/2), as stiff as a layer of points
/// (c ≈ 4.7 km/s).
fn rigid_floor(h: f64, friction: f64) -> RigidBody<2> {
    let omega = 4.7e3 / (h / 2.0);
    let mut floor = RigidBody::half_space(
        "floor",
        Vector2::zeros(),
        Vector2::new(0.0, 1.0),
        omega * omega,
        friction,
    );
    floor.penalty_per_mass = true;
    floor
}

/// Observed after `steps` steps: the top outer point's height and radius, the bottom
/// outer point's radius, and F_yy and σ_yy of a point next to the wall.
fn observe(s: &Solver<2>) -> [f64; 5] {
    let p = &s.particles;
    let (top, bottom) = corners(s);
    [
        p.position[top][1],
        p.position[top][0],
        p.position[bottom][0],
        p.deformation[bottom][(1, 1)],
        p.stress[bottom][(1, 1)],
    ]
}

/// The top and bottom points of the outer column (by where they started).
fn corners(s: &Solver<2>) -> (usize, usize) {
    let x0 = &s.particles.reference_position;
    let nearest = |to: Vector2<f64>| {
        (0..x0.len())
            .min_by(|&a, &b| (x0[a] - to).norm().total_cmp(&(x0[b] - to).norm()))
            .unwrap()
    };
    (
        nearest(Vector2::new(2e-3, 6e-3)),
        nearest(Vector2::new(2e-3, 0.0)),
    )
}

fn run(model: &ElastoPlastic, case: Case, steps: usize) -> [f64; 5] {
    let mut s = bar(model, case);
    for _ in 0..steps {
        s.step().unwrap();
    }
    observe(&s)
}

fn check(case: Case, steps: usize) {
    let model = copper();
    let mut s = bar(&model, case);
    let (top, bottom) = corners(&s);
    let mut t = Tangent::new(&s, vec![seeded(&model, &FREE).unwrap()]).unwrap();
    for _ in 0..steps {
        s.step_with(&mut t).unwrap();
    }
    let plain = run(&model, case, steps);
    assert_eq!(observe(&s), plain, "the pass changed the run");
    let x_top = t.position(&s, top);
    let x_bottom = t.position(&s, bottom);
    let exact = [
        x_top[1],
        x_top[0],
        x_bottom[0],
        t.deformation(&s, bottom)[(1, 1)],
        t.stress(&s, bottom)[(1, 1)],
    ];
    let alpha = s.blocks[0].state[bottom].alpha;
    assert!(alpha > 0.05, "the wall layer yields (α = {alpha})");
    for (k, name) in FREE.iter().enumerate() {
        let p = model.param(name).unwrap();
        let at = |v: f64| {
            let m = model.map_params(|n, x| if n == *name { v } else { x });
            run(&m, case, steps)
        };
        let central = |h: f64| {
            let (up, down) = (at(p + h), at(p - h));
            std::array::from_fn::<f64, 5, _>(|q| (up[q] - down[q]) / (2.0 * h))
        };
        let steps_fd = [central(1e-5 * p), central(1e-6 * p), central(1e-7 * p)];
        for (q, e) in exact.iter().enumerate() {
            let d = e.eps[k];
            // scaled by the parameter and the quantity's largest scaled sensitivity
            let scale = (0..FREE.len())
                .map(|j| (e.eps[j] * model.param(FREE[j]).unwrap()).abs())
                .fold(0.0, f64::max);
            let error = |fd: &[f64; 5]| (d - fd[q]).abs() * p / scale;
            let error = steps_fd.iter().map(error).fold(f64::INFINITY, f64::min);
            eprintln!(
                "{case:?} q{q} d/d{name}: exact {d:.6e} fd {:.6e} rel {error:.1e}",
                steps_fd[0][q]
            );
            // round-off amplified through 300 steps is ~1e-5 of the largest scaled
            // sensitivity at h/p = 1e-7 (measured at most 8.9e-6, USF, the top point's
            // radius); a missing term of the derivative is off by 1e-2 or more
            assert!(
                error < 3e-5,
                "q{q} d/d{name}: exact {d:e}, fd {:?}",
                steps_fd.map(|f| f[q])
            );
        }
    }
}

#[test]
fn axisymmetric_musl_derivatives_match_central_differences() {
    check(Case::new(Kinematics::Axisymmetric, Scheme::Musl), 300);
}

#[test]
fn plane_strain_usf_derivatives_match_central_differences() {
    check(Case::new(Kinematics::PlaneStrain, Scheme::Usf), 300);
}

/// USL only while it is stable: this impact sets a free surface crossing node planes,
/// and plane strain USL leaves the energy balance after about 230 steps (axisymmetric:
/// 47), the derivatives growing with the instability before it.
#[test]
fn plane_strain_usl_derivatives_match_central_differences() {
    check(Case::new(Kinematics::PlaneStrain, Scheme::Usl), 100);
}

/// uGIMP: the weights of the box of nodes the fixed reference domain meets.
#[test]
fn plane_strain_ugimp_derivatives_match_central_differences() {
    let case = Case {
        kernel: ShapeFunction::UGimp,
        ..Case::new(Kinematics::PlaneStrain, Scheme::Musl)
    };
    check(case, 300);
}

/// A fraction of PIC in the velocity update: v ← (1 − β)(v + a Δt) + β ṽ.
#[test]
fn pic_blend_derivatives_match_central_differences() {
    let case = Case {
        pic_fraction: 0.05,
        ..Case::new(Kinematics::Axisymmetric, Scheme::Musl)
    };
    check(case, 300);
}

/// CPDI: the weights move with the domain's vertices and change with F.
#[test]
fn axisymmetric_cpdi_derivatives_match_central_differences() {
    let case = Case {
        kernel: ShapeFunction::Cpdi,
        ..Case::new(Kinematics::Axisymmetric, Scheme::Musl)
    };
    check(case, 300);
}

/// cpGIMP (the thesis's vertex form, the domain stretched by the diagonal of F).
#[test]
fn plane_strain_cpgimp_derivatives_match_central_differences() {
    let case = Case {
        kernel: ShapeFunction::CpGimp,
        ..Case::new(Kinematics::PlaneStrain, Scheme::Usf)
    };
    check(case, 300);
}

/// CPDI onto a rigid half-space with penalty contact and friction μ = 0.2: the points
/// of the bottom layer slide outwards, sticking near the axis.
#[test]
fn penalty_contact_with_friction_derivatives_match_central_differences() {
    let case = Case {
        kernel: ShapeFunction::Cpdi,
        floor: Floor::Rigid { friction: 0.2 },
        ..Case::new(Kinematics::Axisymmetric, Scheme::Musl)
    };
    check(case, 300);
}

/// CPDI onto the face of an elastic bar with friction μ = 0.1, the transmitter face of
/// an SHPB model: the face moves with the contact force and the contact springs, so its
/// displacement carries the derivatives on to the points. A bar as soft as Z = 20 N s/m
/// lets the face travel more than a tenth of the copper bar's own travel.
#[test]
fn a_face_on_an_elastic_bar_derivatives_match_central_differences() {
    let case = Case {
        kernel: ShapeFunction::Cpdi,
        floor: Floor::Bar {
            friction: 0.1,
            impedance: 20.0,
        },
        ..Case::new(Kinematics::Axisymmetric, Scheme::Musl)
    };
    let mut s = bar(&copper(), case);
    for _ in 0..300 {
        s.step().unwrap();
    }
    let face = s.rigid[0].body.motion.bar.as_ref().unwrap().displacement;
    let travel = 150.0 * s.time;
    assert!(
        face < -0.1 * travel,
        "the face moves: {face:e} m against the bar's {travel:e} m"
    );
    check(case, 300);
}

/// The bar in plane strain on a frictionless rigid half-space (μ = 0): a point in
/// contact is attached at its projection on the plane every step, so the penalty force
/// is normal and the points slide freely outwards.
#[test]
fn frictionless_penalty_contact_derivatives_match_central_differences() {
    let case = Case {
        kernel: ShapeFunction::Cpdi,
        floor: Floor::Rigid { friction: 0.0 },
        ..Case::new(Kinematics::PlaneStrain, Scheme::Musl)
    };
    check(case, 300);
}

/// Plane strain USF, the bar's bottom layer held by springs (κ = 2e11 N/m per m, a
/// point's mass times (c / (h/2))²): the spring forces change with the positions they
/// hold, df = −κ dx.
#[test]
fn spring_condition_derivatives_match_central_differences() {
    let case = Case {
        floor: Floor::Springs { stiffness: 2e11 },
        ..Case::new(Kinematics::PlaneStrain, Scheme::Usf)
    };
    check(case, 300);
}

/// 3D, a 1 mm × 1 mm × 3 mm JC copper block at 150 m/s onto the wall z = 0, tilted by
/// 20 m/s sideways, with the grid shifted every step (0.5 mm cells, 2×2×2 points per
/// cell, 120 steps): the derivatives of the top corner's position with respect to A, B
/// and C against central differences.
#[test]
fn solid_with_grid_shift_derivatives_match_central_differences() {
    use nalgebra::Vector3;
    let free = ["A", "B", "C"];
    let build = |model: &ElastoPlastic| {
        let h = 0.5e-3;
        let mut settings = Settings::<3>::new(Kinematics::Solid, h);
        settings.grid_shift = Some((Vector3::repeat(0.25 * h), 3));
        let mut s = Solver::new(settings);
        let points = fill(
            &Geometry::Box {
                min: Vector3::zeros(),
                max: Vector3::new(1e-3, 1e-3, 3e-3),
            },
            Vector3::repeat(h / 2.0),
            Kinematics::Solid,
        );
        s.add_body(
            "block",
            Arc::new(*model),
            &points,
            Vector3::new(20.0, 0.0, -150.0),
        );
        s.velocity_bcs.push(VelocityBc::wall(2, 0.0, true));
        s.initialize();
        s
    };
    let model = copper();
    let steps = 120;
    let mut s = build(&model);
    let top = s.nearest_particle(&Vector3::new(1e-3, 1e-3, 3e-3));
    let mut t = Tangent::new(&s, vec![seeded(&model, &free).unwrap()]).unwrap();
    for _ in 0..steps {
        s.step_with(&mut t).unwrap();
    }
    let exact = t.position(&s, top);
    assert!(
        s.blocks[0].state.iter().any(|st| st.alpha > 0.01),
        "the block yields"
    );
    for (k, name) in free.iter().enumerate() {
        let p = model.param(name).unwrap();
        let at = |v: f64| {
            let mut r = build(&model.map_params(|n, x| if n == *name { v } else { x }));
            for _ in 0..steps {
                r.step().unwrap();
            }
            r.particles.position[top]
        };
        let scale = (0..3).map(|c| exact[c].eps[k].abs()).fold(0.0, f64::max);
        let error = [1e-5, 1e-7].map(|rel| {
            let h = rel * p;
            let (up, down) = (at(p + h), at(p - h));
            (0..3)
                .map(|c| ((up[c] - down[c]) / (2.0 * h) - exact[c].eps[k]).abs() / scale)
                .fold(0.0, f64::max)
        });
        let error = error[0].min(error[1]);
        eprintln!("3D d(top)/d{name}: error {error:.1e} of {scale:.3e}");
        assert!(error < 3e-5, "d/d{name}: {error:e}");
    }
}

/// Two materials: the bar of `bar` (plane strain, USF) lands on a soft Neo-Hooke block
/// standing on the wall; the block does not depend on A (`seeded_where_present`), but
/// its points move with the bar's: the top of the block against central differences.
#[test]
fn a_body_of_another_material_carries_the_derivatives_it_feels() {
    use materials::seeded::seeded_where_present;
    use materials::{AnyModel, NeoHooke};
    let anvil = AnyModel::NeoHooke(NeoHooke::new(20e9, 0.3, 3000.0));
    let build = |model: &ElastoPlastic| {
        let mut s = bar(model, Case::new(Kinematics::PlaneStrain, Scheme::Usf));
        // the bar starts 2 mm up, the block fills the 2 mm below it
        for x in &mut s.particles.position {
            x[1] += 2e-3;
        }
        s.particles
            .reference_position
            .clone_from(&s.particles.position);
        let h = 0.5e-3;
        let points = fill(
            &Geometry::Box {
                min: Vector2::zeros(),
                max: Vector2::new(2e-3, 2e-3),
            },
            Vector2::repeat(h / 2.0),
            Kinematics::PlaneStrain,
        );
        s.add_body("anvil", Arc::new(anvil), &points, Vector2::zeros());
        s.initialize();
        s
    };
    let model = copper();
    let steps = 200;
    let mut s = build(&model);
    let top = s.blocks[1].range.clone().max_by(|&a, &b| {
        let (x, y) = (&s.particles.position[a], &s.particles.position[b]);
        (x[1] + x[0]).total_cmp(&(y[1] + y[0]))
    });
    let top = top.unwrap();
    let free = ["A"];
    let seeded = vec![
        seeded(&model, &free).unwrap(),
        seeded_where_present(&anvil, &free),
    ];
    let mut t = Tangent::new(&s, seeded).unwrap();
    for _ in 0..steps {
        s.step_with(&mut t).unwrap();
    }
    let exact = t.position(&s, top)[1].eps[0];
    let a = model.param("A").unwrap();
    let at = |v: f64| {
        let mut r = build(&model.map_params(|n, x| if n == "A" { v } else { x }));
        for _ in 0..steps {
            r.step().unwrap();
        }
        r.particles.position[top][1]
    };
    let error = [1e-5, 1e-7].map(|rel| {
        let h = rel * a;
        ((at(a + h) - at(a - h)) / (2.0 * h) / exact - 1.0).abs()
    });
    assert!(exact.abs() * a > 1e-7, "the block feels A: {} m", exact * a);
    assert!(error[0].min(error[1]) < 3e-5, "{exact:e}: {error:?}");
}

#[test]
fn a_kernel_the_pass_does_not_carry_is_refused_with_the_reason() {
    let model = copper();
    let case = Case {
        kernel: ShapeFunction::CpGimpAnalytic,
        ..Case::new(Kinematics::PlaneStrain, Scheme::Musl)
    };
    let e = Tangent::new(&bar(&model, case), vec![seeded(&model, &FREE).unwrap()])
        .err()
        .unwrap();
    assert!(e.to_string().contains("cpgimp-analytic"), "{e}");
    let e = Tangent::new(
        &bar(&model, Case::new(Kinematics::PlaneStrain, Scheme::Musl)),
        vec![seeded(&model, &["E"]).unwrap()],
    )
    .err()
    .unwrap();
    assert!(e.to_string().contains("wave speed"), "{e}");
}

/// The pass's transfers sum by slabs of node rows, each in index order: one thread and
/// two give the same derivatives to the bit (CPDI, whose lists reach two cells' nodes, and
/// penalty contact with friction).
#[test]
fn derivatives_are_the_same_on_one_thread_and_two() {
    let model = copper();
    let cpdi = Case {
        kernel: ShapeFunction::Cpdi,
        ..Case::new(Kinematics::Axisymmetric, Scheme::Musl)
    };
    let contact = Case {
        floor: Floor::Rigid { friction: 0.2 },
        ..Case::new(Kinematics::PlaneStrain, Scheme::Usf)
    };
    for case in [cpdi, contact] {
        let derivatives = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| {
                let mut s = bar(&model, case);
                let mut t = Tangent::new(&s, vec![seeded(&model, &FREE).unwrap()]).unwrap();
                for _ in 0..200 {
                    s.step_with(&mut t).unwrap();
                }
                let n = s.particles.len();
                let eps = |i: usize| {
                    let (x, sigma) = (t.position(&s, i), t.stress(&s, i));
                    let mut all: Vec<f64> = x.iter().flat_map(|d| d.eps.data.0[0]).collect();
                    all.extend(sigma.iter().flat_map(|d| d.eps.data.0[0]));
                    all
                };
                (0..n).flat_map(eps).collect::<Vec<f64>>()
            })
        };
        let (one, two) = (derivatives(1), derivatives(2));
        assert!(
            one.iter().any(|d| *d != 0.0),
            "{case:?}: the pass carries something"
        );
        assert!(
            one.iter()
                .zip(&two)
                .all(|(a, b)| a.to_bits() == b.to_bits()),
            "{case:?}: one and two threads differ"
        );
    }
}
