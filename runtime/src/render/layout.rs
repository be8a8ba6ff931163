//! What the Rust side and the WGSL side of the renderer must agree on, written once.
//!
//! - **Constants** (edge flags, drawn-word bits, workgroup sizes, walk bounds) live here only: every
//!   shader module starts with [`wgsl_constants`], generated from these values, so the WGSL files never
//!   spell a shared number.
//! - **Structs** shared with WGSL (uniforms, list records) are `#[repr(C)]` Pod types here; the WGSL
//!   declarations beside them are parsed with naga in a CPU-only test (`modules.rs`), which compares
//!   every member's offset and each struct's size with these types.

use crate::asset::EdgeFlags;
use crate::highlight::environment;

/// Threads per workgroup of every edge compute pass.
pub(crate) const WORKGROUP: u32 = 256;
/// Workgroups per dispatch dimension (wgpu's default `max_compute_workgroups_per_dimension`).
pub(crate) const MAX_GROUPS: u32 = 65_535;
/// Steps a join walk takes at most: the decoder refuses assets with longer next-index rings.
pub(crate) const MAX_RING: u32 = 4096;
/// Drawn ends the cap-buffer join gathers per vertex; further drawn edges there get no join.
pub(crate) const MAX_GATHER: u32 = 16;
/// Edges per cluster (the asset's `EdgeClusters` section): also the workgroup size of the pass that
/// classifies the edges of the clusters the cull pass kept, one workgroup per cluster.
pub(crate) const CLUSTER_EDGES: u32 = crate::asset::CLUSTER_EDGES as u32;

/// The per-frame contour class, beside the baked [`EdgeFlags`] bits (which use the low byte).
pub(crate) const CONTOUR_CLASS: u32 = 1 << 8;
/// The class of the asset's intersection edges (a section of their own, not mesh edges).
pub(crate) const INTERSECTION_CLASS: u32 = 1 << 9;

/// Bits of a drawn edge's word (classify writes it, joins and draws read it): its colour index in the
/// low byte, then how to build its quad.
pub(crate) mod drawn {
    /// Colour indices into `Frame::colors`.
    pub(crate) const COLOR_CONTOUR: u32 = 0;
    pub(crate) const COLOR_BOUNDARY: u32 = 1;
    pub(crate) const COLOR_MARKED: u32 = 2;
    pub(crate) const COLOR_RIDGE: u32 = 3;
    pub(crate) const COLOR_VALLEY: u32 = 4;
    pub(crate) const COLOR_INTERSECTION: u32 = 5;
    /// Colours per instance.
    pub(crate) const COLOR_COUNT: u32 = 6;
    /// Drawn as a contour (half quad outside the silhouette).
    pub(crate) const CONTOUR: u32 = 1 << 8;
    /// The front face's opposite vertex, inside the silhouette, is v3 (else v2).
    pub(crate) const INSIDE_V3: u32 = 1 << 9;
    /// The edge has a quad on screen this frame.
    pub(crate) const ON_SCREEN: u32 = 1 << 10;
    /// Bits 11 and 12: which ends the near plane moved.
    pub(crate) const CLIPPED_SHIFT: u32 = 11;
    /// A chamfer edge drawn as its lit rounded strip (seed 000): no joins, no caps.
    pub(crate) const HIGHLIGHT: u32 = 1 << 13;
    /// With [`HIGHLIGHT`]: the strip lies on the silhouette (one face turned away), so its outline is
    /// rounded by the outline pass. The contour bit, which highlighted edges do not otherwise use.
    pub(crate) const SILHOUETTE: u32 = CONTOUR;
    /// The rest of the word: the drawn instance's number.
    pub(crate) const INSTANCE_SHIFT: u32 = 14;
}

/// Drawn instances a frame can number (the bits the drawn word has left).
pub(crate) const MAX_INSTANCES: u32 = 1 << (32 - drawn::INSTANCE_SHIFT);

