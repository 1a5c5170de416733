//! Perceptually uniform colour maps (matplotlib's viridis and inferno, sampled at tenths and
//! interpolated linearly in RGB; the error against the full 256-entry tables is invisible).

use plotters::style::RGBColor;

/// A sequential, perceptually uniform colour map.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ColorMap {
    /// Dark blue → green → yellow.
    #[default]
    Viridis,
    /// Black → purple → orange → pale yellow.
    Inferno,
}

const VIRIDIS: [(u8, u8, u8); 11] = [
    (68, 1, 84),
    (72, 36, 117),
    (65, 68, 135),
    (53, 95, 141),
    (42, 120, 142),
    (33, 145, 140),
    (34, 168, 132),
    (68, 191, 112),
    (122, 209, 81),
    (189, 223, 38),
    (253, 231, 37),
];

const INFERNO: [(u8, u8, u8); 11] = [
    (0, 0, 4),
    (22, 11, 57),
    (66, 10, 104),
    (106, 23, 110),
    (147, 38, 103),
    (188, 55, 84),
    (221, 81, 58),
    (243, 120, 25),
    (252, 165, 10),
    (246, 215, 70),
    (252, 255, 164),
];

impl ColorMap {
    /// The colour at t ∈ [0, 1] (clamped; NaN gives the lowest colour).
    pub fn rgb(self, t: f64) -> RGBColor {
        let table = match self {
            ColorMap::Viridis => &VIRIDIS,
            ColorMap::Inferno => &INFERNO,
        };
        let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
        let x = t * (table.len() - 1) as f64;
        let i = (x.floor() as usize).min(table.len() - 2);
        let f = x - i as f64;
        let lerp = |a: u8, b: u8| (f64::from(a) + f * (f64::from(b) - f64::from(a))).round() as u8;
        let (a, b) = (table[i], table[i + 1]);
        RGBColor(lerp(a.0, b.0), lerp(a.1, b.1), lerp(a.2, b.2))
    }
}
