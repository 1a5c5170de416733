//! `woodpile cells`: the unit-cell catalogue of the paper's Table 1 (docs/physics.md §3).

use super::Context;
use crate::CliError;
use woodpile::model::TABLE1_LENGTHS_MM;
use woodpile::UnitCell;

/// Arguments of `woodpile cells`.
#[derive(Debug, Clone, clap::Args)]
pub struct Args {
    /// Also draw the effective-mass curves (paper Fig. 3) into this directory (PNG and SVG).
    #[arg(long, value_name = "DIR")]
    pub plot: Option<std::path::PathBuf>,
}

fn khz(values: &[f64]) -> String {
    values
        .iter()
        .map(|f| format!("{:.2}", f * 1e-3))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The catalogue as a text table.
pub fn table() -> Result<String, CliError> {
    let mut out = format!(
        "{:>8}  {:>12}  {:>7}  {:>15}  {:>15}  {:>15}  {}\n",
        "rod [mm]",
        "total m [g]",
        "M [g]",
        "m_j [g]",
        "k_j [kN/mm]",
        "f_j [kHz]",
        "F_j [kHz] / negative-mass bands [kHz]"
    );
    for l in TABLE1_LENGTHS_MM {
        let cell = UnitCell::table1(l)?;
        let m: Vec<String> = cell
            .resonators
            .iter()
            .map(|r| format!("{:.3}", r.mass_kg * 1e3))
            .collect();
        let k: Vec<String> = cell
            .resonators
            .iter()
            .map(|r| format!("{:.4}", r.stiffness_n_per_m * 1e-6))
            .collect();
        let bands: Vec<String> = cell
            .negative_mass_bands_hz()
            .iter()
            .map(|(lo, hi)| format!("{:.2}-{:.2}", lo * 1e-3, hi * 1e-3))
            .collect();
        out.push_str(&format!(
            "{:>8}  {:>12.3}  {:>7.3}  {:>15}  {:>15}  {:>15}  {}  ({})\n",
            l,
            cell.total_mass_kg() * 1e3,
            cell.primary_mass_kg * 1e3,
            m.join(", "),
            k.join(", "),
            khz(&cell.local_resonances_hz()),
            khz(&cell.free_resonances_hz()),
            bands.join(", ")
        ));
    }
    Ok(out)
}

/// Prints the catalogue.
pub fn run(args: &Args, ctx: &Context) -> Result<(), CliError> {
    print!("{}", table()?);
    if let Some(dir) = &args.plot {
        let files = woodpile_plot::dirs::cells_figures(dir)?;
        if !ctx.quiet {
            println!("wrote {} files to {}", files.len(), dir.display());
        }
    }
    Ok(())
}
