//! `chamfer render`: draw an asset, or a mesh baked on the fly, to a PNG without a window.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use anyhow::{Context, bail};
use chamfer_preprocess::Limits;
use chamfer_preprocess::environment::read_environment;
use chamfer_preprocess::write::{ensure_not_an_input, ensure_replaceable, write_atomically};
use chamfer_runtime::asset::Asset;
use chamfer_runtime::render::{
    Camera, CapMethod, CutRenderer, CutStyle, DEFAULT_LIGHT_DIRECTION, EdgeClasses, EdgeStyle,
    GpuAsset, Highlight, Image, Instance, Light, MeshRenderer, MeshStyle, Offscreen, Pipelines,
    PosedAsset, SceneRenderer, Shading as ShadingModel, StyleSettings, Technique,
};
use clap::{Args, ValueEnum};
use glam::Mat4;

use chamfer_runtime::rig::{Pose, animation_names};
use chamfer_runtime::schema::flag;
use chamfer_runtime::section::ClipPlanes;

use crate::flags::{
    AnimationFlags, BakeFlags, CutFlags, DisplayFlags, SectionFlags, StyleFlags, TechniqueFlags,
    ViewFlags,
};

/// Render an asset (`.chamfer`) or a mesh (baked on the fly with the bake flags) to a PNG.
#[derive(Args)]
#[command(after_help = crate::bake::SAFETY_HELP)]
pub struct RenderArgs {
    /// A `.chamfer` asset, or an OBJ, glTF/GLB or PLY mesh.
    input: PathBuf,
    /// The PNG to write.
    #[arg(short, long)]
    output: PathBuf,
    #[command(flatten)]
    view: ViewArgs,
    #[command(flatten)]
    options: BakeFlags,
}

/// Where the camera is and the frame it fills (shared with `chamfer draw`, so a drawing and a
/// render of the same flags line up pixel for pixel).
#[derive(Args, Clone)]
pub struct CameraArgs {
    /// Image width in pixels.
    #[arg(long, default_value_t = 1024)]
    pub width: u32,
    /// Image height in pixels.
    #[arg(long, default_value_t = 768)]
    pub height: u32,
    #[command(flatten)]
    view: ViewFlags,
}

impl CameraArgs {
    pub fn check(&self) -> anyhow::Result<()> {
        let frame = 1..=chamfer_runtime::camera::MAX_VIEWPORT;
        if !frame.contains(&self.width) || !frame.contains(&self.height) {
            bail!(
                "--width and --height must be 1 to {} pixels, not {}x{}",
                frame.end(),
                self.width,
                self.height
            );
        }
        self.view
            .0
            .check()
            .map_err(|e| anyhow::anyhow!(e.spelled(flag)))
    }

    /// The camera flags, as they would be typed.
    pub fn describe(&self) -> String {
        self.view.0.flags([self.width, self.height])
    }

    /// The orbit camera framing `bounds` (the asset's), as `chamfer render` uses it.
    pub fn camera(&self, bounds: [[f32; 3]; 2]) -> Camera {
        Camera::orbit(bounds, &self.view.0, [self.width, self.height])
    }
}

