//! The opt-in base map's setting as the page keeps it (localStorage, JSON) and as its form gives
//! it, with what the page says about the base map. The template itself is checked when the
//! page hands it over ([`TileTemplate::parse`](super::tiles::TileTemplate::parse)).
//! May import: the tile maths' default server.

use super::tiles::OSM_TEMPLATE;

/// The base map setting: on or off, the tile URL template, the credit line (empty: the
/// server's own).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct BasemapSetting {
    /// Whether the base map is drawn.
    pub on: bool,
    /// The tile server's URL template (checked when handed to the engine).
    pub template: String,
    /// The credit line; empty: the server's own.
    pub attribution: String,
}

/// JavaScript's whitespace for `trim()`: Unicode's `White_Space` without U+0085, with the
/// byte-order mark U+FEFF (the page's form fields were always trimmed so).
fn is_js_space(c: char) -> bool {
    (c.is_whitespace() && c != '\u{85}') || c == '\u{feff}'
}

impl BasemapSetting {
    /// The stored setting from its JSON text (`None`: nothing stored). Off unless `on` is
    /// `true`; OpenStreetMap's template unless `template` is a string with more than spaces
    /// (kept as it is); no credit line unless `attribution` is a string. Damaged text, or JSON
    /// that is not an object, is the default: off, OpenStreetMap, no credit line.
    pub fn from_stored(text: Option<&str>) -> BasemapSetting {
        let v: serde_json::Value = text
            .and_then(|t| serde_json::from_str(t).ok())
            .unwrap_or_default();
        let text_field = |k: &str| v.get(k).and_then(serde_json::Value::as_str);
        BasemapSetting {
            on: v.get("on") == Some(&serde_json::Value::Bool(true)),
            template: text_field("template")
                .filter(|t| !t.trim_matches(is_js_space).is_empty())
                .unwrap_or(OSM_TEMPLATE)
                .to_string(),
            attribution: text_field("attribution").unwrap_or("").to_string(),
        }
    }

    /// The setting from the form's fields: template and credit line trimmed; a blank template
    /// is OpenStreetMap's.
    pub fn from_form(on: bool, template: &str, attribution: &str) -> BasemapSetting {
        let template = template.trim_matches(is_js_space);
        BasemapSetting {
            on,
            template: if template.is_empty() {
                OSM_TEMPLATE
            } else {
                template
            }
            .to_string(),
            attribution: attribution.trim_matches(is_js_space).to_string(),
        }
    }
}

/// What the page says about the base map, for `key`: `off` (the template was refused, `detail`
/// says why), `forgotten` (the cached tiles were deleted), `none_cached` (there were none).
pub fn message(key: &str, detail: &str) -> Option<String> {
    match key {
        "off" => Some(format!("Base map off: {detail}")),
        "forgotten" => Some("Cached tiles deleted from this device.".to_string()),
        "none_cached" => Some("No cached tiles on this device.".to_string()),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn setting(on: bool, template: &str, attribution: &str) -> BasemapSetting {
        BasemapSetting {
            on,
            template: template.to_string(),
            attribution: attribution.to_string(),
        }
    }

    #[test]
    fn nothing_stored_or_damaged_is_off_with_openstreetmap() {
        let default = setting(false, OSM_TEMPLATE, "");
        for text in [
            None,
            Some("{"),
            Some("null"),
            Some("5"),
            Some("\"on\""),
            Some("[true]"),
        ] {
            assert_eq!(BasemapSetting::from_stored(text), default, "{text:?}");
        }
    }

    #[test]
    fn a_stored_setting_is_kept_as_it_is() {
        let s =
            r#"{"on":true,"template":" https://t.example/{z}/{x}/{y}.png","attribution":"© T"}"#;
        assert_eq!(
            BasemapSetting::from_stored(Some(s)),
            setting(true, " https://t.example/{z}/{x}/{y}.png", "© T")
        );
    }

    #[test]
    fn fields_of_the_wrong_kind_are_the_default() {
        let s = r#"{"on":"yes","template":"  \ufeff","attribution":3}"#;
        assert_eq!(
            BasemapSetting::from_stored(Some(s)),
            setting(false, OSM_TEMPLATE, "")
        );
        let s = r#"{"on":1,"template":42}"#;
        assert_eq!(
            BasemapSetting::from_stored(Some(s)),
            setting(false, OSM_TEMPLATE, "")
        );
    }

    #[test]
    fn the_form_is_trimmed_and_a_blank_template_is_openstreetmap() {
        assert_eq!(
            BasemapSetting::from_form(true, "  https://a/{z}/{x}/{y} ", " credit\n"),
            setting(true, "https://a/{z}/{x}/{y}", "credit")
        );
        assert_eq!(
            BasemapSetting::from_form(false, " \t", ""),
            setting(false, OSM_TEMPLATE, "")
        );
    }

    #[test]
    fn the_page_words() {
        assert_eq!(
            message("off", "it is empty").as_deref(),
            Some("Base map off: it is empty")
        );
        assert_eq!(
            message("forgotten", "").as_deref(),
            Some("Cached tiles deleted from this device.")
        );
        assert_eq!(
            message("none_cached", "").as_deref(),
            Some("No cached tiles on this device.")
        );
        assert_eq!(message("elsewhere", ""), None);
    }
}
