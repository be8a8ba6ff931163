//! Resource bindings, declared once. A [`Binding`] names a WGSL variable of group 0 with its index and
//! kind; a [`Bindings`] set is one pipeline layout. Every layout and bind group of the renderer is
//! built from a set, and the CPU-only test in `modules.rs` checks every WGSL module against the sets
//! its pipelines declare (index, name, kind, access, and that an entry point uses nothing else), so a
//! WGSL `@binding` that disagrees with its Rust declaration fails without an adapter.
//!
//! The asset's sections have one binding each, the same in every technique ([`asset`]); what a
//! technique keeps per frame is declared in its own module. Index 0 is the pass's uniform block and
//! [`PARAMS`] a technique's parameters.

use super::RenderError;
use super::target::Target;

/// What a binding holds, as WGSL declares it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Kind {
    /// `var<uniform>`, bound whole.
    Uniform,
    /// `var<uniform>`: one block of a buffer of blocks (one per instance), at a dynamic offset.
    Block,
    /// `var<storage, read>`.
    Read,
    /// `var<storage, read_write>`.
    ReadWrite,
    /// The application's depth: `texture_depth_2d`, or `texture_depth_multisampled_2d` when the
    /// target is multisampled.
    TargetDepth,
    /// `texture_depth_2d` of the frame's own (single-sampled).
    Depth,
    /// `texture_2d<f32>` read with `textureLoad` (not filterable).
    Texture,
}

/// One binding of group 0: its index, the WGSL variable's name and its kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Binding {
    pub(crate) index: u32,
    pub(crate) name: &'static str,
    pub(crate) kind: Kind,
}

impl Binding {
    pub(crate) const fn new(index: u32, name: &'static str, kind: Kind) -> Self {
        Self { index, name, kind }
    }

    fn layout_entry(
        &self,
        stages: wgpu::ShaderStages,
        target: &Target,
    ) -> wgpu::BindGroupLayoutEntry {
        let buffer = |ty, has_dynamic_offset| wgpu::BindingType::Buffer {
            ty,
            has_dynamic_offset,
            min_binding_size: None,
        };
        let texture = |sample_type, multisampled| wgpu::BindingType::Texture {
            sample_type,
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled,
        };
        let ty = match self.kind {
            Kind::Uniform => buffer(wgpu::BufferBindingType::Uniform, false),
            Kind::Block => buffer(wgpu::BufferBindingType::Uniform, true),
            Kind::Read => buffer(wgpu::BufferBindingType::Storage { read_only: true }, false),
            Kind::ReadWrite => buffer(wgpu::BufferBindingType::Storage { read_only: false }, false),
            Kind::TargetDepth => texture(wgpu::TextureSampleType::Depth, target.sample_count > 1),
            Kind::Depth => texture(wgpu::TextureSampleType::Depth, false),
            Kind::Texture => texture(wgpu::TextureSampleType::Float { filterable: false }, false),
        };
        // Textures are read by fragment shaders only.
        let visibility = match self.kind {
            Kind::TargetDepth | Kind::Depth | Kind::Texture => {
                stages & wgpu::ShaderStages::FRAGMENT
            }
            _ => stages,
        };
        wgpu::BindGroupLayoutEntry {
            binding: self.index,
            visibility,
            ty,
            count: None,
        }
    }
}

/// The bindings of one pipeline layout (group 0) and the stages that see them.
#[derive(Debug, PartialEq, Eq)]
pub(crate) struct Bindings {
    pub(crate) label: &'static str,
    pub(crate) stages: wgpu::ShaderStages,
    pub(crate) list: &'static [Binding],
}

impl Bindings {
    /// Compute-stage bindings.
    pub(crate) const fn compute(label: &'static str, list: &'static [Binding]) -> Self {
        Self {
            label,
            stages: wgpu::ShaderStages::COMPUTE,
            list,
        }
    }

    /// Vertex- and fragment-stage bindings.
    pub(crate) const fn draw(label: &'static str, list: &'static [Binding]) -> Self {
        Self {
            label,
            stages: wgpu::ShaderStages::VERTEX_FRAGMENT,
            list,
        }
    }

    /// True if the set holds `binding`.
    pub(crate) fn contains(&self, binding: Binding) -> bool {
        self.list.contains(&binding)
    }

    /// The layout of this set for `target`.
    pub(crate) fn layout(&self, device: &wgpu::Device, target: &Target) -> wgpu::BindGroupLayout {
        let entries: Vec<_> = self
            .list
            .iter()
            .map(|b| b.layout_entry(self.stages, target))
            .collect();
        device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(self.label),
            entries: &entries,
        })
    }

    /// The bind group of this set, each binding's resource given by `resource` (typed errors pass
    /// through: an asset uploaded without an extra a binding needs, a section too large to bind).
    pub(crate) fn group<'r>(
        &self,
        device: &wgpu::Device,
        layout: &wgpu::BindGroupLayout,
        mut resource: impl FnMut(Binding) -> Result<wgpu::BindingResource<'r>, RenderError>,
    ) -> Result<wgpu::BindGroup, RenderError> {
        let entries = self
            .list
            .iter()
            .map(|&b| {
                Ok(wgpu::BindGroupEntry {
                    binding: b.index,
                    resource: resource(b)?,
                })
            })
            .collect::<Result<Vec<_>, RenderError>>()?;
        Ok(device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(self.label),
            layout,
            entries: &entries,
        }))
    }
}

