//! Per asset: its sections in GPU buffers, uploaded byte for byte as the file stores them, and what
//! every frame's classification needs that is fixed per asset (the face planes of each edge).

use std::path::Path;

use glam::Vec3;
use wgpu::util::DeviceExt;

use super::RenderError;
use super::derived::{self, AssetExtras};
use super::target::checked;
use crate::asset::{Asset, EdgeFlags, IndexWidth, SectionKind, attribute_flags};

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
    /// Next ends, then cap heads.
    pub(crate) rings: wgpu::Buffer,
    pub(crate) edge_count: u32,
    pub(crate) head_count: u32,
    pub(crate) heads_offset: u32,
    pub(crate) edges_u16: bool,
    pub(crate) rings_u16: bool,
    pub(crate) has_rings: bool,
    pub(crate) has_chamfers: bool,
    pub(crate) bounds: [[f32; 3]; 2],
    pub(crate) radius_scale: f32,
    /// Per edge, the planes of its two faces, oriented so that a positive dot product with the
    /// homogeneous eye means "faces the camera" (see `face_planes`).
    pub(crate) face_planes: wgpu::Buffer,
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
        if extras == AssetExtras::NONE {
            return Ok(uploaded);
        }
        let map = derived::render_to_topology(asset).ok_or_else(|| RenderError::Unsupported {
            technique: "GpuAsset::with_extras",
            why: "its render vertices do not sit on its topology vertices".into(),
        })?;
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
        for kind in [
            SectionKind::TopologyPositions,
            SectionKind::EdgeVertices,
            SectionKind::EdgeAttributes,
            SectionKind::IntersectionSegments,
        ] {
            check(kind.name(), asset.section_bytes(kind).len())?;
        }
        // One binding for both ring sections: they hold the same kind of value at the same width.
        // Decoded assets store both at one width; a hand-built asset that mixes them is widened.
        let rings_u16 = asset.next_ends.width() == IndexWidth::U16
            && (asset.cap_heads.is_empty() || asset.cap_heads.width() == IndexWidth::U16);
        let mut rings = Vec::new();
        if rings_u16 || asset.next_ends.width() == asset.cap_heads.width() {
            rings.extend_from_slice(asset.next_ends.as_bytes());
            rings.extend_from_slice(asset.cap_heads.as_bytes());
        } else {
            let wide = asset.next_ends.iter().chain(asset.cap_heads.iter());
            rings.extend(wide.flat_map(u32::to_le_bytes));
        }
        check("rings", rings.len())?;
        let planes = face_planes(asset);
        check("face planes", std::mem::size_of_val(planes.as_slice()))?;
        let index_count =
            u32::try_from(asset.mesh_indices.len()).map_err(|_| RenderError::TooLarge {
                what: "mesh_indices",
                bytes: asset.mesh_indices.as_bytes().len() as u64,
                limit,
            })?;
        let edge_count = asset.edge_count() as u32;
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
            rings: upload(device, "rings", &rings, storage),
            edge_count,
            head_count: asset.cap_heads.len() as u32,
            heads_offset: asset.next_ends.len() as u32,
            edges_u16: asset.edge_vertices.width() == IndexWidth::U16,
            rings_u16,
            has_rings: !asset.next_ends.is_empty(),
            has_chamfers: asset.edge_attributes.iter().any(|&w| {
                crate::asset::attribute_flags(w).contains(crate::asset::EdgeFlags::CHAMFER)
            }),
            bounds: [asset.header.bounds_min, asset.header.bounds_max],
            radius_scale: asset.header.radius_scale,
            face_planes: upload(
                device,
                "face planes",
                bytemuck::cast_slice(&planes),
                storage,
            ),
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

    /// Minimum and maximum corners of the model's bounding box.
    pub fn bounds(&self) -> [[f32; 3]; 2] {
        self.bounds
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
            &self.face_planes,
            &self.intersection_segments,
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

    /// Chamfer radii in the edge attributes are multiples of this (the asset header's `radius_scale`).
    pub fn radius_scale(&self) -> f32 {
        self.radius_scale
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

    /// The edges' `v0 v1 v2 v3`, 16-bit if [`GpuAsset::edges_are_16_bit`] (a storage buffer).
    pub fn edge_vertices(&self) -> &wgpu::Buffer {
        &self.edge_vertices
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

/// A buffer holding `bytes` (wgpu pads it to a multiple of four; an empty section gets four zero
/// bytes, since a binding cannot be empty).
fn upload(
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

/// Per edge, the planes (normal, offset) of its two faces: `a` of (v0, v1, v2), `b` of (v1, v0, v3)
/// (negated for [`EdgeFlags::FLIPPED`], so both face the same side of the surface); a boundary or
/// non-manifold edge repeats `a`. The per-frame test then reads two contiguous vectors per edge
/// instead of gathering four vertices. Same arithmetic, in f32, as the GPU would do.
fn face_planes(asset: &Asset) -> Vec<[f32; 4]> {
    let position =
        |i: usize| Vec3::from(asset.topology_positions[asset.edge_vertices.get(i) as usize]);
    let plane = |normal: Vec3, p: Vec3| normal.extend(-normal.dot(p)).to_array();
    let mut planes = Vec::with_capacity(2 * asset.edge_count());
    for (e, &word) in asset.edge_attributes.iter().enumerate() {
        let [p0, p1, p2, p3] = [0, 1, 2, 3].map(|k| position(4 * e + k));
        let flags = attribute_flags(word);
        let a = plane((p1 - p0).cross(p2 - p0), p0);
        let mut b = a;
        if !flags.intersects(EdgeFlags::BOUNDARY | EdgeFlags::NON_MANIFOLD) {
            b = plane((p0 - p1).cross(p3 - p1), p1);
            if flags.contains(EdgeFlags::FLIPPED) {
                b = b.map(|c| -c);
            }
        }
        planes.push(a);
        planes.push(b);
    }
    planes
}
