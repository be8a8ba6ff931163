//! The joined technique's shaders and pipelines, per device and target.

use chamfer_shaders as wgsl;

use super::bindings::{
    ARGS, CLASSIFY, CORNER_DRAW, CULL, DRAW, JOIN, OUTLINE_CORNERS, OUTLINE_STRIPS, PHASE, PLACE,
    RECORDS, SEGMENTS,
};
use crate::render::modules::{Program, Shader};
use crate::render::pipelines::{PipelineSet, Raster};
use crate::render::techniques::post;
use crate::render::{Pipelines as Cache, RenderError, Target};

/// Every module the technique compiles: its name, its parts after the shared constants, its
/// programs.
const SHADERS: [(&str, &[&str], &[Program]); 9] = [
    // Which instances are in view.
    (
        "instances.wgsl",
        &[
            wgsl::COMMON,
            wgsl::SECTION,
            wgsl::FRAME,
            wgsl::LISTS,
            wgsl::INSTANCES,
        ],
        &[Program::compute("place", &PLACE)],
    ),
    // Cluster culling and edge classification, every instance of an asset at once.
    (
        "classify.wgsl",
        &[
            wgsl::COMMON,
            wgsl::SECTION,
            wgsl::BATCH,
            wgsl::BRDF,
            wgsl::HIGHLIGHT,
            wgsl::LISTS,
            wgsl::COMPUTE,
            wgsl::CULL,
            wgsl::CLASSIFY,
        ],
        &[
            Program::compute("mark", &CLASSIFY),
            Program::compute("classify", &CLASSIFY),
            Program::compute("classify_clusters", &CLASSIFY),
            Program::compute("cull", &CULL),
            Program::compute("cull_args", &CULL),
        ],
    ),
    // The frame's bookkeeping over the lists.
    (
        "args.wgsl",
        &[
            wgsl::COMMON,
            wgsl::SECTION,
            wgsl::BATCH,
            wgsl::LISTS,
            wgsl::ARGS,
        ],
        &[
            Program::compute("reset", &ARGS),
            Program::compute("args", &ARGS),
            Program::compute("finish", &ARGS),
        ],
    ),
    // Joins and caps, by next-index walk or cap buffer.
    (
        "joins.wgsl",
        &[
            wgsl::COMMON,
            wgsl::SECTION,
            wgsl::BATCH,
            wgsl::BRDF,
            wgsl::HIGHLIGHT,
            wgsl::LISTS,
            wgsl::COMPUTE,
            wgsl::JOINS,
        ],
        &[
            Program::compute("joins_next", &JOIN),
            Program::compute("joins_heads", &JOIN),
            Program::compute("clear_joins", &JOIN),
        ],
    ),
    // Chamfer records of highlighted edges.
    (
        "chamfers.wgsl",
        &[
            wgsl::COMMON,
            wgsl::SECTION,
            wgsl::BATCH,
            wgsl::BRDF,
            wgsl::HIGHLIGHT,
            wgsl::LISTS,
            wgsl::COMPUTE,
            wgsl::CORNERS,
            wgsl::CHAMFERS,
        ],
        &[Program::compute("chamfer_records", &RECORDS)],
    ),
    // Compacted edge quads.
    (
        "edges.wgsl",
        &[
            wgsl::COMMON,
            wgsl::SECTION,
            wgsl::FRAME,
            wgsl::BRDF,
            wgsl::HIGHLIGHT,
            wgsl::ENVIRONMENT,
            wgsl::DRAW,
            wgsl::DISPLAY,
            wgsl::EDGES,
        ],
        &[
            Program::draw("edge_vertex_main", "edge_fragment", &DRAW),
            Program::draw("strip_vertex", "strip_fragment", &DRAW),
        ],
    ),
    // Round caps.
    (
        "caps.wgsl",
        &[
            wgsl::COMMON,
            wgsl::SECTION,
            wgsl::FRAME,
            wgsl::BRDF,
            wgsl::HIGHLIGHT,
            wgsl::DRAW,
            wgsl::DISPLAY,
            wgsl::CAPS,
        ],
        &[Program::draw("cap_vertex_main", "cap_fragment", &DRAW)],
    ),
    // The highlight's rounded corners, an instance at a time.
    (
        "corner_draw.wgsl",
        &[
            wgsl::COMMON,
            wgsl::SECTION,
            wgsl::FRAME,
            wgsl::BRDF,
            wgsl::HIGHLIGHT,
            wgsl::ENVIRONMENT,
            wgsl::CORNERS,
            wgsl::CORNER_DRAW,
        ],
        &[Program::draw(
            "corner_vertex",
            "corner_fragment",
            &CORNER_DRAW,
        )],
    ),
    // Baked intersection edges.
    (
        "intersections.wgsl",
        &[
            wgsl::COMMON,
            wgsl::SECTION,
            wgsl::FRAME,
            wgsl::DISPLAY,
            wgsl::INTERSECTIONS,
        ],
        &[Program::draw(
            "segment_vertex",
            "segment_fragment",
            &SEGMENTS,
        )],
    ),
];

