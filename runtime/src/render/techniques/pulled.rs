//! The skeleton of the techniques that pull their geometry from the asset's sections in the vertex
//! shader (McGuire–Hughes, the §9.3 shapes, fins, the wireframe, surface angle, the inverted hull;
//! hardware contours use its [`Instances`]): per asset one bind group over its sections; per instance
//! a `Frame` block, a parameters block and one draw call sequence, or, for a technique that draws in
//! batches ([`Pull::BATCHED`]: McGuire–Hughes and fins), per batch of one asset's instances a block
//! of each and one draw sequence for them all, each instance's view a row of a storage buffer
//! (`shaders/batch.wgsl`). A technique of this kind implements [`Pull`] with only what differs;
//! [`PullModule`] makes it a [`Module`]. Instances out of view are culled on the host.

use std::marker::PhantomData;
use std::sync::Arc;

use super::{
    Blocks, Drawn, FrameContext, FrameOptions, InstanceViews, Module, PerAsset, TechniqueFrame,
};
use crate::render::bindings::{self, Binding, Bindings};
use crate::render::layout::{Frame, Layout};
use crate::render::modules::{Program, Shader};
use crate::render::pipelines::{PipelineSet, Raster};
use crate::render::technique::preset_of;
use crate::render::{AssetExtras, GpuAsset, Pipelines, Preset, RenderError, Target, Technique};

/// What a vertex-pulled technique declares; the rest is [`PullModule`]'s.
pub(crate) trait Pull: std::fmt::Debug + Send + Sync + 'static {
    /// The techniques of this module ([`Module::presets`]).
    const PRESETS: &'static [Preset];

    /// [`Module::preset`]: the preset equal to `technique`, else the first.
    fn preset(technique: &Technique) -> &'static Preset {
        preset_of(Self::PRESETS, technique)
    }

    /// The parameters block (`#[repr(C)]`, its WGSL twin named in [`Pull::structs`]); `()` for
    /// none, and then [`Pull::BINDINGS`] has no [`bindings::PARAMS`].
    type Params: bytemuck::Pod + std::fmt::Debug + Send + Sync;
    /// What the draw calls take from the style beyond the blocks (`()` for nothing).
    type Draw: Copy + Default + std::fmt::Debug + Send + Sync;
    /// The bindings of the technique's one layout: [`bindings::FRAME`], [`bindings::PARAMS`] and
    /// the asset sections it reads.
    const BINDINGS: &'static Bindings;

    /// The WGSL module's name (its pass's file) and parts, shared files first.
    const SHADER: (&'static str, &'static [&'static str]);
    /// Draws every instance of an asset in one draw sequence: its parts include `batch.wgsl`
    /// (instead of `frame.wgsl`), its bindings [`bindings::INSTANCE_FRAMES`], and its vertex
    /// shaders find their element with `enter_element`.
    const BATCHED: bool = false;
    /// Its programs (all with [`Pull::BINDINGS`]), each compiled into one pipeline, in order, drawn
    /// as [`Pull::raster`] says.
    const PROGRAMS: &'static [Program];
    /// The Rust twins of its WGSL structs.
    const STRUCTS: &'static [Layout];

    /// The module [`Pull::SHADER`] and [`Pull::PROGRAMS`] declare.
    fn shader() -> Shader {
        let (label, parts) = Self::SHADER;
        Shader::new(label, parts, Self::PROGRAMS.to_vec())
    }

    /// How its pipelines draw: by default pulled triangles over the mesh ([`Raster::over_mesh`]).
    fn raster(target: &Target) -> Raster<'static> {
        Raster::over_mesh(target)
    }

    /// The index buffers of fixed shapes its draws use, made once per device and target.
    fn index_buffers(_cache: &Pipelines) -> Vec<wgpu::Buffer> {
        Vec::new()
    }

    /// The parameters of `drawn` this frame; `None` if the style's technique is not this module's.
    fn params(cx: &FrameContext<'_>, drawn: &Drawn<'_>) -> Option<Self::Params>;

    /// The draw calls' state for this frame.
    fn draw_state(_cx: &FrameContext<'_>) -> Self::Draw {
        Self::Draw::default()
    }

    /// What an asset must be uploaded with: by default, the extras its bindings read.
    fn needs(_technique: &Technique) -> AssetExtras {
        AssetExtras::read_by(Self::BINDINGS)
    }

    /// The resource of one of the asset's section bindings (by default the asset's own section).
    fn resource<'a>(
        asset: &'a GpuAsset,
        binding: Binding,
        technique: &Technique,
    ) -> Result<wgpu::BindingResource<'a>, RenderError> {
        asset.resource(binding, technique.name())
    }

    /// What each of its pipelines draws per instance of an asset.
    const DRAWS: Draws;

    /// Draws `copies` instances of `asset` (its bind group is set; more than one only for a
    /// [`Pull::BATCHED`] technique) with `pipelines`, one per program of [`Pull::PROGRAMS`] in its
    /// order, and its [`Pull::index_buffers`]: by default each pipeline draws what [`Pull::DRAWS`]
    /// says.
    fn draw(
        pipelines: &[wgpu::RenderPipeline],
        _indices: &[wgpu::Buffer],
        _state: Self::Draw,
        pass: &mut wgpu::RenderPass<'_>,
        asset: &GpuAsset,
        copies: u32,
    ) {
        for pipeline in pipelines {
            pass.set_pipeline(pipeline);
            match Self::DRAWS {
                Draws::PerEdge(vertices) => pass.draw(0..vertices, 0..asset.edge_count * copies),
                Draws::PerTriangle(vertices) => {
                    pass.draw(0..vertices, 0..asset.index_count / 3 * copies)
                }
                Draws::Mesh => super::draw_mesh(pass, asset),
            }
        }
    }
}

