//! Changes to a TOML description by field path: `time.end`, `grid.spacing`,
//! `bodies[1].velocity`. A path names existing tables (and existing elements of arrays of
//! tables); its last key may be new, so that an optional field can be set. The changed
//! description is then checked by whoever reads it, as if it had been written so.

use anyhow::{bail, Result};
use toml::Value;

/// One step of a field path: a key, with an array index when written `key[i]`.
#[derive(Debug, PartialEq)]
struct Step<'a> {
    key: &'a str,
    index: Option<usize>,
}

fn steps(path: &str) -> Result<Vec<Step<'_>>> {
    path.split('.')
        .map(|part| {
            let (key, index) = match part.split_once('[') {
                None => (part, None),
                Some((key, rest)) => match rest.strip_suffix(']').map(str::parse::<usize>) {
                    Some(Ok(i)) => (key, Some(i)),
                    _ => bail!("field `{path}`: `{part}` is not key[index]"),
                },
            };
            if key.is_empty() {
                bail!("field `{path}`: an empty key");
            }
            Ok(Step { key, index })
        })
        .collect()
}

/// Set the field at `path` of `description` (a TOML table) to `value`.
pub fn set(description: &mut Value, path: &str, value: Value) -> Result<()> {
    let steps = steps(path)?;
    let (last, parents) = steps.split_last().expect("split gives at least one part");
    let mut here = description;
    for step in parents {
        here = child(here, step, path)?;
    }
    let table = match here {
        Value::Table(t) => t,
        _ => bail!(
            "field `{path}`: `{}` is inside a value that is not a table",
            last.key
        ),
    };
    match last.index {
        None => {
            table.insert(last.key.to_string(), value);
        }
        Some(i) => match table.get_mut(last.key) {
            Some(Value::Array(items)) if i < items.len() => items[i] = value,
            Some(Value::Array(items)) => {
                bail!(
                    "field `{path}`: `{}` has {} elements",
                    last.key,
                    items.len()
                )
            }
            _ => bail!(
                "field `{path}`: `{}` is not an array in the description",
                last.key
            ),
        },
    }
    Ok(())
}

fn child<'v>(here: &'v mut Value, step: &Step, path: &str) -> Result<&'v mut Value> {
    let Value::Table(table) = here else {
        bail!(
            "field `{path}`: `{}` is inside a value that is not a table",
            step.key
        );
    };
    let Some(value) = table.get_mut(step.key) else {
        bail!("field `{path}`: the description has no `{}`", step.key);
    };
    match (step.index, value) {
        (None, value) => Ok(value),
        (Some(i), Value::Array(items)) => {
            let n = items.len();
            items
                .get_mut(i)
                .ok_or_else(|| anyhow::anyhow!("field `{path}`: `{}` has {n} elements", step.key))
        }
        (Some(_), _) => bail!("field `{path}`: `{}` is not an array", step.key),
    }
}

/// A value written on a command line, read as a TOML value (`1e-4`, `true`, `[0, 1]`,
/// `"usl"`); a bare word that is not TOML is taken as a string (`usl`).
pub fn parse_value(text: &str) -> Value {
    let text = text.trim();
    match toml::from_str::<toml::Table>(&format!("v = {text}")) {
        Ok(mut t) => t.remove("v").expect("the key just written"),
        Err(_) => Value::String(text.to_string()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene() -> Value {
        toml::from_str(
            "[time]\nend = 1.0\n[[bodies]]\nname = \"a\"\nvelocity = [0.0, 1.0]\n[[bodies]]\nname = \"b\"\n",
        )
        .unwrap()
    }

    #[test]
    fn fields_are_set_by_path_and_index() {
        let mut s = scene();
        set(&mut s, "time.end", parse_value("2e-3")).unwrap();
        set(&mut s, "time.dt", parse_value("1e-6")).unwrap();
        set(&mut s, "bodies[1].velocity", parse_value("[1.5, 0]")).unwrap();
        set(&mut s, "bodies[0].velocity[1]", parse_value("-3.0")).unwrap();
        assert_eq!(s["time"]["end"].as_float(), Some(2e-3));
        assert_eq!(s["time"]["dt"].as_float(), Some(1e-6));
        assert_eq!(s["bodies"][1]["velocity"][0].as_float(), Some(1.5));
        assert_eq!(s["bodies"][0]["velocity"][1].as_float(), Some(-3.0));
    }

    #[test]
    fn a_path_through_what_is_not_there_is_refused_with_the_field_named() {
        let mut s = scene();
        let e = set(&mut s, "grid.spacing", parse_value("1")).unwrap_err();
        assert_eq!(
            e.to_string(),
            "field `grid.spacing`: the description has no `grid`"
        );
        let e = set(&mut s, "bodies[2].name", parse_value("c")).unwrap_err();
        assert_eq!(
            e.to_string(),
            "field `bodies[2].name`: `bodies` has 2 elements"
        );
        let e = set(&mut s, "time.end.x", parse_value("1")).unwrap_err();
        assert!(e.to_string().contains("not a table"), "{e}");
        assert!(set(&mut s, "bodies[x].name", parse_value("c")).is_err());
    }

    #[test]
    fn command_line_values_are_toml_or_strings() {
        assert_eq!(parse_value("1e-4"), Value::Float(1e-4));
        assert_eq!(parse_value("3"), Value::Integer(3));
        assert_eq!(parse_value("usl"), Value::String("usl".into()));
        assert_eq!(parse_value("\"a b\""), Value::String("a b".into()));
    }
}
