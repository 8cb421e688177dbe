//! `--png OUT.png` (SPEC §4): the SVG pictures of `run` and `bench`
//! rasterised with resvg. All text is drawn with the one font embedded in
//! the binary (DejaVu Sans, `assets/fonts/`), never a system font, so the
//! same picture gives the same pixels on every machine, fonts installed or
//! not.

use std::sync::{Arc, OnceLock};

use super::sink::{Command, Sink, needs_extension, the_file, write_file};

use resvg::tiny_skia::{Pixmap, Transform};
use resvg::usvg::{self, fontdb};

/// DejaVu Sans 2.37 (licence in `assets/fonts/DejaVuSans-LICENSE.txt`).
const FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");
const FAMILY: &str = "DejaVu Sans";

/// Pixels per SVG unit: twice the SVG's size, sharp in print and on
/// high-density screens.
pub const SCALE: f32 = 2.0;

/// The most pixels of one picture; a larger one (a bench of many metrics is
/// tall) is drawn at a smaller scale.
const MAX_PIXELS: f32 = 40e6;

/// The font database: the embedded font alone, standing for every generic
/// family (`sans-serif` from plotters, and the fallback resvg asks for).
fn fonts() -> Arc<fontdb::Database> {
    static FONTS: OnceLock<Arc<fontdb::Database>> = OnceLock::new();
    FONTS
        .get_or_init(|| {
            let mut db = fontdb::Database::new();
            db.load_font_data(FONT.to_vec());
            db.set_sans_serif_family(FAMILY);
            db.set_serif_family(FAMILY);
            db.set_monospace_family(FAMILY);
            db.set_cursive_family(FAMILY);
            db.set_fantasy_family(FAMILY);
            Arc::new(db)
        })
        .clone()
}

/// The scale a picture of `width` × `height` SVG units is drawn at.
fn scale_for(width: f32, height: f32) -> f32 {
    let area = (width * height).max(1.0);
    SCALE.min((MAX_PIXELS / area).sqrt())
}

/// The PNG file of an SVG document, [`SCALE`] times its size (less for a
/// huge one). The same SVG gives the same bytes.
pub fn to_png(svg: &str) -> Result<Vec<u8>, String> {
    rasterise(svg, None)?
        .encode_png()
        .map_err(|e| e.to_string())
}

/// An SVG document's pixels, at `scale` pixels per unit ([`SCALE`], less
/// for a huge one, when `None`).
pub fn rasterise(svg: &str, scale: Option<f32>) -> Result<Pixmap, String> {
    let options = usvg::Options {
        font_family: FAMILY.to_string(),
        fontdb: fonts(),
        ..usvg::Options::default()
    };
    let tree = usvg::Tree::from_str(svg, &options).map_err(|e| e.to_string())?;
    let size = tree.size();
    let scale = scale.unwrap_or_else(|| scale_for(size.width(), size.height()));
    let pixels = |x: f32| (x * scale).ceil().max(1.0) as u32;
    let (width, height) = (pixels(size.width()), pixels(size.height()));
    let mut pixmap = Pixmap::new(width, height)
        .ok_or_else(|| format!("a picture of {width}×{height} pixels is too large"))?;
    resvg::render(
        &tree,
        Transform::from_scale(scale, scale),
        &mut pixmap.as_mut(),
    );
    Ok(pixmap)
}

/// `--png OUT.png`: the same picture as `--svg`, rasterised.
pub static SINK: Sink = Sink {
    option: "--png",
    value_name: "OUT.png",
    help: &[
        (Command::Run, "Write the same picture as a PNG"),
        (Command::Bench, "Write the same plots as a PNG"),
    ],
    draws: true,
    folder: false,
    check: |path| {
        needs_extension(
            path,
            "--png",
            "png",
            "a PNG picture",
            " (`--svg OUT.svg` writes an SVG)",
        )
    },
    files: the_file,
    tuning: None,
    write: |product, path, _| {
        let svg = super::svg::picture(product, path)?;
        let bytes =
            to_png(&svg).map_err(|e| vec![format!("cannot draw `{}`: {e}", path.display())])?;
        write_file(path, bytes)
    },
};