/// What a [`Pull`] pipeline draws per instance of an asset.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Draws {
    /// This many vertices for each edge (instance = edge).
    PerEdge(u32),
    /// This many vertices for each triangle (instance = triangle).
    PerTriangle(u32),
    /// The mesh, indexed, from its vertex buffers.
    Mesh,
}

/// A [`Pull`] technique's pipelines, per device and target.
#[derive(Debug)]
pub(crate) struct PullPipelines<T: Pull> {
    pipelines: Vec<wgpu::RenderPipeline>,
    indices: Vec<wgpu::Buffer>,
    _technique: PhantomData<fn() -> T>,
}

impl<T: Pull> PipelineSet for PullPipelines<T> {
    fn new(cache: &Pipelines) -> Result<Self, RenderError> {
        let shader = T::shader();
        let compiled = cache.compile(&shader)?;
        let pipelines = shader
            .programs
            .iter()
            .map(|p| compiled.render(p.entry, p.fragment, T::raster(cache.target())))
            .collect::<Result<_, _>>()?;
        Ok(Self {
            pipelines,
            indices: T::index_buffers(cache),
            _technique: PhantomData,
        })
    }
}

/// The [`Module`] of a [`Pull`] technique.
pub(crate) struct PullModule<T>(PhantomData<fn() -> T>);

impl<T> PullModule<T> {
    pub(crate) const fn new() -> Self {
        Self(PhantomData)
    }
}

impl<T: Pull> Module for PullModule<T> {
    fn presets(&self) -> &'static [Preset] {
        T::PRESETS
    }

    fn preset(&self, technique: &Technique) -> &'static Preset {
        T::preset(technique)
    }

    fn shaders(&self, _target: &Target) -> Vec<Shader> {
        vec![T::shader()]
    }

    fn structs(&self) -> Vec<Layout> {
        T::STRUCTS.to_vec()
    }

    fn needs(&self, technique: &Technique) -> AssetExtras {
        T::needs(technique)
    }

    fn new_frame(
        &self,
        pipelines: &Pipelines,
        _options: &FrameOptions,
    ) -> Result<Box<dyn TechniqueFrame>, RenderError> {
        Ok(Box::new(PulledFrame::<T> {
            set: pipelines.get::<PullPipelines<T>>()?,
            layout: pipelines.layout(T::BINDINGS),
            instances: if T::BATCHED {
                Instances::batched(pipelines, T::BINDINGS.label)
            } else {
                Instances::new(pipelines, T::BINDINGS.label)
            },
            state: T::Draw::default(),
        }))
    }
}

