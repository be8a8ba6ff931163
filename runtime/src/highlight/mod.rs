//! The chamfer highlight of seed 000 (Hu et al., "Rendering Chamfering Structures of Sharp Edges"):
//! a sharp edge drawn as the thin partial cylinder whose normals sweep from one face's normal to the
//! other's, its Blinn shading integrated over the pixel in closed form (§3.1).
//!
//! - [`table`]: `F(φ, m) = ∫₀^φ cos^m θ dθ`, tabulated per exponent and read with cubic Hermite
//!   interpolation (the derivative, `cos^m φ`, is exact), to within 2e-6 in 1 KiB per exponent.
//! - [`strip`]: the integral of §3.1 over a piece of the arc, the CPU twin of the shader, and a brute-force
//!   reference it is tested against.
//! - [`ggx`]: the same integral under glTF's metallic-roughness shading (GGX, Smith, Schlick, Lambert;
//!   issue 29), by a substitution that makes the GGX lobe smooth and a 16-point rule.
//! - [`environment`]: image-based light, an equirectangular environment prefiltered for one roughness.
//! - `corners`: the rounded corners where chamfer edges of one radius meet (issue 29), found per asset.

// Only the renderer uploads corners: without it (the baker's and Python's build) the module is unused.
#[cfg(any(feature = "render", test))]
pub(crate) mod corners;
pub mod environment;
pub mod ggx;
pub mod strip;
pub mod table;
