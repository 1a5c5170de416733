//! Claim: each paper value is stated once, as a number, and the report's text is derived from it:
//! the text of every reference value reads back to the number it was made from (to the digits the
//! paper prints), and differences are computed from the numbers (percent of the paper's value, or
//! percentage points for fractions).

use woodpile_report::{self as study, PaperValue, Quantity};

const ALL: [PaperValue; 13] = [
    study::RESONANT_TRANSMITTED,
    study::RESONANT_INCIDENT,
    study::RESONANT_RATIO,
    study::RIGID_TRANSMITTED,
    study::RIGID_INCIDENT,
    study::RIGID_RATIO,
    study::RESONANT_ADVANTAGE,
    study::RESONANT_RESTITUTION,
    study::RIGID_RESTITUTION,
    study::GAP_80MM,
    study::BLAST_40MM,
    study::BLAST_80MM,
    study::BLAST_OPTIMUM,
];

#[test]
fn text_reads_back_to_the_number() {
    for p in ALL {
        let text = p.text();
        let digits: String = text
            .chars()
            .filter(|c| c.is_ascii_digit() || *c == '.')
            .collect();
        let shown: f64 = digits.parse().unwrap();
        let si = match p.quantity {
            Quantity::ForceN | Quantity::Coefficient => shown,
            Quantity::Fraction => shown / 100.0,
            Quantity::DurationS => shown * 1e-3,
        };
        assert!(
            (si - p.value).abs() <= 1e-12 * p.value.abs().max(1.0),
            "{}: {text}",
            p.what
        );
        assert_eq!(text.starts_with('~'), p.approximate, "{text}");
    }
}

#[test]
fn differences_follow_from_the_numbers() {
    assert_eq!(
        study::RESONANT_TRANSMITTED.difference(28.5 * 1.1),
        "+10.0 %"
    );
    assert_eq!(study::RESONANT_RATIO.difference(0.209), "+3.0 pp");
    assert_eq!(study::RESONANT_RATIO.format(0.2), "20.0 %");
}
