//! The camera the renderers are given each frame, and an orbit helper that frames a model. Pure
//! math (no GPU): the bake's hidden-line drawings use the same camera as the renderer, so a drawing
//! lies on the picture of the same view pixel for pixel.

use glam::camera::rh::{proj::directx, view::look_at_mat4};
use glam::{Mat4, Vec3, Vec4};

/// The view of one frame. All of the renderers' math happens in model space, so a single
/// model-view matrix carries both the camera and the model's transform.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Model space to view space (right-handed, looking down −Z).
    pub model_view: Mat4,
    /// View space to wgpu clip space (depth 0..1): perspective or orthographic.
    pub projection: Mat4,
    /// Size of the render target in pixels.
    pub viewport: [u32; 2],
}

impl Camera {
    /// True if the projection is orthographic (no perspective divide).
    pub fn is_orthographic(&self) -> bool {
        self.projection.z_axis.w == 0.0 && self.projection.w_axis.w == 1.0
    }

    /// Model space to clip space.
    pub fn view_projection(&self) -> Mat4 {
        self.projection * self.model_view
    }

    /// The camera in model space, homogeneous: its position (w = 1) for a perspective camera, the
    /// direction towards the viewer (w = 0) for an orthographic one.
    pub fn eye(&self) -> Vec4 {
        let towards_viewer = if self.is_orthographic() {
            Vec4::Z
        } else {
            Vec4::W
        };
        self.model_view.inverse() * towards_viewer
    }

    /// World size of one pixel at clip w = 1 (at view depth 1 for perspective, anywhere for orthographic).
    pub fn pixel_scale(&self) -> f32 {
        2.0 / (self.projection.y_axis.y * self.viewport[1].max(1) as f32)
    }

    /// Frames the box `bounds` (min, max corners) from an orbit around its centre.
    pub fn orbit(bounds: [[f32; 3]; 2], orbit: &Orbit, viewport: [u32; 2]) -> Self {
        let [lo, hi] = bounds.map(Vec3::from);
        let center = (lo + hi) * 0.5;
        let radius = ((hi - lo).length() * 0.5).max(1e-6);
        let aspect = viewport[0].max(1) as f32 / viewport[1].max(1) as f32;
        let (azimuth, elevation) = (orbit.azimuth.to_radians(), orbit.elevation.to_radians());
        let towards_eye = Vec3::new(
            elevation.cos() * azimuth.sin(),
            elevation.sin(),
            elevation.cos() * azimuth.cos(),
        );
        let fov_y = orbit.fov_y.to_radians().clamp(1e-3, 3.0);
        let fov_x = 2.0 * ((fov_y * 0.5).tan() * aspect).atan();
        let fit = radius / (fov_y.min(fov_x) * 0.5).sin();
        let distance = orbit
            .distance
            .unwrap_or(fit * 1.02)
            .max(MIN_DISTANCE as f32);
        let eye = center + towards_eye * distance;
        let up = if towards_eye.y.abs() > 0.999 {
            Vec3::Z
        } else {
            Vec3::Y
        };
        let view = look_at_mat4(eye, center, up);
        let (near, far) = (
            (distance - radius * 1.5).max(distance * 1e-3),
            distance + radius * 1.5,
        );
        let projection = if orbit.ortho {
            let half_height = radius * 1.02 * aspect.recip().max(1.0);
            directx::orthographic(
                -half_height * aspect,
                half_height * aspect,
                -half_height,
                half_height,
                distance - radius * 1.5,
                far,
            )
        } else {
            directx::perspective(fov_y, aspect, near, far)
        };
        Self {
            model_view: view,
            projection,
            viewport,
        }
    }
}

/// The widest and tallest frame the front ends render or draw, in pixels.
pub const MAX_VIEWPORT: u32 = 16_384;

/// The nearest an orbit camera may be to the box's centre.
const MIN_DISTANCE: f64 = 1e-6;

crate::schema! {
    /// Where an orbit camera sits around a model's bounding box: the view schema (issue 40), which
    /// `chamfer render`'s and `chamfer draw`'s camera flags, Python's `draw_svg` keywords
    /// (`chamfer.VIEW_SCHEMA`) and the page's view panel are made from. JSON and RON read it with
    /// the same names; unknown keys are refused. [`Orbit::check`] refuses values out of range.
    #[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
    #[serde(default, deny_unknown_fields)]
    pub struct Orbit {
        /// Camera turn around the vertical (+Y) axis, degrees; 0 looks from +Z.
        azimuth: f32 = 35.0, { group: "view", value: "DEG", range: None, example: -50.0,
            conflicts: [], requires: [] },
        /// Camera height above the horizontal plane, degrees (-90 to 90).
        elevation: f32 = 25.0, { group: "view", value: "DEG", range: Some((-90.0, 90.0)),
            example: 60.0, conflicts: [], requires: [] },
        /// Camera distance from the model's centre, mesh units. [default: frame the model]
        distance: Option<f32> = None, { group: "view", value: "DIST",
            range: Some((MIN_DISTANCE, crate::schema::FINITE)), example: Some(4.0),
            conflicts: [], requires: [] },
        /// Vertical field of view of the perspective camera, degrees.
        fov_y: f32 = 35.0, { group: "view", value: "DEG", range: Some((1.0, 170.0)),
            example: 50.0, conflicts: [], requires: [] },
        /// Orthographic camera (parallel projection) instead of perspective; `fov_y` is then
        /// unused.
        ortho: bool = false, { group: "view", value: "", range: None, example: true,
            conflicts: [], requires: [] },
    }
}

