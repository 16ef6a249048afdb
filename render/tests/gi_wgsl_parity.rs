//! The WGSL GI library (shaders/gi/reservoir.wgsl) computes what its Rust mirror
//! (render/src/gi/model.rs and model/jacobian.rs) computes, so the Rust statistical tests vouch
//! for the shader: a compute kernel evaluates the Jacobian, the shift's rejection bits, the
//! target and a small 1/M merge for random and singular configurations, and the results are
//! compared with the Rust functions'. Runs on any adapter (lavapipe here).

use crate::common;

use std::collections::BTreeSet;

use bytemuck::{Pod, Zeroable};
use glam::Vec3;
use restir_render::gi::model::jacobian::reconnection_shift;
use restir_render::gi::model::*;
use restir_render::gpu::readback::read_buffer;
use restir_render::shader_source::compose;
use wgpu::util::DeviceExt;

/// One configuration: the sample point and normal, the receiver that found it, the receiver
/// it is reused at, and the Jacobian window.
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct Case {
    sample_position: [f32; 3],
    j_max: f32,
    sample_normal: [f32; 3],
    _p0: f32,
    seen_from: [f32; 3],
    _p1: f32,
    reused_at: [f32; 3],
    _p2: f32,
}

/// What the kernel writes per case.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
struct Outcome {
    jacobian: f32,
    rejection: u32,
    p_hat: f32,
    weight: f32,
    m: f32,
    picked_other: u32,
    _pad: [u32; 2],
}

const KERNEL: &str = r#"
struct Case {
    sample_position: vec3<f32>,
    j_max: f32,
    sample_normal: vec3<f32>,
    _p0: f32,
    seen_from: vec3<f32>,
    _p1: f32,
    reused_at: vec3<f32>,
    _p2: f32,
}

struct Outcome {
    jacobian: f32,
    rejection: u32,
    p_hat: f32,
    weight: f32,
    m: f32,
    picked_other: u32,
    _pad0: u32,
    _pad1: u32,
}

@group(0) @binding(0) var<storage, read> cases: array<Case>;
@group(0) @binding(1) var<storage, read_write> outcomes: array<Outcome>;

const RECEIVER_NORMAL: vec3<f32> = vec3<f32>(0.0, 0.0, 1.0);
const BRDF: vec3<f32> = vec3<f32>(0.3, 0.25, 0.2);
const RADIANCE: vec3<f32> = vec3<f32>(1.0, 0.5, 0.25);

@compute @workgroup_size(64)
fn parity(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= arrayLength(&cases) {
        return;
    }
    let c = cases[id.x];
    let j = gi_reconnection_jacobian(c.sample_position, c.sample_normal, c.seen_from, c.reused_at);
    let rejection = gi_shift_rejection(j, c.j_max);
    let usable = select(0.0, j, rejection == 0u);
    let cos_here = gi_receiver_cosine(c.reused_at, RECEIVER_NORMAL, c.sample_position);
    let target_here = select(0.0, gi_target(BRDF, RADIANCE, cos_here), rejection == 0u);
    // Canonical: one candidate (w 0.7, p̂ 0.5). Other: one candidate (w 1.3, p̂ 0.8), M = 2.
    var canonical = gi_reservoir_empty();
    gi_reservoir_update(&canonical, c.reused_at, 0u, RADIANCE, 0.7, 0.5, gi_pack(SOURCE_INITIAL, 0u, 0u), 0.3);
    gi_reservoir_finalize(&canonical, 1.0);
    canonical.m = 1.0;
    var other = gi_reservoir_empty();
    gi_reservoir_update(&other, c.sample_position, 1u, RADIANCE, 1.3, 0.8, gi_pack(SOURCE_INITIAL, 0u, 0u), 0.6);
    gi_reservoir_finalize(&other, 1.0);
    other.m = 2.0;
    var s = gi_reservoir_empty();
    gi_reservoir_merge(&s, canonical, 0.5, 1.0, canonical.m, canonical.packed, 0.4);
    gi_reservoir_merge(&s, other, target_here, usable, other.m, gi_pack(SOURCE_SPATIAL, 0u, 0u), 0.9);
    gi_reservoir_finalize(&s, s.m);
    outcomes[id.x] = Outcome(j, rejection, target_here, s.weight, s.m, s.normal, 0u, 0u);
}
"#;

fn cases() -> Vec<Case> {
    let mut out = Vec::new();
    let mut push = |xs: Vec3, n: Vec3, from: Vec3, to: Vec3, j_max: f32| {
        out.push(Case {
            sample_position: xs.into(),
            j_max,
            sample_normal: n.into(),
            seen_from: from.into(),
            reused_at: to.into(),
            ..Zeroable::zeroed()
        })
    };
    // Random configurations, valid and not (receivers on both sides, all distances).
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut u = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 40) as f32 / (1u64 << 24) as f32
    };
    let mut v = |scale: f32| Vec3::new(u() - 0.5, u() - 0.5, u() - 0.5) * 2.0 * scale;
    for _ in 0..2000 {
        let xs = v(3.0);
        let n = v(1.0);
        let (from, to) = (xs + v(2.0), xs + v(2.0));
        push(xs, n, from, to, 1.0 + 20.0 * (v(0.5).x + 0.5));
    }
    // The singular ones: distance 0 at either end, grazing, back face, degenerate normal.
    let (xs, n, q) = (Vec3::ZERO, Vec3::Z, Vec3::new(0.2, 0.1, 1.0));
    for (from, to, normal) in [
        (q, xs, n),
        (xs, q, n),
        (Vec3::X, q, n),
        (q, Vec3::new(0.0, 3.0, 0.0), n),
        (q, Vec3::new(0.0, 0.0, -1.0), n),
        (q, q, Vec3::ZERO),
        (q, Vec3::new(0.0, 0.0, 4.0), n),
        (q, q * 1.01, -n),
    ] {
        push(xs, normal, from, to, 10.0);
    }
    out
}

