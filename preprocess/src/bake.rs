//! The bake pipeline: validate → weld → drop degenerate triangles → adjacency → stitch → classify → order
//! the edges into clusters → caps → intersections (optional) → split normals → assemble the asset.
//! Each step's time is recorded for `chamfer bake --timings` (the edge order counts as `assemble`).

use std::path::Path;
use std::time::Duration;

use chamfer_runtime::asset::{Asset, Header, Indices, MAX_RING, Stats, clusters, pack_attributes};
use glam::Vec3;
use rayon::prelude::*;
// std's clock panics in a browser; this one is std's everywhere else.
use web_time::Instant;

use crate::mesh::{Mark, Mesh, MeshError};
use crate::{
    BakeOptions, Companions, Error, adjacency, caps, classify, degenerate, intersections, load,
    mesh_order, motion, normals, radii, stitch, weld,
};
use chamfer_runtime::asset::corners::VertexCorners;

/// The setting in which a bake with stitching on records the boundary edges stitching started
/// from (a record of the bake's work beside the options' own settings; `inspect` reports
/// stitched = this − the boundary edges left).
pub const STITCH_BOUNDARY_BEFORE: &str = "stitch_boundary_before";

/// A baked asset and what it took.
#[derive(Clone, Debug)]
pub struct Baked {
    /// The asset, ready to [`encode`](Asset::encode).
    pub asset: Asset,
    /// Time per step.
    pub timings: Timings,
    /// Bytes the loaded mesh occupied in memory (the yardstick for peak memory).
    pub mesh_bytes: usize,
    /// What the loader skipped or ignored.
    pub warnings: Vec<String>,
    /// What the intersection search saw, if [`BakeOptions::intersections`] asked for it.
    pub intersections: Option<intersections::IntersectionStats>,
    /// The exact radius of each asset edge (the asset stores them as f16); empty when none has one.
    pub radii: Vec<f32>,
    /// What stitching did (all zero when [`BakeOptions::stitch`] is off or nothing was open).
    pub stitched: stitch::Stitched,
    /// The asset's topology vertex of each vertex of the input mesh (welded, then numbered in the
    /// order the written triangles first use them).
    pub input_vertex_map: Vec<u32>,
}

/// Wall-clock time of each bake step.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Timings {
    /// Reading and parsing the file (zero when baking an in-memory mesh).
    pub parse: Duration,
    /// Welding, remapping triangles and dropping degenerate ones.
    pub weld: Duration,
    /// Building unique edges.
    pub adjacency: Duration,
    /// Stitching cracks (zero when off or the mesh is closed).
    pub stitch: Duration,
    /// Classifying and dropping coplanar edges.
    pub classify: Duration,
    /// Building next-index rings and cap heads.
    pub caps: Duration,
    /// Splitting normals into render vertices.
    pub normals: Duration,
    /// Finding intersection edges (zero unless asked for).
    pub intersections: Duration,
    /// Ordering the edges into clusters and packing the asset's sections.
    pub assemble: Duration,
}

impl Timings {
    /// Everything but parsing.
    pub fn processing(&self) -> Duration {
        self.weld
            + self.adjacency
            + self.stitch
            + self.classify
            + self.caps
            + self.normals
            + self.intersections
            + self.assemble
    }
}

/// Loads and bakes one file; errors name the file.
pub fn bake_file(path: &Path, options: &BakeOptions) -> Result<Baked, Error> {
    options.validate()?;
    let start = Instant::now();
    let loaded = load::load(path, &options.limits)?;
    bake_loaded(path, loaded, start.elapsed(), options)
}

/// Bakes a mesh file's bytes already in memory (see [`load::load_bytes`]); errors name `path`.
pub fn bake_bytes(path: &Path, bytes: &[u8], options: &BakeOptions) -> Result<Baked, Error> {
    options.validate()?;
    let start = Instant::now();
    let loaded = load::load_bytes(path, bytes, &options.limits)?;
    bake_loaded(path, loaded, start.elapsed(), options)
}

/// Bakes a mesh file given in memory with the files it refers to (a web page's dropped files):
/// `path` names it (its extension picks the format; a name ending in `.gz` is inflated, within
/// `options.limits`), and its references (an OBJ's `.mtl`, a `.gltf`'s buffers) are looked up in
/// `companions`. The same file and options bake to the same asset as [`bake_file`].
pub fn bake_with_companions(
    path: &Path,
    bytes: &[u8],
    companions: Companions<'_>,
    options: &BakeOptions,
) -> Result<Baked, Error> {
    options.validate()?;
    let start = Instant::now();
    let bytes = load::read_bytes(path, bytes, &options.limits)?;
    let loaded = load::load_bytes_with(path, &bytes, companions, &options.limits)?;
    bake_loaded(path, loaded, start.elapsed(), options)
}