/// The error for a binding a pass's resources do not cover (a bug: the declaration and the code that
/// binds it disagree).
pub(crate) fn unbound(set: &Bindings, binding: Binding) -> RenderError {
    RenderError::Internal(format!(
        "the {} bindings have no resource for `{}` (binding {})",
        set.label, binding.name, binding.index
    ))
}

/// The uniform block of the pass (a [`Frame`](super::layout::Frame) per instance for the
/// object-space passes).
pub(crate) const FRAME: Binding = Binding::new(0, "frame", Kind::Block);
/// A technique's parameters, a block per instance (its `#[repr(C)]` struct, named in its module).
pub(crate) const PARAMS: Binding = Binding::new(15, "params", Kind::Block);
/// The passes that draw every instance of an asset at once (`shaders/batch.wgsl`): each instance's
/// view, a [`InstanceFrame`](super::layout::InstanceFrame) per instance of the frame.
pub(crate) const INSTANCE_FRAMES: Binding = Binding::new(29, "instance_frames", Kind::Read);

/// The asset's sections as [`GpuAsset`](super::GpuAsset) uploads them, one binding each in every
/// module that reads them ([`GpuAsset::resource`](super::GpuAsset::resource) binds them).
pub(crate) mod asset {
    use super::{Binding, Kind::Read};

    /// `[f32; 3]` per welded vertex.
    pub(crate) const TOPOLOGY: Binding = Binding::new(1, "topology", Read);
    /// `v0 v1 v2 v3` per edge (16-bit halves when the asset's edges are).
    pub(crate) const EDGE_VERTICES: Binding = Binding::new(2, "edge_vertices", Read);
    /// Flags and radius per edge.
    pub(crate) const ATTRIBUTES: Binding = Binding::new(3, "attributes", Read);
    /// The next ends of the edge ends' rings (thesis §13).
    pub(crate) const RINGS: Binding = Binding::new(4, "rings", Read);
    /// Ring heads of the capped vertices (thesis §10.2), at the width of `rings`.
    pub(crate) const CAP_HEADS: Binding = Binding::new(5, "cap_heads", Read);
    /// The edge clusters.
    pub(crate) const CLUSTERS: Binding = Binding::new(6, "clusters", Read);
    /// `[f32; 3]` per render vertex.
    pub(crate) const RENDER_POSITIONS: Binding = Binding::new(7, "render_positions", Read);
    /// `[f32; 3]` per render vertex (crease-split normals).
    pub(crate) const RENDER_NORMALS: Binding = Binding::new(8, "render_normals", Read);
    /// The mesh's triangles (16-bit halves when its index format is).
    pub(crate) const MESH_INDICES: Binding = Binding::new(9, "mesh_indices", Read);
    /// The intersection segments, six `f32` each.
    pub(crate) const SEGMENTS: Binding = Binding::new(10, "segments", Read);
    /// Extra [`AssetExtras::VERTEX_NORMALS`](crate::render::AssetExtras::VERTEX_NORMALS): a smooth
    /// normal per topology vertex.
    pub(crate) const VERTEX_NORMALS: Binding = Binding::new(11, "vertex_normals", Read);
    /// Extra `VERTEX_NORMALS`: the topology vertex of each render vertex.
    pub(crate) const RENDER_TO_TOPOLOGY: Binding = Binding::new(12, "render_to_topology", Read);
    /// Extra [`AssetExtras::FIN_CORNERS`](crate::render::AssetExtras::FIN_CORNERS).
    pub(crate) const FIN_CORNERS: Binding = Binding::new(13, "fin_corners", Read);
    /// Extra [`AssetExtras::TRIANGLE_EDGES`](crate::render::AssetExtras::TRIANGLE_EDGES).
    pub(crate) const TRIANGLE_EDGES: Binding = Binding::new(14, "triangle_edges", Read);
    /// The rounded corners of the chamfer highlight and each edge end's corner
    /// (`shaders/corners.wgsl`).
    pub(crate) const CORNERS: Binding = Binding::new(31, "corners", Read);

    /// Every section binding.
    #[cfg(test)]
    pub(crate) const ALL: [Binding; 15] = [
        TOPOLOGY,
        EDGE_VERTICES,
        ATTRIBUTES,
        RINGS,
        CAP_HEADS,
        CLUSTERS,
        RENDER_POSITIONS,
        RENDER_NORMALS,
        MESH_INDICES,
        SEGMENTS,
        VERTEX_NORMALS,
        RENDER_TO_TOPOLOGY,
        FIN_CORNERS,
        TRIANGLE_EDGES,
        CORNERS,
    ];
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_index_means_one_thing_in_the_shared_bindings() {
        let mut shared = asset::ALL.to_vec();
        shared.extend([FRAME, PARAMS]);
        for a in &shared {
            for b in &shared {
                assert!(
                    a == b || (a.index != b.index && a.name != b.name),
                    "{a:?} {b:?}"
                );
            }
        }
    }
}
