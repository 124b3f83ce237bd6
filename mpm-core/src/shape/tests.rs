//! Every kernel at random points, domains and deformations, in 2D and 3D: partition of
//! unity, zero gradient sum, reproduction of linear fields; uGIMP/cpGIMP weights against
//! a quadrature of the hat over the domain and their gradients against central
//! differences; CPDI against the isoparametric quadrature form of eq. 10.4 (the thesis's
//! hexahedral route, reading §1.3); the linear weights for points without a domain.

use super::*;
use nalgebra::{SMatrix, Vector2, Vector3};

/// A small deterministic generator of uniform numbers in [0, 1).
struct Uniform(u64);

impl Uniform {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// One kernel evaluation: node lattice coordinates (cells from the point's cell corner),
/// weights and gradients [1/m].
struct Evaluation<const D: usize> {
    nodes: Vec<[i64; D]>,
    n: Vec<f64>,
    grad: Vec<SVector<f64, D>>,
}

fn evaluate<K: Kernel<D>, const D: usize>(
    xi: &SVector<f64, D>,
    half: &SVector<f64, D>,
    f: &Matrix3<f64>,
    inv_h: &SVector<f64, D>,
) -> Evaluation<D> {
    evaluate_point::<K, D>(&Point {
        xi: *xi,
        half,
        f,
        hex: None,
        inv_h,
    })
}

impl<const D: usize> Weights<D> for Evaluation<D> {
    fn push(&mut self, offset: [i64; D], n: f64, grad: SVector<f64, D>) {
        self.nodes.push(offset);
        self.n.push(n);
        self.grad.push(grad);
    }
}

/// The kernel's nodes at `point`, checked: each node once, no more than `Kernel::nodes`
/// of them, and all within the reach of the point's largest half-extent (from at most
/// `pad` nodes below the point's cell, `support` nodes from the lowest).
fn evaluate_point<K: Kernel<D>, const D: usize>(point: &Point<'_, D>) -> Evaluation<D> {
    let extent = K::extent(point);
    let reach = Reach::of(extent.max());
    let mut e = Evaluation {
        nodes: Vec::new(),
        n: Vec::new(),
        grad: Vec::new(),
    };
    K::evaluate(point, &mut e);
    assert!(
        e.nodes.len() <= K::nodes(&extent),
        "{} nodes",
        e.nodes.len()
    );
    for (k, m) in e.nodes.iter().enumerate() {
        assert!(!e.nodes[..k].contains(m), "node {m:?} twice");
    }
    for axis in 0..D {
        let lowest = e.nodes.iter().map(|m| m[axis]).min().unwrap();
        let highest = e.nodes.iter().map(|m| m[axis]).max().unwrap();
        let (pad, support) = (reach.pad as i64, reach.support as i64);
        let within = lowest >= -pad && highest - lowest < support && highest < support;
        assert!(within, "axis {axis}: {lowest}..{highest} beyond {reach:?}");
    }
    e
}

/// A random deformation gradient: a stretch of up to `stretch` per axis and a shear of up
/// to 0.5, det F > 0.
fn random_f(u: &mut Uniform, stretch: f64) -> Matrix3<f64> {
    loop {
        let f = Matrix3::from_fn(|i, j| match i == j {
            true => 0.3 + (stretch - 0.3) * u.next(),
            false => u.next() - 0.5,
        });
        if f.determinant() > 0.05 {
            return f;
        }
    }
}

/// Σ N = 1, Σ ∇N = 0, Σ N x_I = x_p and Σ x_I ⊗ ∇N_I = I, with x in cells.
fn check_consistency<const D: usize>(
    e: &Evaluation<D>,
    xi: &SVector<f64, D>,
    inv_h: &SVector<f64, D>,
    what: &str,
) {
    let sum: f64 = e.n.iter().sum();
    assert!((sum - 1.0).abs() < 1e-13, "{what}: Σ N = {sum}");
    let grad_sum: SVector<f64, D> = e.grad.iter().sum();
    assert!(
        grad_sum.norm() < 1e-12 * inv_h.norm(),
        "{what}: Σ ∇N = {grad_sum}"
    );
    for k in 0..D {
        let x: f64 = e.nodes.iter().zip(&e.n).map(|(m, n)| m[k] as f64 * n).sum();
        assert!(
            (x - xi[k]).abs() < 1e-13,
            "{what}: Σ N x = {x} vs {}",
            xi[k]
        );
        let g: SVector<f64, D> = e
            .nodes
            .iter()
            .zip(&e.grad)
            .map(|(m, g)| g * (m[k] as f64 / inv_h[k]))
            .sum();
        assert!(
            (g - SVector::<f64, D>::from_fn(|i, _| f64::from(i == k))).norm() < 1e-12,
            "{what}: Σ x ∇N = {g}"
        );
    }
}

fn consistency<const D: usize>(seed: u64) {
    let mut u = Uniform(seed);
    let inv_h = SVector::<f64, D>::from_fn(|k, _| 2.0 + k as f64);
    for trial in 0..300 {
        let xi = SVector::<f64, D>::from_fn(|_, _| u.next());
        // domains from a point (trial 0) to a full cell wide, stretched up to 4x
        let scale = if trial == 0 { 0.0 } else { 0.5 * u.next() };
        let half = SVector::<f64, D>::from_fn(|k, _| scale / inv_h[k]);
        let f = random_f(&mut u, 4.0);
        check_consistency(
            &evaluate::<Linear, D>(&xi, &half, &f, &inv_h),
            &xi,
            &inv_h,
            "linear",
        );
        check_consistency(
            &evaluate::<UGimp, D>(&xi, &half, &f, &inv_h),
            &xi,
            &inv_h,
            "ugimp",
        );
        check_consistency(
            &evaluate::<CpGimp, D>(&xi, &half, &f, &inv_h),
            &xi,
            &inv_h,
            "cpgimp",
        );
        let analytic = evaluate::<CpGimpAnalytic, D>(&xi, &half, &f, &inv_h);
        check_consistency(&analytic, &xi, &inv_h, "cpgimp-analytic");
        check_consistency(
            &evaluate::<Cpdi, D>(&xi, &half, &f, &inv_h),
            &xi,
            &inv_h,
            "cpdi",
        );
    }
}

#[test]
fn every_kernel_is_a_partition_of_unity_reproducing_linear_fields_2d() {
    consistency::<2>(3);
}

#[test]
fn every_kernel_is_a_partition_of_unity_reproducing_linear_fields_3d() {
    consistency::<3>(5);
}

/// A point without a domain gets the hat (linear) weights from every kernel.
#[test]
fn a_point_without_a_domain_gets_the_linear_weights() {
    let (xi, inv_h) = (Vector3::new(0.3, 0.7, 0.11), Vector3::new(2.0, 4.0, 0.5));
    let f = Matrix3::new(1.5, 0.2, 0.0, 0.1, 0.8, 0.0, 0.0, 0.3, 1.1);
    let reference = evaluate::<Linear, 3>(&xi, &Vector3::zeros(), &f, &inv_h);
    let check = |e: Evaluation<3>, what: &str| {
        for (m, (n, g)) in e.nodes.iter().zip(e.n.iter().zip(&e.grad)) {
            let k = reference.nodes.iter().position(|r| r == m);
            let (rn, rg) = k.map_or((0.0, Vector3::zeros()), |k| {
                (reference.n[k], reference.grad[k])
            });
            assert!(
                (n - rn).abs() < 1e-15 && (g - rg).norm() < 1e-14,
                "{what} at {m:?}"
            );
        }
    };
    check(
        evaluate::<UGimp, 3>(&xi, &Vector3::zeros(), &f, &inv_h),
        "ugimp",
    );
    check(
        evaluate::<CpGimp, 3>(&xi, &Vector3::zeros(), &f, &inv_h),
        "cpgimp",
    );
    check(
        evaluate::<CpGimpAnalytic, 3>(&xi, &Vector3::zeros(), &f, &inv_h),
        "cpgimp-analytic",
    );
    check(
        evaluate::<Cpdi, 3>(&xi, &Vector3::zeros(), &f, &inv_h),
        "cpdi",
    );
}

/// The GIMP factor of node m is the hat averaged over the domain: a 2000-point midpoint
/// rule of (1/2l) ∫ S(x − m) dx per axis, for half-widths up to 2.5 cells (cpGIMP under
/// stretch); the gradients against central differences of the weights in x_p; analytic
/// cpGIMP with F = I is uGIMP.
#[test]
fn gimp_weights_average_the_hat_and_their_gradients_are_the_derivatives() {
    let mut u = Uniform(11);
    let inv_h = nalgebra::Vector2::new(2.0, 5.0);
    for _ in 0..200 {
        let xi = nalgebra::Vector2::new(u.next(), u.next());
        let half = nalgebra::Vector2::new(0.5 * u.next() / inv_h[0], 0.5 * u.next() / inv_h[1]);
        let f = Matrix3::from_diagonal(&Vector3::new(
            0.5 + 4.5 * u.next(),
            0.5 + 4.5 * u.next(),
            1.0,
        ));
        let e = evaluate::<CpGimpAnalytic, 2>(&xi, &half, &f, &inv_h);
        let l: [f64; 2] = std::array::from_fn(|k| half[k] * f[(k, k)] * inv_h[k]);
        for (m, n) in e.nodes.iter().zip(&e.n) {
            let average: f64 = (0..2)
                .map(|k| {
                    let samples = 2000;
                    (0..samples)
                        .map(|s| {
                            let x = xi[k] - l[k] + 2.0 * l[k] * (s as f64 + 0.5) / samples as f64;
                            (1.0 - (x - m[k] as f64).abs()).max(0.0)
                        })
                        .sum::<f64>()
                        / samples as f64
                })
                .product();
            assert!((n - average).abs() < 2e-6, "{n} vs {average}");
        }
        for j in 0..2 {
            let d = 1e-6;
            let shifted = |s: f64| {
                let mut x = xi;
                x[j] += s;
                evaluate::<CpGimpAnalytic, 2>(&x, &half, &f, &inv_h)
            };
            let (up, down) = (shifted(d), shifted(-d));
            if up.nodes != e.nodes || down.nodes != e.nodes {
                continue; // the stencil moved: compare only within one stencil
            }
            for m in 0..e.n.len() {
                let fd = (up.n[m] - down.n[m]) / (2.0 * d) * inv_h[j];
                assert!(
                    (fd - e.grad[m][j]).abs() < 1e-6 * inv_h[j],
                    "{fd} vs {}",
                    e.grad[m][j]
                );
            }
        }
        let (g, ug) = (
            evaluate::<CpGimpAnalytic, 2>(&xi, &half, &Matrix3::identity(), &inv_h),
            evaluate::<UGimp, 2>(&xi, &half, &f, &inv_h),
        );
        assert_eq!(g.nodes, ug.nodes);
        assert_eq!(g.n, ug.n);
    }
}

/// `CpdiHex` at the domain `hex` carried by `f`.
fn evaluate_hex<const D: usize>(
    xi: &SVector<f64, D>,
    hex: &Hex<D>,
    f: &Matrix3<f64>,
    inv_h: &SVector<f64, D>,
) -> Evaluation<D> {
    evaluate_point::<CpdiHex, D>(&Point {
        xi: *xi,
        half: &SVector::zeros(),
        f,
        hex: Some(hex),
        inv_h,
    })
}

/// The weights of `a` and `b` agree node by node (to 1e-13, gradients to 1e-12 of |1/h|).
fn assert_same<const D: usize>(a: &Evaluation<D>, b: &Evaluation<D>, inv_h: &SVector<f64, D>) {
    for (node, (n, g)) in b.nodes.iter().zip(b.n.iter().zip(&b.grad)) {
        let k = a.nodes.iter().position(|m| m == node);
        let (an, ag) = k.map_or((0.0, SVector::zeros()), |k| (a.n[k], a.grad[k]));
        assert!((an - n).abs() < 1e-13, "{node:?}: {an} vs {n}");
        assert!(
            (ag - g).norm() < 1e-12 * inv_h.norm(),
            "{node:?}: {ag} vs {g}"
        );
    }
    let (sa, sb) = (a.n.iter().sum::<f64>(), b.n.iter().sum::<f64>());
    assert!((sa - sb).abs() < 1e-13, "nodes missing: Σ N {sa} vs {sb}");
}

/// The vertices of the box of half-widths `half` deformed by `f` (order of `shape::hex`).
fn deformed_box<const D: usize>(half: &SVector<f64, D>, f: &Matrix3<f64>) -> Vec<SVector<f64, D>> {
    let r = SMatrix::<f64, D, D>::from_fn(|i, k| f[(i, k)] * half[k]);
    (0..corners(D))
        .map(|j| r * SVector::<f64, D>::from_fn(|k, _| if (j >> k) & 1 == 1 { 1.0 } else { -1.0 }))
        .collect()
}

/// A box of random half-widths with every vertex moved by up to `jitter` of them.
fn distorted_box<const D: usize>(
    u: &mut Uniform,
    inv_h: &SVector<f64, D>,
    jitter: f64,
) -> Vec<SVector<f64, D>> {
    let half = SVector::<f64, D>::from_fn(|k, _| (0.1 + 0.4 * u.next()) / inv_h[k]);
    deformed_box(&half, &Matrix3::identity())
        .into_iter()
        .map(|x| x + SVector::<f64, D>::from_fn(|k, _| jitter * (2.0 * u.next() - 1.0) * half[k]))
        .collect()
}

/// The numerical quadrature of eq. 10.4 (`Hex`) against the closed form of `Cpdi`, where
/// both apply: on the deformed parallelepiped itself (F = I), and on the reference box
/// carried by F.
fn hex_against_closed_form<const D: usize>(seed: u64) {
    let mut u = Uniform(seed);
    let inv_h = SVector::<f64, D>::from_fn(|k, _| 2.0 + k as f64);
    for _ in 0..100 {
        let xi = SVector::<f64, D>::from_fn(|_, _| u.next());
        let half = SVector::<f64, D>::from_fn(|k, _| (0.05 + 0.45 * u.next()) / inv_h[k]);
        let f = random_f(&mut u, 3.0);
        let closed = evaluate::<Cpdi, D>(&xi, &half, &f, &inv_h);
        let (centre, current) = Hex::new(&deformed_box(&half, &f)).unwrap();
        assert!(centre.norm() < 1e-15 / inv_h.min());
        assert_same(
            &evaluate_hex(&xi, &current, &Matrix3::identity(), &inv_h),
            &closed,
            &inv_h,
        );
        assert_same(
            &evaluate_hex(&xi, &Hex::boxed(&half), &f, &inv_h),
            &closed,
            &inv_h,
        );
    }
}

#[test]
fn cpdi_closed_form_equals_the_quadrature_of_eq_10_4() {
    hex_against_closed_form::<2>(17);
    hex_against_closed_form::<3>(19);
}

/// On distorted (non-parallel) domains: partition of unity and linear reproduction about
/// the centroid, and the reference quadrature carried by F equals the quadrature of the
/// domain deformed by F.
fn distorted_hex<const D: usize>(seed: u64) {
    let mut u = Uniform(seed);
    let inv_h = SVector::<f64, D>::from_fn(|k, _| 2.0 + k as f64);
    for _ in 0..100 {
        let xi = SVector::<f64, D>::from_fn(|_, _| u.next());
        let vertices = distorted_box(&mut u, &inv_h, 0.4);
        let (_, hex) = Hex::new(&vertices).unwrap();
        let f = random_f(&mut u, 3.0);
        let carried = evaluate_hex(&xi, &hex, &f, &inv_h);
        check_consistency(&carried, &xi, &inv_h, "cpdi-hex");
        let f_d = SMatrix::<f64, D, D>::from_fn(|i, k| f[(i, k)]);
        let moved: Vec<_> = vertices.iter().map(|x| f_d * x).collect();
        let (_, current) = Hex::new(&moved).unwrap();
        assert_same(
            &carried,
            &evaluate_hex(&xi, &current, &Matrix3::identity(), &inv_h),
            &inv_h,
        );
    }
}

#[test]
fn cpdi_on_distorted_domains_is_consistent_and_follows_f() {
    distorted_hex::<2>(29);
    distorted_hex::<3>(31);
}

/// Vertices in the wrong order fold the map: a diagnosed error, not weights.
#[test]
fn a_folded_domain_is_refused() {
    let mut square = deformed_box(&Vector2::new(1.0, 1.0), &Matrix3::identity());
    square.swap(2, 3);
    let e = Hex::new(&square).unwrap_err();
    assert!(e.det_j <= 0.0, "{e}");
    assert!(e.to_string().contains("wrong order"), "{e}");
}

/// cpGIMP's vertex form is CPDI of the shear-free part of F.
#[test]
fn cpgimp_is_cpdi_without_shear() {
    let mut u = Uniform(23);
    let inv_h = Vector3::new(2.0, 3.0, 4.0);
    for _ in 0..50 {
        let xi = Vector3::new(u.next(), u.next(), u.next());
        let half = Vector3::new(0.2 / inv_h[0], 0.1 / inv_h[1], 0.25 / inv_h[2]);
        let f = random_f(&mut u, 5.0);
        let diagonal = Matrix3::from_diagonal(&f.diagonal());
        let (a, b) = (
            evaluate::<CpGimp, 3>(&xi, &half, &f, &inv_h),
            evaluate::<Cpdi, 3>(&xi, &half, &diagonal, &inv_h),
        );
        assert_eq!((a.nodes, a.n), (b.nodes, b.n));
    }
}

#[test]
fn shape_function_names_round_trip_and_a_wrong_one_lists_the_choices() {
    for name in ShapeFunction::NAMES {
        let s: ShapeFunction = name.parse().unwrap();
        assert_eq!(s.name(), name);
    }
    let e = "gimp".parse::<ShapeFunction>().unwrap_err();
    assert!(e.contains("\"cpdi\"") && e.contains("\"gimp\""), "{e}");
}

#[test]
fn the_reach_holds_every_node_a_domain_meets() {
    assert_eq!(Reach::of(0.0), Reach { support: 2, pad: 0 });
    assert_eq!(Reach::of(0.5), Reach { support: 3, pad: 1 });
    assert_eq!(Reach::of(0.25), Reach { support: 3, pad: 1 });
    assert_eq!(Reach::of(1.2), Reach { support: 5, pad: 2 });
    assert_eq!(Reach::box_nodes(&Vector3::new(0.25, 1.2, 0.0)), 3 * 5 * 2);
}

/// A CPDI domain stretched 24× along a sheared diagonal (the bottom layer of the 3D truss)
/// reaches only the nodes of its vertices' cells, at most 4³ = 64, and its weights stay
/// consistent; so does a mildly deformed one, whose vertices' cells share nodes.
#[test]
fn a_far_stretched_cpdi_domain_reaches_at_most_the_nodes_of_its_vertices_cells() {
    let mut u = Uniform(37);
    let inv_h = Vector3::new(2.0, 2.0, 2.0);
    let half = Vector3::repeat(0.25 / 2.0);
    for (stretch, shear) in [(24.0, 3.0), (24.0, 0.0), (1.3, 0.2)] {
        for _ in 0..50 {
            let xi = Vector3::new(u.next(), u.next(), u.next());
            let f = Matrix3::new(1.0, 0.0, shear, 0.0, 1.0, shear, 0.0, 0.0, stretch);
            let e = evaluate::<Cpdi, 3>(&xi, &half, &f, &inv_h);
            assert!(e.nodes.len() <= 64, "{}", e.nodes.len());
            check_consistency(&e, &xi, &inv_h, "stretched cpdi");
            let extent = Cpdi::extent(&Point {
                xi,
                half: &half,
                f: &f,
                hex: None,
                inv_h: &inv_h,
            });
            if stretch > 2.0 {
                assert!(Reach::box_nodes(&extent) > 64, "{extent}");
            } else {
                assert!(e.nodes.len() <= 27, "{}", e.nodes.len());
            }
        }
    }
}
