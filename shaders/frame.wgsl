// The frame uniform of the passes that draw one instance per uniform block: every technique's, but
// the joined technique's compute passes, which read their batch's block instead (batch.wgsl).

@group(0) @binding(0) var<uniform> frame: Frame;
