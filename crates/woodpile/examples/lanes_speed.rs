//! Quick timing of simulate_many against simulate (one thread).
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use woodpile::*;

fn main() -> Result<()> {
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let chains: Vec<Chain> = (0..64)
        .map(|_| {
            let rods: Vec<u32> = (0..20)
                .map(|_| TABLE1_LENGTHS_MM[rng.random_range(0..7)])
                .collect();
            ChainBuilder::table1_rods(&rods, CellModel::Resonant)
                .unwrap()
                .build()
                .unwrap()
        })
        .collect();
    let ex = Excitation::Impact(Striker::paper());
    for method in [
        Method::Rk4 { time_step_s: 1e-7 },
        Method::Dopri5 {
            rtol: 1e-6,
            atol: 1e-12,
        },
        Method::for_peak_tolerance(1e-5)?,
    ] {
        let settings = RunSettings {
            method,
            sample_interval_s: 2e-3,
            ..RunSettings::paper_impact()
        };
        let t = std::time::Instant::now();
        for c in &chains {
            simulate(c, &ex, &settings, &mut ())?;
        }
        let scalar = t.elapsed().as_secs_f64() / chains.len() as f64;
        print!("{method:?}: scalar {:.3} ms", scalar * 1e3);
        let jobs: Vec<Job> = chains
            .iter()
            .map(|chain| Job {
                chain,
                excitation: &ex,
                settings: &settings,
            })
            .collect();
        let only: Option<usize> = std::env::args().nth(1).map(|a| a.parse().unwrap());
        for w in LaneWidth::ALL
            .into_iter()
            .filter(|w| only.is_none_or(|n| n == w.lanes()))
        {
            let t = std::time::Instant::now();
            let r = simulate_many(&jobs, w);
            assert!(r.iter().all(|r| r.is_ok()));
            let per = t.elapsed().as_secs_f64() / chains.len() as f64;
            print!("  {w:?} {:.3} ms ({:.2}x)", per * 1e3, scalar / per);
        }
        println!();
    }
    Ok(())
}
