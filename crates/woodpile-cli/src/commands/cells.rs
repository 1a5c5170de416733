//! `woodpile cells`: the unit-cell catalogue of the paper's Table 1 (docs/physics.md §3), or
//! the cell of any rod derived from Timoshenko beam theory (`--rod`, docs/physics.md §13).

use super::Context;
use crate::CliError;
use woodpile::model::TABLE1_LENGTHS_MM;
use woodpile::UnitCell;
use woodpile_io::cells::{derive, DerivedCell, RodRequest};
use woodpile_io::scenario::ReductionSpec;

/// Arguments of `woodpile cells`.
#[derive(Debug, Clone, clap::Args)]
pub struct Args {
    /// Also draw the effective-mass curves (paper Fig. 3) into this directory (PNG and SVG).
    #[arg(long, value_name = "DIR")]
    pub plot: Option<std::path::PathBuf>,
    /// With --plot: damp every resonator at this ratio ζ and draw Re M_eff (docs/physics.md §14).
    #[arg(long, value_name = "ZETA", default_value_t = 0.0, requires = "plot")]
    pub resonator_ratio: f64,
    /// Derive the cell of a rod of this length, in mm, from Timoshenko beam theory instead of
    /// printing the catalogue.
    #[arg(long, value_name = "LENGTH_MM", allow_negative_numbers = true)]
    pub rod: Option<f64>,
    /// Outer diameter of the rod, in mm.
    #[arg(long, value_name = "MM", default_value_t = woodpile::defaults::ROD_DIAMETER_MM, requires = "rod")]
    pub diameter_mm: f64,
    /// Inner diameter of a tube, in mm (default: a solid rod).
    #[arg(long, value_name = "MM", requires = "rod")]
    pub inner_diameter_mm: Option<f64>,
    /// Material preset of the rod.
    #[arg(long, value_name = "NAME", default_value = woodpile::defaults::ELEMENT_MATERIAL, requires = "rod")]
    pub material: String,
    /// Number of resonators, 1–4 (default: one per centre-blocked mode below 38 kHz).
    #[arg(long, value_name = "L", requires = "rod")]
    pub modes: Option<usize>,
    /// Reduction: pole-zero (total mass, poles and zeros exact) or modal-mass.
    #[arg(
        long,
        value_name = "NAME",
        default_value = "pole-zero",
        requires = "rod"
    )]
    pub reduction: String,
    /// Print the derived cell as one JSON object.
    #[arg(long, requires = "rod")]
    pub json: bool,
}

/// The derived cell of `--rod`; errors name the flags.
fn derived(args: &Args, length_mm: f64) -> Result<DerivedCell, CliError> {
    let reduction = match args.reduction.as_str() {
        "pole-zero" => ReductionSpec::PoleZero,
        "modal-mass" => ReductionSpec::ModalMass,
        other => {
            return Err(CliError::invalid(
                "--reduction",
                other,
                "valid: pole-zero, modal-mass",
            ))
        }
    };
    let request = RodRequest {
        length_mm,
        diameter_mm: args.diameter_mm,
        inner_diameter_mm: args.inner_diameter_mm,
        material: args.material.clone(),
        modes: args.modes,
        reduction,
    };
    let flag = |k: &str| {
        match k {
            "diameter_mm" => "--diameter-mm",
            "inner_diameter_mm" => "--inner-diameter-mm",
            "material" => "--material",
            "cell.modes" => "--modes",
            _ => "--rod",
        }
        .to_string()
    };
    derive(&request, &flag)
}

/// `values` scaled by `scale`, each with `digits` decimals, separated by commas.
fn joined(values: impl IntoIterator<Item = f64>, scale: f64, digits: usize) -> String {
    let texts: Vec<String> = values
        .into_iter()
        .map(|x| {
            // A value below the last printed decimal keeps its significant digits.
            let v = x * scale;
            if v != 0.0 && v.abs() < 0.5 * 10f64.powi(-(digits as i32)) {
                format!("{v:.3e}")
            } else {
                format!("{v:.digits$}")
            }
        })
        .collect();
    texts.join(", ")
}

/// A derived cell as text.
fn derived_text(c: &DerivedCell) -> String {
    let list = |v: &[f64], digits: usize| joined(v.iter().copied(), 1.0, digits);
    let tube = if c.inner_diameter_mm > 0.0 {
        format!(" (tube, inner {} mm)", c.inner_diameter_mm)
    } else {
        String::new()
    };
    let r = &c.resonators;
    format!(
        "rod {} mm × {} mm{tube}, {}: {} resonator(s), {} reduction (docs/physics.md §13)\n\
         total mass {:.4} g, primary mass M {:.4} g\n\
         m_j [g]      {}\n\
         k_j [kN/mm]  {}\n\
         f_j [kHz]    {}   (rod centre-blocked: {})\n\
         F_j [kHz]    {}   (rod free-free symmetric: {})\n",
        c.length_mm,
        c.diameter_mm,
        c.material,
        r.len(),
        c.reduction,
        c.total_mass_g,
        c.primary_mass_g,
        joined(r.iter().map(|r| r.mass_g), 1.0, 4),
        joined(r.iter().map(|r| r.stiffness_kn_per_mm), 1.0, 4),
        joined(r.iter().map(|r| r.frequency_khz), 1.0, 2),
        list(&c.rod_centre_blocked_khz, 2),
        list(&c.free_resonances_khz, 2),
        list(&c.rod_free_free_khz, 2),
    )
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
        let r = &cell.resonators;
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
            joined(r.iter().map(|r| r.mass_kg), 1e3, 3),
            joined(r.iter().map(|r| r.stiffness_n_per_m), 1e-6, 4),
            joined(cell.local_resonances_hz(), 1e-3, 2),
            joined(cell.free_resonances_hz(), 1e-3, 2),
            bands.join(", ")
        ));
    }
    Ok(out)
}

/// Prints the catalogue, or the derived cell of `--rod`.
pub fn run(args: &Args, ctx: &Context) -> Result<(), CliError> {
    if let Some(length_mm) = args.rod {
        let cell = derived(args, length_mm)?;
        if args.json {
            let text = serde_json::to_string_pretty(&cell)
                .map_err(|e| CliError::invalid("--json", "", e.to_string()))?;
            crate::out::println(text)?;
        } else {
            crate::out::print(derived_text(&cell))?;
        }
        return Ok(());
    }
    crate::out::print(table()?)?;
    if let Some(dir) = &args.plot {
        let files = woodpile_plot::dirs::cells_figures(dir, args.resonator_ratio)?;
        if !ctx.quiet {
            crate::out::println(format_args!(
                "wrote {} files to {}",
                files.len(),
                dir.display()
            ))?;
        }
    }
    Ok(())
}