impl Orbit {
    /// Refuses numbers that are not finite and values outside their entries' ranges.
    pub fn check(&self) -> Result<(), crate::schema::SchemaError> {
        use crate::schema::Schema;
        self.check_combinations()?;
        self.check_ranges()
    }

    /// This view in a frame of `viewport` pixels as `chamfer render`'s flags, as they would be
    /// typed (a drawing's description quotes them, so the same view can be asked for again).
    pub fn flags(&self, viewport: [u32; 2]) -> String {
        use crate::schema::Schema;
        let mut flags = vec![
            format!("--width {}", viewport[0]),
            format!("--height {}", viewport[1]),
        ];
        flags.extend(self.to_flags());
        flags.join(" ")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eye_is_a_point_for_perspective_and_a_direction_for_orthographic() {
        let bounds = [[-1.0; 3], [1.0; 3]];
        let perspective = Camera::orbit(bounds, &Orbit::default(), [64, 48]);
        let eye = perspective.eye();
        assert!(!perspective.is_orthographic());
        assert!((eye.w - 1.0).abs() < 1e-6);
        // The orbit's eye is at the fitted distance from the box's centre, above and in front.
        assert!(eye.truncate().length() > 3.0 && eye.y > 0.0 && eye.z > 0.0);

        let ortho = Camera::orbit(
            bounds,
            &Orbit {
                ortho: true,
                ..Orbit::default()
            },
            [64, 48],
        );
        let towards = ortho.eye();
        assert!(ortho.is_orthographic());
        assert!(towards.w.abs() < 1e-6);
        let expected = eye.truncate().normalize();
        assert!((towards.truncate().normalize() - expected).length() < 1e-4);
    }

    #[test]
    fn the_box_fits_the_view() {
        let bounds = [[-1.0, -2.0, -0.5], [3.0, 1.0, 0.5]];
        for orthographic in [false, true] {
            for aspect in [[200, 100], [100, 200]] {
                let orbit = Orbit {
                    ortho: orthographic,
                    ..Orbit::default()
                };
                let camera = Camera::orbit(bounds, &orbit, aspect);
                let mvp = camera.view_projection();
                for corner in 0..8 {
                    let p = Vec3::new(
                        bounds[corner & 1][0],
                        bounds[(corner >> 1) & 1][1],
                        bounds[corner >> 2][2],
                    );
                    let c = mvp * p.extend(1.0);
                    let ndc = c.truncate() / c.w;
                    assert!(
                        ndc.x.abs() <= 1.0 && ndc.y.abs() <= 1.0,
                        "{ndc} {orthographic}"
                    );
                    assert!((0.0..=1.0).contains(&ndc.z), "{ndc}");
                }
            }
        }
    }

    #[test]
    fn the_view_schema_checks_its_ranges_and_reads_json() {
        use crate::schema::Schema;
        assert_eq!(Orbit::default().check(), Ok(()));
        for entry in Orbit::ENTRIES {
            let mut orbit = Orbit::default();
            entry.set_example(&mut orbit);
            assert_eq!(orbit.check(), Ok(()), "{}", entry.name);
            assert_ne!(orbit, Orbit::default(), "{}", entry.name);
        }
        for bad in [
            Orbit {
                elevation: 91.0,
                ..Orbit::default()
            },
            Orbit {
                azimuth: f32::INFINITY,
                ..Orbit::default()
            },
            Orbit {
                distance: Some(0.0),
                ..Orbit::default()
            },
            Orbit {
                fov_y: 180.0,
                ..Orbit::default()
            },
        ] {
            assert!(bad.check().is_err(), "{bad:?}");
        }
        let orbit: Orbit =
            serde_json::from_str(r#"{"azimuth": -50, "ortho": true}"#).expect("json");
        assert_eq!(
            (orbit.azimuth, orbit.ortho, orbit.elevation),
            (-50.0, true, 25.0)
        );
        assert!(serde_json::from_str::<Orbit>(r#"{"zoom": 2}"#).is_err());
        assert_eq!(
            Orbit {
                distance: Some(3.0),
                ..Orbit::default()
            }
            .to_flags(),
            [
                "--azimuth 35",
                "--elevation 25",
                "--distance 3",
                "--fov-y 35"
            ]
        );
    }
}
