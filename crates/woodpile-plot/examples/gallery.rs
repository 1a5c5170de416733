//! Renders every figure kind from real runs into a directory, to look at them:
//! `cargo run -p woodpile-plot --example gallery -- OUT_DIR`.

use std::path::{Path, PathBuf};
use woodpile::analysis::{
    contact_spectrum_map, energy_map, force_map, layer_by_layer, linspace, Spectrum,
    SpectrumSettings,
};
use woodpile::model::TABLE1_LENGTHS_MM;
use woodpile::{
    simulate, BlastProfile, CellModel, ChainBuilder, EffectiveMassCurve, Excitation, RunSettings,
    Striker, Trajectory, UnitCell, PAPER_OPTIMIZED_CHAIN_MM,
};
use woodpile_plot as plot;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = PathBuf::from(std::env::args().nth(1).unwrap_or_else(|| "gallery".into()));
    std::fs::create_dir_all(&out)?;
    let stem = |name: &str| out.join(name);

    // Impact on the optimised chain.
    let chain =
        ChainBuilder::table1_rods(&PAPER_OPTIMIZED_CHAIN_MM, CellModel::Resonant)?.build()?;
    let impact = Excitation::Impact(Striker::paper());
    let settings = RunSettings::paper_impact();
    let mut t = Trajectory::default();
    simulate(&chain, &impact, &settings, &mut t)?;
    let title = "20 resonant rods (paper blast optimum), impact 1.98 m/s";
    plot::force_map(&force_map(&t)?, title, Some("striker"), &stem("force_map"))?;
    plot::energy_map(
        &energy_map(&t)?,
        title,
        Some("striker"),
        &stem("energy_map"),
    )?;
    let n = chain.len();
    let series = [
        (0, "contact 0 (striker)"),
        (1, "contact 1"),
        (n, "contact N (wall)"),
    ]
    .map(|(c, l)| plot::Series::new(l, t.contact_force_n(c)));
    plot::force_histories(&t.times_s, &series, title, &stem("force_histories"))?;
    plot::chain_picture(
        &chain,
        "paper blast optimum (top to bottom)",
        Some("striker"),
        &stem("chain"),
    )?;
    draw_spectra(&t, &[], title, &stem("spectra"))?;

    draw_blast_and_effective_mass(&stem)?;

    // Layer-by-layer protocol.
    let p = layer_by_layer(&chain, &impact, &settings)?;
    plot::protocol_map(&p.wall_force_map, title, &stem("protocol_map"))?;
    let full = simulate(&chain, &impact, &settings, &mut ())?;
    plot::peaks_per_layer(
        &[
            plot::Series::new(
                "protocol: wall force of the first k rods",
                p.peak_wall_force_n,
            ),
            plot::Series::new(
                "full chain: contact k",
                full.contact_peak_forces_n[1..].to_vec(),
            ),
        ],
        title,
        "peak force [N]",
        &stem("protocol_peaks"),
    )?;

    // A made-up GA history.
    let points: Vec<plot::ConvergencePoint> = (0..60)
        .map(|g| plot::ConvergencePoint {
            generation: g,
            best: 28.0 + 60.0 * (-(g as f64) / 10.0).exp(),
            mean: 40.0 + 70.0 * (-(g as f64) / 15.0).exp(),
        })
        .collect();
    plot::convergence(
        &points,
        "transmitted force [N]",
        "BGA (synthetic data)",
        &stem("convergence"),
    )?;
    draw_lattice(&stem("interface_forces"), &stem("lattice_view"))?;
    println!("figures in {}", out.display());
    Ok(())
}

