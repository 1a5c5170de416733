//! Claim: the lab-physics keys of a scenario (`[damping]`, `[preload]`, `kind = "drive"` and
//! `"rest"`) mean exactly what docs/physics.md §14 says: a file with every key resolves to the
//! `Damping`, `Preload` and `Drive` written out by hand below (compared with `==`: the file format
//! only moves numbers, and converts mm to m as everywhere else), a drive's defaults (ramp, run
//! duration) are the core's, `to_toml()` writes a file that resolves to the same chain,
//! excitation and settings, and each bad input is an error naming its key: a user who gets a
//! lab setting wrong must be told which line to fix, not get a silently different model.

use std::path::Path;
use woodpile::{
    ContactDamping, Damping, Drive, DriveQuantity, Excitation, Material, Preload, ResonatorDamping,
    RunSettings, Signal, Sweep, Wall,
};
use woodpile_io::scenario::{resolve, Resolved, Scenario};

const CHAIN: &str = "[chain]\nrods_mm = [80, 40, 20]\n";

const EVERY_KEY: &str = r#"
[excitation]
kind = "drive"
drive = "displacement"
signal = "chirp"
amplitude = 1e-7
start_hz = 1000.0
end_hz = 20000.0
sweep_duration_s = 2e-3
sweep = "logarithmic"
ramp_s = 1e-4
tip = { kind = "cap", material = "steel", cap_radius_mm = 4.0 }
[damping]
contact = "hunt-crossley"
restitution = 0.8
striker = { contact = "viscoelastic", viscous_time_s = 1e-6 }
wall = { contact = "restitution", restitution = 0.95 }
allow_pull = true
impact_speed_m_s = 0.5
resonator_ratio = 0.02
resonators = [{ element = 1, resonator = 1, ratio = 0.05 }]
on_site_time_s = 0.01
[preload]
force_n = 2.0
gravity_m_s2 = 9.81
[run]
duration_s = 1e-3
"#;

fn resolved(dir: &Path, rest: &str) -> Result<Resolved, woodpile_io::Error> {
    resolve(&Scenario::parse(&format!("{CHAIN}{rest}"))?, dir)
}

#[test]
fn every_key_resolves_to_the_values_written() {
    let r = resolved(Path::new("."), EVERY_KEY).unwrap();
    let damping = Damping {
        contacts: ContactDamping::HuntCrossley { restitution: 0.8 },
        striker: Some(ContactDamping::Viscoelastic { time_s: 1e-6 }),
        wall: Some(ContactDamping::Restitution { coefficient: 0.95 }),
        allow_pull: true,
        resonator_ratio: 0.02,
        resonator_overrides: vec![ResonatorDamping {
            element: 1,
            resonator: 1,
            ratio: 0.05,
        }],
        on_site_time_s: Some(0.01),
        impact_speed_m_s: Some(0.5),
    };
    assert_eq!(r.chain.damping(), &damping);
    let preload = Preload {
        force_n: 2.0,
        gravity_m_s2: 9.81,
    };
    assert_eq!(r.chain.preload(), &preload);
    let tip = Wall::Cap {
        material: Material::preset("steel").unwrap(),
        radius_m: 4.0 * 1e-3,
    };
    let drive = Drive {
        quantity: DriveQuantity::Displacement { tip },
        signal: Signal::Chirp {
            amplitude: 1e-7,
            start_hz: 1000.0,
            end_hz: 20000.0,
            duration_s: 2e-3,
            sweep: Sweep::Logarithmic,
        },
        ramp_s: 1e-4,
    };
    assert_eq!(r.excitation, Excitation::Drive(drive));

    // Defaults: a force drive, the signal's own ramp, the core's run duration; a table signal
    // read from `time_s,value`.
    let h = resolved(
        Path::new("."),
        "[excitation]\nkind = \"drive\"\nsignal = \"harmonic\"\namplitude = 0.5\nfrequency_hz = 2000.0\n",
    )
    .unwrap();
    let harmonic = Drive::force(Signal::Harmonic {
        amplitude: 0.5,
        frequency_hz: 2000.0,
    });
    assert_eq!(h.excitation, Excitation::Drive(harmonic));
    assert_eq!(
        h.settings.duration_s,
        RunSettings::paper_for(&h.excitation).duration_s
    );
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("s.csv"), "time_s,value\n0,0\n1e-4,1e-6\n").unwrap();
    let t = resolved(
        dir.path(),
        "[excitation]\nkind = \"drive\"\nsignal = \"table\"\nfile = \"s.csv\"\n",
    )
    .unwrap();
    let table = Drive::force(Signal::Table {
        times_s: vec![0.0, 1e-4],
        values: vec![0.0, 1e-6],
    });
    assert_eq!(t.excitation, Excitation::Drive(table));
    std::fs::write(dir.path().join("s.csv"), "time_s,force_n\n0,0\n1e-4,1\n").unwrap();
    let e = resolved(
        dir.path(),
        "[excitation]\nkind = \"drive\"\nsignal = \"table\"\nfile = \"s.csv\"\n",
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("line 1") && e.contains("time_s,value"), "{e}");
}

#[test]
fn written_out_scenarios_resolve_to_the_same_model() {
    for rest in [
        EVERY_KEY,
        "[excitation]\nkind = \"drive\"\nsignal = \"chirp\"\namplitude = 0.1\nstart_hz = 100.0\nend_hz = 3e4\nsweep_duration_s = 5e-3\n[damping]\ncontact = \"restitution\"\nrestitution = 0.9\n",
        "[excitation]\nkind = \"rest\"\n[preload]\ngravity_m_s2 = 9.81\n",
    ] {
        let s = Scenario::parse(&format!("{CHAIN}{rest}")).unwrap();
        let a = resolve(&s, Path::new(".")).unwrap();
        let text = s.to_toml();
        let b = resolve(&Scenario::parse(&text).unwrap(), Path::new("."))
            .unwrap_or_else(|e| panic!("{e}\n{text}"));
        assert_eq!(a.chain, b.chain, "{text}");
        assert_eq!(a.excitation, b.excitation, "{text}");
        assert_eq!(a.settings, b.settings, "{text}");
    }
}

#[test]
fn bad_lab_keys_name_their_key() {
    let drive = "[excitation]\nkind = \"drive\"\n";
    let harmonic = "signal = \"harmonic\"\namplitude = 1.0\n";
    for (rest, key) in [
        ("[damping]\ncontact = \"sticky\"\n", "contact = \"sticky\""),
        (
            "[damping]\ncontact = \"restitution\"\nrestitution = 1.5\n",
            "damping.restitution",
        ),
        (
            "[damping]\ncontact = \"viscoelastic\"\nviscous_time_s = 1e-6\nrestitution = 0.9\n",
            "damping.restitution",
        ),
        (drive, "excitation.signal"),
        (&format!("{drive}{harmonic}"), "excitation.frequency_hz"),
        (
            "[damping]\nresonators = [{ element = 99, resonator = 1, ratio = 0.1 }]\n",
            "damping.resonators[0].element",
        ),
        ("[preload]\nforce_n = -1.0\n", "preload.force_n"),
        ("[damping]\nimpact_speed_m_s = 1.0\n", "damping.impact_speed_m_s"),
        (
            &format!("{drive}{harmonic}frequency_hz = 1e3\ndrive = \"force\"\ntip = {{ kind = \"cap\" }}\n"),
            "excitation.tip",
        ),
    ] {
        let e = resolved(Path::new("."), rest)
            .map(|_| ())
            .expect_err(rest)
            .to_string();
        assert!(e.contains(key), "{rest}: error `{e}` does not name {key}");
    }
}
