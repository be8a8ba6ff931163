//! The WGSL modules of the renderer and what they declare. A technique declares each module it
//! compiles as a [`Shader`]: its source, assembled from the files of the `chamfer-shaders` crate
//! (the constants generated from Rust in `layout.rs` first, then the shared definitions a pass needs,
//! then the pass), and the [`Program`]s made of it, each with the bindings of its layout. Pipelines
//! are compiled from these declarations only (`Pipelines::compile`), and the CPU-only tests below
//! check every declaration of every technique against its WGSL with naga: the modules validate, the
//! bindings agree (index, name, kind, access; an entry point binds nothing its layout lacks), and
//! every struct shared with Rust has the Rust layout.

use super::bindings::Bindings;
use super::layout::wgsl_constants;

/// A WGSL module and the pipelines compiled from it.
#[derive(Debug)]
pub(crate) struct Shader {
    /// The module's name in errors and GPU debuggers (its pass's file).
    pub(crate) label: &'static str,
    pub(crate) source: String,
    pub(crate) programs: Vec<Program>,
}

impl Shader {
    /// The module of `parts` (shared files first, the pass last) with its programs.
    pub(crate) fn new(label: &'static str, parts: &[&str], programs: Vec<Program>) -> Self {
        let mut source = wgsl_constants();
        for part in parts {
            source.push_str(part);
            source.push('\n');
        }
        Self {
            label,
            source,
            programs,
        }
    }
}

/// One pipeline's entry points and the bindings of its layout.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Program {
    /// The compute or vertex entry point.
    pub(crate) entry: &'static str,
    /// The fragment entry point of a render pipeline.
    pub(crate) fragment: Option<&'static str>,
    pub(crate) bindings: &'static Bindings,
}

impl Program {
    /// A compute pipeline of `entry`.
    pub(crate) const fn compute(entry: &'static str, bindings: &'static Bindings) -> Self {
        Self {
            entry,
            fragment: None,
            bindings,
        }
    }