/// Every constant the shaders share with Rust, by its WGSL name.
pub(crate) fn constants() -> Vec<(&'static str, u32)> {
    vec![
        ("BOUNDARY", EdgeFlags::BOUNDARY.0.into()),
        ("NON_MANIFOLD", EdgeFlags::NON_MANIFOLD.0.into()),
        ("RIDGE", EdgeFlags::RIDGE.0.into()),
        ("VALLEY", EdgeFlags::VALLEY.0.into()),
        ("MARKED", EdgeFlags::MARKED.0.into()),
        ("MATERIAL", EdgeFlags::MATERIAL.0.into()),
        ("FLIPPED", EdgeFlags::FLIPPED.0.into()),
        ("CHAMFER", EdgeFlags::CHAMFER.0.into()),
        ("CONTOUR", CONTOUR_CLASS),
        ("INTERSECTION", INTERSECTION_CLASS),
        ("COLOR_CONTOUR", drawn::COLOR_CONTOUR),
        ("COLOR_BOUNDARY", drawn::COLOR_BOUNDARY),
        ("COLOR_MARKED", drawn::COLOR_MARKED),
        ("COLOR_RIDGE", drawn::COLOR_RIDGE),
        ("COLOR_VALLEY", drawn::COLOR_VALLEY),
        ("COLOR_INTERSECTION", drawn::COLOR_INTERSECTION),
        ("COLOR_COUNT", drawn::COLOR_COUNT),
        ("DRAWN_CONTOUR", drawn::CONTOUR),
        ("INSIDE_V3", drawn::INSIDE_V3),
        ("ON_SCREEN", drawn::ON_SCREEN),
        ("CLIPPED_SHIFT", drawn::CLIPPED_SHIFT),
        ("DRAWN_HIGHLIGHT", drawn::HIGHLIGHT),
        ("DRAWN_SILHOUETTE", drawn::SILHOUETTE),
        ("INSTANCE_SHIFT", drawn::INSTANCE_SHIFT),
        ("WORKGROUP", WORKGROUP),
        ("MAX_GROUPS", MAX_GROUPS),
        ("MAX_RING", MAX_RING),
        ("MAX_GATHER", MAX_GATHER),
        ("CLUSTER_EDGES", CLUSTER_EDGES),
        ("COS_POWER_SAMPLES", crate::highlight::table::SAMPLES as u32),
        ("ENV_SPECULAR_WIDTH", environment::SPECULAR_SIZE[0]),
        ("ENV_SPECULAR_HEIGHT", environment::SPECULAR_SIZE[1]),
        ("ENV_IRRADIANCE_WIDTH", environment::IRRADIANCE_SIZE[0]),
        ("ENV_IRRADIANCE_HEIGHT", environment::IRRADIANCE_SIZE[1]),
        ("SHADE_PBR", SHADE_PBR),
        ("SECTION_PLANES", crate::section::MAX_PLANES as u32),
        ("SHADE_ENVIRONMENT", SHADE_ENVIRONMENT),
        ("CORNER_WORDS", crate::highlight::corners::CORNER_WORDS),
        ("DISPLAY_HIDDEN", DISPLAY_HIDDEN),
        ("DISPLAY_HIDDEN_COLOR", DISPLAY_HIDDEN_COLOR),
        ("DISPLAY_PIXELS", DISPLAY_PIXELS),
        ("DISPLAY_FADE", DISPLAY_FADE),
        ("DISPLAY_FADE_ORTHO", DISPLAY_FADE_ORTHO),
        ("DISPLAY_CHAINED", DISPLAY_CHAINED),
    ]
}

/// Bits of `Lighting::pbr` and `MeshFrame::pbr`: shade with glTF's metallic-roughness model.
pub(crate) const SHADE_PBR: u32 = 1;
/// ... and add the image-based light of the `environment` binding.
pub(crate) const SHADE_ENVIRONMENT: u32 = 2;

/// Bits of `Display::flags` (display.rs, display.wgsl): hidden edges are drawn.
pub(crate) const DISPLAY_HIDDEN: u32 = 1;
/// ... in the hidden colour, not their class colour.
pub(crate) const DISPLAY_HIDDEN_COLOR: u32 = 2;
/// ... broken by the 32-pixel pattern, not by dashes.
pub(crate) const DISPLAY_PIXELS: u32 = 4;
/// Edges fade with distance.
pub(crate) const DISPLAY_FADE: u32 = 8;
/// ... over clip z (orthographic cameras), not clip w.
pub(crate) const DISPLAY_FADE_ORTHO: u32 = 16;
/// The hidden pattern's phase continues along chains of drawn edges (the joined technique's
/// `phases`, phase.wgsl); without it each edge starts its pattern at its end 0.
pub(crate) const DISPLAY_CHAINED: u32 = 32;

/// The WGSL declarations of [`constants`], put in front of every shader module.
/// The flat thread index of a 2D dispatch ([`workgroups`](super::pipelines::workgroups)): a second
/// row of workgroups is only used once the first is full (MAX_GROUPS workgroups, see also
/// `args.wgsl`), so rows have a fixed length. (`num_workgroups` would do, but D3D12 leaves it 0 for
/// indirect dispatches without wgpu's validation.)
const THREAD_INDEX: &str = "fn thread_index(id: vec3<u32>) -> u32 {
    return id.y * (MAX_GROUPS * WORKGROUP) + id.x;
}
";