/// The Rust side of the kernel, step for step.
fn expected(c: &Case) -> Outcome {
    let v = |a: [f32; 3]| Vec3::from(a);
    let (xs, n, from, to) = (
        v(c.sample_position),
        v(c.sample_normal),
        v(c.seen_from),
        v(c.reused_at),
    );
    let shift = reconnection_shift(xs, n, from, to, c.j_max);
    let jacobian =
        restir_render::gi::model::jacobian::reconnection_jacobian(xs, n, from, to).unwrap_or(0.0);
    let rejection = shift.err().unwrap_or(0);
    let usable = shift.unwrap_or(0.0);
    let radiance = Vec3::new(1.0, 0.5, 0.25);
    let cos_here = receiver_cosine(to, Vec3::Z, xs);
    let target_here = if rejection == 0 {
        gi_target(Vec3::new(0.3, 0.25, 0.2), radiance, cos_here)
    } else {
        0.0
    };
    let sample = |position: Vec3| GiSample {
        position,
        normal: Vec3::Z,
        radiance,
        source_pdf: 1.0,
        age: 0,
    };
    let mut canonical = GiReservoir::empty();
    canonical.update(sample(to), 0.7, 0.5, 0.3);
    canonical.finalize(1.0);
    canonical.m = 1.0;
    let mut other = GiReservoir::empty();
    other.update(sample(xs), 1.3, 0.8, 0.6);
    other.finalize(1.0);
    other.m = 2.0;
    let mut s = GiReservoir::empty();
    gi_merge(&mut s, &canonical, 0.5, 1.0, canonical.m, 0.4);
    let picked_other = gi_merge(&mut s, &other, target_here, usable, other.m, 0.9);
    s.finalize(s.m);
    Outcome {
        jacobian,
        rejection,
        p_hat: target_here,
        weight: s.weight,
        m: s.m,
        picked_other: picked_other as u32,
        _pad: [0; 2],
    }
}

fn close(a: f32, b: f32) -> bool {
    // Both sides are f32 with the same operations; the shader's inverseSqrt and fused
    // multiply-adds may round differently, by a few ulps per step.
    (a - b).abs() <= 1e-5 * a.abs().max(b.abs()) + 1e-30
}

#[test]
fn wgsl_gi_library_matches_the_rust_mirror() {
    let gpu = common::gpu();
    let mut source = compose("gi/reservoir.wgsl", &BTreeSet::new()).unwrap();
    source.push_str(KERNEL);
    let module = gpu
        .device
        .create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("gi parity"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
    let pipeline = gpu
        .device
        .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("gi parity"),
            layout: None,
            module: &module,
            entry_point: Some("parity"),
            compilation_options: Default::default(),
            cache: None,
        });
    let cases = cases();
    let input = gpu
        .device
        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("cases"),
            contents: bytemuck::cast_slice(&cases),
            usage: wgpu::BufferUsages::STORAGE,
        });
    let size = (cases.len() * std::mem::size_of::<Outcome>()) as u64;
    let output = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("outcomes"),
        size,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let bind_group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &pipeline.get_bind_group_layout(0),
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: input.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: output.as_entire_binding(),
            },
        ],
    });
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_compute_pass(&Default::default());
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.dispatch_workgroups((cases.len() as u32).div_ceil(64), 1, 1);
    }
    gpu.queue.submit([encoder.finish()]);
    let got: Vec<Outcome> = read_buffer(&gpu, &output, 0, size);
    if let Some(e) = gpu.take_error() {
        panic!("GPU error: {e}");
    }
    let (mut valid, mut rejected) = (0, 0);
    for (i, (c, g)) in cases.iter().zip(&got).enumerate() {
        let e = expected(c);
        let what = format!("case {i}: GPU {g:?}, Rust {e:?}");
        assert!(close(g.jacobian, e.jacobian), "{what}");
        assert_eq!(g.rejection, e.rejection, "{what}");
        assert!(close(g.p_hat, e.p_hat), "{what}");
        assert!(close(g.weight, e.weight) && g.m == e.m, "{what}");
        assert_eq!(g.picked_other, e.picked_other, "{what}");
        if e.rejection == 0 {
            valid += 1
        } else {
            rejected += 1
        }
    }
    // Both branches must be exercised for the comparison to mean anything.
    assert!(
        valid > 300 && rejected > 300,
        "{valid} valid, {rejected} rejected"
    );
}
