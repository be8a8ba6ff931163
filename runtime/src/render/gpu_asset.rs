//! Per asset: its sections in GPU buffers, uploaded byte for byte as the file stores them.
//!
//! Nothing is derived per edge for the default technique: classification computes the face planes
//! from the positions, and the clusters come from the asset. The edge section is bound in windows
//! ("chunks") of whole clusters that each fit a storage binding, so an asset is limited by its other
//! per-edge sections instead: the next ends (2 indices per edge) must fit one binding, which on a
//! 128 MiB device is about 16.7 M edges at 32 bits.

use std::path::Path;

use glam::Vec3;
use wgpu::util::DeviceExt;

use super::RenderError;
use super::bindings::{self, Binding};
use super::derived::{self, AssetExtras};
use super::target::checked;
use crate::asset::{Asset, IndexWidth, SectionKind};

/// A validated asset on the GPU. Create it once; any number of renderers can draw from it (it is a
/// set of shared buffer handles, cheap to clone).
///
/// Index sections keep their file width: 16-bit sections are read in halves by the shaders, and
/// the mesh's index buffer uses the matching [`wgpu::IndexFormat`].
#[derive(Clone, Debug)]
pub struct GpuAsset {
    pub(crate) render_positions: wgpu::Buffer,
    pub(crate) render_normals: wgpu::Buffer,
    pub(crate) mesh_indices: wgpu::Buffer,
    pub(crate) index_format: wgpu::IndexFormat,
    pub(crate) index_count: u32,
    pub(crate) topology_positions: wgpu::Buffer,
    pub(crate) edge_vertices: wgpu::Buffer,
    pub(crate) edge_attributes: wgpu::Buffer,
    /// Next ends, per edge end.
    pub(crate) rings: wgpu::Buffer,
    /// Ring heads of the capped vertices, at the width of `rings`.
    pub(crate) cap_heads: wgpu::Buffer,
    /// The edge clusters ([`EdgeCluster`](crate::asset::EdgeCluster) each).
    pub(crate) clusters: wgpu::Buffer,
    /// Edges per window of the edge section (a multiple of the cluster size).
    pub(crate) chunk_edges: u32,
    /// The device's largest storage binding, in bytes.
    pub(crate) binding_limit: u64,
    pub(crate) edge_count: u32,
    pub(crate) head_count: u32,
    pub(crate) edges_u16: bool,
    pub(crate) rings_u16: bool,
    pub(crate) has_rings: bool,
    pub(crate) has_chamfers: bool,
    pub(crate) bounds: [[f32; 3]; 2],
    /// No boundary edge: a section's cut faces can be filled.
    pub(crate) closed: bool,
    pub(crate) radius_scale: f32,
    /// What [`AssetExtras`] the upload derived.
    pub(crate) extras: AssetExtras,
    /// This upload's identity, shared by its clones: renderers keep per-asset state by it.
    pub(crate) key: std::sync::Arc<()>,
    /// The intersection segments, six `f32` each (end 0, end 1), or a placeholder when none.
    pub(crate) intersection_segments: wgpu::Buffer,
    pub(crate) intersection_count: u32,
    /// [`AssetExtras::VERTEX_NORMALS`]: `vec4<f32>` per topology vertex.
    pub(crate) vertex_normals: Option<wgpu::Buffer>,
    /// [`AssetExtras::VERTEX_NORMALS`]: the topology vertex (`u32`) of each render vertex.
    pub(crate) render_to_topology: Option<wgpu::Buffer>,
    /// [`AssetExtras::FIN_CORNERS`]: `vec4<u32>` per edge.
    pub(crate) fin_corners: Option<wgpu::Buffer>,
    /// [`AssetExtras::TRIANGLE_EDGES`]: `u32` per triangle.
    pub(crate) triangle_edges: Option<wgpu::Buffer>,
    /// The highlight's rounded corners and each edge end's corner (`highlight::corners`), for an
    /// asset with chamfer edges; else a placeholder.
    pub(crate) corners: wgpu::Buffer,
    pub(crate) corner_count: u32,
    /// The skin and morph targets of an animated asset ([`PosedAsset`](super::PosedAsset)).
    pub(crate) motion: Option<std::sync::Arc<super::pose::GpuMotion>>,
}

impl GpuAsset {
    /// Uploads `asset` (already validated by [`Asset::decode`]).
    ///
    /// Fails with [`RenderError::TooLarge`] if a section exceeds the device's storage binding limit.
    pub fn new(device: &wgpu::Device, asset: &Asset) -> Result<Self, RenderError> {
        Self::with_extras(device, asset, AssetExtras::NONE)
    }