pub(crate) fn wgsl_constants() -> String {
    let mut text = String::from("// Generated from runtime/src/render/layout.rs: do not edit.\n");
    for (name, value) in constants() {
        text.push_str(&format!("const {name}: u32 = {value}u;\n"));
    }
    text.push_str("const PI: f32 = 3.14159265358979;\n");
    // Beside the constants it depends on, so the formula has one source.
    text.push_str(THREAD_INDEX);
    // The GGX arc rule's nodes and weights (highlight/ggx.rs).
    let nodes = crate::highlight::ggx::NODES;
    let pairs: Vec<String> = nodes
        .iter()
        .map(|(x, w)| format!("vec2<f32>({x:?}, {w:?})"))
        .collect();
    text.push_str(&format!(
        "const GGX_NODES: array<vec2<f32>, {}> = array<vec2<f32>, {}>({});\n\n",
        nodes.len(),
        nodes.len(),
        pairs.join(", ")
    ));
    text
}

/// `Frame` in `shaders/common.wgsl`: the per-frame uniform of the object-space edge passes.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct Frame {
    pub(crate) mvp: [[f32; 4]; 4],
    pub(crate) eye: [f32; 4],
    pub(crate) proj_z: [f32; 4],
    pub(crate) colors: [[f32; 4]; drawn::COLOR_COUNT as usize],
    pub(crate) viewport: [f32; 2],
    pub(crate) pixel_scale: f32,
    pub(crate) width: f32,
    pub(crate) min_width: f32,
    pub(crate) depth_ref: f32,
    pub(crate) bias_px: f32,
    pub(crate) classes: u32,
    pub(crate) cull_back: u32,
    pub(crate) edges_u16: u32,
    pub(crate) rings_u16: u32,
    pub(crate) edge_count: u32,
    pub(crate) head_count: u32,
    pub(crate) first_edge: u32,
    pub(crate) half_quads: u32,
    pub(crate) cap_capacity: u32,
    pub(crate) highlight: u32,
    pub(crate) radius_scale: f32,
    pub(crate) reverse_z: u32,
    pub(crate) _pad: u32,
    pub(crate) frustum: [[f32; 4]; 4],
    pub(crate) light_position: [f32; 4],
    pub(crate) light_axis: [f32; 4],
    pub(crate) indices_u16: u32,
    pub(crate) triangle_count: u32,
    pub(crate) instance: u32,
    pub(crate) capacity: u32,
    pub(crate) batch: u32,
    pub(crate) batch_instances: u32,
    pub(crate) table_mask: u32,
    pub(crate) survivor_capacity: u32,
    /// The section planes in the instance's model space (`ClipPlanes::rows`).
    pub(crate) section: [[f32; 4]; crate::section::MAX_PLANES],
    /// The hidden edges' style and the distance fade.
    pub(crate) display: DisplayFrame,
}

/// `Rank` in `shaders/phase.wgsl`: one directed item of a chain of drawn edges.
pub(crate) const RANK_BYTES: u64 = 16;

/// `Display` in `shaders/common.wgsl` (read by `shaders/display.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct DisplayFrame {
    pub(crate) hidden_color: [f32; 4],
    /// Opacity, width, dash period, dash count.
    pub(crate) hidden: [f32; 4],
    pub(crate) dashes: [[f32; 4]; 4],
    /// Start, end, opacity and width multiples.
    pub(crate) fade: [f32; 4],
    pub(crate) flags: u32,
    pub(crate) pixels: u32,
    pub(crate) _pad0: u32,
    pub(crate) _pad1: u32,
}

/// `InstanceFrame` in `shaders/common.wgsl`: one instance's camera in its model space, for the
/// joined technique's batches (`shaders/batch.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct InstanceFrame {
    pub(crate) mvp: [[f32; 4]; 4],
    pub(crate) eye: [f32; 4],
    pub(crate) frustum: [[f32; 4]; 4],
    /// The asset's bounds; `lo[3]` is the instance's depth reference.
    pub(crate) lo: [f32; 4],
    pub(crate) hi: [f32; 4],
    pub(crate) colors: [[f32; 4]; drawn::COLOR_COUNT as usize],
    /// The highlight's light in the instance's model space (`PunctualLight::position`, `spot`).
    pub(crate) light_position: [f32; 4],
    pub(crate) light_axis: [f32; 4],
    pub(crate) visible: u32,
    pub(crate) _pad0: u32,
    pub(crate) _pad1: u32,
    pub(crate) _pad2: u32,
    /// The instance's section planes in its model space.
    pub(crate) section: [[f32; 4]; crate::section::MAX_PLANES],
}

