//! The recipe form as the page shows it: the form for the files of an unrecognised upload (one
//! fieldset per file, a row per sensor with its column and unit selects, set to the draft's
//! rule or the engine's first guess), the recipe the form's values make, and the preview of
//! what a recipe read. `render` in `www/util.js` builds the elements; `www/recipes.js` keeps the
//! events, the storage and the downloads.
//! May import: [`super::check`], [`super::form`], `super::schema`, `io` and `view`.

use super::check::{FileGuess, Report};
use super::form::{
    column_options, file_hint, guess_columns, preview_number, sensor_label, time_unit_label,
    unit_label,
};
use super::schema::{Column, FileRule, Recipe, Sensor, TimeUnit, RECIPE_VERSION};
use crate::io::import::fileset::base;
use crate::view::El;

/// The name a recipe gets when the form's name field is left empty.
pub const DEFAULT_NAME: &str = "my logger";

/// The form's state: the files described (`check::describe`) and the draft recipe whose rules
/// the rows start from.
#[derive(Debug, Clone)]
pub struct Form {
    files: Vec<FileGuess>,
    draft: Vec<FileRule>,
}

/// One sensor row's values as the page reads them from its selects: the row's file (its name,
/// the fieldset's `data-file`) and its selects in the row's order.
#[derive(Debug, Clone, Default, serde::Deserialize)]
pub struct RowValues {
    /// The file's name (`data-file`).
    pub file: String,
    /// The row's selects.
    pub selects: Vec<SelectValue>,
}

/// A select of a row: its `data-k` (`sensor`, `time_unit`, `unit`) or its `data-col` (`t`,
/// `x`, …), and its value.
#[derive(Debug, Clone, Default, serde::Deserialize)]
pub struct SelectValue {
    /// `data-k`.
    #[serde(default)]
    pub k: Option<String>,
    /// `data-col`.
    #[serde(default)]
    pub col: Option<String>,
    /// The chosen option's value.
    pub value: String,
}

impl Form {
    /// The form for `files`, its rows starting from the rules of `draft` (if any).
    pub fn new(files: Vec<FileGuess>, draft: Option<Recipe>) -> Self {
        Form {
            files,
            draft: draft.map(|d| d.files).unwrap_or_default(),
        }
    }

    /// File `name` of the form, or an error naming it.
    fn file(&self, name: &str) -> Result<&FileGuess, String> {
        self.files
            .iter()
            .find(|f| f.name == name)
            .ok_or_else(|| format!("the form has no file `{name}`"))
    }

    /// The draft's rules for a file (those naming its base name), in order: row `i` starts
    /// from rule `i`.
    fn rules(&self, g: &FileGuess) -> Vec<&FileRule> {
        self.draft
            .iter()
            .filter(|r| r.pattern == base(&g.name))
            .collect()
    }

    /// The whole form, in order: its heading, what it is for, the files, the name and the
    /// buttons, the saved message, the warnings and the preview.
    pub fn view(&self) -> Vec<El> {
        let name = El::new("input")
            .attr("id", "recipe-name")
            .attr("type", "text")
            .attr("value", DEFAULT_NAME)
            .attr("maxlength", "100")
            .attr("aria-label", "Recipe name");
        let button = |id: &'static str, class: &'static str, text: &str| {
            let b = El::new("button").attr("id", id).attr("type", "button");
            match class {
                "" => b,
                c => b.class(c),
            }
            .text(text)
        };
        vec![
            El::new("h3").text("Describe these files"),
            El::new("p").class("hint").text(
                "No known recorder wrote these files. Say what each holds: the preview below shows the first rows \
                 as they will be read, in SI units, and warns when a unit looks wrong. The same mapping works with \
                 pdr run --recipe FILE.",
            ),
            El::new("div")
                .class("recipe-files")
                .children(self.files.iter().map(|g| self.file_view(g))),
            El::new("div")
                .class("controls")
                .child(El::new("label").text("name ").child(name))
                .child(button("recipe-run", "primary", "Read with this mapping"))
                .child(button("recipe-save", "", "Save as recipe"))
                .child(button("recipe-download", "small", "Download recipe (JSON)")),
            El::new("p").attr("id", "recipe-saved").class("hint"),
            El::new("ul")
                .attr("id", "recipe-warnings")
                .class("messages")
                .attr("aria-live", "polite"),
            El::new("div").attr("id", "recipe-preview"),
        ]
    }

