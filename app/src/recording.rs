//! Recordings (docs/src/viewer.md, "Recordings"): every frame as a PNG (what the display shows: the
//! tonemapped image or the debug view) or an EXR (the linear radiance), and an animated GIF of what
//! the display shows. `render --out-sequence DIR --gif FILE.gif` and the viewer's Record toggle
//! write the same files: `DIR/frame-00000.png` (or `.exr`), one per frame.

use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

use anyhow::{Context, bail};
use image::codecs::gif::{GifEncoder, Repeat};
use image::{Delay, Frame, RgbaImage};
use restir_render::LinearImage;

/// What each frame of a sequence is written as.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SequenceFormat {
    /// What the display shows, sRGB RGBA8.
    Png,
    /// The linear radiance, untonemapped.
    Exr,
}

impl SequenceFormat {
    pub fn parse(text: &str) -> anyhow::Result<SequenceFormat> {
        match text {
            "png" => Ok(SequenceFormat::Png),
            "exr" => Ok(SequenceFormat::Exr),
            _ => bail!("--sequence-format '{text}': expected png or exr"),
        }
    }

    fn extension(self) -> &'static str {
        match self {
            SequenceFormat::Png => "png",
            SequenceFormat::Exr => "exr",
        }
    }
}

/// Where a recording goes.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RecordingPlan {
    pub sequence: Option<(PathBuf, SequenceFormat)>,
    pub gif: Option<PathBuf>,
    /// Frames per second of the GIF's playback.
    pub fps: f32,
}

/// One frame as the recorder takes it: the display's pixels and/or the linear image.
pub struct RecordedFrame<'a> {
    pub width: u32,
    pub height: u32,
    /// sRGB RGBA8, what the display shows (needed for PNG sequences and the GIF).
    pub rgba: Option<&'a [u8]>,
    /// Linear radiance (needed for EXR sequences).
    pub linear: Option<&'a LinearImage>,
}

/// A recording in progress.
pub struct Recorder {
    sequence: Option<(PathBuf, SequenceFormat)>,
    gif: Option<(PathBuf, GifEncoder<BufWriter<File>>)>,
    delay: Delay,
    size: Option<(u32, u32)>,
    frames: u32,
}

/// The file of frame `index` of a sequence in `dir`.
pub fn frame_path(dir: &Path, index: u32, format: SequenceFormat) -> PathBuf {
    dir.join(format!("frame-{index:05}.{}", format.extension()))
}

impl Recorder {
    /// Creates the folder and the GIF file (one-line errors naming them).
    pub fn start(plan: &RecordingPlan) -> anyhow::Result<Recorder> {
        if let Some((dir, _)) = &plan.sequence {
            std::fs::create_dir_all(dir)
                .with_context(|| format!("--out-sequence {}: cannot create", dir.display()))?;
            // A folder that exists but cannot be written fails here, not after the frames.
            let probe = dir.join(".restir-write-test");
            std::fs::write(&probe, b"")
                .with_context(|| format!("--out-sequence {}: cannot write there", dir.display()))?;
            let _ = std::fs::remove_file(probe);
        }
        let gif = match &plan.gif {
            None => None,
            Some(path) => {
                if !path
                    .extension()
                    .is_some_and(|e| e.eq_ignore_ascii_case("gif"))
                {
                    bail!("--gif '{}': expected a .gif file", path.display());
                }
                let file = File::create(path)
                    .with_context(|| format!("--gif {}: cannot create", path.display()))?;
                // Speed 10 of 1..=30: NeuQuant on a tenth of the pixels, a good palette
                // for a few hundred frames of a small image in seconds, not minutes.
                let mut encoder = GifEncoder::new_with_speed(BufWriter::new(file), 10);
                encoder.set_repeat(Repeat::Infinite)?;
                Some((path.clone(), encoder))
            }
        };
        let fps = if plan.fps.is_finite() && plan.fps > 0.0 {
            plan.fps
        } else {
            30.0
        };
        Ok(Recorder {
            sequence: plan.sequence.clone(),
            gif,
            delay: Delay::from_numer_denom_ms(1000, fps.round().max(1.0) as u32),
            size: None,
            frames: 0,
        })
    }

    /// Whether frames must come with the display's pixels.
    pub fn wants_display(&self) -> bool {
        self.gif.is_some() || matches!(self.sequence, Some((_, SequenceFormat::Png)))
    }

    /// Whether frames must come with the linear image.
    pub fn wants_linear(&self) -> bool {
        matches!(self.sequence, Some((_, SequenceFormat::Exr)))
    }

    pub fn frames(&self) -> u32 {
        self.frames
    }

