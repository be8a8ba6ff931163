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
        let (azimuth, elevation) = (
            orbit.azimuth_deg.to_radians(),
            orbit.elevation_deg.to_radians(),
        );
        let towards_eye = Vec3::new(
            elevation.cos() * azimuth.sin(),
            elevation.sin(),
            elevation.cos() * azimuth.cos(),
        );
        let fov_y = orbit.fov_y_deg.to_radians().clamp(1e-3, 3.0);
        let fov_x = 2.0 * ((fov_y * 0.5).tan() * aspect).atan();
        let fit = radius / (fov_y.min(fov_x) * 0.5).sin();
        let distance = orbit.distance.unwrap_or(fit * 1.02).max(1e-6);
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
        let projection = if orbit.orthographic {
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

/// Where an orbit camera sits around a model's bounding box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Orbit {
    /// Turn around the vertical (+Y) axis, degrees; 0 looks from +Z.
    pub azimuth_deg: f32,
    /// Height above the horizontal plane, degrees.
    pub elevation_deg: f32,
    /// Distance from the box's centre; `None` fits the box's bounding sphere in view.
    pub distance: Option<f32>,
    /// Orthographic instead of perspective.
    pub orthographic: bool,
    /// Vertical field of view of the perspective camera, degrees.
    pub fov_y_deg: f32,
}

impl Default for Orbit {
    fn default() -> Self {
        Self {
            azimuth_deg: 35.0,
            elevation_deg: 25.0,
            distance: None,
            orthographic: false,
            fov_y_deg: 35.0,
        }
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
                orthographic: true,
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
                    orthographic,
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
}
