//! The fixed cost of a compute dispatch on this adapter: frames of 1, 10 and 100 dispatches of one
//! empty workgroup each in one compute pass, timed from encoding to the GPU finishing (medians). What
//! a technique pays per dispatch before any work (BENCHMARKS.md "Scenes in batches (issue 28)").
//!
//! ```text
//! cargo run --release -p chamfer-preprocess --example bench_dispatch -- [--frames 21]
//! ```

use std::time::Instant;

use chamfer_runtime::render::Offscreen;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut frames = 21;
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--frames" => frames = args.next().ok_or("--frames needs a number")?.parse()?,
            other => return Err(format!("unknown argument {other}").into()),
        }
    }
    let gpu = Offscreen::new()?;
    let module = gpu
        .device
        .create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("empty"),
            source: wgpu::ShaderSource::Wgsl(
                "@group(0) @binding(0) var<storage, read_write> sink: array<u32>;\n\
                 @compute @workgroup_size(64) fn main(@builtin(global_invocation_id) id: vec3<u32>) {\n\
                 if id.x == 0u { sink[0] = sink[0] + 1u; } }"
                    .into(),
            ),
        });
    let pipeline = gpu
        .device
        .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("empty"),
            layout: None,
            module: &module,
            entry_point: Some("main"),
            compilation_options: Default::default(),
            cache: None,
        });
    let sink = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("sink"),
        size: 16,
        usage: wgpu::BufferUsages::STORAGE,
        mapped_at_creation: false,
    });
    let group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("sink"),
        layout: &pipeline.get_bind_group_layout(0),
        entries: &[wgpu::BindGroupEntry {
            binding: 0,
            resource: sink.as_entire_binding(),
        }],
    });
    println!(
        "adapter: {} ({:?}), {frames} frames (medians)\n",
        gpu.info.name, gpu.info.backend
    );
    println!("| dispatches in one pass | frame ms | per dispatch ms |");
    println!("|---:|---:|---:|");
    let mut base = 0.0;
    for count in [0u32, 1, 10, 100] {
        let mut times = Vec::new();
        for round in 0..frames + 2 {
            let start = Instant::now();
            let mut encoder = gpu.encoder();
            {
                let mut pass = encoder.begin_compute_pass(&Default::default());
                pass.set_pipeline(&pipeline);
                pass.set_bind_group(0, &group, &[]);
                for _ in 0..count {
                    pass.dispatch_workgroups(1, 1, 1);
                }
            }
            gpu.submit(encoder)?;
            if round >= 2 {
                times.push(start.elapsed().as_secs_f64() * 1e3);
            }
        }
        times.sort_by(f64::total_cmp);
        let median = times[times.len() / 2];
        if count == 0 {
            base = median;
        }
        let per = if count == 0 {
            String::from("—")
        } else {
            format!("{:.3}", (median - base) / f64::from(count))
        };
        println!("| {count} | {median:.3} | {per} |");
    }
    Ok(())
}