fn bake_loaded(
    path: &Path,
    loaded: load::Loaded,
    parse: Duration,
    options: &BakeOptions,
) -> Result<Baked, Error> {
    let name = path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let mut baked =
        bake_moving(loaded.mesh, loaded.motion.as_ref(), &name, options).map_err(|e| match e {
            Error::Mesh { source, .. } => Error::Mesh {
                path: path.to_owned(),
                source,
            },
            other => other,
        })?;
    baked.timings.parse = parse;
    baked.warnings = loaded.warnings;
    if let Some(input) = loaded.motion {
        let vertices = baked.asset.topology_positions.len();
        let (motion, differ) = motion::attach(input, &baked.input_vertex_map, vertices);
        if differ > 0 {
            baked.warnings.push(format!(
                "{differ} vertices were welded into a vertex with other joints, weights or morph \
                 deltas: in motion they follow it"
            ));
        }
        baked.asset.motion = motion;
    }
    Ok(baked)
}

/// Bakes an in-memory mesh; `source` names it in the asset and in errors.
///
/// Consumes the mesh so its arrays can be freed as soon as each step is done with them.
/// The result depends only on the mesh and the options, never on the thread count.
pub fn bake(mesh: Mesh, source: &str, options: &BakeOptions) -> Result<Baked, Error> {
    bake_moving(mesh, None, source, options)
}

/// [`bake`] of a mesh that `motion` moves (per input vertex): edges between vertices that move
/// apart are kept even where the rest pose is flat (see [`classify::classify_moving`]); the
/// motion itself is attached by the caller.
fn bake_moving(
    mesh: Mesh,
    motion: Option<&motion::InputMotion>,
    source: &str,
    options: &BakeOptions,
) -> Result<Baked, Error> {
    options.validate()?;
    let mesh_error = |source_error| Error::Mesh {
        path: source.into(),
        source: source_error,
    };
    mesh.validate().map_err(mesh_error)?;
    let mesh_bytes = mesh.memory_bytes();
    let mut stats = Stats {
        input_vertices: mesh.positions.len() as u64,
        input_triangles: mesh.triangles.len() as u64,
        ..Stats::default()
    };
    let mut timings = Timings::default();
    let mut clock = Instant::now();
    let mut lap = |slot: &mut Duration| {
        *slot = clock.elapsed();
        clock = Instant::now();
    };

    let Mesh {
        positions,
        mut triangles,
        mut materials,
        marks,
        ..
    } = mesh;
    let welded = weld::weld(&positions, options.weld.distance(&positions));
    drop(positions);
    triangles
        .par_iter_mut()
        .for_each(|t| *t = t.map(|i| welded.remap[i as usize]));
    let marks: Vec<Mark> = marks
        .iter()
        .map(|m| Mark {
            vertices: m.vertices.map(|i| welded.remap[i as usize]),
            ..*m
        })
        .collect();
    let mut positions = welded.positions;
    let mut input_vertex_map = welded.remap;
    stats.welded_vertices = positions.len() as u64;
    if materials.windows(2).all(|w| w[0] == w[1]) {
        materials = Vec::new(); // one material: no seams to look for
    }
    stats.degenerate_triangles =
        degenerate::remove_degenerate(&mut triangles, &mut materials, &positions) as u64;
    if triangles.is_empty() {
        return Err(mesh_error(MeshError::AllDegenerate {
            count: stats.degenerate_triangles as usize,
        }));
    }
    // Coherent triangles, vertices numbered by first use: what the clusters cull by and what the
    // compact format's codecs need (mesh_order.rs).
    let order = mesh_order::triangle_order(&positions, &triangles);
    let new_of = mesh_order::reorder_mesh(&mut positions, &mut triangles, &mut materials, &order);
    drop(order);
    let marks: Vec<Mark> = marks
        .iter()
        .map(|m| Mark {
            vertices: m.vertices.map(|i| new_of[i as usize]),
            ..*m
        })
        .collect();
    input_vertex_map
        .par_iter_mut()
        .for_each(|v| *v = new_of[*v as usize]);
    drop(new_of);
    lap(&mut timings.weld);

    let mut edges = adjacency::adjacency(&triangles, &materials, positions.len());
    lap(&mut timings.adjacency);
    let mut stitched = stitch::Stitched::default();
    if let Some(tolerance) = options.stitch.distance(&positions) {
        (edges, stitched) =
            stitch::stitch(&positions, &mut triangles, &mut materials, edges, tolerance);
    }
    drop(materials);
    lap(&mut timings.stitch);

    let rigid = motion.map(|m| motion::rigid_groups(m, &input_vertex_map, positions.len()));
    stats.edges = classify::classify_moving(
        &positions,
        &mut edges,
        &marks,
        options.coplanar_deg,
        options.crease_deg,
        rigid.as_deref(),
    );
    drop(rigid);
    stats.chamfer = radii::assign_radii(
        &positions,
        &mut edges,
        options.radius,
        options.radius_valleys,
    );
    lap(&mut timings.classify);

    refuse_long_rings(&positions, &edges).map_err(mesh_error)?;
    // Edges go into the order they are written in (the runtime's clusters cull) before the rings
    // are built, so the rings need no renumbering and the copies are made while memory is low;
    // the steps below do not depend on the edges' order. Timed as part of `assemble`.
    let corners = VertexCorners::new(triangles.as_flattened(), positions.len());
    let order = mesh_order::edge_order(&corners, &triangles, &edges);
    mesh_order::reorder(&mut edges, &mut caps::Rings::default(), &order);
    drop(order);
    let mut ordering = Duration::ZERO;
    lap(&mut ordering);

    let rings = caps::rings_around(&corners, &triangles, &edges, positions.len());
    lap(&mut timings.caps);

    // Before the normals step, which consumes the triangles; over the welded positions, so
    // neighbours are recognised by index.
    let found = options
        .intersections
        .then(|| intersections::find_intersections(&positions, &triangles));
    lap(&mut timings.intersections);

    let render = normals::split_normals_around(corners, &positions, &triangles, &edges);
    drop(triangles);
    lap(&mut timings.normals);

    let radii = edges.radii.clone();
    let intersection_stats = found.as_ref().map(|f| f.stats);
    let mut asset = assemble(source, options, stats, &positions, edges, rings, render);
    if options.stitch != crate::Stitch::Off {
        // Provenance beside the tolerance: inspect reports it with the boundary edges left.
        asset.header.settings.push((
            STITCH_BOUNDARY_BEFORE.into(),
            stitched.boundary_before.to_string(),
        ));
    }
    if let Some(found) = found {
        asset.intersection_segments = found.segments;
        asset.intersection_starts = found.starts;
    }
    asset.edge_clusters = (0..clusters::cluster_count(asset.edge_count()))
        .into_par_iter()
        .map(|c| clusters::cluster_of(&asset, c))
        .collect();
    lap(&mut timings.assemble);
    timings.assemble += ordering;
    Ok(Baked {
        asset,
        timings,
        mesh_bytes,
        warnings: Vec::new(),
        radii,
        intersections: intersection_stats,
        stitched,
        input_vertex_map,
    })
}