/// The outline pass's programs (after the application's pass, reading its depth).
const OUTLINE: [Program; 2] = [
    Program::draw("strip_trim_vertex", "strip_trim_fragment", &OUTLINE_STRIPS),
    Program::draw(
        "corner_trim_vertex",
        "corner_trim_fragment",
        &OUTLINE_CORNERS,
    ),
];

/// The dash phases' module (phase.wgsl), compiled while hidden lines are patterned.
pub(crate) fn phase_shader() -> Shader {
    Shader::new(
        "phase.wgsl",
        &[
            wgsl::COMMON,
            wgsl::SECTION,
            wgsl::FRAME,
            wgsl::LISTS,
            wgsl::PHASE,
        ],
        vec![
            Program::compute("rank_args", &ARGS),
            Program::compute("rank_init", &PHASE),
            Program::compute("rank_jump", &PHASE),
            Program::compute("rank_cut", &PHASE),
            Program::compute("rank_finish", &PHASE),
        ],
    )
}

/// The dash phases' passes: the first time a frame draws patterned hidden lines.
#[derive(Debug)]
pub(crate) struct PhasePipelines {
    pub(crate) args: wgpu::ComputePipeline,
    pub(crate) init: wgpu::ComputePipeline,
    pub(crate) jump: wgpu::ComputePipeline,
    pub(crate) cut: wgpu::ComputePipeline,
    pub(crate) finish: wgpu::ComputePipeline,
}

impl PipelineSet for PhasePipelines {
    fn new(cache: &Cache) -> Result<Self, RenderError> {
        let shader = phase_shader();
        let module = cache.compile(&shader)?;
        Ok(Self {
            args: module.compute("rank_args")?,
            init: module.compute("rank_init")?,
            jump: module.compute("rank_jump")?,
            cut: module.compute("rank_cut")?,
            finish: module.compute("rank_finish")?,
        })
    }
}

/// Every module the technique compiles for `target`: the outline pass reads its depth as the target
/// samples it.
pub(crate) fn shaders(target: &Target) -> Vec<Shader> {
    let mut all: Vec<Shader> = SHADERS
        .iter()
        .map(|&(label, parts, programs)| Shader::new(label, parts, programs.to_vec()))
        .collect();
    all.push(Shader::new(
        "outline.wgsl",
        &[
            wgsl::COMMON,
            wgsl::SECTION,
            wgsl::FRAME,
            wgsl::BRDF,
            wgsl::HIGHLIGHT,
            wgsl::DRAW,
            wgsl::CORNERS,
            post::depth_source(target),
            wgsl::OUTLINE,
        ],
        OUTLINE.to_vec(),
    ));
    all
}

/// The technique's pipelines.
#[derive(Debug)]
pub(crate) struct JoinedPipelines {
    pub(crate) place: wgpu::ComputePipeline,
    pub(crate) reset: wgpu::ComputePipeline,
    pub(crate) mark: wgpu::ComputePipeline,
    pub(crate) classify: wgpu::ComputePipeline,
    pub(crate) cull: wgpu::ComputePipeline,
    pub(crate) cull_args: wgpu::ComputePipeline,
    pub(crate) classify_clusters: wgpu::ComputePipeline,
    pub(crate) finish: wgpu::ComputePipeline,
    pub(crate) args: wgpu::ComputePipeline,
    pub(crate) joins_next: wgpu::ComputePipeline,
    pub(crate) joins_heads: wgpu::ComputePipeline,
    pub(crate) clear_joins: wgpu::ComputePipeline,
    pub(crate) chamfer_records: wgpu::ComputePipeline,
    pub(crate) edges: wgpu::RenderPipeline,
    pub(crate) strips: wgpu::RenderPipeline,
    pub(crate) caps: wgpu::RenderPipeline,
    pub(crate) corners: wgpu::RenderPipeline,
    pub(crate) segments: wgpu::RenderPipeline,
    pub(crate) outline_strips: wgpu::RenderPipeline,
    pub(crate) outline_corners: wgpu::RenderPipeline,
}

