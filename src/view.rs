//! A piece of the page as the engine describes it: elements, their attributes, their text. The
//! page's words and structure are made here, where native tests can read them; `render` in
//! `www/util.js` turns a tree into DOM elements and does nothing else.
//! May import: nothing.

use serde::ser::{SerializeMap, SerializeTuple};
use serde::{Serialize, Serializer};

/// A node: an element, or text. Serialised as `[tag, {attribute: value}, [children]]` or a
/// string, the shape `render` reads.
#[derive(Debug, Clone, PartialEq)]
pub enum Node {
    /// An element with its attributes and children.
    Element(El),
    /// Text.
    Text(String),
}

/// An element: a tag, its attributes in order, its children.
#[derive(Debug, Clone, PartialEq)]
pub struct El {
    /// The tag name (`p`, `button`, …).
    pub tag: &'static str,
    /// The attributes, `(name, value)`, in the order set.
    pub attrs: Vec<(&'static str, String)>,
    /// The children, elements and text, in order.
    pub children: Vec<Node>,
}

impl El {
    /// An element `tag` with no attributes and no children.
    pub fn new(tag: &'static str) -> Self {
        El {
            tag,
            attrs: Vec::new(),
            children: Vec::new(),
        }
    }

    /// Sets attribute `name` (`class`, `data-…`, `aria-label`, `disabled`, …).
    pub fn attr(mut self, name: &'static str, value: impl Into<String>) -> Self {
        self.attrs.push((name, value.into()));
        self
    }

    /// Sets `class`.
    pub fn class(self, class: &'static str) -> Self {
        self.attr("class", class)
    }

    /// Appends text.
    pub fn text(mut self, text: impl Into<String>) -> Self {
        self.children.push(Node::Text(text.into()));
        self
    }

    /// Appends an element.
    pub fn child(mut self, child: El) -> Self {
        self.children.push(Node::Element(child));
        self
    }

    /// Appends elements.
    pub fn children(mut self, children: impl IntoIterator<Item = El>) -> Self {
        self.children
            .extend(children.into_iter().map(Node::Element));
        self
    }

    /// The value of attribute `name`, if set.
    pub fn get(&self, name: &str) -> Option<&str> {
        self.attrs
            .iter()
            .find(|(k, _)| *k == name)
            .map(|(_, v)| v.as_str())
    }

    /// All the text inside, in document order (what a reader of the page sees).
    pub fn text_content(&self) -> String {
        let mut out = String::new();
        self.collect_text(&mut out);
        out
    }

    fn collect_text(&self, out: &mut String) {
        for c in &self.children {
            match c {
                Node::Text(t) => out.push_str(t),
                Node::Element(e) => e.collect_text(out),
            }
        }
    }

    /// Every element inside (this one first), depth first.
    pub fn descendants(&self) -> Vec<&El> {
        let mut out = vec![self];
        for c in &self.children {
            if let Node::Element(e) = c {
                out.extend(e.descendants());
            }
        }
        out
    }
}

impl Serialize for El {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        struct Attrs<'a>(&'a [(&'static str, String)]);
        impl Serialize for Attrs<'_> {
            fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                let mut m = s.serialize_map(Some(self.0.len()))?;
                for (k, v) in self.0 {
                    m.serialize_entry(k, v)?;
                }
                m.end()
            }
        }
        let mut t = s.serialize_tuple(3)?;
        t.serialize_element(self.tag)?;
        t.serialize_element(&Attrs(&self.attrs))?;
        t.serialize_element(&self.children)?;
        t.end()
    }
}

impl Serialize for Node {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Node::Element(e) => e.serialize(s),
            Node::Text(t) => s.serialize_str(t),
        }
    }
}

/// A whole number with a comma every three digits ("12,345"), as `toLocaleString('en')`
/// writes it.
pub fn thousands(n: u64) -> String {
    let digits = n.to_string();
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i) % 3 == 0 {
            out.push(',');
        }
        out.push(c);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn serialises_in_the_shape_render_reads() {
        let e = El::new("p")
            .class("hint")
            .attr("data-step", "3")
            .text("step ")
            .child(El::new("b").text("3"));
        assert_eq!(
            serde_json::to_string(&e).unwrap(),
            r#"["p",{"class":"hint","data-step":"3"},["step ",["b",{},["3"]]]]"#
        );
        assert_eq!(e.text_content(), "step 3");
        assert_eq!(e.get("data-step"), Some("3"));
        assert_eq!(e.descendants().len(), 2);
    }

    #[test]
    fn thousands_are_grouped() {
        assert_eq!(thousands(0), "0");
        assert_eq!(thousands(999), "999");
        assert_eq!(thousands(2000), "2,000");
        assert_eq!(thousands(1_234_567), "1,234,567");
    }
}
