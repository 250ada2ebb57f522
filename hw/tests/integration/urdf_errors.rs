//! Broken rigs give errors that name the file, the element, the field and the reason; never a panic.

use knotlab_hw::rig::{DEFAULT_URDF, Rig, RigError};

/// The shipped URDF with one substring replaced (which must occur).
fn broken(from: &str, to: &str) -> String {
    assert!(DEFAULT_URDF.contains(from), "fixture text not found: {from}");
    DEFAULT_URDF.replacen(from, to, 1)
}

fn load_err(text: &str) -> String {
    match Rig::from_urdf_str(text, "broken.urdf") {
        Ok(_) => panic!("a broken rig loaded"),
        Err(e) => e.to_string(),
    }
}

/// The shipped URDF loads with four arms and a limit on each of their 24 axes and three instruments'
/// 15 joints.
#[test]
fn the_shipped_rig_loads_with_four_arms() {
    let rig = Rig::shipped().unwrap();
    assert_eq!(rig.arms.len(), 4);
    assert_eq!(rig.tree.joints.iter().filter(|j| j.limit.is_some()).count(), 6 * 4 + 5 * 3);
}

/// A joint naming a parent link that does not exist is refused naming the file, the joint and the link.
#[test]
fn a_joint_naming_a_missing_parent_link_is_named() {
    let text = broken("<parent link=\"left_link1\"/>", "<parent link=\"left_link9\"/>");
    let err = load_err(&text);
    assert!(err.starts_with("broken.urdf:"), "{err}");
    assert!(
        err.contains("joint 'left_joint2', parent: names link 'left_link9', which does not exist"),
        "{err}"
    );
}

/// A joint without a parent element is refused naming the joint, its line and the missing element.
#[test]
fn a_joint_without_a_parent_element_is_named_with_its_line() {
    let text = broken("    <parent link=\"left_link1\"/>\n", "");
    let err = load_err(&text);
    assert!(err.starts_with("broken.urdf: 1 problem(s)"), "{err}");
    let line = text.lines().position(|l| l.contains("<joint name=\"left_joint2\"")).unwrap() + 1;
    assert!(err.contains(&format!("joint 'left_joint2' (line {line}), parent: missing element")), "{err}");
}

/// A box without a size is refused naming its link and the missing attribute.
#[test]
fn a_box_without_a_size_is_named_by_its_link() {
    let text = broken("<box size=\"0.12 0.5 0.13\"/>", "<box/>");
    let err = load_err(&text);
    assert!(err.contains("link 'left_link2' <box>") && err.contains("size: missing attribute"), "{err}");
}

/// Malformed XML is refused as an XML error in the document, not loaded.
#[test]
fn malformed_xml_gives_the_position() {
    let text = broken("<link name=\"table\">", "<link name=\"table\"");
    let err = load_err(&text);
    assert!(err.contains("document, xml:") && err.contains(":"), "{err}");
}

/// A joint limit whose lower bound lies above its upper is refused naming the joint and both bounds.
#[test]
fn a_limit_with_lower_above_upper_is_named() {
    let text =
        broken("lower=\"-2.0943951023931953\" upper=\"2.0943951023931953\"", "lower=\"2.5\" upper=\"1.0\"");
    let err = load_err(&text);
    assert!(err.contains("joint 'left_joint5', limit: lower 2.5 must be below upper 1"), "{err}");
}

/// A NaN velocity limit and a NaN origin are both reported in one error, each naming its field.
#[test]
fn a_nan_limit_and_a_nan_origin_are_named_together() {
    let text = broken("velocity=\"4.6600291028248595\"", "velocity=\"nan\"");
    let text = text.replacen("<origin xyz=\"0.0 0.0 0.4318\"", "<origin xyz=\"0.0 NaN 0.4318\"", 1);
    let err = load_err(&text);
    assert!(err.contains("2 problem(s)"), "{err}");
    assert!(err.contains("limit.velocity: not finite: NaN"), "{err}");
    assert!(err.contains("joint 'left_wrist_pitch', origin.xyz: not finite"), "{err}");
}

/// An arm missing one of its joints is refused naming the arm and the missing joint.
#[test]
fn a_missing_arm_joint_is_named() {
    let text = broken("name=\"camera_joint4\"", "name=\"camera_joint_four\"");
    let err = load_err(&text);
    assert!(err.contains("arm 'camera', joints: no joint 'camera_joint4'"), "{err}");
}

/// A collision mesh is refused naming the link and its collision element: only boxes, capsules and spheres.
#[test]
fn an_unsupported_collision_shape_is_named() {
    // Both the visual and the collision element use it; only collision geometry matters.
    let text = DEFAULT_URDF.replace("<box size=\"1.9 0.6 0.8\"/>", "<mesh filename=\"table.stl\"/>");
    let err = load_err(&text);
    assert!(err.contains("link 'table' collision 0, geometry: only boxes, capsules and spheres"), "{err}");
}

/// A link given two parents, making a cycle or a second root in the tree, is refused.
#[test]
fn a_cycle_is_refused() {
    // Hang the gantry from the left arm's tip: the gantry gets two parents.
    let text = broken(
        "<parent link=\"world\"/>\n    <child link=\"gantry\"/>",
        "<parent link=\"left_tip\"/>\n    <child link=\"gantry\"/>",
    );
    let err = load_err(&text);
    assert!(err.contains("cycle") || err.contains("more than one root"), "{err}");
}

/// A URDF file that cannot be read is refused as a read error naming its path.
#[test]
fn an_unreadable_file_names_the_file() {
    let err = Rig::from_file(std::path::Path::new("/nonexistent/rig.urdf")).unwrap_err();
    assert!(matches!(err, RigError::Read { .. }));
    assert!(err.to_string().starts_with("/nonexistent/rig.urdf: cannot read"), "{err}");
}

/// Empty, non-XML, malformed-geometry and non-robot documents are refused naming the file.
#[test]
fn garbage_is_a_parse_error() {
    for text in [
        "",
        "not xml",
        "<robot name=\"x\"><link name=\"a\"><collision><geometry><box size=\"1 1\"/></geometry></collision></link></robot>",
        "<urdf/>",
    ] {
        assert!(
            Rig::from_urdf_str(text, "junk.urdf").unwrap_err().to_string().starts_with("junk.urdf: "),
            "{text}"
        );
    }
}

/// A document nested deeper than urdf-rs can read without overflowing its stack (it reads elements by
/// recursion: 1,500 levels overflowed a test thread) is refused before urdf-rs sees it, whether it is
/// well-formed or its elements are left open (which roxmltree refuses but urdf-rs still recursed
/// into), naming the depth.
#[test]
fn a_document_nested_too_deep_is_refused_open_or_closed() {
    let closed = format!("<robot name=\"r\">{}{}</robot>", "<a>".repeat(3000), "</a>".repeat(3000));
    let open = format!("<robot name=\"r\">{}", "<link name=\"l\">".repeat(3000));
    for text in [closed, open] {
        let e = load_err(&text);
        assert!(e.contains("elements nested deeper than 64"), "{e}");
    }
    // Comments, declarations and self-closing elements do not deepen it.
    let shallow = format!(
        "<?xml version=\"1.0\"?><!-- {} --><robot name=\"r\">{}</robot>",
        "<a>".repeat(100),
        "<b/>".repeat(100)
    );
    let e = load_err(&shallow);
    assert!(!e.contains("nested deeper"), "{e}");
}
