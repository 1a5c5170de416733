//! Claim: the keys table (`woodpile_io::scenario::keys()`) is the scenario file. (1) Every key of
//! the table is a key of the file: a scenario giving all of them at once (each set to a value
//! other than its default) parses, and its emitted form parses back to the same completed
//! scenario, so every key round-trips through emission; (2) every key the emitter writes is in
//! the table; (3) completion writes the table's default for every key left out, in sparse
//! scenarios that leave out every key with a fixed default at least once (so the two agree and neither restates the core's defaults). No tolerance:
//! floats are written in their shortest round-trip form and compared exactly.

use woodpile_io::scenario::{key, keys, KeyDefault, KeyType, Scenario};

use toml::{Table, Value};

/// A value other than the key's default, valid for its type.
fn example(k: &woodpile_io::scenario::Key) -> Option<Value> {
    Some(match k.ty {
        KeyType::Float => Value::Float(match k.default {
            KeyDefault::Float(x) if x != 0.0 => 2.0 * x,
            _ => 0.375,
        }),
        KeyType::Integer => Value::Integer(2),
        KeyType::Bool => Value::Boolean(k.default != KeyDefault::Bool(true)),
        KeyType::String => Value::String("load.csv".into()),
        KeyType::Name => Value::String(k.choices.last()?.to_string()),
        KeyType::Material => Value::String("steel".into()),
        KeyType::IntegerList => Value::Array(vec![Value::Integer(20), Value::Integer(30)]),
        // Tables are made by their keys.
        _ => return None,
    })
}

/// Sets `path` (dotted; `name[]` is a list holding one table) in `t`.
fn insert(t: &mut Table, path: &[&str], value: Value) {
    let (head, rest) = (path[0], &path[1..]);
    if rest.is_empty() {
        t.insert(head.to_string(), value);
        return;
    }
    let inner = match head.strip_suffix("[]") {
        Some(list) => {
            let list = t
                .entry(list)
                .or_insert_with(|| Value::Array(vec![Value::Table(Table::new())]));
            &mut list.as_array_mut().unwrap()[0]
        }
        None => t.entry(head).or_insert_with(|| Value::Table(Table::new())),
    };
    insert(inner.as_table_mut().unwrap(), rest, value);
}

/// Every leaf path of `v` (`name[]` for a list of tables), with its value.
fn leaves(prefix: &str, v: &Value, out: &mut Vec<(String, Value)>) {
    match v {
        Value::Table(t) => {
            for (k, v) in t {
                let p = if prefix.is_empty() {
                    k.clone()
                } else {
                    format!("{prefix}.{k}")
                };
                leaves(&p, v, out);
            }
        }
        Value::Array(a) if a.first().is_some_and(Value::is_table) => {
            for item in a {
                leaves(&format!("{prefix}[]"), item, out);
            }
        }
        _ => out.push((prefix.to_string(), v.clone())),
    }
}

#[test]
fn every_key_of_the_table_round_trips_and_the_emitter_writes_no_other() {
    let mut doc = Table::new();
    for k in keys() {
        if let Some(v) = example(k) {
            insert(&mut doc, &k.name.split('.').collect::<Vec<_>>(), v);
        }
    }
    let text = toml::to_string(&doc).unwrap();
    let s = Scenario::parse(&text)
        .unwrap_or_else(|e| panic!("the table names a key the file has not: {e}\n{text}"));
    let emitted = s.to_toml();
    let back = Scenario::parse(&emitted).unwrap_or_else(|e| panic!("{e}\n{emitted}"));
    assert_eq!(back, s.complete(), "{emitted}");
    let mut written = Vec::new();
    leaves(
        "",
        &Value::Table(emitted.parse::<Table>().unwrap()),
        &mut written,
    );
    for (path, _) in &written {
        assert!(
            key(path).is_some(),
            "{path} is written but not in the keys table"
        );
    }
    for k in keys().iter().filter(|k| example(k).is_some()) {
        assert!(
            written.iter().any(|(p, _)| p == k.name),
            "{} is in the table but not written",
            k.name
        );
    }
}

/// The table's default of `path` as a TOML value (None: no fixed default).
fn default_value(path: &str) -> Option<Value> {
    match &key(path)?.default {
        KeyDefault::Float(x) => Some(Value::Float(*x)),
        KeyDefault::Bool(b) => Some(Value::Boolean(*b)),
        KeyDefault::Name(n) => Some(Value::String(n.to_string())),
        _ => None,
    }
}

/// Scenarios that leave out every key they can, one per kind of excitation, wall, damping,
/// preload, element and integrator.
const SPARSE: [&str; 7] = [
    "[chain]\nrods_mm = [20, 40]\n",
    "[chain]\nelements = [{ rod_mm = 40 }, { kind = \"rod\", length_mm = 45.0, cell = { modes = 1 } }, { kind = \"sphere\" }]\n\
     [excitation]\nkind = \"blast\"\n[wall]\nkind = \"flat\"\n[damping]\nstriker = {}\nwall = {}\n[preload]\n",
    "[chain]\nrods_mm = [20]\n[excitation]\nkind = \"drive\"\ndrive = \"displacement\"\n\
     signal = \"chirp\"\namplitude = 1e-6\nstart_hz = 100.0\nend_hz = 1e4\nsweep_duration_s = 1e-3\n",
    "[chain]\nrods_mm = [20]\n[excitation]\nkind = \"drive\"\nsignal = \"harmonic\"\namplitude = 1.0\nfrequency_hz = 1e3\n",
    "[chain]\nrods_mm = [20]\n[run]\nintegrator = \"dopri5\"\n",
    "[chain]\nrods_mm = [20]\n[excitation]\nkind = \"rest\"\n[wall]\nkind = \"free\"\n",
    "[chain]\nrods_mm = [20]\n[run]\npeak_tolerance = 1e-4\n",
];

#[test]
fn completion_writes_the_tables_defaults() {
    let mut checked = Vec::new();
    for text in SPARSE {
        let s = Scenario::parse(text).unwrap();
        let (mut given, mut completed) = (Vec::new(), Vec::new());
        leaves("", &Value::Table(text.parse().unwrap()), &mut given);
        leaves("", &Value::try_from(s.complete()).unwrap(), &mut completed);
        for (path, value) in completed {
            if given.iter().any(|(p, _)| *p == path) {
                continue;
            }
            if let Some(default) = default_value(&path) {
                assert_eq!(value, default, "{text}: {path}");
                checked.push(path);
            }
        }
    }
    // Every key with a fixed default was left out and completed at least once.
    let never: Vec<&str> = (keys().iter())
        .filter(|k| default_value(k.name).is_some() && !checked.iter().any(|p| p == k.name))
        .map(|k| k.name)
        .collect();
    assert!(never.is_empty(), "never completed: {never:?}");
}