/// `Post` in `shaders/post.wgsl`: the uniform of the post-processes.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct Post {
    pub(crate) inv_projection: [[f32; 4]; 4],
    pub(crate) mvp: [[f32; 4]; 4],
    pub(crate) color: [f32; 4],
    pub(crate) viewport: [f32; 2],
    pub(crate) depth_ref: f32,
    pub(crate) _pad: u32,
    /// The first instance's section planes in its model space (its normal or mask pass).
    pub(crate) section: [[f32; 4]; crate::section::MAX_PLANES],
}

/// `PunctualLight` in `shaders/brdf.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct PunctualLight {
    pub(crate) position: [f32; 4],
    pub(crate) color: [f32; 4],
    pub(crate) spot: [f32; 4],
    pub(crate) cone: [f32; 4],
}

/// `Lighting` in `shaders/highlight.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct Lighting {
    pub(crate) light: PunctualLight,
    pub(crate) material: [f32; 4],
    pub(crate) base: [f32; 4],
    pub(crate) pbr: u32,
    pub(crate) corners: u32,
    pub(crate) _pad1: u32,
    pub(crate) _pad2: u32,
}

/// `MeshFrame` in `shaders/mesh.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct MeshFrame {
    pub(crate) mvp: [[f32; 4]; 4],
    pub(crate) light: PunctualLight,
    pub(crate) color: [f32; 4],
    pub(crate) ambient: f32,
    pub(crate) specular: f32,
    pub(crate) shininess: f32,
    pub(crate) pbr: u32,
    pub(crate) eye: [f32; 4],
    pub(crate) surface: [f32; 4],
    /// The instance's section planes in its model space.
    pub(crate) section: [[f32; 4]; crate::section::MAX_PLANES],
}

/// `CutFrame` in `shaders/cut.wgsl`: one plane of one instance's cut faces.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct CutFrame {
    pub(crate) mvp: [[f32; 4]; 4],
    pub(crate) section: [[f32; 4]; crate::section::MAX_PLANES],
    pub(crate) bounds: [f32; 4],
    pub(crate) color: [f32; 4],
    pub(crate) hatch_color: [f32; 4],
    pub(crate) hatch: [f32; 4],
    pub(crate) plane: u32,
    pub(crate) hatch_in_model: u32,
    pub(crate) indices_u16: u32,
    pub(crate) reverse_z: u32,
    pub(crate) outline: [f32; 4],
    pub(crate) screen: [f32; 4],
    pub(crate) proj_z: [f32; 4],
}

/// `DrawArgs` in `shaders/compute.wgsl`: one indirect draw's arguments.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct DrawArgs {
    pub(crate) vertex_count: u32,
    pub(crate) instance_count: u32,
    pub(crate) first_vertex: u32,
    pub(crate) first_instance: u32,
}

/// The head of `Out` in `shaders/compute.wgsl`, before its `cap_list`.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct Out {
    pub(crate) edges: DrawArgs,
    pub(crate) caps: DrawArgs,
    pub(crate) needed: u32,
    pub(crate) kept_clusters: u32,
    pub(crate) survivors_wanted: u32,
    pub(crate) instances_in_view: u32,
}

/// `Cap` in `shaders/compute.wgsl`: a round join.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct Cap {
    pub(crate) end: u32,
    pub(crate) color: u32,
    pub(crate) radius: f32,
    pub(crate) from_dir: u32,
    pub(crate) to_dir: u32,
}

/// `ScreenRecord` in `shaders/common.wgsl`: a drawn edge's quad on screen, per slot.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct ScreenRecord {
    pub(crate) ends: [f32; 4],
    pub(crate) depth_w: [f32; 4],
    pub(crate) extents: [f32; 4],
}

/// `ChamferRecord` in `shaders/highlight.wgsl`: what a highlighted edge's pixels need, per slot.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct ChamferRecord {
    pub(crate) n1: [f32; 4],
    pub(crate) n2: [f32; 4],
    pub(crate) end0: [f32; 4],
    pub(crate) end1: [f32; 4],
    pub(crate) eye: [f32; 4],
    pub(crate) hand_over: [f32; 4],
    pub(crate) light_position: [f32; 4],
    pub(crate) light_axis: [f32; 4],
}

/// The head of `Survivors` in `shaders/cull.wgsl`, before its list of kept clusters: the list's
/// running count and its final length.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct Survivors {
    pub(crate) count: u32,
    pub(crate) kept: u32,
    pub(crate) _pad: [u32; 2],
}

