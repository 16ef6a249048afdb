//! `KHR_texture_basisu`: a KTX2 image holding Basis Universal data (ETC1S or UASTC LDR)
//! transcoded to 8-bit RGBA by basisu (a pure-Rust, bit-exact port of the reference
//! transcoder). Only the base level is read, like every other image of this loader.
//!
//! The texels come out as they were encoded, in the colour space the file declares: sRGB for
//! base colour and emissive images, linear for metallic-roughness (KHR_texture_basisu asks
//! exactly that of files), the same bytes a PNG of the image would hold. The renderer then
//! decodes them per slot as it does PNG and JPEG texels.

use std::panic::{AssertUnwindSafe, catch_unwind};

use basisu::{DecodeFlags, SourceFormat, TargetFormat, Transcoder};
use image::RgbaImage;

/// The KTX2 file identifier («KTX 20»\r\n\x1A\n).
const IDENTIFIER: [u8; 12] = [
    0xAB, b'K', b'T', b'X', b' ', b'2', b'0', 0xBB, b'\r', b'\n', 0x1A, b'\n',
];

/// The largest image transcoded (texels): what the `image` crate's default allocation limit
/// (512 MiB) allows a PNG. A corrupt header must not make the transcoder allocate more.
const MAX_TEXELS: u64 = 1 << 27;

pub(super) fn is_ktx2(bytes: &[u8]) -> bool {
    bytes.starts_with(&IDENTIFIER)
}

/// The base level as RGBA8. The error is one line for `SceneError::Image`.
pub(super) fn decode(bytes: &[u8]) -> Result<RgbaImage, String> {
    match catch_unwind(AssertUnwindSafe(|| transcode(bytes))) {
        Ok(result) => result,
        Err(_) => Err("the Basis Universal transcoder crashed on this file".to_string()),
    }
}

fn transcode(bytes: &[u8]) -> Result<RgbaImage, String> {
    check_header(bytes)?;
    let transcoder = Transcoder::new(bytes)
        .map_err(|e| format!("not a readable Basis Universal KTX2 file ({e:?})"))?;
    let source = transcoder.source_format();
    if !matches!(source, SourceFormat::Etc1s | SourceFormat::UastcLdr) {
        // HDR and ASTC sources are not part of KHR_texture_basisu (nor 8-bit).
        return Err(format!(
            "its {source:?} data is not ETC1S or UASTC LDR, the two KHR_texture_basisu allows"
        ));
    }
    let level = transcoder
        .image_level_info(0)
        .map_err(|e| format!("no base level ({e:?})"))?;
    let (width, height) = (level.width, level.height);
    if width == 0 || height == 0 || width as u64 * height as u64 > MAX_TEXELS {
        return Err(format!(
            "its base level is {width}×{height}, outside 1 to {MAX_TEXELS} texels"
        ));
    }
    let rgba = transcoder
        .transcode(0, TargetFormat::Rgba32, DecodeFlags::NONE)
        .map_err(|e| format!("{source:?} data does not transcode ({e:?})"))?;
    RgbaImage::from_raw(width, height, rgba).ok_or_else(|| {
        format!("the transcoder returned the wrong number of bytes for {width}×{height}")
    })
}

/// The header's sizes checked before the transcoder trusts them: a flipped bit in a level's
/// `uncompressedByteLength` would otherwise have it allocate up to 2^64 bytes for the
/// Zstandard output (an allocation failure aborts the process; nothing can catch it).
fn check_header(bytes: &[u8]) -> Result<(), String> {
    let at = |offset: usize, width: usize| -> Result<u64, String> {
        let field = bytes
            .get(offset..offset + width)
            .ok_or_else(|| format!("the header is cut short ({} bytes)", bytes.len()))?;
        Ok(field.iter().rev().fold(0u64, |n, &b| n << 8 | b as u64))
    };
    let (width, height) = (at(20, 4)?, at(24, 4)?);
    let (layers, faces, levels) = (at(32, 4)?, at(36, 4)?, at(40, 4)?.max(1));
    if width == 0 || height == 0 || width * height > MAX_TEXELS {
        return Err(format!(
            "its base level is {width}×{height}, outside 1 to {MAX_TEXELS} texels"
        ));
    }
    if layers > 1 || faces != 1 || levels > 32 {
        return Err(format!(
            "{layers} layers, {faces} faces, {levels} levels: a glTF texture is one 2D image"
        ));
    }
    // A level holds at most 16 bytes per 4×4 block of the base level (UASTC's rate; ETC1S
    // is smaller), compressed or not.
    let most = width.div_ceil(4) * height.div_ceil(4) * 16;
    let file = bytes.len() as u64;
    for level in 0..levels as usize {
        let entry = 80 + 24 * level;
        let (offset, length, uncompressed) = (at(entry, 8)?, at(entry + 8, 8)?, at(entry + 16, 8)?);
        if offset.checked_add(length).is_none_or(|end| end > file) || uncompressed > most {
            return Err(format!(
                "level {level} claims bytes {offset}..+{length} of {file} and {uncompressed} \
                 bytes uncompressed (at most {most})"
            ));
        }
    }
    Ok(())
}