/// Every asset written must decode: no vertex may have more kept edge ends than the runtime's
/// join walk follows.
fn refuse_long_rings(positions: &[Vec3], edges: &adjacency::Edges) -> Result<(), MeshError> {
    let mut ends = vec![0u32; positions.len()];
    for edge in &edges.vertices {
        for &v in &edge[..2] {
            ends[v as usize] = ends[v as usize].saturating_add(1);
        }
    }
    match ends.iter().position(|&n| n > MAX_RING) {
        None => Ok(()),
        Some(vertex) => Err(MeshError::RingTooLong {
            vertex: vertex as u32,
            position: positions[vertex].to_array(),
            ends: u64::from(ends[vertex]),
            limit: MAX_RING,
        }),
    }
}

/// Packs the results into the asset's sections, as narrow as the counts allow.
fn assemble(
    source: &str,
    options: &BakeOptions,
    stats: Stats,
    positions: &[Vec3],
    edges: adjacency::Edges,
    rings: caps::Rings,
    render: normals::RenderMesh,
) -> Asset {
    let (bounds_min, bounds_max) = crate::mesh::bounds(positions);
    let radius_scale = edges.radii.iter().fold(0.0f32, |m, &r| m.max(r));
    let edge_attributes = edges
        .flags
        .par_iter()
        .enumerate()
        .map(|(e, &flags)| {
            pack_attributes(
                flags,
                edges.radii.get(e).copied().unwrap_or(0.0),
                radius_scale,
            )
        })
        .collect();
    let render_vertices = render.positions.len();
    let mut indices = render.indices;
    crate::compact::rotate_as_the_codec(&mut indices, render_vertices);
    let edge_count = edges.len();
    let edge_vertices: Vec<u32> = bytemuck::allocation::cast_vec(edges.vertices);
    Asset {
        header: Header {
            source: source.to_owned(),
            generator: concat!("chamfer-preprocess ", env!("CARGO_PKG_VERSION")).to_owned(),
            settings: options.describe(),
            bounds_min: bounds_min.to_array(),
            bounds_max: bounds_max.to_array(),
            radius_scale,
            stats,
            sections: Vec::new(),
        },
        render_positions: render.positions,
        render_normals: render.normals,
        mesh_indices: Indices::with_bound(indices, render_vertices),
        topology_positions: positions.iter().map(|p| p.to_array()).collect(),
        edge_vertices: Indices::with_bound(edge_vertices, positions.len()),
        edge_attributes,
        next_ends: Indices::with_bound(rings.next, 2 * edge_count),
        cap_heads: Indices::with_bound(rings.heads, 2 * edge_count),
        intersection_segments: Vec::new(),
        intersection_starts: Vec::new(),
        edge_clusters: Vec::new(),
        motion: Default::default(),
    }
}
