//! Lecture 3's height maps: any greyscale PNG loads, and every bad input (missing file, not
//! an image, a 1x1 map, a map beyond the texture limit, NaN heights) is a clear error naming
//! the input and the problem.

use classic_gpgpu::lecture3::HeightMap;
use std::path::{Path, PathBuf};

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("lecture3-height-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// CRC-32 (the PNG chunk checksum), bit by bit.
fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = 0xffff_ffffu32;
    for &b in bytes {
        crc ^= b as u32;
        for _ in 0..8 {
            crc = if crc & 1 != 0 {
                (crc >> 1) ^ 0xedb8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

/// A PNG that declares `w x h` 8-bit grey pixels in its header and holds no pixel data.
fn png_header_only(w: u32, h: u32) -> Vec<u8> {
    let mut header = w.to_be_bytes().to_vec();
    header.extend_from_slice(&h.to_be_bytes());
    header.extend_from_slice(&[8, 0, 0, 0, 0]);
    let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
    for (kind, data) in [(b"IHDR", &header[..]), (b"IDAT", &[]), (b"IEND", &[])] {
        let mut chunk = kind.to_vec();
        chunk.extend_from_slice(data);
        png.extend_from_slice(&(data.len() as u32).to_be_bytes());
        png.extend_from_slice(&chunk);
        png.extend_from_slice(&crc32(&chunk).to_be_bytes());
    }
    png
}

fn load_error(path: &Path, max_side: u32) -> String {
    HeightMap::load(path, max_side).unwrap_err().to_string()
}

#[test]
fn greyscale_and_colour_pngs_load_bottom_row_first() {
    let path = scratch("grey.png");
    // 3 x 2, top row 0, 51, 102; bottom row 153, 204, 255.
    image::save_buffer(
        &path,
        &[0, 51, 102, 153, 204, 255],
        3,
        2,
        image::ColorType::L8,
    )
    .unwrap();
    let map = HeightMap::load(&path, 64).unwrap();
    assert_eq!((map.width(), map.height()), (3, 2));
    assert_eq!(map.heights(), &[0.6, 0.8, 1.0, 0.0, 0.2, 0.4]);
    let path = scratch("colour.png");
    image::save_buffer(&path, &[255u8; 2 * 2 * 3], 2, 2, image::ColorType::Rgb8).unwrap();
    assert!(HeightMap::load(&path, 64)
        .unwrap()
        .heights()
        .iter()
        .all(|&h| h == 1.0));
}

#[test]
fn a_missing_file_is_named() {
    let path = scratch("no-such-map.png");
    let err = load_error(&path, 64);
    assert!(
        err.contains("no-such-map.png") && err.contains("cannot open"),
        "{err}"
    );
}

#[test]
fn a_file_that_is_not_an_image_is_named() {
    let path = scratch("not-an-image.png");
    std::fs::write(&path, "height,0.5\n").unwrap();
    let err = load_error(&path, 64);
    assert!(
        err.contains("not-an-image.png") && err.contains("not a readable image"),
        "{err}"
    );
}

#[test]
fn a_1x1_map_has_no_patch() {
    let path = scratch("one.png");
    image::save_buffer(&path, &[7], 1, 1, image::ColorType::L8).unwrap();
    let err = load_error(&path, 64);
    assert!(
        err.contains("one.png") && err.contains("1x1") && err.contains("2x2"),
        "{err}"
    );
}

#[test]
fn a_map_beyond_the_texture_limit_is_refused_before_decoding() {
    let path = scratch("huge.png");
    std::fs::write(&path, png_header_only(100_000, 3)).unwrap();
    let err = load_error(&path, 16384);
    assert!(
        err.contains("huge.png") && err.contains("100000x3") && err.contains("16384"),
        "{err}"
    );
    // The same check on a real image against a small limit.
    let path = scratch("forty.png");
    image::save_buffer(&path, &[0u8; 40 * 40], 40, 40, image::ColorType::L8).unwrap();
    let err = load_error(&path, 32);
    assert!(err.contains("GL_MAX_TEXTURE_SIZE = 32"), "{err}");
}

#[test]
fn nan_or_out_of_range_heights_are_refused() {
    let err = HeightMap::new("test map", 2, 2, vec![0.0, f32::NAN, 0.5, 1.0])
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("test map") && err.contains("(1, 0)") && err.contains("NaN"),
        "{err}"
    );
    let err = HeightMap::new("test map", 2, 2, vec![0.0, 0.1, 1.5, 1.0])
        .unwrap_err()
        .to_string();
    assert!(err.contains("1.5"), "{err}");
    let err = HeightMap::new("test map", 2, 2, vec![0.0; 3])
        .unwrap_err()
        .to_string();
    assert!(err.contains("3 heights"), "{err}");
}
