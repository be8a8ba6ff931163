//! Bevy's asset processor bakes mesh files named by their `.meta` ([`ChamferBake`]): the processed
//! asset is the bytes `chamfer bake` makes with the `.meta`'s settings, and it is baked again when
//! the `.meta` or the file changes.

use std::path::{Path, PathBuf};

use bevy::asset::processor::{AssetProcessor, ProcessStatus, ProcessorState};
use bevy::asset::{AssetMode, AssetPath, AssetPlugin};
use bevy::prelude::*;
use bevy::tasks::block_on;
use chamfer_bevy::{BakeSettings, ChamferAsset, ChamferPlugin, bake_to_asset};
use chamfer_runtime::asset::Asset;
use chamfer_tests::fixture;

/// A source folder and the processed folder beside it.
struct Folders {
    _root: tempfile::TempDir,
    source: PathBuf,
    processed: PathBuf,
}

impl Folders {
    fn new() -> Self {
        let root = tempfile::tempdir().expect("tempdir");
        let source = root.path().join("assets");
        let processed = root.path().join("imported_assets");
        std::fs::create_dir(&source).expect("assets folder");
        Self {
            _root: root,
            source,
            processed,
        }
    }

    /// Puts `fixture` in the assets as `name`, with a `.meta` asking for [`ChamferBake`] with
    /// `settings` (RON).
    fn add(&self, name: &str, fixture_path: &str, settings: &str) {
        std::fs::copy(fixture(fixture_path), self.source.join(name)).expect("copy");
        self.set_meta(name, settings);
    }

    fn set_meta(&self, name: &str, settings: &str) {
        let meta = format!(
            "(\n    meta_format_version: \"1.0\",\n    asset: Process(\n        processor: \"ChamferBake\",\n        settings: {settings},\n    ),\n)\n"
        );
        std::fs::write(self.source.join(format!("{name}.meta")), meta).expect("meta");
    }

    fn processed(&self, name: &str) -> Vec<u8> {
        std::fs::read(self.processed.join(name)).expect("processed asset")
    }
}

/// An app that processes `folders` (no window, no renderer) and has finished processing.
fn process(folders: &Folders) -> App {
    let mut app = App::new();
    app.add_plugins((
        MinimalPlugins,
        AssetPlugin {
            file_path: folders.source.to_string_lossy().into_owned(),
            processed_file_path: folders.processed.to_string_lossy().into_owned(),
            mode: AssetMode::Processed,
            use_asset_processor_override: Some(true),
            watch_for_changes_override: Some(false),
            ..default()
        },
    ))
    .init_asset::<Mesh>()
    .add_plugins(ChamferPlugin);
    app.finish();
    app.cleanup();
    let processor = app.world().resource::<AssetProcessor>().clone();
    for _ in 0..10_000 {
        app.update();
        if block_on(processor.get_state()) == ProcessorState::Finished {
            return app;
        }
        std::thread::sleep(std::time::Duration::from_millis(2));
    }
    panic!("the processor did not finish");
}

fn status(app: &App, name: &str) -> ProcessStatus {
    let processor = app.world().resource::<AssetProcessor>().clone();
    block_on(
        processor
            .data()
            .wait_until_processed(AssetPath::from(name.to_owned())),
    )
}

/// What `chamfer bake` makes of `fixture_path` named `name` (the name is in the asset).
fn baked(name: &str, fixture_path: &str, settings: &BakeSettings) -> Vec<u8> {
    let bytes = std::fs::read(fixture(fixture_path)).expect("fixture");
    bake_to_asset(Path::new(name), &bytes, settings).expect("bake")
}

/// Issue 40: every entry of the bake schema is a `.meta` setting. One asset per entry, its `.meta`
/// giving the entry's example (and what it requires), all processed in one run: each processed
/// file is what the same settings bake (chamfer bake's flags and the page's settings are checked
/// against those too).
#[test]
fn every_schema_option_is_a_meta_setting_that_bakes_what_the_settings_bake() {
    use chamfer_runtime::schema::{Schema, Value};

    let folders = Folders::new();
    let mut expected = Vec::new();
    for entry in BakeSettings::ENTRIES {
        let mut settings = BakeSettings::default();
        let mut ron = Vec::new();
        for name in entry.requires.iter().copied().chain([entry.name]) {
            let entry = BakeSettings::entry(name).expect("known");
            entry.set_example(&mut settings);
            let value = match entry.example().expect("an example") {
                Value::Number(x) => format!("{x:?}"),
                value => value.to_string(),
            };
            // An entry without a default is an Option field: RON spells it Some(..).
            let value = if entry.default().is_none() {
                format!("Some({value})")
            } else {
                value
            };
            ron.push(format!("{name}: {value}"));
        }
        let name = format!("{}.glb", entry.name);
        folders.add(
            &name,
            "shapes/cube-cad-jittered.glb",
            &format!("({})", ron.join(", ")),
        );
        let plain = baked(
            &name,
            "shapes/cube-cad-jittered.glb",
            &BakeSettings::default(),
        );
        expected.push((
            name.clone(),
            baked(&name, "shapes/cube-cad-jittered.glb", &settings),
            plain,
        ));
    }
    let app = process(&folders);
    let mut changed = 0;
    for (name, bytes, plain) in expected {
        assert_eq!(status(&app, &name), ProcessStatus::Processed, "{name}");
        assert!(
            folders.processed(&name) == bytes,
            "{name}: other bytes than its settings"
        );
        changed += usize::from(bytes != plain);
    }
    // Most examples change what is baked (the limits and some tolerances do not, on this cube).
    assert!(changed >= 5, "only {changed} settings changed the asset");
}