    /// Writes one frame (every frame of a recording has the first one's size).
    pub fn push(&mut self, frame: &RecordedFrame) -> anyhow::Result<()> {
        let size = (frame.width, frame.height);
        if *self.size.get_or_insert(size) != size {
            bail!(
                "recording: frame {} is {}x{}, the first was {}x{} (a recording keeps one size)",
                self.frames,
                size.0,
                size.1,
                self.size.unwrap().0,
                self.size.unwrap().1
            );
        }
        let rgba = || {
            frame
                .rgba
                .context("recording: the frame has no display pixels")
        };
        if let Some((dir, format)) = &self.sequence {
            let path = frame_path(dir, self.frames, *format);
            match format {
                SequenceFormat::Png => {
                    restir_render::image::save_png_rgba8(&path, size.0, size.1, rgba()?)?
                }
                SequenceFormat::Exr => frame
                    .linear
                    .context("recording: the frame has no linear image")?
                    .save_exr(&path)?,
            }
        }
        if let Some((path, encoder)) = &mut self.gif {
            let image = RgbaImage::from_raw(size.0, size.1, rgba()?.to_vec())
                .context("recording: the display pixels do not fill the frame")?;
            encoder
                .encode_frame(Frame::from_parts(image, 0, 0, self.delay))
                .with_context(|| format!("--gif {}: cannot write", path.display()))?;
        }
        self.frames += 1;
        Ok(())
    }

    /// Closes the files; returns what was written, for a message.
    pub fn finish(self) -> anyhow::Result<String> {
        let mut written = Vec::new();
        if let Some((dir, format)) = &self.sequence {
            written.push(format!(
                "{} {} frames in {}",
                self.frames,
                format.extension(),
                dir.display()
            ));
        }
        if let Some((path, encoder)) = self.gif {
            // The encoder writes the trailer when it is dropped; flush its buffer first.
            drop(encoder);
            written.push(format!("{} ({} frames)", path.display(), self.frames));
        }
        Ok(written.join(", "))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::AnimationDecoder;
    use image::codecs::gif::GifDecoder;

    #[test]
    fn a_gif_decodes_to_its_frames_and_a_sequence_has_one_file_per_frame() {
        let dir = std::env::temp_dir().join(format!("restir-recording-{}", std::process::id()));
        let gif = dir.join("clip.gif");
        std::fs::create_dir_all(&dir).unwrap();
        let plan = RecordingPlan {
            sequence: Some((dir.join("frames"), SequenceFormat::Png)),
            gif: Some(gif.clone()),
            fps: 30.0,
        };
        let mut r = Recorder::start(&plan).unwrap();
        assert!(r.wants_display() && !r.wants_linear());
        for i in 0..5u8 {
            let rgba: Vec<u8> = (0..6 * 4)
                .flat_map(|_| [i * 50, 0, 255 - i * 50, 255])
                .collect();
            r.push(&RecordedFrame {
                width: 6,
                height: 4,
                rgba: Some(&rgba),
                linear: None,
            })
            .unwrap();
        }
        let bad = [0u8; 8];
        assert!(
            r.push(&RecordedFrame {
                width: 2,
                height: 1,
                rgba: Some(&bad),
                linear: None
            })
            .is_err()
        );
        r.finish().unwrap();
        let decoder = GifDecoder::new(std::io::BufReader::new(File::open(&gif).unwrap())).unwrap();
        let frames = decoder.into_frames().collect_frames().unwrap();
        assert_eq!(frames.len(), 5);
        assert!(frames.iter().all(|f| f.buffer().dimensions() == (6, 4)));
        // The last frame is blue-ish red: 200, 0, 55 (a palette of 256 keeps flat colours).
        let p = frames[4].buffer().get_pixel(1, 1).0;
        assert!(p[0] > 180 && p[2] < 80, "{p:?}");
        assert!(frame_path(&dir.join("frames"), 4, SequenceFormat::Png).is_file());
        assert!(!frame_path(&dir.join("frames"), 5, SequenceFormat::Png).exists());
    }

    #[test]
    fn bad_destinations_are_one_line_errors() {
        let plan = RecordingPlan {
            gif: Some(PathBuf::from("clip.png")),
            ..Default::default()
        };
        let e = Recorder::start(&plan).err().unwrap().to_string();
        assert!(e.contains("--gif 'clip.png': expected a .gif file"), "{e}");
        let blocker = std::env::temp_dir().join(format!("restir-blocker-{}", std::process::id()));
        std::fs::write(&blocker, b"a file").unwrap();
        let plan = RecordingPlan {
            sequence: Some((blocker.join("frames"), SequenceFormat::Exr)),
            ..Default::default()
        };
        let e = format!("{:#}", Recorder::start(&plan).err().unwrap());
        assert!(
            e.contains("--out-sequence") && e.contains("cannot create"),
            "{e}"
        );
        assert!(SequenceFormat::parse("tiff").is_err());
    }
}
