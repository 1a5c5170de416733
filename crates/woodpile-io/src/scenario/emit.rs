//! Writes a completed scenario as commented TOML (every key explicit). The document is the
//! scenario's serde form (`toml::Table`, in the order of the structs' fields); this module only
//! lays it out: one `[table]` per section, one line per key with the comment of [`keys`] beside
//! it, nested tables inline, a list of tables one entry per line, and floats in their shortest
//! round-trip form.

use super::keys::{key, keys, toml_float as float, KeyType};
use super::Scenario;
use std::fmt::Write;
use toml::{Table, Value};

/// A value on one line: scalars, arrays `[a, b]`, tables `{ k = v, … }`.
fn inline(v: &Value) -> String {
    match v {
        Value::Float(x) => float(*x),
        Value::Table(t) => {
            let parts: Vec<String> = t
                .iter()
                .map(|(k, v)| format!("{k} = {}", inline(v)))
                .collect();
            format!("{{ {} }}", parts.join(", "))
        }
        Value::Array(a) => {
            let parts: Vec<String> = a.iter().map(inline).collect();
            format!("[{}]", parts.join(", "))
        }
        other => other.to_string(),
    }
}

/// Pads `line` to a column and appends a comment (none when empty; above a long line).
fn commented(out: &mut String, line: &str, comment: &str) {
    if comment.is_empty() {
        let _ = writeln!(out, "{line}");
    } else if line.len() > 40 {
        let _ = writeln!(out, "# {comment}\n{line}");
    } else {
        let _ = writeln!(out, "{line:<40} # {comment}");
    }
}

/// The comment of the key at `path` in the keys table ("" when it has none).
fn comment(path: &str) -> String {
    key(path).map(|k| k.comment()).unwrap_or_default()
}

/// One `key = value` line of table `section`; a list of tables is written one entry per line.
fn entry(out: &mut String, section: &str, k: &str, v: &Value) {
    let path = format!("{section}.{k}");
    match v {
        Value::Array(items) if !items.is_empty() && items.iter().all(Value::is_table) => {
            let _ = writeln!(out, "# {}", comment(&path));
            let _ = writeln!(out, "{k} = [");
            for item in items {
                let _ = writeln!(out, "    {},", inline(item));
            }
            let _ = writeln!(out, "]");
        }
        _ => commented(out, &format!("{k} = {}", inline(v)), &comment(&path)),
    }
}

/// The TOML text of a (completed) scenario.
pub(crate) fn to_toml(s: &Scenario) -> String {
    let mut o = String::from(
        "# woodpile scenario: every key written out with its value (docs/physics.md's defaults unless set).\n",
    );
    let doc = match Table::try_from(s) {
        Ok(doc) => doc,
        // A scenario is plain data: serialising it cannot fail.
        Err(e) => return format!("{o}# cannot write this scenario: {e}\n"),
    };
    for (k, v) in doc.iter().filter(|(_, v)| !v.is_table()) {
        commented(&mut o, &format!("{k} = {}", inline(v)), &comment(k));
    }
    // Sections in the order of the keys table; an absent optional one is named in a comment.
    let sections = keys()
        .iter()
        .filter(|k| k.ty == KeyType::Table && !k.name.contains('.'));
    for section in sections.map(|k| k.name) {
        match doc.get(section) {
            Some(Value::Table(t)) => {
                let _ = writeln!(o, "\n[{section}]");
                for (k, v) in t {
                    entry(&mut o, section, k, v);
                }
            }
            _ => {
                let _ = writeln!(o, "\n# [{section}]: {}", comment(section));
            }
        }
    }
    o
}
