//! `chamfer.pose`: an animated asset's topology positions in a pose (issue 41), posed on the CPU
//! by the runtime's own formula (`Motion::pose_positions`), the pose chosen by the animation
//! schema (`chamfer.ANIMATION_SCHEMA`, the flags of `chamfer render`).

use chamfer_runtime::rig::{AnimationSettings, animation_names};
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::prelude::*;

use crate::asset::PyAsset;
use crate::errors;

/// Where an animated asset's topology vertices are in a pose: float32 (V, 3), the rows of
/// `asset.topology_positions` moved. `animation` is an animation's number or name
/// (`asset.rig["animations"]`), sampled at `time` seconds; `weights` sets the morph targets'
/// weights (one per target). With neither, the rig's rest pose. Raises OptionsError when the asset
/// has no such animation, another number of morph targets, or does not move at all.
#[pyfunction]
#[pyo3(signature = (asset, animation = None, time = 0.0, weights = None))]
pub fn pose<'py>(
    py: Python<'py>,
    asset: &Bound<'py, PyAsset>,
    animation: Option<&Bound<'py, PyAny>>,
    time: f32,
    weights: Option<Vec<f32>>,
) -> PyResult<Bound<'py, PyArray2<f32>>> {
    let asset = asset.get().asset();
    let rig = &asset.motion.rig;
    let animation = match animation {
        None => None,
        Some(value) => {
            let name = match value.extract::<u64>() {
                Ok(index) => index.to_string(),
                Err(_) => value
                    .extract::<String>()
                    .map_err(|_| errors::options("animation must be a number or a name".into()))?,
            };
            let index = rig.animation(&name).ok_or_else(|| {
                errors::options(format!(
                    "animation {name:?}: no such animation ({})",
                    animation_names(rig)
                ))
            })?;
            Some(index as u64)
        }
    };
    // The weights may be more than the schema's numbers hold: they are checked below.
    let settings = AnimationSettings {
        animation,
        time,
        pose: None,
    };
    let moving = (!rig.is_empty()).then_some(rig);
    let mut pose = match settings.pose_of(moving) {
        Ok(Some(pose)) => pose,
        Ok(None) => match moving {
            Some(rig) => chamfer_runtime::rig::Pose::rest(rig),
            None => {
                return Err(errors::options(
                    "the asset does not move (no skin, morph targets or animations)".into(),
                ));
            }
        },
        Err(e) => return Err(errors::options(e.to_string())),
    };
    if let Some(weights) = weights {
        if weights.len() != pose.weights.len() || !weights.iter().all(|w| w.is_finite()) {
            return Err(errors::options(format!(
                "weights must be {} finite numbers, one per morph target, not {weights:?}",
                pose.weights.len()
            )));
        }
        pose.weights = weights;
    }
    let positions = py.detach(|| {
        asset
            .motion
            .pose_positions(&asset.topology_positions, &pose)
    });
    let rows = positions.len();
    PyArray1::from_vec(py, positions.into_flattened()).reshape([rows, 3])
}
