//! A scene: which `.chamfer` assets, and the instances of them with their transforms, so a glTF
//! scene keeps its structure (one asset per mesh, drawn and moved per instance) instead of being
//! flattened into one asset. A small JSON file beside its assets, written by `chamfer bake --scene`
//! and read by `chamfer render` and the runtime.
//!
//! ```json
//! { "format": "chamfer-scene", "version": 1,
//!   "assets": ["robot.mesh0.chamfer", "robot.mesh1.chamfer"],
//!   "instances": [{ "asset": 0, "transform": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1], "name": "arm" }] }
//! ```
//! Transforms are model to world, 16 numbers in column-major order (glTF's). Asset names are plain
//! file names in the scene file's folder: a scene never reaches outside it.

use serde::{Deserialize, Serialize};

/// The `format` every scene file names.
pub const SCENE_FORMAT: &str = "chamfer-scene";
/// The scene file version this crate reads and writes.
pub const SCENE_VERSION: u32 = 1;
/// The largest scene file read: a million instances fit in well under this.
pub const MAX_SCENE_BYTES: u64 = 1 << 28;

/// A scene description.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SceneFile {
    /// Always [`SCENE_FORMAT`].
    pub format: String,
    /// Always [`SCENE_VERSION`] for files this crate writes.
    pub version: u32,
    /// The assets, as file names in the scene file's folder.
    pub assets: Vec<String>,
    /// The drawn instances.
    pub instances: Vec<SceneInstance>,
}

/// One drawn copy of an asset.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SceneInstance {
    /// Index into [`SceneFile::assets`].
    pub asset: u32,
    /// Model to world, column-major.
    pub transform: [f32; 16],
    /// The node's name, if it had one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
}

/// Why a scene file cannot be used.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum SceneError {
    /// Not JSON of the scene's shape.
    #[error("not a scene file: {0}")]
    Parse(String),
    /// Another format or version.
    #[error(
        "a {format} file of version {version}; this reader takes {SCENE_FORMAT} version {SCENE_VERSION}"
    )]
    Version {
        /// The file's `format`.
        format: String,
        /// The file's `version`.
        version: u32,
    },
    /// An asset name that is not a plain file name in the scene's folder.
    #[error("asset {0:?} is not a plain file name (no folders, no `..`)")]
    AssetName(String),
    /// An instance of an asset the file does not list.
    #[error("instance {instance} draws asset {asset}, but the scene lists {assets}")]
    AssetIndex {
        /// The instance.
        instance: usize,
        /// Its asset index.
        asset: u32,
        /// How many assets there are.
        assets: usize,
    },
    /// A transform with a number that is not finite.
    #[error("instance {0} has a transform that is not finite")]
    Transform(usize),
}

impl SceneFile {
    /// A scene of `assets` and `instances` in the current format.
    pub fn new(assets: Vec<String>, instances: Vec<SceneInstance>) -> Self {
        Self {
            format: SCENE_FORMAT.to_owned(),
            version: SCENE_VERSION,
            assets,
            instances,
        }
    }

    /// Parses and validates a scene file's bytes.
    pub fn parse(bytes: &[u8]) -> Result<Self, SceneError> {
        let scene: Self =
            serde_json::from_slice(bytes).map_err(|e| SceneError::Parse(e.to_string()))?;
        scene.validate()?;
        Ok(scene)
    }

    /// Checks the format, the asset names, the instances' asset indices and transforms.
    pub fn validate(&self) -> Result<(), SceneError> {
        if self.format != SCENE_FORMAT || self.version != SCENE_VERSION {
            return Err(SceneError::Version {
                format: self.format.clone(),
                version: self.version,
            });
        }
        for name in &self.assets {
            let plain = !name.is_empty()
                && name != "."
                && name != ".."
                && !name.contains(['/', '\\', '\0'])
                && !name.starts_with('~');
            if !plain {
                return Err(SceneError::AssetName(name.clone()));
            }
        }
        for (i, instance) in self.instances.iter().enumerate() {
            if instance.asset as usize >= self.assets.len() {
                return Err(SceneError::AssetIndex {
                    instance: i,
                    asset: instance.asset,
                    assets: self.assets.len(),
                });
            }
            if !instance.transform.iter().all(|v| v.is_finite()) {
                return Err(SceneError::Transform(i));
            }
        }
        Ok(())
    }

    /// The file's text (pretty JSON, one instance per line).
    pub fn to_json(&self) -> String {
        let mut text = format!(
            "{{\n  \"format\": {},\n  \"version\": {},\n  \"assets\": {},\n  \"instances\": [",
            json(&self.format),
            self.version,
            json(&self.assets)
        );
        for (i, instance) in self.instances.iter().enumerate() {
            text.push_str(if i == 0 { "\n    " } else { ",\n    " });
            text.push_str(&json(instance));
        }
        text.push_str("\n  ]\n}\n");
        text
    }
}

fn json<T: Serialize>(value: &T) -> String {
    serde_json::to_string(value).unwrap_or_else(|e| format!("\"{e}\""))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn identity() -> [f32; 16] {
        [
            1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0,
        ]
    }

    fn scene() -> SceneFile {
        SceneFile::new(
            vec!["a.chamfer".into(), "b.chamfer".into()],
            vec![
                SceneInstance {
                    asset: 1,
                    transform: identity(),
                    name: Some("door".into()),
                },
                SceneInstance {
                    asset: 0,
                    transform: identity(),
                    name: None,
                },
            ],
        )
    }

    #[test]
    fn a_scene_round_trips_through_its_text() {
        let scene = scene();
        assert_eq!(SceneFile::parse(scene.to_json().as_bytes()), Ok(scene));
    }

    #[test]
    fn bad_scenes_are_refused_by_name() {
        let mut bad = scene();
        bad.instances[0].asset = 2;
        let text = bad.to_json();
        assert!(matches!(
            SceneFile::parse(text.as_bytes()),
            Err(SceneError::AssetIndex { asset: 2, .. })
        ));
        for name in ["../x.chamfer", "/etc/passwd", "sub/x.chamfer", "..", ""] {
            let mut bad = scene();
            bad.assets[0] = name.into();
            assert_eq!(
                SceneFile::parse(bad.to_json().as_bytes()),
                Err(SceneError::AssetName(name.into())),
                "{name}"
            );
        }
        let text = scene().to_json().replacen("1.0", "1e999", 1);
        assert!(SceneFile::parse(text.as_bytes()).is_err());
        let mut other = scene();
        other.version = 2;
        assert!(matches!(
            SceneFile::parse(other.to_json().as_bytes()),
            Err(SceneError::Version { version: 2, .. })
        ));
        assert!(matches!(
            SceneFile::parse(br#"{"format": 3}"#),
            Err(SceneError::Parse(_))
        ));
    }
}