    /// A file's fieldset: its name, what it looks like, a row per draft rule (one empty row
    /// without any) and the button that adds a row.
    fn file_view(&self, g: &FileGuess) -> El {
        let rows = self.rules(g).len().max(1);
        El::new("fieldset")
            .class("recipe-file")
            .attr("data-file", g.name.as_str())
            .child(El::new("legend").text(base(&g.name)))
            .child(El::new("p").class("hint").text(file_hint(g)))
            .child(
                El::new("div")
                    .class("recipe-sensors")
                    .children((0..rows).map(|i| self.row_of(g, i))),
            )
            .child(
                El::new("button")
                    .attr("type", "button")
                    .class("small recipe-more")
                    .text("+ another sensor in this file"),
            )
    }

    /// Row `index` of file `name`: its sensor select (the draft rule's sensor, else "not used")
    /// and its fields.
    pub fn row(&self, name: &str, index: usize) -> Result<El, String> {
        Ok(self.row_of(self.file(name)?, index))
    }

    fn row_of(&self, g: &FileGuess, index: usize) -> El {
        let rule = self.rules(g).get(index).copied();
        let sensor = rule.map(|r| r.sensor);
        let options = std::iter::once((String::new(), "not used".to_string())).chain(
            Sensor::ALL
                .iter()
                .map(|&s| (s.as_str().to_string(), sensor_label(s))),
        );
        let chosen = sensor.map_or("", |s| s.as_str());
        El::new("div")
            .class("recipe-sensor controls")
            .child(
                El::new("label")
                    .text("sensor ")
                    .child(select("data-k", "sensor", options, chosen)),
            )
            .child(fields_of(g, rule, index, sensor))
    }

    /// The fields of row `index` of file `name` for `sensor` (as in the JSON; empty for "not
    /// used"): after the user chose another sensor.
    pub fn fields(&self, name: &str, index: usize, sensor: &str) -> Result<El, String> {
        let g = self.file(name)?;
        let sensor = match sensor {
            "" => None,
            s => Some(
                Sensor::ALL
                    .into_iter()
                    .find(|x| x.as_str() == s)
                    .ok_or_else(|| format!("no sensor `{s}`"))?,
            ),
        };
        Ok(fields_of(
            g,
            self.rules(g).get(index).copied(),
            index,
            sensor,
        ))
    }

    /// The recipe (JSON) the form's values make, named `name` ([`DEFAULT_NAME`] when empty): a
    /// file entry for each row with a sensor, with its file's separator and header. Its
    /// errors (a column that is not one) are the recipe reader's to tell, as for a recipe file.
    pub fn recipe(&self, name: &str, rows: &[RowValues]) -> Result<String, String> {
        let mut files = Vec::new();
        for row in rows {
            let g = self.file(&row.file)?;
            let get = |k: &str| {
                row.selects
                    .iter()
                    .find(|s| s.k.as_deref() == Some(k))
                    .map(|s| &s.value)
            };
            let Some(sensor) = get("sensor").filter(|s| !s.is_empty()) else {
                continue;
            };
            let columns: serde_json::Map<String, serde_json::Value> = row
                .selects
                .iter()
                .filter_map(|s| Some((s.col.clone()?, column_value(g.header, &s.value))))
                .collect();
            let mut rule = serde_json::json!({
                "match": base(&g.name),
                "sensor": sensor,
                "delimiter": g.delimiter,
                "header": g.header,
                "columns": columns,
            });
            if let Some(t) = get("time_unit") {
                rule["time_unit"] = t.as_str().into();
            }
            if let Some(u) = get("unit").filter(|u| !u.is_empty()) {
                rule["unit"] = u.as_str().into();
            }
            files.push(rule);
        }
        let name = match name.trim() {
            "" => DEFAULT_NAME,
            n => n,
        };
        let recipe = serde_json::json!({ "recipe": RECIPE_VERSION, "name": name, "files": files });
        Ok(recipe.to_string())
    }
}

/// A column select's value in the recipe: the header name for a file with a header, else the
/// 1-based number (`null` when it is not a number, which the recipe reader refuses).
fn column_value(header: bool, v: &str) -> serde_json::Value {
    if header {
        return v.into();
    }
    match v.trim().parse::<u64>() {
        Ok(n) => n.into(),
        Err(_) => v
            .trim()
            .parse::<f64>()
            .map_or(serde_json::Value::Null, Into::into),
    }
}