    /// Uploads `asset` with what each of `techniques` needs beyond the sections (the union of
    /// their [`Technique::needs`](super::Technique::needs)).
    pub fn for_techniques(
        device: &wgpu::Device,
        asset: &Asset,
        techniques: &[super::Technique],
    ) -> Result<Self, RenderError> {
        let extras = techniques
            .iter()
            .fold(AssetExtras::NONE, |all, t| all | t.needs());
        Self::with_extras(device, asset, extras)
    }

    /// Uploads `asset` and derives `extras` from it on the CPU (see [`AssetExtras`]).
    ///
    /// Fails with [`RenderError::Unsupported`] if an extra cannot be derived (an asset whose render
    /// vertices do not sit on its topology vertices, which the bake never writes).
    pub fn with_extras(
        device: &wgpu::Device,
        asset: &Asset,
        extras: AssetExtras,
    ) -> Result<Self, RenderError> {
        let mut uploaded = checked(device, "the asset's buffers", || {
            Self::upload(device, asset)
        })??;
        if extras == AssetExtras::NONE && asset.motion.is_empty() {
            return Ok(uploaded);
        }
        let map = derived::render_to_topology(asset).ok_or_else(|| RenderError::Unsupported {
            technique: "GpuAsset::with_extras",
            why: "its render vertices do not sit on its topology vertices".into(),
        })?;
        if !asset.motion.is_empty() {
            uploaded.motion = checked(device, "the asset's skin", || {
                super::pose::GpuMotion::new(device, asset, &map)
            })?
            .map(std::sync::Arc::new);
        }
        let storage = wgpu::BufferUsages::STORAGE;
        let extra = |label: &str, bytes: &[u8]| {
            checked(device, label, || upload(device, label, bytes, storage))
        };
        if extras.contains(AssetExtras::VERTEX_NORMALS) {
            let normals = derived::vertex_normals(asset, &map);
            uploaded.vertex_normals =
                Some(extra("vertex normals", bytemuck::cast_slice(&normals))?);
            uploaded.render_to_topology =
                Some(extra("render to topology", bytemuck::cast_slice(&map))?);
        }
        if extras.contains(AssetExtras::FIN_CORNERS) {
            let corners = derived::fin_corners(asset, &map);
            uploaded.fin_corners = Some(extra("fin corners", bytemuck::cast_slice(&corners))?);
        }
        if extras.contains(AssetExtras::TRIANGLE_EDGES) {
            let masks = derived::triangle_edges(asset, &map);
            uploaded.triangle_edges = Some(extra("triangle edges", bytemuck::cast_slice(&masks))?);
        }
        uploaded.extras = extras;
        Ok(uploaded)
    }

    /// The extras this upload derived.
    pub fn extras(&self) -> AssetExtras {
        self.extras
    }

