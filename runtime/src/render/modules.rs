//! The WGSL module of each pipeline, assembled from the files of the `chamfer-shaders` crate: the
//! constants generated from Rust (`layout.rs`) first, then the shared definitions a pass needs, then
//! the pass itself.

use chamfer_shaders as wgsl;

use super::layout::wgsl_constants;

fn assemble(parts: &[&str]) -> String {
    let mut source = wgsl_constants();
    for part in parts {
        source.push_str(part);
        source.push('\n');
    }
    source
}

/// Cluster culling and edge classification.
pub(crate) fn classify() -> String {
    assemble(&[
        wgsl::COMMON,
        wgsl::HIGHLIGHT,
        wgsl::LISTS,
        wgsl::COMPUTE,
        wgsl::CULL,
        wgsl::CLASSIFY,
    ])
}

/// Workgroup counts of the next-index join pass.
pub(crate) fn args() -> String {
    assemble(&[wgsl::COMMON, wgsl::LISTS, wgsl::ARGS])
}

/// Joins and caps, by next-index walk or cap buffer.
pub(crate) fn joins() -> String {
    assemble(&[
        wgsl::COMMON,
        wgsl::HIGHLIGHT,
        wgsl::LISTS,
        wgsl::COMPUTE,
        wgsl::JOINS,
    ])
}

/// Chamfer records of highlighted edges.
pub(crate) fn chamfers() -> String {
    assemble(&[
        wgsl::COMMON,
        wgsl::HIGHLIGHT,
        wgsl::LISTS,
        wgsl::COMPUTE,
        wgsl::CHAMFERS,
    ])
}

/// Compacted edge quads.
pub(crate) fn edges() -> String {
    assemble(&[wgsl::COMMON, wgsl::HIGHLIGHT, wgsl::DRAW, wgsl::EDGES])
}

/// Intersection edges.
pub(crate) fn intersections() -> String {
    assemble(&[wgsl::COMMON, wgsl::INTERSECTIONS])
}

/// Round caps.
pub(crate) fn caps() -> String {
    assemble(&[wgsl::COMMON, wgsl::HIGHLIGHT, wgsl::DRAW, wgsl::CAPS])
}

/// McGuire–Hughes edges and caps, classified per vertex.
pub(crate) fn mcguire_hughes() -> String {
    assemble(&[
        wgsl::COMMON,
        wgsl::FLAT,
        wgsl::VERTEX_EDGES,
        wgsl::MCGUIRE_HUGHES,
    ])
}

/// Half-hex, plug and house edges.
pub(crate) fn alternate() -> String {
    assemble(&[
        wgsl::COMMON,
        wgsl::FLAT,
        wgsl::VERTEX_EDGES,
        wgsl::ALTERNATE,
    ])
}

/// Fins extruded along the normals.
pub(crate) fn fins() -> String {
    assemble(&[wgsl::COMMON, wgsl::FLAT, wgsl::FINS])
}

/// The barycentric wireframe.
pub(crate) fn wireframe() -> String {
    assemble(&[wgsl::COMMON, wgsl::TRIANGLES, wgsl::WIREFRAME])
}

/// The hardware contour passes.
pub(crate) fn hardware() -> String {
    assemble(&[wgsl::COMMON, wgsl::FLAT, wgsl::TRIANGLES, wgsl::HARDWARE])
}

/// Surface-angle contours.
pub(crate) fn surface_angle() -> String {
    assemble(&[wgsl::COMMON, wgsl::SURFACE_ANGLE])
}

/// The inverted hull.
pub(crate) fn inverted_hull() -> String {
    assemble(&[wgsl::COMMON, wgsl::FLAT, wgsl::INVERTED_HULL])
}

/// The hybrid depth shader, for a multisampled depth or not.
pub(crate) fn hybrid(multisampled: bool) -> String {
    assemble(&[post_depth(multisampled), wgsl::POST, wgsl::HYBRID])
}

/// Image-space operators, for a multisampled depth or not.
pub(crate) fn image_space(multisampled: bool) -> String {
    assemble(&[post_depth(multisampled), wgsl::POST, wgsl::IMAGE_SPACE])
}

fn post_depth(multisampled: bool) -> &'static str {
    if multisampled {
        wgsl::DEPTH_MULTI
    } else {
        wgsl::DEPTH_SINGLE
    }
}

/// The lit mesh.
pub(crate) fn mesh() -> String {
    assemble(&[wgsl::MESH])
}

/// Every module the renderer compiles, by name: what the CPU-only naga test validates.
#[cfg(test)]
pub(crate) fn all() -> Vec<(&'static str, String)> {
    vec![
        ("classify", classify()),
        ("args", args()),
        ("joins", joins()),
        ("chamfers", chamfers()),
        ("edges", edges()),
        ("caps", caps()),
        ("intersections", intersections()),
        ("mesh", mesh()),
        ("mcguire_hughes", mcguire_hughes()),
        ("alternate", alternate()),
        ("fins", fins()),
        ("wireframe", wireframe()),
        ("hardware", hardware()),
        ("surface_angle", surface_angle()),
        ("inverted_hull", inverted_hull()),
        ("hybrid", hybrid(false)),
        ("hybrid msaa", hybrid(true)),
        ("image_space", image_space(false)),
        ("image_space msaa", image_space(true)),
    ]
}

