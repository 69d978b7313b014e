//! The joint changed by key: `section.key = value` settings (a flag's, a `--params` file's, a
//! `bellows-sweep --vary`'s) written into the joint's TOML table and read back through the one
//! type, so a key is checked (its name, the kind of its value) wherever it comes from.

use super::DesignSpec;
use crate::error::{Error, Result};

/// The seed joint with each key of `table` (sections merged key by key) replaced; the error
/// is TOML's (an unknown key, a value of the wrong kind).
pub fn over_seed(table: &toml::Table) -> std::result::Result<DesignSpec, String> {
    let mut base = as_table(&DesignSpec::seed()).map_err(|e| e.to_string())?;
    merge(&mut base, table);
    toml::Value::Table(base).try_into().map_err(|e: toml::de::Error| e.message().to_string())
}

/// `joint` with each `(section.key, value)` setting applied (its text kept).
pub fn with_keys(joint: &DesignSpec, settings: &[(String, toml::Value)]) -> Result<DesignSpec> {
    let mut table = as_table(joint)?;
    for (key, value) in settings {
        set(&mut table, key, value.clone()).map_err(Error::input)?;
    }
    let mut changed: DesignSpec = toml::Value::Table(table).try_into().map_err(|e: toml::de::Error| {
        let keys: Vec<&str> = settings.iter().map(|(k, _)| k.as_str()).collect();
        Error::input(format!("{}: {}", keys.join(", "), e.message()))
    })?;
    changed.text = joint.text.clone();
    Ok(changed)
}

/// The joint as a TOML table.
pub fn as_table(joint: &DesignSpec) -> Result<toml::Table> {
    toml::Table::try_from(joint).map_err(|e| Error::Internal(format!("the joint as TOML: {e}")))
}

/// Sets `key` (`section.key`, or a top-level key) of `table` to `value`.
pub fn set(table: &mut toml::Table, key: &str, value: toml::Value) -> std::result::Result<(), String> {
    match key.split_once('.') {
        None => {
            table.insert(key.to_string(), value);
        }
        Some((section, key)) => {
            let entry = table.entry(section.to_string()).or_insert_with(|| toml::Value::Table(toml::Table::new()));
            let Some(section_table) = entry.as_table_mut() else {
                return Err(format!("{section:?} is not a section"));
            };
            section_table.insert(key.to_string(), value);
        }
    }
    Ok(())
}

/// `base` with `over`'s keys: tables merged key by key, anything else replaced.
fn merge(base: &mut toml::Table, over: &toml::Table) {
    for (key, value) in over {
        match (base.get_mut(key), value) {
            (Some(toml::Value::Table(b)), toml::Value::Table(o)) => merge(b, o),
            _ => {
                base.insert(key.clone(), value.clone());
            }
        }
    }
}

/// A command line's text as a TOML value: an integer, a float, a boolean, else a string.
pub fn value_of(text: &str) -> toml::Value {
    if let Ok(i) = text.parse::<i64>() {
        return toml::Value::Integer(i);
    }
    if let Ok(v) = text.parse::<f64>() {
        return toml::Value::Float(v);
    }
    match text {
        "true" => toml::Value::Boolean(true),
        "false" => toml::Value::Boolean(false),
        _ => toml::Value::String(text.to_string()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_seed_round_trips_and_a_key_changes_it_alone() {
        let seed = DesignSpec::seed();
        assert_eq!(over_seed(&toml::Table::new()).unwrap(), seed);
        let text = seed.to_toml();
        assert_eq!(DesignSpec::from_deck(&text, "deck").unwrap(), seed);
        let changed = with_keys(&seed, &[("bellows.plies".into(), value_of("3")), ("joint.penalty".into(), value_of("1e5"))]).unwrap();
        assert_eq!((changed.bellows.plies, changed.joint.penalty), (3, 1e5));
        assert_eq!(DesignSpec { bellows: seed.bellows.clone(), joint: seed.joint.clone(), ..changed }, seed);
        let e = with_keys(&seed, &[("bellows.pliess".into(), value_of("3"))]).unwrap_err().to_string();
        assert!(e.contains("unknown field `pliess`"), "{e}");
        let e = with_keys(&seed, &[("bellows.plies".into(), value_of("three"))]).unwrap_err().to_string();
        assert!(e.contains("bellows.plies"), "{e}");
    }

    #[test]
    fn a_file_of_some_keys_keeps_the_seeds_others() {
        let table: toml::Table = "[bellows]\nplies = 3\n[joint]\nincrements = 10\n".parse().unwrap();
        let joint = over_seed(&table).unwrap();
        assert_eq!((joint.bellows.plies, joint.joint.increments, joint.bellows.pitch, joint.material.hardening_modulus), (3, 10, 24.0, 1000.0));
    }
}