/// A select with the attribute `key` = `name` (`data-k="unit"`, `data-col="x"`), its options
/// `(value, label)`, the one whose value is `chosen` selected.
fn select(
    key: &'static str,
    name: &str,
    options: impl IntoIterator<Item = (String, String)>,
    chosen: &str,
) -> El {
    El::new("select")
        .attr(key, name)
        .children(options.into_iter().map(|(value, label)| {
            let o = El::new("option").attr("value", value.as_str());
            let o = if value == chosen {
                o.attr("selected", "")
            } else {
                o
            };
            o.text(label)
        }))
}

/// A row's fields for `sensor`: a column select per field (the rule's column, else the first
/// guess for the file's `index`-th sensor), the time unit (the rule's, else ms) and, for a
/// sensor with units, the unit (the rule's when it is for this sensor, else the SI one).
fn fields_of(g: &FileGuess, rule: Option<&FileRule>, index: usize, sensor: Option<Sensor>) -> El {
    let span = El::new("span").class("recipe-fields controls");
    let Some(sensor) = sensor else { return span };
    let options = column_options(g);
    let ruled = |k: &str| {
        let named = rule.map(|r| r.columns.named()).unwrap_or_default();
        named
            .into_iter()
            .find(|(n, _)| *n == k)
            .map(|(_, c)| match c {
                Column::Number(n) => n.to_string(),
                Column::Name(s) => s.clone(),
            })
    };
    let mut span = span;
    for (k, at) in guess_columns(g.columns.len(), sensor, index) {
        let chosen = ruled(k).or_else(|| options.get(at).map(|o| o.0.clone()));
        let label = if k == "t" {
            "time ".into()
        } else {
            format!("{k} ")
        };
        let sel = select(
            "data-col",
            k,
            options.clone(),
            chosen.as_deref().unwrap_or(""),
        );
        span = span.child(El::new("label").text(label).child(sel));
    }
    let time = rule.map_or(TimeUnit::Ms, |r| r.time_unit);
    let times = TimeUnit::ALL
        .iter()
        .map(|u| (u.as_str().to_string(), time_unit_label(*u).to_string()));
    span = span.child(El::new("label").text("time in ").child(select(
        "data-k",
        "time_unit",
        times,
        time.as_str(),
    )));
    if let Some(first) = sensor.units().first() {
        let unit = rule
            .filter(|r| r.sensor == sensor)
            .and_then(|r| r.unit)
            .unwrap_or(*first);
        let units = sensor
            .units()
            .iter()
            .map(|u| (u.as_str().to_string(), unit_label(*u)));
        span = span.child(El::new("label").text("unit ").child(select(
            "data-k",
            "unit",
            units,
            unit.as_str(),
        )));
    }
    span
}

/// What a recipe read, as the form shows it: the messages (`li`: the error, or the warnings
/// then the notes) and a table per file (its first rows, under the file's name and facts).
pub fn preview_view(result: Result<&Report, &str>) -> (Vec<El>, Vec<El>) {
    let r = match result {
        Err(e) => return (vec![El::new("li").class("error").text(e)], Vec::new()),
        Ok(r) => r,
    };
    let li = |class: &'static str, t: &String| El::new("li").class(class).text(t.as_str());
    let messages = r
        .warnings
        .iter()
        .map(|w| li("warn", w))
        .chain(r.notes.iter().map(|n| li("note", n)))
        .collect();
    let tables = r
        .files
        .iter()
        .map(|f| {
            let head = El::new("tr").children(f.columns.iter().map(|c| El::new("th").text(*c)));
            let rows = f.rows.iter().map(|row| {
                El::new("tr").children(row.iter().map(|v| El::new("td").text(preview_number(*v))))
            });
            El::new("div")
                .class("recipe-table")
                .child(El::new("h4").text(format!("{} — {}", base(&f.file), facts(f))))
                .child(
                    El::new("table")
                        .child(El::new("thead").child(head))
                        .child(El::new("tbody").children(rows)),
                )
        })
        .collect();
    (messages, tables)
}

