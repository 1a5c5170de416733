//! The effective mass of the Table 1 rods (paper Fig. 3): M_eff(ω)/M_total, negative between
//! each local resonance and the next zero.

use super::doc::Doc;
use super::study::Setup;
use crate::Error;
use std::path::PathBuf;
use woodpile_plot::dirs::cells_figures;

/// The two figures: 20–40 mm rods, then 50–80 mm rods.
pub struct Cells {
    /// The files of both figures.
    pub files: Vec<PathBuf>,
}

/// Draws the effective-mass curves of the catalogue.
pub fn run(s: &Setup) -> Result<Cells, Error> {
    s.bar.stage("effective-mass curves");
    let files = cells_figures(&s.figs, 0.0)?;
    s.bar.inc(1);
    Ok(Cells { files })
}

impl Cells {
    /// The section.
    pub fn write(&self, doc: &mut Doc) {
        let ef = &self.files;
        doc.h2("Effective mass of the rods (Fig. 3)");
        doc.p("M_eff(ω)/M_total of the Table 1 unit cells (paper Eq. 3, 4): negative between each local resonance f_j and the next zero F_j (shaded).");
        doc.figure(&ef[..2.min(ef.len())], "Effective mass of the 20, 30, 40 mm rods (one resonator each) (Fig. 3 a). What to see: M_eff/M_total is negative (shaded) above each rod's local resonance, in bands that move down as the rods get longer.",
        );
        if ef.len() > 2 {
            doc.figure(&ef[2..], "Effective mass of the 50–80 mm rods (two resonators each) (Fig. 3 b). What to see: two negative-mass bands per rod (first and third bending modes), lower for longer rods.",
            );
        }
    }
}