/// The frame of a [`Pull`] technique.
#[derive(Debug)]
struct PulledFrame<T: Pull> {
    set: Arc<PullPipelines<T>>,
    layout: wgpu::BindGroupLayout,
    instances: Instances<T::Params>,
    state: T::Draw,
}

impl<T: Pull> TechniqueFrame for PulledFrame<T> {
    fn prepare(
        &mut self,
        cx: &FrameContext<'_>,
        _encoder: &mut wgpu::CommandEncoder,
    ) -> Result<(), RenderError> {
        self.state = T::draw_state(cx);
        let technique = cx.style.technique;
        self.instances.prepare(
            cx,
            T::BINDINGS,
            &self.layout,
            |d| T::params(cx, d),
            |asset, binding| T::resource(asset, binding, &technique),
        )
    }

    fn render(&self, pass: &mut wgpu::RenderPass<'_>) {
        let set = &self.set;
        self.instances.each_batch(pass, |pass, asset, copies| {
            T::draw(
                &set.pipelines,
                &set.indices,
                self.state,
                pass,
                asset,
                copies,
            )
        });
    }

    fn gpu_bytes(&self) -> u64 {
        self.instances.gpu_bytes()
    }
}

/// Per frame, the instances of a technique with one layout: a `Frame` and a `P` block each (or, in
/// batches, each batch), and one bind group per asset over the blocks and its sections.
#[derive(Debug)]
pub(crate) struct Instances<P> {
    pub(crate) frames: Blocks,
    /// `None` when `P` is `()`.
    params: Option<Blocks>,
    /// Each instance's view, when the technique draws in batches.
    views: Option<InstanceViews>,
    groups: PerAsset<wgpu::BindGroup>,
    /// Per instance (or batch): its asset's group, its blocks' offsets and its instances.
    draws: Vec<(usize, [u32; 2], u32)>,
    /// The technique the groups bind for: another one may bind other resources.
    made_for: Option<Technique>,
    _params: PhantomData<fn() -> P>,
}

impl<P: bytemuck::Pod> Instances<P> {
    pub(crate) fn new(cache: &Pipelines, label: &'static str) -> Self {
        let size = std::mem::size_of::<P>();
        Self {
            frames: Blocks::new(cache, label, std::mem::size_of::<Frame>()),
            params: (size > 0).then(|| Blocks::new(cache, label, size)),
            views: None,
            groups: PerAsset::default(),
            draws: Vec::new(),
            made_for: None,
            _params: PhantomData,
        }
    }

    /// Instances drawn in batches: a block per batch of one asset's instances, each instance's
    /// view in a storage buffer.
    pub(crate) fn batched(cache: &Pipelines, label: &'static str) -> Self {
        Self {
            views: Some(InstanceViews::new(cache)),
            ..Self::new(cache, label)
        }
    }