#[cfg(test)]
mod tests {
    use super::*;

    /// The decoded PNG: width, height and RGBA pixels.
    fn decode(bytes: &[u8]) -> (u32, u32, Vec<u8>) {
        let pixmap = Pixmap::decode_png(bytes).expect("a PNG");
        (pixmap.width(), pixmap.height(), pixmap.data().to_vec())
    }

    fn pixel(image: &(u32, u32, Vec<u8>), x: u32, y: u32) -> [u8; 4] {
        let i = 4 * (y * image.0 + x) as usize;
        [image.2[i], image.2[i + 1], image.2[i + 2], image.2[i + 3]]
    }

    const PICTURE: &str = r##"<svg xmlns="http://www.w3.org/2000/svg" width="100" height="50" viewBox="0 0 100 50">
<rect width="100" height="50" fill="#ffffff"/>
<rect x="10" y="10" width="20" height="20" fill="#ff0000"/>
</svg>"##;

    #[test]
    fn draws_at_twice_the_size() {
        let image = decode(&to_png(PICTURE).expect("drawn"));
        assert_eq!((image.0, image.1), (200, 100));
        assert_eq!(pixel(&image, 40, 40), [255, 0, 0, 255]);
        assert_eq!(pixel(&image, 100, 40), [255, 255, 255, 255]);
    }

    /// Text takes the embedded font whatever family it asks for: glyphs
    /// put dark pixels where the text is, and only there.
    #[test]
    fn text_is_drawn_with_the_embedded_font() {
        for family in ["sans-serif", "serif", "No Such Font", "DejaVu Sans"] {
            let svg = format!(
                r##"<svg xmlns="http://www.w3.org/2000/svg" width="120" height="40">
<rect width="120" height="40" fill="#ffffff"/>
<text x="5" y="25" font-family="{family}" font-size="20" fill="#000000">Hello</text>
</svg>"##
            );
            let image = decode(&to_png(&svg).expect("drawn"));
            let dark = |x0: u32, x1: u32| {
                (x0..x1)
                    .flat_map(|x| (0..image.1).map(move |y| (x, y)))
                    .filter(|&(x, y)| pixel(&image, x, y)[0] < 128)
                    .count()
            };
            assert!(dark(10, 100) > 100, "no text drawn for {family}");
            assert_eq!(dark(140, 240), 0, "ink right of the text for {family}");
        }
    }

    #[test]
    fn same_svg_same_bytes() {
        let svg = PICTURE.replace("</svg>", "<text x=\"40\" y=\"30\">0.5</text></svg>");
        assert_eq!(to_png(&svg), to_png(&svg));
    }

    #[test]
    fn a_huge_picture_is_drawn_smaller() {
        assert_eq!(scale_for(800.0, 900.0), SCALE);
        let s = scale_for(1240.0, 9000.0);
        assert!(s < SCALE && (1240.0 * s) * (9000.0 * s) <= MAX_PIXELS * 1.001);
    }

    #[test]
    fn not_svg_is_an_error() {
        assert!(to_png("not a picture").is_err());
    }

    #[test]
    fn picture_files_need_their_extension() {
        use std::path::Path;
        let svg = super::super::svg::SINK.check;
        let png = SINK.check;
        assert!(svg(Path::new("a.svg")).is_ok() && png(Path::new("b.PNG")).is_ok());
        let e = svg(Path::new("out.png")).expect_err("refused");
        assert!(e.contains("`--svg out.png`") && e.contains(".svg"), "{e}");
        let e = png(Path::new("out.svg")).expect_err("refused");
        assert!(e.contains("`--png out.svg`"), "{e}");
        assert!(png(Path::new("noext")).is_err());
    }
}