/// What the preview says of a file above its table: its sensor, the samples previewed, the
/// rate, the median magnitude and the lines skipped with the first reason ("accelerometer ·
/// 2,000 samples previewed · 100 Hz · median |v| 9.81").
pub fn facts(f: &super::check::FileReport) -> String {
    let mut facts = vec![
        f.sensor.to_string(),
        format!(
            "{} samples previewed",
            crate::view::thousands(f.samples as u64)
        ),
    ];
    if let Some(r) = f.rate_hz {
        facts.push(format!("{} Hz", preview_number(r)));
    }
    if let Some(m) = f.median {
        facts.push(format!("median |v| {}", preview_number(m)));
    }
    if f.skipped > 0 {
        let why = f.errors.first().map_or("", |e| e.message.as_str());
        facts.push(format!("{} lines skipped ({why})", f.skipped));
    }
    facts.join(" · ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::import::recipe::check::FileReport;
    use crate::io::import::recipe::Delimiter;
    use crate::view::Node;

    fn guess(name: &str, columns: usize) -> FileGuess {
        FileGuess {
            name: name.into(),
            delimiter: Delimiter::Comma,
            header: false,
            columns: (1..=columns).map(|i| i.to_string()).collect(),
            first: vec![(0..columns).map(|i| format!("{i}.5")).collect()],
        }
    }

    fn form() -> Form {
        let draft = Recipe::from_json(
            r#"{"recipe": 1, "name": "my logger", "files": [{"match": "acc.csv", "sensor": "accelerometer",
                "delimiter": "comma", "columns": {"t": 1, "x": 2, "y": 3, "z": 4}, "time_unit": "ms"}]}"#,
        )
        .unwrap();
        Form::new(
            vec![guess("walk/acc.csv", 4), guess("walk/imu.csv", 7)],
            Some(draft),
        )
    }

    /// The `(data-col or data-k, selected value)` of every select inside.
    fn selected(e: &El) -> Vec<(String, String)> {
        e.descendants()
            .into_iter()
            .filter(|s| s.tag == "select")
            .map(|s| {
                let key = s.get("data-col").or(s.get("data-k")).unwrap().to_string();
                let chosen = s
                    .descendants()
                    .into_iter()
                    .find(|o| o.get("selected").is_some());
                (
                    key,
                    chosen
                        .and_then(|o| o.get("value"))
                        .unwrap_or("?")
                        .to_string(),
                )
            })
            .collect()
    }

    fn pairs(p: &[(&str, &str)]) -> Vec<(String, String)> {
        p.iter()
            .map(|(a, b)| (a.to_string(), b.to_string()))
            .collect()
    }

    #[test]
    fn the_form_starts_from_the_draft_and_keeps_the_page_ids() {
        let view = form().view();
        let ids: Vec<&str> = view
            .iter()
            .flat_map(|e| e.descendants())
            .filter_map(|e| e.get("id"))
            .collect();
        let want = [
            "recipe-name",
            "recipe-run",
            "recipe-save",
            "recipe-download",
            "recipe-saved",
        ];
        assert_eq!(
            ids,
            [&want[..], &["recipe-warnings", "recipe-preview"]].concat()
        );
        let files = &view[2];
        let sets: Vec<&El> = files
            .descendants()
            .into_iter()
            .filter(|e| e.tag == "fieldset")
            .collect();
        assert_eq!(sets[0].get("data-file"), Some("walk/acc.csv"));
        assert!(sets[0]
            .text_content()
            .starts_with("acc.csvcomma-separated, no header · first row: 0.5"));
        let acc = [
            ("sensor", "accelerometer"),
            ("t", "1"),
            ("x", "2"),
            ("y", "3"),
            ("z", "4"),
        ];
        assert_eq!(
            selected(sets[0]),
            pairs(&[&acc[..], &[("time_unit", "ms"), ("unit", "m/s2")]].concat())
        );
        // No rule for imu.csv: one row, "not used", no fields.
        assert_eq!(selected(sets[1]), pairs(&[("sensor", "")]));
        assert!(sets[1]
            .text_content()
            .ends_with("+ another sensor in this file"));
    }

    #[test]
    fn a_second_sensor_takes_the_next_three_columns() {
        let f = form();
        let fields = f.fields("walk/imu.csv", 1, "gyroscope").unwrap();
        let want = [
            ("t", "1"),
            ("x", "5"),
            ("y", "6"),
            ("z", "7"),
            ("time_unit", "ms"),
            ("unit", "rad/s"),
        ];
        assert_eq!(selected(&fields), pairs(&want));
        assert_eq!(fields.get("class"), Some("recipe-fields controls"));
        let labels: Vec<&Node> = fields
            .descendants()
            .into_iter()
            .filter(|e| e.tag == "label")
            .map(|e| &e.children[0])
            .collect();
        let words = ["time ", "x ", "y ", "z ", "time in ", "unit "];
        assert_eq!(
            labels,
            words
                .map(|w| Node::Text(w.into()))
                .iter()
                .collect::<Vec<_>>()
        );
        assert!(f.fields("walk/imu.csv", 0, "").unwrap().children.is_empty());
        assert!(f.fields("walk/imu.csv", 0, "thermometer").is_err());
        assert!(f.row("walk/none.csv", 0).is_err());
        assert_eq!(
            selected(&f.row("walk/acc.csv", 1).unwrap()),
            pairs(&[("sensor", "")])
        );
    }

    #[test]
    fn the_values_make_a_recipe_the_reader_takes() {
        let row = |file: &str, sensor: &str, unit: &str, cols: &[(&str, &str)]| {
            let k = [("sensor", sensor), ("time_unit", "ms"), ("unit", unit)];
            let select = |k: Option<&str>, col: Option<&str>, value: &str| SelectValue {
                k: k.map(Into::into),
                col: col.map(Into::into),
                value: value.into(),
            };
            let first = k[..1].iter().map(|(k, v)| select(Some(k), None, v));
            let columns = cols.iter().map(|(c, v)| select(None, Some(c), v));
            let units = k[1..].iter().map(|(k, v)| select(Some(k), None, v));
            RowValues {
                file: file.into(),
                selects: first.chain(columns).chain(units).collect(),
            }
        };
        let cols = [("t", "1"), ("x", "2"), ("y", "3"), ("z", "4")];
        let rows = [
            row("walk/acc.csv", "accelerometer", "g", &cols),
            row("walk/imu.csv", "", "", &[]),
        ];
        let json = form().recipe("  ", &rows).unwrap();
        let r = Recipe::from_json(&json).unwrap();
        assert_eq!(r.name, DEFAULT_NAME);
        assert_eq!(r.files.len(), 1, "a row not used is left out");
        assert_eq!(r.files[0].pattern, "acc.csv");
        assert_eq!(r.files[0].columns.x, Some(Column::Number(2)));
        assert_eq!(r.files[0].unit.map(|u| u.as_str()), Some("g"));
        let named = form().recipe("Test logger", &rows[..1]).unwrap();
        assert_eq!(Recipe::from_json(&named).unwrap().name, "Test logger");
        // A column that is not one: the reader's error, as for a recipe file.
        let bad = form().recipe(
            "x",
            &[row("walk/acc.csv", "accelerometer", "", &[("t", "")])],
        );
        assert!(Recipe::from_json(&bad.unwrap()).is_err());
        assert!(form()
            .recipe("x", &[row("walk/other.csv", "gyroscope", "", &[])])
            .is_err());
    }

    #[test]
    fn the_preview_shows_the_messages_and_a_table_per_file() {
        let (messages, tables) = preview_view(Err("no file matches \"acc.csv\""));
        assert_eq!(messages[0].get("class"), Some("error"));
        assert!(tables.is_empty());
        let report = Report {
            recipe: "r".into(),
            files: vec![FileReport {
                file: "walk/acc.csv".into(),
                sensor: "accelerometer",
                columns: vec!["t s", "x m/s²"],
                rows: vec![vec![0.001, 9.806649]],
                samples: 2000,
                skipped: 0,
                errors: Vec::new(),
                rate_hz: Some(100.0),
                median: Some(9.81),
            }],
            warnings: vec!["acc.csv: odd".into()],
            notes: vec!["a note".into()],
        };
        let (messages, tables) = preview_view(Ok(&report));
        let classes: Vec<_> = messages.iter().map(|m| m.get("class").unwrap()).collect();
        assert_eq!(classes, ["warn", "note"]);
        assert_eq!(
            tables[0].text_content(),
            "acc.csv — accelerometer · 2,000 samples previewed · 100 Hz · median |v| 9.81t sx m/s²0.0019.80665"
        );
        assert_eq!(tables[0].get("class"), Some("recipe-table"));
    }
}
