//! The next-experiment ranking checked by refits: SHPB records in one rate band (as the
//! 945 set) leave A and C confounded; of two candidate tests, the one `design::rank` puts
//! first must shrink the scatter of the refitted parameters over noise seeds more than the
//! one it puts last.

use fitting::fit::levels::model::Material;
use fitting::fit::objective::Block;
use fitting::fit::optimize::run::{run_fit, Optimizer};
use fitting::fit::params::FreeParam;
use fitting::fit::sets::fit_set::FitSet;
use fitting::fit::statistics::design::{rank, CandidateTest};
use fitting::fit::synthetic::synth::gaussian;
use materials::material::Model;
use rand::SeedableRng;
use std::path::Path;

const FREE: [&str; 4] = ["A", "B", "N", "C"];
/// Noise: 1 % of each record's peak.
const NOISE: f64 = 0.01;
const BAND: [CandidateTest; 2] = [
    CandidateTest::Shpb {
        rate: 2000.0,
        temperature: 293.15,
    },
    CandidateTest::Shpb {
        rate: 2600.0,
        temperature: 293.15,
    },
];

fn truth() -> Material {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/materials");
    let m = materials::load_elasto_plastic(dir.join("steel_945.toml")).unwrap();
    m.map_params(|n, v| match n {
        "A" => 400e6,
        "B" => 500e6,
        "N" => 0.4,
        "C" => 0.02,
        _ => v,
    })
}

/// `test` at the truth with noise from `rng`.
fn noisy(test: &CandidateTest, m: &Material, rng: &mut rand_pcg::Pcg64) -> Block {
    let mut block = test.block(m).unwrap();
    let peak = block.measured.iter().fold(0.0f64, |a, y| a.max(y.abs()));
    for y in &mut block.measured {
        *y += NOISE * peak * gaussian(rng);
    }
    block
}

/// The free parameters refitted to `blocks`.
fn refit(m: &Material, blocks: Vec<Block>) -> Vec<f64> {
    let params = vec![
        FreeParam::new("A", 100e6, 2000e6, 600e6).unwrap(),
        FreeParam::new("B", 10e6, 4000e6, 600e6).unwrap(),
        FreeParam::new("N", 0.05, 1.5, 0.4).unwrap(),
        FreeParam::new("C", 0.0, 0.2, 0.05).unwrap(),
    ];
    let set = FitSet {
        ftol: 1e-10,
        ..FitSet::in_memory("design check", *m, params, blocks)
    };
    let fit = run_fit(&set, Optimizer::LmExact, &|_| {
        std::ops::ControlFlow::Continue(())
    })
    .unwrap();
    FREE.iter()
        .map(|n| fit.material.param(n).unwrap())
        .collect()
}

/// Sample standard deviation of each parameter over the refits, relative to the truth.
fn scatter(fits: &[Vec<f64>], m: &Material) -> Vec<f64> {
    (0..FREE.len())
        .map(|k| {
            let n = fits.len() as f64;
            let mean = fits.iter().map(|f| f[k]).sum::<f64>() / n;
            let var = fits.iter().map(|f| (f[k] - mean).powi(2)).sum::<f64>() / (n - 1.0);
            var.sqrt() / m.param(FREE[k]).unwrap()
        })
        .collect()
}

#[test]
fn the_test_ranked_first_shrinks_the_refit_scatter_more_than_the_last() {
    let m = truth();
    let candidates = [
        CandidateTest::Shpb {
            rate: 3000.0,
            temperature: 293.15,
        },
        CandidateTest::Tensile {
            rate: 1e-3,
            temperature: 293.15,
        },
    ];
    let mut rng = rand_pcg::Pcg64::seed_from_u64(1);
    let base: Vec<Block> = BAND.iter().map(|t| noisy(t, &m, &mut rng)).collect();
    let (now, ranked) = rank(&base.iter().collect::<Vec<_>>(), &m, &FREE, &candidates).unwrap();
    let (first, last) = (ranked[0].test, ranked[1].test);
    assert_eq!(
        first,
        candidates[1],
        "ranked {:?}",
        ranked
            .iter()
            .map(|r| (r.test, r.shrink))
            .collect::<Vec<_>>()
    );
    assert!(
        now.worst_pair.2.abs() > 0.9,
        "A and C confounded in one band: {:?}",
        now.worst_pair
    );
    let seeds = 8;
    let mut with = |test: CandidateTest| -> Vec<f64> {
        let fits: Vec<Vec<f64>> = (0..seeds)
            .map(|_| {
                let mut blocks: Vec<Block> = BAND.iter().map(|t| noisy(t, &m, &mut rng)).collect();
                blocks.push(noisy(&test, &m, &mut rng));
                refit(&m, blocks)
            })
            .collect();
        scatter(&fits, &m)
    };
    let (s_first, s_last) = (with(first), with(last));
    let geometric = |s: &[f64]| s.iter().map(|x| x.ln()).sum::<f64>() / s.len() as f64;
    for r in &ranked {
        let relative: Vec<f64> = (r.after.std_errors.iter().zip(FREE))
            .map(|(se, n)| se / m.param(n).unwrap())
            .collect();
        eprintln!(
            "expected relative standard errors with {}: {relative:?} (shrink {:.3})",
            r.test, r.shrink
        );
    }
    eprintln!("relative scatter of A, B, N, C over {seeds} seeds: with {first}: {s_first:?}; with {last}: {s_last:?}");
    assert!(
        geometric(&s_first) < geometric(&s_last),
        "with {first}: {s_first:?}, with {last}: {s_last:?}"
    );
    assert!(s_first[3] < 0.5 * s_last[3], "C: {s_first:?} vs {s_last:?}");
}