/// How the picture is taken (shared with `chamfer demo`).
#[derive(Args, Clone)]
pub struct ViewArgs {
    #[command(flatten)]
    camera: CameraArgs,
    /// What to draw.
    #[arg(long, value_enum, default_value_t = Style::Edges)]
    style: Style,
    #[command(flatten)]
    look: StyleFlags,
    /// Cut the model open: the mesh and the edges keep what the planes keep; the cut faces of
    /// closed meshes are filled and the cut outlined.
    #[command(flatten)]
    section: SectionFlags,
    #[command(flatten)]
    cut: CutFlags,
    /// Display modes (hidden-line, X-ray, wireframe), hidden edges in their own style, edges
    /// fading with distance.
    #[command(flatten)]
    display: DisplayFlags,
    /// The pose of an animated asset (a glTF's skins, morph targets and animations).
    #[command(flatten)]
    animation: AnimationFlags,
    /// Pose the asset by its animation of this name (or number), like --animation.
    #[arg(long, value_name = "NAME", conflicts_with = "animation")]
    animation_name: Option<String>,
    /// Which technique draws the edges (`--style edges`).
    #[arg(long, default_value = "joined", value_parser = technique_names(),
          long_help = technique_help())]
    technique: String,
    #[command(flatten)]
    parameters: TechniqueFlags,
    /// Edge classes to draw (intersection edges need `bake --intersections`).
    #[arg(
        long,
        value_delimiter = ',',
        value_parser = clap::builder::PossibleValuesParser::new(EdgeClasses::names()),
        default_values_t = EdgeClasses::names().map(str::to_owned)
    )]
    classes: Vec<String>,
    /// How edges join.
    #[arg(long, value_enum, default_value_t = Caps::NextIndex)]
    caps: Caps,
    /// `--style chamfer`: direction towards a parallel light, model space.
    #[arg(long, value_name = "X,Y,Z", value_delimiter = ',', allow_hyphen_values = true,
          default_values_t = DEFAULT_LIGHT_DIRECTION, conflicts_with = "light_pos")]
    light_dir: Vec<f32>,
    /// `--style chamfer`: position of a point light, model space (instead of --light-dir).
    #[arg(
        long,
        value_name = "X,Y,Z",
        value_delimiter = ',',
        allow_hyphen_values = true
    )]
    light_pos: Option<Vec<f32>>,
    /// `--style chamfer`: Blinn's model of seed 000 (--diffuse, --specular, --shininess) or glTF's
    /// metallic-roughness model (--base-color, --metallic, --roughness).
    #[arg(long, value_enum, default_value_t = Shading::Blinn)]
    shading: Shading,
    /// `--shading pbr`: base colour, linear RGB 0 to 1.
    #[arg(long, value_name = "R,G,B", value_delimiter = ',', default_values_t = StyleSettings::BASE_COLOR)]
    base_color: Vec<f32>,
    /// `--shading pbr`: light strips and faces by this environment too (an equirectangular Radiance
    /// .hdr, +Y up, its middle facing -Z, in model space), prefiltered for --roughness.
    #[arg(long, value_name = "FILE.hdr")]
    env: Option<PathBuf>,
    /// `--style chamfer` with --light-pos: make the light a spot shining this way.
    #[arg(
        long,
        value_name = "X,Y,Z",
        value_delimiter = ',',
        allow_hyphen_values = true,
        requires = "light_pos"
    )]
    spot_dir: Option<Vec<f32>>,
    /// `--spot-dir`: the cone's inner and outer half-angles, degrees.
    #[arg(long, value_name = "INNER,OUTER", value_delimiter = ',', default_values_t = [20.0, 30.0])]
    spot_angles: Vec<f32>,
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum Shading {
    /// Seed 000's Blinn model.
    Blinn,
    /// glTF's metallic-roughness model (GGX, Smith, Schlick).
    Pbr,
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum Style {
    /// The lit mesh alone.
    Mesh,
    /// The lit mesh and its edges.
    Edges,
    /// Blinn-lit mesh, chamfer edges (those with a radius: see --radius) as lit rounded strips
    /// (seed 000), contours as lines.
    Chamfer,
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum Caps {
    /// Walk each drawn edge end's next-index ring (thesis §13).
    NextIndex,
    /// Walk each vertex's ring from the cap buffer (thesis §10.5).
    CapBuffer,
    /// Plain quads.
    None,
}

fn technique_names() -> clap::builder::PossibleValuesParser {
    clap::builder::PossibleValuesParser::new(Technique::names())
}

fn technique_help() -> String {
    let mut help = String::from("Which technique draws the edges (`--style edges`):\n");
    for technique in Technique::all() {
        help.push_str(&format!(
            "  {:<16} {}\n",
            technique.name(),
            technique.summary()
        ));
    }
    help
}

impl ViewArgs {
    /// The pose the animation flags ask each of `assets` in (`None`: as stored). In a scene of
    /// several assets the still ones are drawn as they are; a single still asset with animation
    /// flags is refused.
    fn poses(&self, assets: &[Asset]) -> anyhow::Result<Vec<Option<Pose>>> {
        let spelled = |e: chamfer_runtime::schema::SchemaError| anyhow::anyhow!(e.spelled(flag));
        assets
            .iter()
            .map(|asset| {
                let rig = (!asset.motion.rig.is_empty()).then_some(&asset.motion.rig);
                if rig.is_none() && assets.len() > 1 {
                    return Ok(None);
                }
                let mut settings = self.animation.0;
                if let Some(name) = &self.animation_name {
                    let rig = rig.context("--animation-name needs an animated asset")?;
                    let index = rig.animation(name).with_context(|| {
                        format!(
                            "--animation-name {name:?}: no such animation (the asset's: {})",
                            animation_names(rig)
                        )
                    })?;
                    settings.animation = Some(index as u64);
                }
                settings.pose_of(rig).map_err(spelled)
            })
            .collect()
    }

    /// The technique named by `--technique`.
    pub fn technique(&self) -> anyhow::Result<Technique> {
        let technique = Technique::from_name(&self.technique)
            .with_context(|| format!("--technique {}: no such technique", self.technique))?;
        self.parameters.apply(technique)
    }

    fn check(&self) -> anyhow::Result<()> {
        self.camera.check()?;
        self.look
            .0
            .check()
            .map_err(|e| anyhow::anyhow!(e.spelled(flag)))?;
        self.section
            .0
            .check()
            .and_then(|()| self.cut.0.check())
            .and_then(|()| self.animation.0.check())
            .map_err(|e| anyhow::anyhow!(e.spelled(flag)))?;
        if self.animation.1.contains(&"time")
            && self.animation.0.animation.is_none()
            && self.animation_name.is_none()
        {
            bail!("--time needs --animation or --animation-name");
        }
        if self.env.is_some() && (self.style != Style::Chamfer || self.shading != Shading::Pbr) {
            bail!("--env needs --style chamfer --shading pbr");
        }
        if self.base_color.len() != 3
            || !self
                .base_color
                .iter()
                .all(|c| c.is_finite() && (0.0..=1.0).contains(c))
        {
            bail!("--base-color needs three numbers from 0 to 1");
        }
        if self.spot_dir.as_ref().is_some_and(|d| {
            d.len() != 3 || !d.iter().all(|c| c.is_finite()) || d.iter().all(|&c| c == 0.0)
        }) {
            bail!("--spot-dir needs three finite numbers (a direction not 0,0,0)");
        }
        if !matches!(self.spot_angles[..], [inner, outer]
            if inner.is_finite() && outer.is_finite() && 0.0 <= inner && inner <= outer && outer <= 90.0)
        {
            bail!("--spot-angles needs INNER,OUTER degrees with 0 <= INNER <= OUTER <= 90");
        }
        let light = self.light_pos.as_deref().unwrap_or(&self.light_dir);
        if light.len() != 3
            || !light.iter().all(|c| c.is_finite())
            || (self.light_pos.is_none() && light.iter().all(|&c| c == 0.0))
        {
            bail!("--light-dir / --light-pos need three finite numbers (a direction not 0,0,0)");
        }
        let technique = self.technique()?;
        self.display
            .0
            .check_for(&technique, self.look.0.edge_width)
            .map_err(|e| anyhow::anyhow!(e.spelled(flag)))?;
        Ok(())
    }

    fn edge_style(&self) -> EdgeStyle {
        // The parser took only the names of the table.
        let classes = EdgeClasses::from_names(self.classes.iter().map(String::as_str))
            .unwrap_or(EdgeClasses::ALL);
        let highlight = (self.style == Style::Chamfer).then(|| self.highlight());
        self.look.0.edges(EdgeStyle {
            technique: self.technique().unwrap_or_default(),
            classes,
            highlight,
            caps: match self.caps {
                Caps::NextIndex => CapMethod::NextIndex,
                Caps::CapBuffer => CapMethod::CapBuffer,
                Caps::None => CapMethod::None,
            },
            section: self.clip_planes(),
            display: self.display.0.display(),
            ..EdgeStyle::default()
        })
    }

    /// The section's planes (checked in `check`).
    fn clip_planes(&self) -> ClipPlanes {
        ClipPlanes::from_section(&self.section.0).unwrap_or_default()
    }
}

impl ViewArgs {
    fn light(&self) -> Light {
        let three = |v: &[f32]| [v[0], v[1], v[2]];
        match (&self.light_pos, &self.spot_dir) {
            (Some(p), Some(d)) => Light::Spot {
                position: three(p),
                direction: three(d),
                inner_deg: self.spot_angles[0],
                outer_deg: self.spot_angles[1],
            },
            (Some(p), None) => Light::Point(three(p)),
            _ => Light::Directional(three(&self.light_dir)),
        }
    }

    /// The chamfer highlight as `--style chamfer` draws it.
    fn highlight(&self) -> Highlight {
        let look = &self.look.0;
        let shading = match self.shading {
            Shading::Pbr => ShadingModel::Pbr(look.pbr([
                self.base_color[0],
                self.base_color[1],
                self.base_color[2],
            ])),
            Shading::Blinn => ShadingModel::Blinn(look.blinn()),
        };
        look.highlight(self.light(), shading)
    }

    fn mesh_style(&self) -> MeshStyle {
        let style = if self.style == Style::Chamfer {
            self.look.0.mesh_style(&self.highlight())
        } else {
            MeshStyle::default()
        };
        MeshStyle {
            section: self.clip_planes(),
            ..style
        }
    }
}

pub fn run(args: &RenderArgs) -> anyhow::Result<()> {
    args.view.check()?;
    let mut inputs = vec![args.input.as_path()];
    inputs.extend(args.view.env.as_deref());
    ensure_not_an_input(&args.output, &inputs)?;
    ensure_replaceable(&args.output)?;
    let options = args.options.to_options()?;
    let name = args.input.to_string_lossy().to_ascii_lowercase();
    let (assets, instances) = if name.ends_with(".scene.json") {
        let scene = chamfer_preprocess::scene::read_scene(&args.input, &options.limits)?;
        (scene.assets, scene.instances)
    } else {
        let read = chamfer_preprocess::input::read_asset(&args.input, &options)?;
        for warning in &read.warnings {
            crate::warn(format_args!("warning: {}: {warning}", args.input.display()));
        }
        (vec![read.asset], vec![(0, Mat4::IDENTITY)])
    };
    let (image, adapter) = render_scene(&assets, &instances, &args.view)
        .with_context(|| format!("{}: cannot render", args.input.display()))?;
    write_png(&image, &args.output)?;
    let triangles: u64 = instances
        .iter()
        .map(|&(a, _)| assets[a].triangle_count() as u64)
        .sum();
    let edges: u64 = instances
        .iter()
        .map(|&(a, _)| assets[a].edge_count() as u64)
        .sum();
    crate::say(format_args!(
        "{} ({} instances of {} assets: {triangles} triangles, {edges} edges) -> {} ({}x{}, {adapter})",
        args.input.display(),
        instances.len(),
        assets.len(),
        args.output.display(),
        image.width,
        image.height,
    ))
}

/// The picture's background, straight RGBA (hidden-line faces take its colour).
const BACKGROUND: [f32; 4] = [1.0; 4];

/// Renders `asset` as `view` says; returns the image and the adapter's name.
pub fn render(asset: &Asset, view: &ViewArgs) -> anyhow::Result<(Image, String)> {
    render_scene(std::slice::from_ref(asset), &[(0, Mat4::IDENTITY)], view)
}

/// Renders the instances of `assets` (asset index, model to world) as `view` says, the camera
/// framing all of them.
pub fn render_scene(
    assets: &[Asset],
    instances: &[(usize, Mat4)],
    view: &ViewArgs,
) -> anyhow::Result<(Image, String)> {
    view.check()?;
    let gpu = Offscreen::new()?;
    fits_the_device(&gpu.device.limits(), view)?;
    let target = gpu.target(
        view.camera.width,
        view.camera.height,
        view.look.0.samples as u32,
    )?;
    let pipelines = Pipelines::new(&gpu.device, &target.formats())?;
    let technique = view.technique()?;
    let environment = match &view.env {
        Some(path) => Some(Arc::new(read_environment(path, &Limits::DEFAULT)?)),
        None => None,
    };
    let uploaded = assets
        .iter()
        .map(|asset| GpuAsset::for_techniques(&gpu.device, asset, &[technique]))
        .collect::<Result<Vec<_>, _>>()?;
    let mut encoder = gpu.encoder();
    let mut posed = Vec::with_capacity(assets.len());
    for (gpu_asset, pose) in uploaded.iter().zip(view.poses(assets)?) {
        posed.push(match pose {
            Some(pose) => {
                let mut posed = PosedAsset::new(&pipelines, gpu_asset)?;
                posed.prepare(&gpu.queue, &mut encoder, &pose)?;
                Some(posed)
            }
            None => None,
        });
    }
    let shown: Vec<&GpuAsset> = uploaded
        .iter()
        .zip(&posed)
        .map(|(still, posed)| posed.as_ref().map_or(still, PosedAsset::asset))
        .collect();
    let drawn: Vec<Instance<'_>> = instances
        .iter()
        .map(|&(a, transform)| Instance::new(shown[a]).with_transform(transform))
        .collect();
    let camera = view
        .camera
        .camera(Instance::scene_bounds(&drawn).unwrap_or([[0.0; 3], [1.0; 3]]));
    let mesh_style = view
        .display
        .0
        .faces()
        .mesh_style(view.mesh_style(), BACKGROUND);
    let mut mesh = MeshRenderer::for_scenes(&pipelines)?;
    mesh.set_environment(environment.clone());
    if let Some(style) = &mesh_style {
        mesh.prepare_scene(&gpu.queue, &camera, &drawn, style);
    }
    let section = view.clip_planes();
    let cut = match section.is_empty() {
        true => None,
        false => {
            let mut cut = CutRenderer::new(&pipelines)?;
            let style = CutStyle::from_settings(section, &view.cut.0);
            cut.prepare(&gpu.queue, &camera, &drawn, &style);
            Some(cut)
        }
    };
    let mut edges = SceneRenderer::new(&pipelines);
    edges.set_environment(environment);
    let prepared = match view.style {
        Style::Mesh => None,
        _ => Some(edges.prepare(
            &gpu.queue,
            &mut encoder,
            &camera,
            &drawn,
            &view.edge_style(),
        )?),
    };
    {
        let mut pass = target.begin_pass(&mut encoder, BACKGROUND.map(f64::from));
        if mesh_style.is_some() {
            mesh.render(&mut pass);
        }
        if let Some(cut) = &cut {
            cut.render(&mut pass);
        }
        if let Some(prepared) = &prepared {
            prepared.render(&mut pass);
        }
    }
    if let Some(prepared) = &prepared {
        prepared.finish(&mut encoder, &target.views())?;
    }
    gpu.submit(encoder)?;
    let adapter = format!("{} ({:?})", gpu.info.name, gpu.info.backend);
    Ok((target.read(&gpu)?, adapter))
}

/// Refuses a picture larger than the device's textures or its largest buffer (the readback), so
/// the request fails with a message instead of in the device's error handler.
fn fits_the_device(limits: &wgpu::Limits, view: &ViewArgs) -> anyhow::Result<()> {
    let largest = limits.max_texture_dimension_2d;
    let (width, height) = (view.camera.width, view.camera.height);
    if width > largest || height > largest {
        bail!(
            "{}x{} pixels is larger than this device's textures (at most {largest} on a side)",
            width,
            height
        );
    }
    let row =
        (u64::from(width) * 4).next_multiple_of(u64::from(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT));
    let readback = row * u64::from(height);
    if readback > limits.max_buffer_size {
        bail!(
            "{}x{} pixels needs a {readback}-byte readback buffer, more than this device's {} bytes",
            width,
            height,
            limits.max_buffer_size
        );
    }
    Ok(())
}

/// Writes `image` as an RGBA PNG, atomically.
pub fn write_png(image: &Image, path: &Path) -> anyhow::Result<()> {
    write_atomically(path, |out| {
        let mut encoder = png::Encoder::new(out, image.width, image.height);
        encoder.set_color(png::ColorType::Rgba);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header().map_err(std::io::Error::other)?;
        writer
            .write_image_data(&image.rgba)
            .map_err(std::io::Error::other)?;
        writer.finish().map_err(std::io::Error::other)
    })?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use clap::Parser;

    use super::*;

    #[derive(Parser)]
    struct View {
        #[command(flatten)]
        view: ViewArgs,
    }

    fn view(width: &str, height: &str) -> ViewArgs {
        View::parse_from(["render", "--width", width, "--height", height]).view
    }

    #[test]
    fn pictures_larger_than_the_device_allows_are_refused_with_its_limits() {
        let small = wgpu::Limits::downlevel_defaults(); // 2048 px textures, 256 MiB buffers
        assert!(fits_the_device(&small, &view("2048", "1024")).is_ok());
        let error = fits_the_device(&small, &view("4096", "16")).expect_err("too wide");
        assert!(error.to_string().contains("at most 2048"), "{error}");
        let tiny_buffers = wgpu::Limits {
            max_buffer_size: 1 << 20,
            ..small
        };
        let error = fits_the_device(&tiny_buffers, &view("1024", "1024")).expect_err("readback");
        assert!(error.to_string().contains("readback"), "{error}");
    }
}
