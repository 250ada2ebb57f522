//! When urdf-rs refuses a document, find which element is at fault: urdf-rs reports a missing field
//! without saying where, so the document is walked once more with roxmltree to name the element and
//! its line.

use super::error::Problem;

/// Attributes and children each element must have, as urdf-rs requires them.
fn required(tag: &str) -> (&'static [&'static str], &'static [&'static str]) {
    match tag {
        "robot" => (&["name"], &[]),
        "link" => (&["name"], &[]),
        "joint" => (&["name", "type"], &["parent", "child"]),
        "parent" | "child" => (&["link"], &[]),
        "box" => (&["size"], &[]),
        "capsule" | "cylinder" => (&["radius", "length"], &[]),
        "sphere" => (&["radius"], &[]),
        "mesh" => (&["filename"], &[]),
        "mass" => (&["value"], &[]),
        "limit" => (&["velocity"], &[]),
        "visual" | "collision" => (&[], &["geometry"]),
        _ => (&[], &[]),
    }
}

/// Deepest nesting of elements a URDF may have: a robot's deepest element (`robot > link > visual >
/// geometry > box`) is five down. urdf-rs reads elements by recursion, and a document nested some
/// thousands deep overflows the stack before it can refuse it.
pub const MAX_DEPTH: usize = 64;

/// A problem when `text` nests elements deeper than [`MAX_DEPTH`], found without recursion (by
/// roxmltree, whose parser keeps its own stack); `None` otherwise, also when it is no XML at all
/// (urdf-rs and [`diagnose`] say why).
pub fn too_deep(text: &str) -> Option<Problem> {
    let Ok(doc) = roxmltree::Document::parse(text) else {
        return lexically_too_deep(text);
    };
    let mut depth = vec![0usize; doc.descendants().count() + 1];
    for node in doc.descendants() {
        let d = node.parent().map_or(0, |p| depth[p.id().get() as usize] + 1);
        depth[node.id().get() as usize] = d;
        if d > MAX_DEPTH {
            let line = doc.text_pos_at(node.range().start).row;
            return Some(Problem::new(
                "document",
                "depth",
                format!("elements nested deeper than {MAX_DEPTH} (line {line})"),
            ));
        }
    }
    None
}

/// [`too_deep`] for a text that is no well-formed XML (elements left open, say), which urdf-rs still
/// reads by recursion before it refuses it: opening tags less closing ones, comments, processing
/// instructions, CDATA and declarations skipped.
fn lexically_too_deep(text: &str) -> Option<Problem> {
    let bytes = text.as_bytes();
    let (mut depth, mut i) = (0usize, 0usize);
    let skip_to = |from: usize, end: &[u8]| {
        bytes[from..].windows(end.len()).position(|w| w == end).map_or(bytes.len(), |k| from + k + end.len())
    };
    while i < bytes.len() {
        if bytes[i] != b'<' {
            i += 1;
            continue;
        }
        let rest = &bytes[i..];
        i = if rest.starts_with(b"<!--") {
            skip_to(i, b"-->")
        } else if rest.starts_with(b"<![CDATA[") {
            skip_to(i, b"]]>")
        } else if rest.starts_with(b"<?") {
            skip_to(i, b"?>")
        } else if rest.starts_with(b"<!") {
            skip_to(i, b">")
        } else if rest.starts_with(b"</") {
            depth = depth.saturating_sub(1);
            skip_to(i, b">")
        } else {
            let end = skip_to(i, b">");
            if end > i + 1 && bytes[end.saturating_sub(2)] != b'/' {
                depth += 1;
                if depth > MAX_DEPTH {
                    let line = text[..i].matches('\n').count() + 1;
                    return Some(Problem::new(
                        "document",
                        "depth",
                        format!("elements nested deeper than {MAX_DEPTH} (line {line})"),
                    ));
                }
            }
            end
        };
    }
    None
}

/// Problems that explain why urdf-rs refused `text`; empty when none is found.
pub fn diagnose(text: &str) -> Vec<Problem> {
    let doc = match roxmltree::Document::parse(text) {
        Ok(doc) => doc,
        Err(e) => return vec![Problem::new("document", "xml", e.to_string())],
    };
    let mut problems = Vec::new();
    let root = doc.root_element();
    if root.tag_name().name() != "robot" {
        problems.push(Problem::new(
            "document",
            "root",
            format!("must be <robot>, found <{}>", root.tag_name().name()),
        ));
    }
    for node in root.descendants().filter(|n| n.is_element()) {
        let tag = node.tag_name().name();
        let line = doc.text_pos_at(node.range().start).row;
        // Name the element by its own name, or by the named element it sits in.
        let owner = node.ancestors().find(|a| {
            a.is_element() && a.attribute("name").is_some() && matches!(a.tag_name().name(), "link" | "joint")
        });
        let element = match (node.attribute("name"), owner) {
            (Some(name), _) if matches!(tag, "link" | "joint" | "robot") => {
                format!("{tag} '{name}' (line {line})")
            }
            (_, Some(o)) => format!(
                "{} '{}' <{tag}> (line {line})",
                o.tag_name().name(),
                o.attribute("name").unwrap_or_default()
            ),
            _ => format!("<{tag}> (line {line})"),
        };
        let (attributes, children) = required(tag);
        for attribute in attributes {
            if node.attribute(*attribute).is_none() {
                problems.push(Problem::new(&element, *attribute, "missing attribute"));
            }
        }
        for child in children {
            if !node.children().any(|c| c.is_element() && c.tag_name().name() == *child) {
                problems.push(Problem::new(&element, *child, "missing element"));
            }
        }
    }
    problems
}
