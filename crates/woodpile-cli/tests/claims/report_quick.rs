//! Claim: `woodpile report --quick --out DIR` runs everything the paper's figures need (impact on
//! homogeneous chains, resonant and rigid GAs, NSGA-II's force–mass front with the resonant
//! optimum placed on it, the layer-by-layer protocol, the blast cases, the
//! GAs over derived cells, the effective-mass curves) and writes report.md, a self-contained report.html and every figure it
//! names; a second run reuses the cached GA results; an output location that cannot be written
//! is refused with exit code 2 and leaves no report behind.
//! No tolerance: file existence, references and exit codes are exact.

use crate::common;

use std::path::Path;

/// The figure paths (`figures/….png`) a Markdown report names in `![…](…)` links.
fn figures_named(md: &str) -> Vec<String> {
    let mut out = Vec::new();
    for line in md.lines().filter(|l| l.starts_with("![")) {
        if let Some(start) = line.rfind("](") {
            let rest = &line[start + 2..];
            if let Some(end) = rest.find(')') {
                out.push(rest[..end].to_string());
            }
        }
    }
    out
}

#[test]
fn quick_report_writes_every_file_it_names() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("report");
    let o = common::run_in(
        tmp.path(),
        &["report", "--quick", "--out", out.to_str().unwrap(), "-q"],
    );
    assert!(
        o.status.success(),
        "report failed: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    assert!(!html.is_empty());
    let figures = figures_named(&md);
    // Impact (4 chains × 5 + 1), optima (2 × 5: Fig. 6 is their energy maps), the force–mass
    // front and its hypervolume (2), protocol (2), blast (4 × 4 + 1 + the F0 × Td sweep), the
    // fine design space's optimum (1), Fig. 3 (2).
    assert_eq!(figures.len(), 57, "figures named: {figures:?}");
    assert!(figures.contains(&"figures/pareto_force_mass.png".to_string()));
    // The front section says in numbers where the breeder optimum sits.
    let section = &md[md
        .find("## Force against mass")
        .expect("the front's section")..];
    assert!(
        section.contains("The breeder GA's resonant optimum (")
            && (section.contains("No design of the front dominates it")
                || section.contains("A design of the front dominates it")),
        "{}",
        &section[..section.len().min(2000)]
    );
    for f in &figures {
        let png = out.join(f);
        assert!(png.is_file(), "{f} is named in report.md but missing");
        assert!(
            std::fs::metadata(&png).unwrap().len() > 1000,
            "{f} is empty"
        );
        let svg = out.join(f.trim_end_matches(".png").to_string() + ".svg");
        assert!(svg.is_file(), "{} missing", svg.display());
        assert!(
            html.contains(&format!("data-file=\"{f}\"")),
            "report.html does not embed {f}"
        );
    }
    assert_eq!(
        html.matches("<img src=\"data:image/svg+xml;base64,")
            .count(),
        figures.len()
    );
    // The comparison table carries the paper's numbers beside ours.
    for paper in ["28.5 N", "159.6 N", "85.5 N", "0.2570", "0.4991", "8.3 %"] {
        assert!(
            md.contains(paper),
            "comparison table lacks the paper's {paper}"
        );
    }
    // Four GA results in the cache (resonant, rigid, derived cells at 7 and 61 lengths) and the
    // NSGA-II front; a rerun reuses them.
    let cached = std::fs::read_dir(out.join("cache")).unwrap().count();
    assert_eq!(cached, 5);
    // The rerun without --quiet, its stderr a pipe: one progress line per stage (see
    // progress_lines for the format).
    let o = common::run_in(
        tmp.path(),
        &["report", "--quick", "--out", out.to_str().unwrap()],
    );
    assert!(o.status.success());
    let stderr = String::from_utf8_lossy(&o.stderr);
    crate::progress_lines::check_lines(&stderr, "report", woodpile_report::STEPS);
    for stage in [
        "homogeneous chains under impact",
        "resonant GA",
        "force vs mass front (NSGA-II)",
        "layer-by-layer protocol",
        "blast cases",
        "transmission spectrum",
        "writing the report",
    ] {
        assert!(
            stderr.lines().any(|l| l.ends_with(stage)),
            "no progress line for the stage {stage:?} in:\n{stderr}"
        );
    }
    let md2 = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(md2.contains("all four GA results reused from cache/"));
}

#[test]
fn unwritable_or_foreign_output_is_refused() {
    let tmp = tempfile::tempdir().unwrap();
    // A file where the directory should be.
    let file = common::write(tmp.path(), "taken", "x");
    let o = common::run_in(
        tmp.path(),
        &["report", "--quick", "--out", file.to_str().unwrap()],
    );
    assert_eq!(o.status.code(), Some(2));
    // A directory holding something else.
    let other = tmp.path().join("other");
    std::fs::create_dir(&other).unwrap();
    common::write(&other, "notes.txt", "mine");
    let o = common::run_in(
        tmp.path(),
        &["report", "--quick", "--out", other.to_str().unwrap()],
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--out"));
    assert!(!other.join("report.md").exists());
    // Below a file: cannot be created.
    let below = file.join("report");
    let o = common::run_in(
        tmp.path(),
        &["report", "--quick", "--out", below.to_str().unwrap()],
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(!Path::new(&below).exists());
}