    fn upload(device: &wgpu::Device, asset: &Asset) -> Result<Self, RenderError> {
        let limit = device
            .limits()
            .max_storage_buffer_binding_size
            .min(device.limits().max_buffer_size);
        let check = |what: &'static str, bytes: usize| {
            let bytes = bytes as u64;
            if bytes > limit {
                Err(RenderError::TooLarge { what, bytes, limit })
            } else {
                Ok(())
            }
        };
        let storage = wgpu::BufferUsages::STORAGE;
        let section = |kind: SectionKind, usage| {
            upload(device, kind.name(), asset.section_bytes(kind), usage)
        };
        let clusters = asset.clusters();
        let cluster_bytes: &[u8] = bytemuck::cast_slice(&clusters);
        for kind in [
            SectionKind::TopologyPositions,
            SectionKind::EdgeAttributes,
            SectionKind::IntersectionSegments,
        ] {
            check(kind.name(), asset.section_bytes(kind).len())?;
        }
        check("edge_clusters", cluster_bytes.len())?;
        // Per-frame state is one u32 per edge (the joined technique's slots).
        check("edge state", 4 * asset.edge_count())?;
        // The edge section is bound in windows of whole clusters: as many as one binding holds.
        let edge_bytes = 4 * asset.edge_vertices.width().bytes() as u64;
        let cluster = crate::asset::CLUSTER_EDGES as u64;
        let chunk_edges =
            (limit / edge_bytes / cluster * cluster).min(u64::from(u32::MAX) / cluster * cluster);
        if chunk_edges == 0 {
            check(
                "edge_vertices",
                asset.section_bytes(SectionKind::EdgeVertices).len(),
            )?;
        }
        // Both ring sections at one width, each in its own binding. Decoded assets store both at one
        // width; a hand-built asset that mixes them is widened.
        let rings_u16 = asset.next_ends.width() == IndexWidth::U16
            && (asset.cap_heads.is_empty() || asset.cap_heads.width() == IndexWidth::U16);
        let widen = |indices: &crate::asset::Indices| -> Vec<u8> {
            if rings_u16 || indices.width() == IndexWidth::U32 {
                indices.as_bytes().to_vec()
            } else {
                indices.iter().flat_map(u32::to_le_bytes).collect()
            }
        };
        let (next_ends, cap_heads) = (widen(&asset.next_ends), widen(&asset.cap_heads));
        check("next_ends", next_ends.len())?;
        check("cap_heads", cap_heads.len())?;
        let index_count =
            u32::try_from(asset.mesh_indices.len()).map_err(|_| RenderError::TooLarge {
                what: "mesh_indices",
                bytes: asset.mesh_indices.as_bytes().len() as u64,
                limit,
            })?;
        let edge_count = asset.edge_count() as u32;
        let has_chamfers = asset
            .edge_attributes
            .iter()
            .any(|&w| crate::asset::attribute_flags(w).contains(crate::asset::EdgeFlags::CHAMFER));
        let corners = if has_chamfers {
            crate::highlight::corners::Corners::find(asset)
        } else {
            Default::default()
        };
        // At least the count's word, so the binding has the size the shaders declare.
        let corner_words = corners.words();
        check("corners", 16 * corner_words.len())?;
        Ok(Self {
            // Vertex and index buffers are storage buffers too, for techniques that pull triangles.
            render_positions: section(
                SectionKind::RenderPositions,
                wgpu::BufferUsages::VERTEX | storage,
            ),
            render_normals: section(
                SectionKind::RenderNormals,
                wgpu::BufferUsages::VERTEX | storage,
            ),
            mesh_indices: section(
                SectionKind::MeshIndices,
                wgpu::BufferUsages::INDEX | storage,
            ),
            index_format: match asset.mesh_indices.width() {
                IndexWidth::U16 => wgpu::IndexFormat::Uint16,
                IndexWidth::U32 => wgpu::IndexFormat::Uint32,
            },
            index_count,
            topology_positions: section(SectionKind::TopologyPositions, storage),
            edge_vertices: section(SectionKind::EdgeVertices, storage),
            edge_attributes: section(SectionKind::EdgeAttributes, storage),
            rings: upload(device, "next ends", &next_ends, storage),
            cap_heads: upload(device, "cap heads", &cap_heads, storage),
            clusters: upload(device, "edge clusters", cluster_bytes, storage),
            chunk_edges: chunk_edges as u32,
            binding_limit: limit,
            edge_count,
            head_count: asset.cap_heads.len() as u32,
            edges_u16: asset.edge_vertices.width() == IndexWidth::U16,
            rings_u16,
            has_rings: !asset.next_ends.is_empty(),
            has_chamfers,
            bounds: [asset.header.bounds_min, asset.header.bounds_max],
            closed: asset.is_closed(),
            radius_scale: asset.header.radius_scale,
            extras: AssetExtras::NONE,
            key: std::sync::Arc::new(()),
            intersection_segments: upload(
                device,
                "intersection segments",
                asset.section_bytes(SectionKind::IntersectionSegments),
                storage,
            ),
            intersection_count: asset.intersection_segments.len() as u32,
            vertex_normals: None,
            render_to_topology: None,
            fin_corners: None,
            triangle_edges: None,
            corners: upload(
                device,
                "rounded corners",
                bytemuck::cast_slice(&corner_words),
                storage,
            ),
            corner_count: corners.corners.len() as u32,
            motion: None,
        })
    }

    /// Reads, validates and uploads the asset file at `path`.
    pub fn load(device: &wgpu::Device, path: &Path) -> Result<Self, RenderError> {
        let read_error = |source| RenderError::Read {
            path: path.to_owned(),
            source,
        };
        // Only a regular file: a FIFO or a device would block or never end.
        let metadata = std::fs::metadata(path).map_err(read_error)?;
        if !metadata.is_file() {
            return Err(read_error(std::io::Error::other("not a regular file")));
        }
        let bytes = std::fs::read(path).map_err(read_error)?;
        let asset = Asset::decode(&bytes).map_err(|source| RenderError::Decode {
            path: path.to_owned(),
            source,
        })?;
        Self::new(device, &asset)
    }

    /// Minimum and maximum corners of the model's bounding box (of its pose, for a
    /// [`PosedAsset`](super::PosedAsset)'s).
    pub fn bounds(&self) -> [[f32; 3]; 2] {
        self.bounds
    }

    /// The rig of an animated asset (its joints, morph targets and animations); `None` for a still
    /// one. Pose it with a [`PosedAsset`](super::PosedAsset).
    pub fn rig(&self) -> Option<&crate::rig::Rig> {
        self.motion.as_deref().map(super::pose::GpuMotion::rig)
    }

    /// True if the mesh is closed ([`Asset::is_closed`](crate::asset::Asset::is_closed)), so a
    /// section's cut faces are filled ([`CutRenderer`](super::CutRenderer)).
    pub fn is_closed(&self) -> bool {
        self.closed
    }

    /// The centre of the model's bounding box.
    pub fn center(&self) -> Vec3 {
        (Vec3::from(self.bounds[0]) + Vec3::from(self.bounds[1])) * 0.5
    }

    /// GPU bytes of the buffers this upload derived for `extras` (0 for extras it did not derive).
    pub fn extras_bytes(&self, extras: AssetExtras) -> u64 {
        let size = |b: &Option<wgpu::Buffer>| b.as_ref().map_or(0, wgpu::Buffer::size);
        let mut bytes = 0;
        if extras.contains(AssetExtras::VERTEX_NORMALS) {
            bytes += size(&self.vertex_normals) + size(&self.render_to_topology);
        }
        if extras.contains(AssetExtras::FIN_CORNERS) {
            bytes += size(&self.fin_corners);
        }
        if extras.contains(AssetExtras::TRIANGLE_EDGES) {
            bytes += size(&self.triangle_edges);
        }
        bytes
    }

    /// GPU bytes of the asset's buffers.
    pub fn gpu_bytes(&self) -> u64 {
        [
            &self.render_positions,
            &self.render_normals,
            &self.mesh_indices,
            &self.topology_positions,
            &self.edge_vertices,
            &self.edge_attributes,
            &self.rings,
            &self.cap_heads,
            &self.clusters,
            &self.intersection_segments,
            &self.corners,
        ]
        .iter()
        .map(|b| b.size())
        .chain(
            [
                &self.vertex_normals,
                &self.fin_corners,
                &self.triangle_edges,
            ]
            .into_iter()
            .flatten()
            .map(|b| b.size()),
        )
        .sum()
    }

    /// GPU bytes of the edge sections alone (edge vertices, attributes, next ends, cap heads,
    /// clusters): what the edges cost beyond the mesh.
    pub fn edge_bytes(&self) -> u64 {
        [
            &self.edge_vertices,
            &self.edge_attributes,
            &self.rings,
            &self.cap_heads,
            &self.clusters,
        ]
        .iter()
        .map(|b| b.size())
        .sum()
    }

    /// Chamfer radii in the edge attributes are multiples of this (the asset header's `radius_scale`).
    pub fn radius_scale(&self) -> f32 {
        self.radius_scale
    }

    /// The rounded corners the chamfer highlight draws where chamfer edges of one radius meet
    /// (issue 29; 0 for an asset without chamfer edges).
    pub fn corner_count(&self) -> u32 {
        self.corner_count
    }

    /// Number of edges.
    pub fn edge_count(&self) -> u32 {
        self.edge_count
    }

    /// Number of triangles in the mesh.
    pub fn triangle_count(&self) -> u32 {
        self.index_count / 3
    }

    /// The topology positions, `[f32; 3]` per welded vertex (a storage buffer).
    pub fn topology_positions(&self) -> &wgpu::Buffer {
        &self.topology_positions
    }

    /// The edges' `v0 v1 v2 v3`, 16-bit if [`GpuAsset::edges_are_16_bit`] (a storage buffer, which
    /// may be larger than one binding: see [`GpuAsset::edge_chunks`]).
    pub fn edge_vertices(&self) -> &wgpu::Buffer {
        &self.edge_vertices
    }

    /// The edge section in one binding, for the passes that cannot work in chunks; fails with
    /// [`RenderError::TooLarge`] when it does not fit one.
    pub(crate) fn whole_edge_vertices(&self) -> Result<&wgpu::Buffer, RenderError> {
        let bytes = self.edge_vertices.size();
        if bytes > self.binding_limit {
            return Err(RenderError::TooLarge {
                what: "edge_vertices",
                bytes,
                limit: self.binding_limit,
            });
        }
        Ok(&self.edge_vertices)
    }

    /// The windows the edge section is bound in, `(first edge, edges)` each: one for any asset
    /// whose edges fit a storage binding; each starts on a cluster boundary.
    pub fn edge_chunks(&self) -> impl Iterator<Item = (u32, u32)> + '_ {
        let chunk = self.chunk_edges.max(1);
        (0..self.edge_count.div_ceil(chunk).max(1)).map(move |k| {
            let first = k * chunk;
            (first, chunk.min(self.edge_count - first))
        })
    }

    /// The edge section's window of chunk `(first, edges)` (see [`GpuAsset::edge_chunks`]).
    pub(crate) fn edge_window(&self, (first, edges): (u32, u32)) -> wgpu::BufferBinding<'_> {
        let bytes_per_edge = if self.edges_u16 { 8 } else { 16 };
        let size = (u64::from(edges) * bytes_per_edge).max(4);
        wgpu::BufferBinding {
            buffer: &self.edge_vertices,
            offset: u64::from(first) * bytes_per_edge,
            size: std::num::NonZeroU64::new(size.min(self.edge_vertices.size())),
        }
    }

    /// The resource of the section `binding` names (see [`bindings::asset`]), for `technique`'s
    /// bind groups: the edge section whole (or [`RenderError::TooLarge`]), an extra the upload did
    /// not derive is [`RenderError::MissingAssetData`].
    pub(crate) fn resource(
        &self,
        binding: Binding,
        technique: &'static str,
    ) -> Result<wgpu::BindingResource<'_>, RenderError> {
        use bindings::asset::*;
        fn extra<'b>(
            buffer: &'b Option<wgpu::Buffer>,
            technique: &'static str,
            needs: &'static str,
        ) -> Result<&'b wgpu::Buffer, RenderError> {
            buffer
                .as_ref()
                .ok_or(RenderError::MissingAssetData { technique, needs })
        }
        let buffer = match binding {
            TOPOLOGY => &self.topology_positions,
            EDGE_VERTICES => self.whole_edge_vertices()?,
            ATTRIBUTES => &self.edge_attributes,
            RINGS => &self.rings,
            CAP_HEADS => &self.cap_heads,
            CLUSTERS => &self.clusters,
            RENDER_POSITIONS => &self.render_positions,
            RENDER_NORMALS => &self.render_normals,
            MESH_INDICES => &self.mesh_indices,
            SEGMENTS => &self.intersection_segments,
            CORNERS => &self.corners,
            VERTEX_NORMALS => extra(
                &self.vertex_normals,
                technique,
                "AssetExtras::VERTEX_NORMALS",
            )?,
            RENDER_TO_TOPOLOGY => extra(
                &self.render_to_topology,
                technique,
                "AssetExtras::VERTEX_NORMALS",
            )?,
            FIN_CORNERS => extra(&self.fin_corners, technique, "AssetExtras::FIN_CORNERS")?,
            TRIANGLE_EDGES => extra(
                &self.triangle_edges,
                technique,
                "AssetExtras::TRIANGLE_EDGES",
            )?,
            other => {
                return Err(RenderError::Internal(format!(
                    "{technique} binds {} as a section of the asset",
                    other.name
                )));
            }
        };
        Ok(buffer.as_entire_binding())
    }

    /// True if [`GpuAsset::edge_vertices`] holds 16-bit indices, two per word.
    pub fn edges_are_16_bit(&self) -> bool {
        self.edges_u16
    }

    /// Flags and radius per edge (a storage buffer).
    pub fn edge_attributes(&self) -> &wgpu::Buffer {
        &self.edge_attributes
    }
}

/// The vertex buffers of the passes that draw the mesh with vertex buffers: the render positions
/// at location 0 and the render normals at location 1.
pub(crate) const VERTEX_LAYOUTS: [Option<wgpu::VertexBufferLayout<'static>>; 2] = {
    const POSITION: [wgpu::VertexAttribute; 1] = wgpu::vertex_attr_array![0 => Float32x3];
    const NORMAL: [wgpu::VertexAttribute; 1] = wgpu::vertex_attr_array![1 => Float32x3];
    [
        Some(wgpu::VertexBufferLayout {
            array_stride: 12,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &POSITION,
        }),
        Some(wgpu::VertexBufferLayout {
            array_stride: 12,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &NORMAL,
        }),
    ]
};

/// A buffer holding `bytes` (wgpu pads it to a multiple of four; an empty section gets four zero
/// bytes, since a binding cannot be empty).
pub(crate) fn upload(
    device: &wgpu::Device,
    label: &str,
    bytes: &[u8],
    usage: wgpu::BufferUsages,
) -> wgpu::Buffer {
    let contents = if bytes.is_empty() {
        &[0u8; 4][..]
    } else {
        bytes
    };
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        contents,
        usage,
    })
}