#[cfg(test)]
mod tests {
    use std::collections::HashMap;

    use wgpu::naga;

    use super::super::layout::{self, constants};
    use super::all;

    fn parse(name: &str, source: &str) -> naga::Module {
        let module = naga::front::wgsl::parse_str(source)
            .unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(source)));
        // What every WebGPU-core device has (unpack2x16float needs the f16-in-f32 capability).
        let mut validator = naga::valid::Validator::new(
            naga::valid::ValidationFlags::all(),
            naga::valid::Capabilities::SHADER_FLOAT16_IN_FLOAT32,
        );
        validator
            .validate(&module)
            .unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(source)));
        module
    }

    /// Struct name -> (size, members with offsets) as naga lays it out.
    fn structs(module: &naga::Module) -> HashMap<String, (u32, Vec<(String, u32)>)> {
        let mut out = HashMap::new();
        for (_, ty) in module.types.iter() {
            if let (Some(name), naga::TypeInner::Struct { members, span }) = (&ty.name, &ty.inner) {
                let members = members
                    .iter()
                    .map(|m| (m.name.clone().unwrap_or_default(), m.offset))
                    .collect();
                out.insert(name.clone(), (*span, members));
            }
        }
        out
    }

    #[test]
    fn every_module_parses_and_validates_on_the_cpu() {
        let modules = all();
        assert!(modules.len() >= 18);
        for (name, source) in &modules {
            parse(name, source);
        }
    }

    #[test]
    fn a_broken_module_is_caught_without_an_adapter() {
        // The check above can fail: a type error and an unknown identifier are both refused.
        let source = format!(
            "{}fn f() -> u32 {{ return 1.5; }}",
            layout::wgsl_constants()
        );
        let module = naga::front::wgsl::parse_str(&source);
        assert!(module.is_err());
        let source = format!(
            "{}fn f() -> u32 {{ return NOT_A_CONSTANT; }}",
            layout::wgsl_constants()
        );
        assert!(naga::front::wgsl::parse_str(&source).is_err());
    }

    #[test]
    fn shared_structs_have_the_same_layout_in_rust_and_wgsl() {
        let mut seen: HashMap<&str, usize> = HashMap::new();
        for (name, source) in all() {
            let module = parse(name, &source);
            let declared = structs(&module);
            for rust in layout::layouts() {
                let Some((size, members)) = declared.get(rust.wgsl) else {
                    continue;
                };
                *seen.entry(rust.wgsl).or_default() += 1;
                for &(member, offset) in &rust.members {
                    let wgsl = members.iter().find(|(m, _)| m == member);
                    assert_eq!(
                        wgsl.map(|&(_, o)| o as usize),
                        Some(offset),
                        "{name}: {}.{member} is at {offset} in Rust",
                        rust.wgsl
                    );
                }
                for (member, offset) in members {
                    if rust.members.iter().any(|(m, _)| m == member) {
                        continue;
                    }
                    // A member only WGSL has must be the trailing runtime-sized list after the head
                    // the Rust struct describes.
                    assert_eq!(
                        (*offset as usize, member == &members[members.len() - 1].0),
                        (rust.size, true),
                        "{name}: {}.{member} is not in the Rust struct",
                        rust.wgsl
                    );
                }
                if members.len() == rust.members.len() {
                    assert_eq!(*size as usize, rust.size, "{name}: size of {}", rust.wgsl);
                }
            }
        }
        for rust in layout::layouts() {
            assert!(
                seen.contains_key(rust.wgsl),
                "no module declares {}",
                rust.wgsl
            );
        }
    }

    #[test]
    fn shared_constants_have_the_rust_values() {
        for (name, source) in all() {
            let module = parse(name, &source);
            for (constant, value) in constants() {
                let found = module
                    .constants
                    .iter()
                    .find(|(_, c)| c.name.as_deref() == Some(constant))
                    .map(|(_, c)| &module.global_expressions[c.init]);
                let literal = match found {
                    Some(naga::Expression::Literal(naga::Literal::U32(v))) => Some(*v),
                    Some(other) => panic!("{name}: {constant} is {other:?}"),
                    // naga drops constants a module does not use.
                    None => None,
                };
                assert!(literal.is_none_or(|v| v == value), "{name}: {constant}");
            }
            // No WGSL file declares a shared constant of its own: each name appears once, in the
            // generated prelude.
            for (constant, _) in constants() {
                let declared = source.matches(&format!("const {constant}:")).count();
                assert_eq!(declared, 1, "{name}: {constant} declared {declared} times");
            }
        }
    }
}
