#[path = "../tests/claims/fit_common.rs"]
mod fit_common;
use fit_common::*;
fn main() {
    let mut problem = problem(synthetic(0.0, 0), &model);
    if std::env::args().count() > 1 { problem.parameters[0].initial = 0.7; }
    let x0 = problem.initial_values();
    let r = woodpile::fit::residuals(&problem, &x0).unwrap();
    println!("m={} cost={}", r.len(), 0.5*r.iter().map(|v|v*v).sum::<f64>());
    let j = woodpile::fit::jacobian(&problem, &x0, 1e-7).unwrap();
    for c in &j { println!("col norm {:e}", c.iter().map(|v|v*v).sum::<f64>().sqrt()); }
    let rt = woodpile::fit::residuals(&problem, &TRUTH).unwrap();
    println!("cost at truth {}", 0.5*rt.iter().map(|v|v*v).sum::<f64>());
    let res = woodpile::fit::fit(&problem, &woodpile::fit::FitSettings { starts: 1, ..Default::default() }).unwrap();
    println!("{:?}", res.starts);
}