/// The joined technique's hidden pass (display.wgsl): edges, caps and intersections where the
/// depth hides them. Compiled the first time a frame draws hidden edges; `None` on a target
/// without depth.
#[derive(Debug)]
pub(crate) struct HiddenPipelines(pub(crate) Option<Hidden>);

#[derive(Debug)]
pub(crate) struct Hidden {
    pub(crate) edges: wgpu::RenderPipeline,
    pub(crate) caps: wgpu::RenderPipeline,
    pub(crate) segments: wgpu::RenderPipeline,
}

impl PipelineSet for HiddenPipelines {
    fn new(cache: &Cache) -> Result<Self, RenderError> {
        let shaders = shaders(cache.target());
        let module = |label: &str| {
            let shader = shaders
                .iter()
                .find(|s| s.label == label)
                .ok_or_else(|| RenderError::Internal(format!("no module {label}")))?;
            cache.compile(shader)
        };
        let over_mesh = || Raster::over_mesh(cache.target());
        Ok(Self(
            match (
                module("edges.wgsl")?.render_hidden(
                    "edge_vertex_main",
                    Some("edge_fragment"),
                    over_mesh(),
                )?,
                module("caps.wgsl")?.render_hidden(
                    "cap_vertex_main",
                    Some("cap_fragment"),
                    over_mesh(),
                )?,
                module("intersections.wgsl")?.render_hidden(
                    "segment_vertex",
                    Some("segment_fragment"),
                    over_mesh(),
                )?,
            ) {
                (Some(edges), Some(caps), Some(segments)) => Some(Hidden {
                    edges,
                    caps,
                    segments,
                }),
                _ => None,
            },
        ))
    }
}

impl PipelineSet for JoinedPipelines {
    fn new(cache: &Cache) -> Result<Self, RenderError> {
        let [
            instances,
            classify,
            args,
            joins,
            chamfers,
            edges,
            caps,
            corners,
            intersections,
            outline,
        ] = shaders(cache.target())
            .try_into()
            .map_err(|_| RenderError::Internal("the joined technique's shaders".into()))?;
        let classify = cache.compile(&classify)?;
        let args = cache.compile(&args)?;
        let joins = cache.compile(&joins)?;
        let chamfers = cache.compile(&chamfers)?;
        let edges = cache.compile(&edges)?;
        let caps = cache.compile(&caps)?;
        let intersections = cache.compile(&intersections)?;
        let over_mesh = || Raster::over_mesh(cache.target());
        let outline = cache.compile(&outline)?;
        // Into the finished single-sample colour, without depth (outline.wgsl tests the scene's).
        let over_finished = || Raster {
            buffers: &[],
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: None,
            multisample: wgpu::MultisampleState::default(),
            color: Some(cache.target().blended_color()),
        };
        Ok(Self {
            place: cache.compile(&instances)?.compute("place")?,
            reset: args.compute("reset")?,
            mark: classify.compute("mark")?,
            classify: classify.compute("classify")?,
            cull: classify.compute("cull")?,
            cull_args: classify.compute("cull_args")?,
            classify_clusters: classify.compute("classify_clusters")?,
            finish: args.compute("finish")?,
            args: args.compute("args")?,
            joins_next: joins.compute("joins_next")?,
            joins_heads: joins.compute("joins_heads")?,
            clear_joins: joins.compute("clear_joins")?,
            chamfer_records: chamfers.compute("chamfer_records")?,
            edges: edges.render("edge_vertex_main", Some("edge_fragment"), over_mesh())?,
            strips: edges.render("strip_vertex", Some("strip_fragment"), over_mesh())?,
            caps: caps.render("cap_vertex_main", Some("cap_fragment"), over_mesh())?,
            corners: cache.compile(&corners)?.render(
                "corner_vertex",
                Some("corner_fragment"),
                over_mesh(),
            )?,
            segments: intersections.render(
                "segment_vertex",
                Some("segment_fragment"),
                over_mesh(),
            )?,
            outline_strips: outline.render(
                "strip_trim_vertex",
                Some("strip_trim_fragment"),
                over_finished(),
            )?,
            outline_corners: outline.render(
                "corner_trim_vertex",
                Some("corner_trim_fragment"),
                over_finished(),
            )?,
        })
    }
}