    /// Writes each instance's blocks (its parameters from `params`) and makes the group of each new
    /// asset over `bindings`, the sections' resources from `resource`.
    pub(crate) fn prepare<'a>(
        &mut self,
        cx: &FrameContext<'a>,
        bindings: &'static Bindings,
        layout: &wgpu::BindGroupLayout,
        params: impl Fn(&Drawn<'_>) -> Option<P>,
        resource: impl for<'g> Fn(
            &'g GpuAsset,
            Binding,
        ) -> Result<wgpu::BindingResource<'g>, RenderError>,
    ) -> Result<(), RenderError> {
        // One block per instance, or per batch of an asset's instances (each instance's view in
        // `views`), with the first instance of each.
        let (order, runs): (Vec<usize>, Vec<(usize, usize)>) = match &self.views {
            None => (
                (0..cx.instances.len()).collect(),
                (0..cx.instances.len()).map(|i| (i, 1)).collect(),
            ),
            Some(_) => {
                let order = super::by_asset(cx.instances);
                // An instance index of a draw numbers one instance's elements after another's.
                let runs = super::batches(cx.instances, &order, |asset| {
                    let elements = asset.edge_count.max(asset.index_count / 3).max(1);
                    (u32::MAX / elements) as usize
                });
                (order, runs)
            }
        };
        let frames: Vec<Frame> = runs
            .iter()
            .map(|&(first, count)| {
                let mut frame = super::frame_uniform(cx, &cx.instances[order[first]], first);
                frame.batch_instances = count as u32;
                frame
            })
            .collect();
        let blocks = runs
            .iter()
            .map(|&(first, _)| {
                params(&cx.instances[order[first]]).ok_or_else(|| super::mismatch(cx))
            })
            .collect::<Result<Vec<P>, RenderError>>()?;
        let mut regrown = self.frames.write(cx.pipelines, cx.queue, &frames);
        if let Some(params) = &mut self.params {
            regrown |= params.write(cx.pipelines, cx.queue, &blocks);
        }
        if let Some(views) = &mut self.views {
            let rows: Vec<_> = order
                .iter()
                .enumerate()
                .map(|(i, &d)| super::instance_view(cx, &cx.instances[d], i, [[0.0; 4]; 4]))
                .collect();
            regrown |= views.write(cx.pipelines, cx.queue, &rows);
        }
        if regrown || self.made_for != Some(cx.style.technique) {
            self.groups.clear();
            self.made_for = Some(cx.style.technique);
        }
        self.groups.retain(cx.instances);
        self.draws.clear();
        let device = cx.pipelines.device();
        for (i, &(first, count)) in runs.iter().enumerate() {
            let drawn = &cx.instances[order[first]];
            let (frames, params, views) = (&self.frames, &self.params, &self.views);
            let group = self.groups.index(drawn.asset, |asset| {
                bindings.group(device, layout, |binding| {
                    match block(frames, params, views, binding) {
                        Some(block) => Ok(block),
                        None => resource(asset, binding),
                    }
                })
            })?;
            let params = self.params.as_ref().map_or(0, |p| p.offset(i));
            self.draws
                .push((group, [self.frames.offset(i), params], count as u32));
        }
        Ok(())
    }

    /// The resource of [`bindings::FRAME`], [`bindings::PARAMS`] or
    /// [`bindings::INSTANCE_FRAMES`] (the blocks' and views' buffers).
    pub(crate) fn block(&self, binding: Binding) -> Option<wgpu::BindingResource<'_>> {
        block(&self.frames, &self.params, &self.views, binding)
    }

    /// The dynamic offsets of an instance's blocks, in binding order.
    fn offsets<'o>(&self, offsets: &'o [u32; 2]) -> &'o [u32] {
        if self.params.is_some() {
            offsets
        } else {
            &offsets[..1]
        }
    }

    /// For each instance: sets its group and blocks on `pass` and calls `draw` with its asset.
    pub(crate) fn each(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        mut draw: impl FnMut(&mut wgpu::RenderPass<'_>, &GpuAsset),
    ) {
        self.each_batch(pass, |pass, asset, _| draw(pass, asset));
    }

    /// For each instance, or batch: sets its group and blocks on `pass` and calls `draw` with its
    /// asset and how many of its instances it draws.
    pub(crate) fn each_batch(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        mut draw: impl FnMut(&mut wgpu::RenderPass<'_>, &GpuAsset, u32),
    ) {
        for (group, offsets, copies) in &self.draws {
            let (asset, bind_group) = self.groups.get(*group);
            pass.set_bind_group(0, bind_group, self.offsets(offsets));
            draw(pass, asset, *copies);
        }
    }

    /// Per instance, its asset and its blocks' offsets (for passes with other groups).
    pub(crate) fn draws(&self) -> impl Iterator<Item = (&GpuAsset, &[u32])> + '_ {
        self.draws.iter().map(|(group, offsets, _)| {
            let (asset, _) = self.groups.get(*group);
            (asset, self.offsets(offsets))
        })
    }

    pub(crate) fn gpu_bytes(&self) -> u64 {
        self.frames.gpu_bytes()
            + self.params.as_ref().map_or(0, Blocks::gpu_bytes)
            + self.views.as_ref().map_or(0, InstanceViews::gpu_bytes)
    }
}

fn block<'b>(
    frames: &'b Blocks,
    params: &'b Option<Blocks>,
    views: &'b Option<InstanceViews>,
    binding: Binding,
) -> Option<wgpu::BindingResource<'b>> {
    match binding {
        bindings::FRAME => Some(frames.binding()),
        bindings::PARAMS => params.as_ref().map(Blocks::binding),
        bindings::INSTANCE_FRAMES => views.as_ref().map(|v| v.buffer.as_entire_binding()),
        _ => None,
    }
}
