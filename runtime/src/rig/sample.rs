//! Sampling an animation channel at a time (glTF 2.0 §3.11.4 and Appendix C): step, linear
//! (spherical for rotations) and cubic Hermite splines. Before the first key a channel holds the
//! first value, after the last the last one.

use super::{Channel, Interpolation, Target};

/// Checks one channel's keys: at least one, finite, strictly increasing times, and `stride`
/// finite numbers per key.
pub(super) fn check_keys(times: &[f32], values: &[f32], stride: usize) -> Result<(), String> {
    if times.is_empty() {
        return Err("has no keys".into());
    }
    if let Some(k) = times.iter().position(|t| !t.is_finite()) {
        return Err(format!("key {k}'s time is not a finite number"));
    }
    if let Some(k) = times.windows(2).position(|w| w[1] <= w[0]) {
        return Err(format!(
            "key times are not increasing: key {} at {} s follows {} s",
            k + 1,
            times[k + 1],
            times[k]
        ));
    }
    if (values.len() as u64) != times.len() as u64 * stride as u64 {
        return Err(format!(
            "{} values for {} keys of {stride} numbers",
            values.len(),
            times.len()
        ));
    }
    if let Some(v) = values.iter().position(|x| !x.is_finite()) {
        return Err(format!("value {v} is not a finite number"));
    }
    Ok(())
}

/// The channel's value at `time` into `out` (`target.components()` numbers); rotations come out
/// as unit quaternions.
///
/// Contract: the channel passed [`Rig::validate`](super::Rig::validate) (keys increasing, values
/// filling them); `out` has `components` numbers.
pub fn sample(channel: &Channel, time: f32, out: &mut [f32]) {
    let times = &channel.times;
    let value = |key: usize| key_value(channel, key, 1);
    let last = times.len() - 1;
    // The first key after `time`: keys `next - 1` and `next` bracket it.
    let next = times.partition_point(|&t| t <= time);
    let rotation = matches!(channel.target, Target::Rotation(_));
    if next == 0 || next > last {
        out.copy_from_slice(value(if next == 0 { 0 } else { last }));
    } else {
        between(channel, next, time, out);
    }
    if rotation {
        let q = glam::Quat::from_slice(out).normalize();
        out.copy_from_slice(&q.to_array());
    }
}

/// Part `part` of key `key`'s values: for a cubic spline 0 is the in-tangent, 1 the value and 2
/// the out-tangent; other channels hold only the value (asked for as part 1).
fn key_value(channel: &Channel, key: usize, part: usize) -> &[f32] {
    let n = channel.target.components();
    let at = match channel.interpolation {
        Interpolation::CubicSpline => (3 * key + part) * n,
        _ => key * n,
    };
    &channel.values[at..at + n]
}

/// The value between keys `next - 1` and `next`.
fn between(channel: &Channel, next: usize, time: f32, out: &mut [f32]) {
    let times = &channel.times;
    let value = |key: usize| key_value(channel, key, 1);
    let (k, t0, t1) = (next - 1, times[next - 1], times[next]);
    let dt = t1 - t0;
    let s = ((time - t0) / dt).clamp(0.0, 1.0);
    match channel.interpolation {
        Interpolation::Step => out.copy_from_slice(value(k)),
        Interpolation::Linear if matches!(channel.target, Target::Rotation(_)) => {
            let q = |v: &[f32]| glam::Quat::from_slice(v).normalize();
            out.copy_from_slice(&q(value(k)).slerp(q(value(k + 1)), s).to_array());
        }
        Interpolation::Linear => {
            for ((o, a), b) in out.iter_mut().zip(value(k)).zip(value(k + 1)) {
                *o = a + (b - a) * s;
            }
        }
        Interpolation::CubicSpline => {
            let (out_tangent, in_tangent) = (key_value(channel, k, 2), key_value(channel, next, 0));
            let (s2, s3) = (s * s, s * s * s);
            let (h00, h10) = (2.0 * s3 - 3.0 * s2 + 1.0, s3 - 2.0 * s2 + s);
            let (h01, h11) = (-2.0 * s3 + 3.0 * s2, s3 - s2);
            for (i, o) in out.iter_mut().enumerate() {
                *o = h00 * value(k)[i]
                    + h10 * dt * out_tangent[i]
                    + h01 * value(k + 1)[i]
                    + h11 * dt * in_tangent[i];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn channel(
        target: Target,
        interpolation: Interpolation,
        times: &[f32],
        values: &[f32],
    ) -> Channel {
        Channel {
            target,
            interpolation,
            times: times.to_vec(),
            values: values.to_vec(),
        }
    }

    fn at(channel: &Channel, time: f32) -> Vec<f32> {
        let mut out = vec![0.0; channel.target.components()];
        sample(channel, time, &mut out);
        out
    }

    #[test]
    fn linear_step_and_clamping() {
        let c = channel(
            Target::Translation(0),
            Interpolation::Linear,
            &[1.0, 3.0],
            &[0.0, 0.0, 0.0, 2.0, 4.0, 6.0],
        );
        assert_eq!(at(&c, 2.0), [1.0, 2.0, 3.0]);
        assert_eq!(at(&c, 0.0), [0.0, 0.0, 0.0]);
        assert_eq!(at(&c, 9.0), [2.0, 4.0, 6.0]);
        let step = Channel {
            interpolation: Interpolation::Step,
            ..c
        };
        assert_eq!(at(&step, 2.9), [0.0, 0.0, 0.0]);
        assert_eq!(at(&step, 3.0), [2.0, 4.0, 6.0]);
    }

    #[test]
    fn rotations_are_spherical() {
        let half = std::f32::consts::FRAC_1_SQRT_2;
        let c = channel(
            Target::Rotation(0),
            Interpolation::Linear,
            &[0.0, 1.0],
            &[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, half, half],
        );
        // Halfway between 0° and 90° about z is 45°, a unit quaternion (a plain lerp is not).
        let q = glam::Quat::from_slice(&at(&c, 0.5));
        let expected = glam::Quat::from_rotation_z(std::f32::consts::FRAC_PI_4);
        assert!(q.angle_between(expected) < 1e-5, "{q:?}");
    }

    #[test]
    fn cubic_splines_pass_through_keys_and_follow_tangents() {
        // One component: value 0 → 1 over 2 s, tangents 0 at the first key's out and 3 at the
        // second key's in (per second). Hermite: p(s) = h01 + h11·dt·3.
        let c = channel(
            Target::Weights { first: 0, count: 1 },
            Interpolation::CubicSpline,
            &[0.0, 2.0],
            &[9.0, 0.0, 0.0, 3.0, 1.0, 9.0],
        );
        assert_eq!(at(&c, 0.0), [0.0]);
        assert_eq!(at(&c, 2.0), [1.0]);
        let s = 0.5f32;
        let expected = (-2.0 * s.powi(3) + 3.0 * s * s) + (s.powi(3) - s * s) * 2.0 * 3.0;
        assert!((at(&c, 1.0)[0] - expected).abs() < 1e-6);
    }

    #[test]
    fn bad_keys_are_named() {
        for (times, values, expected) in [
            (&[0.0, 0.0][..], &[1.0, 2.0][..], "not increasing"),
            (&[0.0][..], &[1.0, 2.0][..], "2 values"),
            (&[][..], &[][..], "no keys"),
            (&[f32::NAN][..], &[1.0][..], "finite"),
        ] {
            let error = check_keys(times, values, 1).expect_err(expected);
            assert!(error.contains(expected), "{expected}: {error}");
        }
    }
}