/// Bytes per slot of the drawn list: `vec2<u32>` (edge, word).
pub(crate) const DRAWN_BYTES: u64 = 8;
/// Bytes per drawn edge end of the joins list: `vec2<u32>` (packed split directions).
pub(crate) const JOIN_BYTES_PER_END: u64 = 8;

/// A Rust struct's layout as the WGSL side must see it: member names with byte offsets, and size
/// (compared with naga's layout of the WGSL twin by the CPU test in `modules.rs`).
#[derive(Clone, Copy, Debug)]
#[cfg_attr(not(test), allow(dead_code))]
pub(crate) struct Layout {
    pub(crate) wgsl: &'static str,
    pub(crate) size: usize,
    pub(crate) members: &'static [(&'static str, usize)],
}

/// The [`Layout`] of `$ty`, the WGSL struct `$wgsl`, with these members.
macro_rules! layout {
    ($wgsl:literal, $ty:ty, [$($field:ident),* $(,)?]) => {
        $crate::render::layout::Layout {
            wgsl: $wgsl,
            size: std::mem::size_of::<$ty>(),
            members: &[$((stringify!($field), std::mem::offset_of!($ty, $field))),*],
        }
    };
}

pub(crate) use layout;

/// Every struct the shared WGSL files declare (each technique lists its own:
/// `Module::structs`).
#[cfg(test)]
pub(crate) fn layouts() -> Vec<Layout> {
    vec![
        layout!(
            "Frame",
            Frame,
            [
                mvp,
                eye,
                proj_z,
                colors,
                viewport,
                pixel_scale,
                width,
                min_width,
                depth_ref,
                bias_px,
                classes,
                cull_back,
                edges_u16,
                rings_u16,
                edge_count,
                head_count,
                first_edge,
                half_quads,
                cap_capacity,
                highlight,
                radius_scale,
                reverse_z,
                _pad,
                frustum,
                light_position,
                light_axis,
                indices_u16,
                triangle_count,
                instance,
                capacity,
                batch,
                batch_instances,
                table_mask,
                survivor_capacity,
                section,
                display,
            ]
        ),
        layout!(
            "Display",
            DisplayFrame,
            [
                hidden_color,
                hidden,
                dashes,
                fade,
                flags,
                pixels,
                _pad0,
                _pad1
            ]
        ),
        layout!(
            "InstanceFrame",
            InstanceFrame,
            [
                mvp,
                eye,
                frustum,
                lo,
                hi,
                colors,
                light_position,
                light_axis,
                visible,
                _pad0,
                _pad1,
                _pad2,
                section
            ]
        ),
        layout!(
            "PunctualLight",
            PunctualLight,
            [position, color, spot, cone]
        ),
        layout!(
            "Lighting",
            Lighting,
            [light, material, base, pbr, corners, _pad1, _pad2]
        ),
        layout!(
            "Post",
            Post,
            [
                inv_projection,
                mvp,
                color,
                viewport,
                depth_ref,
                _pad,
                section
            ]
        ),
        layout!(
            "MeshFrame",
            MeshFrame,
            [
                mvp, light, color, ambient, specular, shininess, pbr, eye, surface, section
            ]
        ),
        layout!(
            "CutFrame",
            CutFrame,
            [
                mvp,
                section,
                bounds,
                color,
                hatch_color,
                hatch,
                plane,
                hatch_in_model,
                indices_u16,
                reverse_z,
                outline,
                screen,
                proj_z
            ]
        ),
        layout!(
            "DrawArgs",
            DrawArgs,
            [vertex_count, instance_count, first_vertex, first_instance]
        ),
        layout!("Cap", Cap, [end, color, radius, from_dir, to_dir]),
        layout!(
            "Out",
            Out,
            [
                edges,
                caps,
                needed,
                kept_clusters,
                survivors_wanted,
                instances_in_view
            ]
        ),
        layout!("ScreenRecord", ScreenRecord, [ends, depth_w, extents]),
        layout!(
            "EdgeCluster",
            crate::asset::EdgeCluster,
            [center, radius, axis, cos_angle, flags]
        ),
        layout!("Survivors", Survivors, [count, kept, _pad]),
        layout!(
            "ChamferRecord",
            ChamferRecord,
            [
                n1,
                n2,
                end0,
                end1,
                eye,
                hand_over,
                light_position,
                light_axis
            ]
        ),
        layout!(
            "Corner",
            crate::highlight::corners::Corner,
            [sphere, vertex, normals, far]
        ),
    ]
}