    /// A render pipeline of `vertex` and `fragment`.
    pub(crate) const fn draw(
        vertex: &'static str,
        fragment: &'static str,
        bindings: &'static Bindings,
    ) -> Self {
        Self {
            entry: vertex,
            fragment: Some(fragment),
            bindings,
        }
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use std::collections::HashMap;

    use wgpu::naga;

    use super::super::bindings::{Binding, Kind};
    use super::super::layout::{self, Layout, constants};
    use super::super::techniques;
    use super::super::{Target, Technique};
    use super::Shader;

    /// The targets every declaration is checked for: one and four samples, with and without
    /// stencil (some techniques declare different modules or programs for each).
    fn targets() -> Vec<Target> {
        let color = wgpu::TextureFormat::Rgba8Unorm;
        let mut all = Vec::new();
        for depth in [
            wgpu::TextureFormat::Depth32Float,
            wgpu::TextureFormat::Depth24PlusStencil8,
        ] {
            for samples in [1, 4] {
                all.push(Target::new(color, Some(depth), samples));
            }
        }
        all
    }

    /// Every shader every technique (and the mesh pass) declares for every target in [`targets`],
    /// once each, with the target it was declared for and the structs it shares with Rust.
    pub(crate) fn all() -> Vec<(Target, Shader, Vec<Layout>)> {
        let mut out: Vec<(Target, Shader, Vec<Layout>)> = Vec::new();
        for target in targets() {
            for module in techniques::modules() {
                for shader in module.shaders(&target) {
                    if !out
                        .iter()
                        .any(|(_, s, _)| s.source == shader.source && s.programs == shader.programs)
                    {
                        out.push((target, shader, module.structs()));
                    }
                }
            }
            for shader in [super::super::mesh::shader(), super::super::cut::shader()] {
                if !out.iter().any(|(_, s, _)| s.source == shader.source) {
                    out.push((target, shader, Vec::new()));
                }
            }
            let pose = super::super::pose::shader();
            if !out.iter().any(|(_, s, _)| s.source == pose.source) {
                out.push((target, pose, super::super::pose::structs()));
            }
        }
        out
    }

    pub(crate) fn parse(name: &str, source: &str) -> (naga::Module, naga::valid::ModuleInfo) {
        let module = naga::front::wgsl::parse_str(source)
            .unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(source)));
        // What every WebGPU-core device has (unpack2x16float needs the f16-in-f32 capability).
        let mut validator = naga::valid::Validator::new(
            naga::valid::ValidationFlags::all(),
            naga::valid::Capabilities::SHADER_FLOAT16_IN_FLOAT32,
        );
        let info = validator
            .validate(&module)
            .unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(source)));
        (module, info)
    }

    /// True if the WGSL global `var` is what `kind` declares for `target`.
    fn kind_matches(
        module: &naga::Module,
        var: &naga::GlobalVariable,
        kind: Kind,
        target: &Target,
    ) -> bool {
        use naga::{AddressSpace, ImageClass, ScalarKind, StorageAccess, TypeInner};
        let image = |class: ImageClass| {
            matches!(&module.types[var.ty].inner,
                TypeInner::Image { dim: naga::ImageDimension::D2, arrayed: false, class: c } if *c == class)
        };
        match kind {
            Kind::Uniform | Kind::Block => var.space == AddressSpace::Uniform,
            Kind::Read => {
                var.space
                    == AddressSpace::Storage {
                        access: StorageAccess::LOAD,
                    }
            }
            Kind::ReadWrite => {
                var.space
                    == AddressSpace::Storage {
                        access: StorageAccess::LOAD | StorageAccess::STORE,
                    }
            }
            Kind::TargetDepth => image(ImageClass::Depth {
                multi: target.sample_count > 1,
            }),
            Kind::Depth => image(ImageClass::Depth { multi: false }),
            Kind::Texture => image(ImageClass::Sampled {
                kind: ScalarKind::Float,
                multi: false,
            }),
        }
    }

    /// Where `shader`'s WGSL disagrees with its declared programs (empty: it agrees): a program
    /// whose entry point is missing or of another stage, a resource an entry point uses that its
    /// layout lacks or declares otherwise, a declared binding the WGSL declares otherwise.
    pub(crate) fn binding_mismatches(shader: &Shader, target: &Target) -> Vec<String> {
        let (module, info) = parse(shader.label, &shader.source);
        let mut found = Vec::new();
        let describe = |binding: &Binding| {
            format!("{} ({:?} at {})", binding.name, binding.kind, binding.index)
        };
        let global_at = |index: u32| {
            module.global_variables.iter().find(|(_, v)| {
                v.binding
                    .as_ref()
                    .is_some_and(|b| b.group == 0 && b.binding == index)
            })
        };
        for program in &shader.programs {
            let stages: Vec<(&str, naga::ShaderStage)> = match program.fragment {
                _ if program.bindings.stages == wgpu::ShaderStages::COMPUTE => {
                    vec![(program.entry, naga::ShaderStage::Compute)]
                }
                Some(fragment) => vec![
                    (program.entry, naga::ShaderStage::Vertex),
                    (fragment, naga::ShaderStage::Fragment),
                ],
                None => vec![(program.entry, naga::ShaderStage::Vertex)],
            };
            for (entry, stage) in stages {
                let Some(index) = module
                    .entry_points
                    .iter()
                    .position(|e| e.name == entry && e.stage == stage)
                else {
                    found.push(format!(
                        "{}: no {stage:?} entry point {entry}",
                        shader.label
                    ));
                    continue;
                };
                let usage = info.get_entry_point(index);
                for (handle, var) in module.global_variables.iter() {
                    let Some(binding) = &var.binding else {
                        continue;
                    };
                    if usage[handle].is_empty() {
                        continue;
                    }
                    let name = var.name.as_deref().unwrap_or("?");
                    let declared = program
                        .bindings
                        .list
                        .iter()
                        .find(|b| binding.group == 0 && b.index == binding.binding);
                    match declared {
                        None => found.push(format!(
                            "{}: {entry} uses {name} at @group({}) @binding({}), which the {} layout lacks",
                            shader.label, binding.group, binding.binding, program.bindings.label
                        )),
                        Some(b) if b.name != name || !kind_matches(&module, var, b.kind, target) => {
                            found.push(format!(
                                "{}: {entry} uses {name} at @binding({}) where the {} layout declares {}",
                                shader.label,
                                binding.binding,
                                program.bindings.label,
                                describe(b)
                            ))
                        }
                        Some(_) => {}
                    }
                }
            }
            for b in program.bindings.list {
                if let Some((_, var)) = global_at(b.index) {
                    let name = var.name.as_deref().unwrap_or("?");
                    if b.name != name || !kind_matches(&module, var, b.kind, target) {
                        found.push(format!(
                            "{}: @binding({}) is {name} in WGSL, {} in the {} layout",
                            shader.label,
                            b.index,
                            describe(b),
                            program.bindings.label
                        ));
                    }
                }
            }
        }
        found
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

    /// Where the structs `module` declares differ from their Rust twins in `layouts` (empty: they
    /// agree); returns the names of the structs it declares among them too.
    pub(crate) fn struct_mismatches(
        label: &str,
        module: &naga::Module,
        layouts: &[Layout],
    ) -> (Vec<String>, Vec<&'static str>) {
        let declared = structs(module);
        let mut found = Vec::new();
        let mut seen = Vec::new();
        for rust in layouts {
            let Some((size, members)) = declared.get(rust.wgsl) else {
                continue;
            };
            seen.push(rust.wgsl);
            for &(member, offset) in rust.members {
                let wgsl = members.iter().find(|(m, _)| m == member);
                if wgsl.map(|&(_, o)| o as usize) != Some(offset) {
                    found.push(format!(
                        "{label}: {}.{member} is at {offset} in Rust, {:?} in WGSL",
                        rust.wgsl,
                        wgsl.map(|w| w.1)
                    ));
                }
            }
            for (member, offset) in members {
                if rust.members.iter().any(|(m, _)| m == member) {
                    continue;
                }
                // A member only WGSL has must be the trailing runtime-sized list after the head
                // the Rust struct describes.
                if (*offset as usize, member == &members[members.len() - 1].0) != (rust.size, true)
                {
                    found.push(format!(
                        "{label}: {}.{member} is not in the Rust struct",
                        rust.wgsl
                    ));
                }
            }
            if members.len() == rust.members.len() && *size as usize != rust.size {
                found.push(format!(
                    "{label}: {} is {size} bytes in WGSL, {} in Rust",
                    rust.wgsl, rust.size
                ));
            }
        }
        (found, seen)
    }

    #[test]
    fn every_declared_module_parses_and_validates_on_the_cpu() {
        let all = all();
        // Every technique declares at least one module, so this is never vacuous.
        assert!(all.len() >= 19, "{} modules", all.len());
        for (_, shader, _) in &all {
            parse(shader.label, &shader.source);
        }
    }

    #[test]
    fn every_technique_declares_its_modules() {
        for technique in Technique::all() {
            let module = techniques::module(&technique);
            for target in targets() {
                let shaders = module.shaders(&target);
                assert!(!shaders.is_empty(), "{}", technique.name());
                assert!(
                    shaders.iter().all(|s| !s.programs.is_empty()),
                    "{}",
                    technique.name()
                );
            }
        }
    }

    #[test]
    fn every_wgsl_binding_agrees_with_its_rust_declaration() {
        for (target, shader, _) in all() {
            let found = binding_mismatches(&shader, &target);
            assert!(found.is_empty(), "{found:#?}");
        }
    }

    #[test]
    fn a_wgsl_binding_changed_by_hand_is_caught_without_an_adapter() {
        let (target, shader, _) = all()
            .into_iter()
            .find(|(_, s, _)| s.label == "fins.wgsl")
            .expect("the fins module");
        let edited = |from: &str, to: &str| {
            assert!(shader.source.contains(from), "{from}");
            let changed = Shader {
                source: shader.source.replace(from, to),
                programs: shader.programs.clone(),
                label: shader.label,
            };
            binding_mismatches(&changed, &target)
        };
        let declaration = "@group(0) @binding(3) var<storage, read> attributes";
        // Another index, another access, another name: each is found.
        assert!(
            !edited(
                declaration,
                "@group(0) @binding(12) var<storage, read> attributes"
            )
            .is_empty()
        );
        assert!(
            !edited(
                declaration,
                "@group(0) @binding(3) var<storage, read_write> attributes"
            )
            .is_empty()
        );
        // A name: renamed everywhere, the module still validates, but the layout names another.
        let renamed = Shader {
            source: shader.source.replace("attributes", "attribute_words"),
            programs: shader.programs.clone(),
            label: shader.label,
        };
        assert!(!binding_mismatches(&renamed, &target).is_empty());
        // The unchanged module agrees (the control).
        assert!(binding_mismatches(&shader, &target).is_empty());
    }

    #[test]
    fn shared_structs_have_the_same_layout_in_rust_and_wgsl() {
        let mut seen: HashMap<&str, usize> = HashMap::new();
        let mut found = Vec::new();
        for (_, shader, own) in all() {
            let (module, _) = parse(shader.label, &shader.source);
            let mut layouts = layout::layouts();
            layouts.extend(own);
            let (mismatches, declared) = struct_mismatches(shader.label, &module, &layouts);
            found.extend(mismatches);
            for name in declared {
                *seen.entry(name).or_default() += 1;
            }
        }
        assert!(found.is_empty(), "{found:#?}");
        let mut every = layout::layouts();
        for module in techniques::modules() {
            every.extend(module.structs());
        }
        for rust in every {
            assert!(
                seen.contains_key(rust.wgsl),
                "no module declares {}",
                rust.wgsl
            );
        }
    }

    #[test]
    fn a_parameters_struct_out_of_step_with_its_wgsl_is_caught() {
        let (_, shader, own) = all()
            .into_iter()
            .find(|(_, s, _)| s.label == "fins.wgsl")
            .expect("the fins module");
        assert!(!own.is_empty(), "fins declares its parameters");
        let (module, _) = parse(shader.label, &shader.source);
        assert!(struct_mismatches(shader.label, &module, &own).0.is_empty());
        // Two members swapped in the WGSL: their offsets no longer match the Rust struct's.
        let swapped = shader.source.replace(
            "    thickness: f32,\n    in_pixels: u32,",
            "    in_pixels: u32,\n    thickness: f32,",
        );
        assert_ne!(swapped, shader.source);
        let (module, _) = parse(shader.label, &swapped);
        assert!(!struct_mismatches(shader.label, &module, &own).0.is_empty());
    }

    #[test]
    fn a_broken_module_is_caught_without_an_adapter() {
        // The parse check can fail: a type error and an unknown identifier are both refused.
        let source = format!(
            "{}fn f() -> u32 {{ return 1.5; }}",
            layout::wgsl_constants()
        );
        assert!(naga::front::wgsl::parse_str(&source).is_err());
        let source = format!(
            "{}fn f() -> u32 {{ return NOT_A_CONSTANT; }}",
            layout::wgsl_constants()
        );
        assert!(naga::front::wgsl::parse_str(&source).is_err());
    }

    #[test]
    fn shared_constants_have_the_rust_values() {
        for (_, shader, _) in all() {
            let (name, source) = (shader.label, &shader.source);
            let (module, _) = parse(name, source);
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