#[test]
fn a_glb_is_baked_with_its_meta_settings_and_again_when_they_change() {
    let folders = Folders::new();
    folders.add("part.glb", "shapes/cube-cad-jittered.glb", "()");
    let app = process(&folders);
    assert_eq!(status(&app, "part.glb"), ProcessStatus::Processed);
    let plain = folders.processed("part.glb");
    assert_eq!(
        plain,
        baked(
            "part.glb",
            "shapes/cube-cad-jittered.glb",
            &BakeSettings::default()
        )
    );
    drop(app);

    // New bake options in the .meta: processed again at the next start, with them.
    folders.set_meta("part.glb", "(radius_rel: Some(0.01), compact: true)");
    let app = process(&folders);
    assert_eq!(status(&app, "part.glb"), ProcessStatus::Processed);
    let rounded = folders.processed("part.glb");
    let settings = BakeSettings {
        radius_rel: Some(0.01),
        compact: true,
        ..BakeSettings::default()
    };
    assert_eq!(
        rounded,
        baked("part.glb", "shapes/cube-cad-jittered.glb", &settings)
    );
    assert_ne!(rounded, plain);
    drop(app);

    // A new source file: baked again.
    std::fs::copy(
        fixture("shapes/pyramid-fans-mirrored.glb"),
        folders.source.join("part.glb"),
    )
    .expect("replace");
    let app = process(&folders);
    assert_eq!(
        folders.processed("part.glb"),
        baked("part.glb", "shapes/pyramid-fans-mirrored.glb", &settings)
    );
    drop(app);
}

#[test]
fn a_processed_file_loads_as_a_chamfer_asset_with_its_mesh() {
    let folders = Folders::new();
    folders.add(
        "part.ply",
        "shapes/cube-marked-le.ply",
        "(crease_deg: 45.0)",
    );
    folders.add("cube.obj", "shapes/cube.obj", "()");
    let mut app = process(&folders);
    let server = app.world().resource::<AssetServer>().clone();
    let part: Handle<ChamferAsset> = server.load("part.ply");
    let mesh: Handle<Mesh> = server.load("part.ply#mesh");
    let obj: Handle<ChamferAsset> = server.load("cube.obj");
    for _ in 0..10_000 {
        app.update();
        if server.is_loaded_with_dependencies(&part) && server.is_loaded_with_dependencies(&obj) {
            break;
        }
        assert!(
            !server.load_state(&part).is_failed(),
            "{:?}",
            server.load_state(&part)
        );
        std::thread::sleep(std::time::Duration::from_millis(2));
    }
    let assets = app.world().resource::<Assets<ChamferAsset>>();
    let part = assets.get(&part).expect("part loaded");
    let expected = Asset::decode(&baked(
        "part.ply",
        "shapes/cube-marked-le.ply",
        &BakeSettings {
            crease_deg: 45.0,
            ..BakeSettings::default()
        },
    ))
    .expect("decode");
    assert_eq!(*part.asset, expected);
    assert_eq!(part.mesh, mesh);
    let meshes = app.world().resource::<Assets<Mesh>>();
    let mesh = meshes.get(&mesh).expect("mesh loaded");
    assert_eq!(mesh.count_vertices(), part.asset.render_positions.len());
    assert_eq!(
        assets.get(&obj).expect("obj loaded").asset.edge_count(),
        12,
        "cube.obj's 12 edges"
    );
}

#[test]
fn a_broken_file_or_bad_settings_fail_to_process_and_say_why() {
    let folders = Folders::new();
    folders.add("truncated.glb", "broken/truncated.glb", "()");
    folders.add(
        "part.glb",
        "shapes/cube-cad-jittered.glb",
        "(crease_deg: -5.0)",
    );
    folders.add("good.glb", "shapes/cube-cad-jittered.glb", "()");
    let app = process(&folders);
    assert_eq!(status(&app, "truncated.glb"), ProcessStatus::Failed);
    assert_eq!(status(&app, "part.glb"), ProcessStatus::Failed);
    for name in ["truncated.glb", "part.glb"] {
        // Nothing is left where processing failed (Bevy had opened an empty file there).
        let left = folders.processed.join(name);
        assert!(!left.exists(), "{}: left behind", left.display());
        let meta = folders.processed.join(format!("{name}.meta"));
        assert!(!meta.exists(), "{}: left behind", meta.display());
    }
    // The others still bake.
    assert_eq!(status(&app, "good.glb"), ProcessStatus::Processed);

    // The errors the processor logs name the file and the problem.
    let bytes = std::fs::read(fixture("broken/truncated.glb")).expect("fixture");
    let error = bake_to_asset(Path::new("truncated.glb"), &bytes, &BakeSettings::default())
        .expect_err("truncated");
    assert!(error.to_string().contains("truncated.glb"), "{error}");
    let settings = BakeSettings {
        crease_deg: -5.0,
        ..BakeSettings::default()
    };
    let bytes = std::fs::read(fixture("shapes/cube-cad-jittered.glb")).expect("fixture");
    let error = bake_to_asset(Path::new("part.glb"), &bytes, &settings).expect_err("settings");
    let message = error.to_string();
    assert!(
        message.contains("part.glb") && message.contains("crease"),
        "{message}"
    );
}