/// The lattice figures of `examples/lattice.toml` (3 × 3 rods, 4 layers, struck off centre).
fn draw_lattice(interfaces: &Path, view: &Path) -> Result<(), Box<dyn std::error::Error>> {
    use woodpile_io::lattice::{contacts_json, LatticeScenario};
    let toml = include_str!("../../../examples/lattice.toml");
    let resolved = LatticeScenario::parse(toml, "lattice.toml")?.resolve()?;
    let mut ode =
        woodpile::ode::LatticeOde::new(&resolved.lattice, &resolved.striker, resolved.at_m)?;
    let run = woodpile::simulate::simulate_lattice(&mut ode, &resolved.settings)?;
    let layout = plot::dirs::layout_of(&resolved.lattice, &contacts_json(&resolved));
    let t = &run.times_s;
    let windows = plot::dirs::interface_windows(t, (t[0], t[t.len() - 1]));
    let title = "3 × 3 rods, 4 layers, struck at (13, 0) mm";
    plot::interface_forces(
        &layout,
        t,
        &run.contact_forces_n,
        &windows,
        plot::MapColours::Auto,
        title,
        interfaces,
    )?;
    plot::lattice_view(&layout, &run.contact_peak_forces_n, title, view)?;
    Ok(())
}

fn draw_spectra(
    t: &Trajectory,
    bands: &[(f64, f64)],
    title: &str,
    stem: &Path,
) -> Result<(), Box<dyn std::error::Error>> {
    let n = t.n_elements;
    let settings = SpectrumSettings::default();
    let spectra: Vec<(String, Spectrum)> = [(0, "contact 0"), (1, "contact 1"), (n, "wall")]
        .iter()
        .map(|&(c, l)| {
            Ok((
                l.to_string(),
                Spectrum::of(&t.contact_force_n(c), 1e-6, &settings)?,
            ))
        })
        .collect::<Result<_, woodpile::Error>>()?;
    let refs: Vec<(String, &Spectrum)> = spectra.iter().map(|(l, s)| (l.clone(), s)).collect();
    plot::spectra(&refs, bands, title, 60e3, stem)?;
    Ok(())
}

/// The blast on 80 mm rods (spectra with bands, force and spectrum maps) and the catalogue's
/// effective mass.
fn draw_blast_and_effective_mass(
    stem: &dyn Fn(&str) -> PathBuf,
) -> Result<(), Box<dyn std::error::Error>> {
    // Blast on 80 mm rods: spectra with bands.
    let chain80 = ChainBuilder::table1_rods(&[80; 20], CellModel::Resonant)?.build()?;
    let blast = Excitation::Blast(BlastProfile::paper());
    let mut t80 = Trajectory::default();
    simulate(&chain80, &blast, &RunSettings::paper_blast(), &mut t80)?;
    let title80 = "20 × 80 mm resonant rods, Friedlander blast 200 N / 0.2 ms";
    let bands = UnitCell::table1(80)?.negative_mass_bands_hz();
    draw_spectra(&t80, &bands, title80, &stem("spectra_80mm_blast"))?;
    plot::force_map(
        &force_map(&t80)?,
        title80,
        Some("load"),
        &stem("force_map_80mm_blast"),
    )?;
    plot::spectrum_map(
        &contact_spectrum_map(&t80, &SpectrumSettings::default())?,
        title80,
        60e3,
        Some("load"),
        &stem("spectrum_map_80mm_blast"),
    )?;

    // Effective mass of the catalogue.
    let f = linspace(0.0, 60e3, 3000);
    let curves: Vec<(String, EffectiveMassCurve)> = TABLE1_LENGTHS_MM
        .iter()
        .map(|&l| {
            Ok((
                format!("{l} mm"),
                EffectiveMassCurve::of(&UnitCell::table1(l)?, &f),
            ))
        })
        .collect::<Result<_, woodpile::Error>>()?;
    plot::effective_mass(
        &curves[..3],
        "Effective mass, 20–40 mm rods (one resonator)",
        5.0,
        &stem("effective_mass_a"),
    )?;
    plot::effective_mass(
        &curves[3..],
        "Effective mass, 50–80 mm rods (two resonators)",
        5.0,
        &stem("effective_mass_b"),
    )?;
    Ok(())
}
