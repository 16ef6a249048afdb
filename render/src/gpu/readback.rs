//! Copying GPU buffers back to the CPU (images, stats, timestamps, inspector records).

use bytemuck::Pod;

/// Copies `size` bytes of `source` into a fresh mappable buffer, waits, and returns them
/// as `T`s. Blocking: for headless use, tests and one-off inspector reads.
pub fn read_buffer<T: Pod>(
    gpu: &super::Gpu,
    source: &wgpu::Buffer,
    offset: u64,
    size: u64,
) -> Vec<T> {
    if size == 0 {
        return Vec::new();
    }
    let staging = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    encoder.copy_buffer_to_buffer(source, offset, &staging, 0, size);
    gpu.queue.submit([encoder.finish()]);
    map_and_read(gpu, &staging)
}

/// Maps an already-filled MAP_READ buffer and returns its contents.
pub fn map_and_read<T: Pod>(gpu: &super::Gpu, staging: &wgpu::Buffer) -> Vec<T> {
    let (tx, rx) = std::sync::mpsc::channel();
    staging.map_async(wgpu::MapMode::Read, .., move |r| {
        let _ = tx.send(r);
    });
    gpu.wait_idle();
    let mapped = matches!(rx.recv(), Ok(Ok(())));
    if !mapped {
        log::error!("buffer readback failed to map");
        return Vec::new();
    }
    let out = match staging.get_mapped_range(..) {
        Ok(view) => bytemuck::pod_collect_to_vec(&view),
        Err(e) => {
            log::error!("buffer readback failed: {e}");
            Vec::new()
        }
    };
    staging.unmap();
    out
}

/// Reads an RGBA8 texture (rows padded to 256 bytes on the GPU) into tight rows.
pub fn read_rgba8_texture(gpu: &super::Gpu, texture: &wgpu::Texture) -> Vec<u8> {
    let (w, h) = (texture.width(), texture.height());
    let padded =
        (w * 4).div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    let staging = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("texture readback"),
        size: (padded * h) as u64,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    encoder.copy_texture_to_buffer(
        texture.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &staging,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded),
                rows_per_image: Some(h),
            },
        },
        texture.size(),
    );
    gpu.queue.submit([encoder.finish()]);
    let bytes: Vec<u8> = map_and_read(gpu, &staging);
    if bytes.is_empty() {
        return vec![0; (w * h * 4) as usize];
    }
    bytes
        .chunks_exact(padded as usize)
        .flat_map(|row| row[..(w * 4) as usize].iter().copied())
        .collect()
}

const SLOT_FREE: u8 = 0;
const SLOT_COPIED: u8 = 1;
const SLOT_MAPPING: u8 = 2;
const SLOT_READY: u8 = 3;

struct RingSlot {
    buffer: wgpu::Buffer,
    state: std::sync::Arc<std::sync::atomic::AtomicU8>,
    tag: u64,
    len: u64,
}

/// A few mappable buffers used in turn, so per-frame data (stats, timestamps) comes back
/// without the CPU waiting for the GPU. When every slot is in flight (nobody collected for
/// a while) the ring grows, up to `MAX_SLOTS`; only then is a frame's data dropped.
pub struct ReadbackRing {
    slots: Vec<RingSlot>,
    size: u64,
    label: String,
}

const MAX_SLOTS: usize = 64;

impl ReadbackRing {
    pub fn new(device: &wgpu::Device, size: u64, count: usize, label: &str) -> ReadbackRing {
        let mut ring = ReadbackRing {
            slots: Vec::new(),
            size,
            label: label.to_string(),
        };
        for _ in 0..count {
            ring.add_slot(device);
        }
        ring
    }

    fn add_slot(&mut self, device: &wgpu::Device) {
        self.slots.push(RingSlot {
            buffer: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(&self.label),
                size: self.size,
                usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            state: Default::default(),
            tag: 0,
            len: 0,
        });
    }

    /// Records a copy of `len` bytes of `source` into a free slot; false if none is free
    /// and the ring cannot grow any more.
    pub fn copy_from(
        &mut self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        source: &wgpu::Buffer,
        len: u64,
        tag: u64,
    ) -> bool {
        use std::sync::atomic::Ordering;
        let free = self
            .slots
            .iter()
            .position(|s| s.state.load(Ordering::Acquire) == SLOT_FREE);
        let index = match free {
            Some(i) => i,
            None if self.slots.len() < MAX_SLOTS => {
                self.add_slot(device);
                self.slots.len() - 1
            }
            None => return false,
        };
        let slot = &mut self.slots[index];
        encoder.copy_buffer_to_buffer(source, 0, &slot.buffer, 0, len);
        slot.tag = tag;
        slot.len = len;
        slot.state.store(SLOT_COPIED, Ordering::Release);
        true
    }

    /// Starts mapping every slot whose copy has been submitted.
    pub fn after_submit(&mut self) {
        use std::sync::atomic::Ordering;
        for slot in &self.slots {
            if slot.state.load(Ordering::Acquire) != SLOT_COPIED {
                continue;
            }
            slot.state.store(SLOT_MAPPING, Ordering::Release);
            let state = slot.state.clone();
            slot.buffer
                .map_async(wgpu::MapMode::Read, 0..slot.len, move |r| {
                    state.store(
                        if r.is_ok() { SLOT_READY } else { SLOT_FREE },
                        Ordering::Release,
                    );
                });
        }
    }

    /// The data of every slot that has arrived, ordered by tag.
    pub fn collect(&mut self) -> Vec<(u64, Vec<u8>)> {
        use std::sync::atomic::Ordering;
        let mut out = Vec::new();
        for slot in &mut self.slots {
            if slot.state.load(Ordering::Acquire) != SLOT_READY {
                continue;
            }
            if let Ok(view) = slot.buffer.get_mapped_range(0..slot.len) {
                out.push((slot.tag, view.to_vec()));
            }
            slot.buffer.unmap();
            slot.state.store(SLOT_FREE, Ordering::Release);
        }
        out.sort_by_key(|(tag, _)| *tag);
        out
    }

    /// True while some copy has not come back yet.
    pub fn in_flight(&self) -> bool {
        use std::sync::atomic::Ordering;
        self.slots
            .iter()
            .any(|s| matches!(s.state.load(Ordering::Acquire), SLOT_COPIED | SLOT_MAPPING))
    }
}
