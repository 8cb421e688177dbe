//! The pictures of `scen run` and `scen bench` (SPEC §4 "Pictures"): the
//! SVG read back (axes, legend, exact C-obstacles, faded large layers) and
//! the PNG decoded (its size, and the path's colour where the path is).

mod common;

use common::Test;
use resvg::tiny_skia::Pixmap;

/// A disk robot around a disk obstacle, and a plan whose goal is walled in.
const DISKS: &str = r#"scenario "Disks"
world {
  bounds (0, 0) (10, 5)
  disk pillar (5, 2.5) 1
  segment w1 (8, 3.5) (9.5, 3.5)
  segment w2 (9.5, 3.5) (9.5, 4.8)
  segment w3 (9.5, 4.8) (8, 4.8)
  segment w4 (8, 4.8) (8, 3.5)
}
robot round disk 0.5
robot dot point
plan around astar round {
  start (1, 2.5)
  goal (9, 1)
  cell 0.25
}
plan shut astar dot {
  start (1, 1)
  goal (8.75, 4.1)
  cell 0.25
}
"#;

/// The attribute `name` of an SVG element's text.
fn attr<'a>(element: &'a str, name: &str) -> Option<&'a str> {
    let at = element.find(&format!(" {name}=\""))? + name.len() + 3;
    let rest = &element[at..];
    Some(&rest[..rest.find('"')?])
}

fn num(element: &str, name: &str) -> f64 {
    attr(element, name)
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| panic!("no number {name} in {element}"))
}

/// The lines of `svg` that start an element `<tag` and contain `with`.
fn elements<'a>(svg: &'a str, tag: &str, with: &str) -> Vec<&'a str> {
    svg.lines()
        .filter(|l| l.starts_with(&format!("<{tag} ")) && l.contains(with))
        .collect()
}

/// The text of `<text ...>TEXT</text>` lines with `with` in the tag.
fn texts(svg: &str, with: &str) -> Vec<(String, String)> {
    elements(svg, "text", with)
        .into_iter()
        .filter_map(|l| {
            let open = l.find('>')?;
            let close = l.rfind("</text>")?;
            Some((l[..open].to_string(), l[open + 1..close].to_string()))
        })
        .collect()
}

/// The part of `svg` between the line `<g id="ID"...` and its `</g>`.
fn group<'a>(svg: &'a str, id: &str) -> &'a str {
    let start = svg
        .find(&format!("<g id=\"{id}\""))
        .unwrap_or_else(|| panic!("no group {id}"));
    let end = svg[start..].find("</g>").map_or(svg.len(), |e| start + e);
    &svg[start..end]
}

fn run_disks(extra: &[&str]) -> (Test, String) {
    let mut args = vec!["run", "-q", "--svg", "out.svg", "disks.scen"];
    args.extend_from_slice(extra);
    let t = Test::new().file("disks.scen", DISKS).args(&args);
    t.run();
    let svg = std::fs::read_to_string(t.dir().join("out.svg")).expect("out.svg written");
    (t, svg)
}

/// The bounds rectangle: its left and bottom pixel, and pixels per unit.
fn bounds_frame(svg: &str, world: (f64, f64)) -> (f64, f64, f64) {
    let bounds = elements(svg, "rect", "id=\"bounds\"");
    let b = bounds.first().expect("a bounds rectangle");
    let (x, y, w, h) = (num(b, "x"), num(b, "y"), num(b, "width"), num(b, "height"));
    let scale = w / world.0;
    assert!((h / world.1 - scale).abs() < 0.01, "unequal axes: {b}");
    (x, y + h, scale)
}

#[test]
fn the_axes_have_ticks_in_world_units_where_they_say() {
    let (_, svg) = run_disks(&[]);
    let (left, bottom, scale) = bounds_frame(&svg, (10.0, 5.0));
    for (axis, along) in [("x-axis", "x"), ("y-axis", "y")] {
        let ticks = texts(group(&svg, axis), "class=\"tick\"");
        assert!(ticks.len() >= 3, "{axis}: {ticks:?}");
        let values: Vec<f64> = ticks
            .iter()
            .map(|(_, t)| t.parse().unwrap_or_else(|_| panic!("tick {t}")))
            .collect();
        // One step of 1, 2 or 5 × 10^k between ticks.
        let step = values[1] - values[0];
        let mantissa = step / 10f64.powf(step.log10().floor());
        assert!(
            [1.0, 2.0, 5.0].iter().any(|m| (mantissa - m).abs() < 1e-9),
            "{axis} step {step}"
        );
        for w in values.windows(2) {
            assert!((w[1] - w[0] - step).abs() < 1e-9, "{axis}: {values:?}");
        }
        // The ticks cover the bounds: 0 to 10 along x, 0 to 5 along y.
        let hi = if along == "x" { 10.0 } else { 5.0 };
        assert!(
            values[0] <= 0.0 && *values.last().unwrap_or(&0.0) >= hi - step,
            "{values:?}"
        );
        // Each label stands where its value is in the world.
        for ((tag, _), v) in ticks.iter().zip(&values) {
            if along == "x" {
                assert!(
                    (num(tag, "x") - (left + v * scale)).abs() < 0.02,
                    "{tag} for {v}"
                );
            } else {
                // The label's baseline is a little under the tick.
                let y = num(tag, "y") - 4.0;
                assert!((y - (bottom - v * scale)).abs() < 0.02, "{tag} for {v}");
            }
        }
    }
}

#[test]
fn the_legend_names_each_plan_its_colour_and_whether_it_found_a_path() {
    let (_, svg) = run_disks(&[]);
    let legend = group(&svg, "legend");
    let plans = texts(legend, "class=\"plan\"");
    let names: Vec<&str> = plans.iter().map(|(_, t)| t.as_str()).collect();
    assert_eq!(names.len(), 2, "{names:?}");
    assert!(
        names[0].starts_with("around (astar): found, length "),
        "{names:?}"
    );
    assert_eq!(names[1], "shut (astar): not found");
    // Each plan's swatch is in the colour of its path.
    let swatches = elements(legend, "line", "stroke-width=\"4\"");
    let paths = elements(&svg, "polyline", "class=\"path\"");
    assert_eq!(paths.len(), 1, "one path found");
    assert_eq!(attr(swatches[0], "stroke"), attr(paths[0], "stroke"));
    assert_ne!(attr(swatches[0], "stroke"), attr(swatches[1], "stroke"));
    // A key to what else is drawn.
    let keys: Vec<String> = texts(legend, "class=\"key\"")
        .into_iter()
        .map(|(_, t)| t)
        .collect();
    for key in [
        "obstacles",
        "C-obstacles (obstacles grown by the robot)",
        "robot",
        "start",
        "goal",
    ] {
        assert!(keys.iter().any(|k| k == key), "no key {key} in {keys:?}");
    }
    // The legend is below the plot.
    let frame = elements(&svg, "rect", "id=\"frame\"");
    let plot_bottom = num(frame[0], "y") + num(frame[0], "height");
    for (tag, _) in texts(legend, "class=") {
        assert!(num(&tag, "y") > plot_bottom + 30.0, "{tag} over the plot");
    }
}

#[test]
fn a_disk_grown_by_a_disk_robot_is_a_circle_of_the_summed_radii() {
    let (_, svg) = run_disks(&[]);
    let (left, bottom, scale) = bounds_frame(&svg, (10.0, 5.0));
    let pillar = elements(&svg, "circle", "id=\"pillar\"");
    let pillar = pillar.first().expect("the pillar");
    let grown_layer = svg
        .split("<g class=\"layer\"")
        .find(|g| g.contains("data-key=\"C-obstacles"))
        .and_then(|g| g.split("</g>").next())
        .expect("a C-obstacle layer");
    let circles: Vec<&str> = grown_layer
        .lines()
        .filter(|l| l.starts_with("<circle "))
        .collect();
    assert_eq!(circles.len(), 1, "{grown_layer}");
    let c = circles[0];
    let (cx, cy) = (left + 5.0 * scale, bottom - 2.5 * scale);
    for e in [c, *pillar] {
        assert!(
            (num(e, "cx") - cx).abs() < 0.01 && (num(e, "cy") - cy).abs() < 0.01,
            "{e}"
        );
    }
    assert!((num(c, "r") - 1.5 * scale).abs() < 0.01, "{c}");
    assert!((num(pillar, "r") - 1.0 * scale).abs() < 0.01, "{pillar}");
    // The walls, grown, are stadiums: two half circles each.
    assert_eq!(grown_layer.matches("<path ").count(), 4, "{grown_layer}");
    assert!(grown_layer.contains("A"), "{grown_layer}");
}

#[test]
fn the_png_is_the_picture_rasterised() {
    let (t, svg) = run_disks(&["--png", "out.png"]);
    let bytes = std::fs::read(t.dir().join("out.png")).expect("out.png written");
    let image = Pixmap::decode_png(&bytes).expect("a PNG");
    let root = svg.lines().find(|l| l.starts_with("<svg ")).expect("<svg>");
    let (w, h) = (num(root, "width"), num(root, "height"));
    assert_eq!(
        (image.width(), image.height()),
        ((2.0 * w).ceil() as u32, (2.0 * h).ceil() as u32)
    );
    let pixel = |x: f64, y: f64| {
        let p = image
            .pixel((2.0 * x) as u32, (2.0 * y) as u32)
            .expect("inside")
            .demultiply();
        [p.red(), p.green(), p.blue()]
    };
    // The path's colour at the middle of each of its segments.
    let path = elements(&svg, "polyline", "class=\"path\"")[0];
    let colour = attr(path, "stroke").expect("a colour");
    let rgb = |hex: &str| {
        let v = u32::from_str_radix(hex.trim_start_matches('#'), 16).expect("hex");
        [(v >> 16) as u8, (v >> 8) as u8, v as u8]
    };
    let want = rgb(colour);
    let points: Vec<(f64, f64)> = attr(path, "points")
        .expect("points")
        .split(' ')
        .filter_map(|p| {
            let (x, y) = p.split_once(',')?;
            Some((x.parse().ok()?, y.parse().ok()?))
        })
        .collect();
    assert!(points.len() >= 2);
    let ends = [points[0], points[points.len() - 1]];
    let mut checked = 0;
    for w in points.windows(2) {
        let (x, y) = ((w[0].0 + w[1].0) / 2.0, (w[0].1 + w[1].1) / 2.0);
        // The start and goal markers cover the path's ends.
        if ends.iter().any(|e| (e.0 - x).hypot(e.1 - y) < 10.0) {
            continue;
        }
        let got = pixel(x, y);
        let near = got.iter().zip(want).all(|(a, b)| a.abs_diff(b) <= 12);
        assert!(
            near,
            "pixel {got:?} at ({x}, {y}) is not the path's {want:?}"
        );
        checked += 1;
    }
    assert!(checked >= 5, "only {checked} points of the path checked");
    // The background where nothing is drawn: the top right corner.
    assert_eq!(pixel(w - 2.0, 2.0), rgb("#fcfcfa"));
    // Text was drawn: the title band has dark pixels.
    let dark = (0..(2.0 * w) as u32)
        .flat_map(|x| (0..40).map(move |y| (x, y)))
        .filter(|&(x, y)| image.pixel(x, y).is_some_and(|p| p.red() < 100))
        .count();
    assert!(dark > 200, "no title drawn ({dark} dark pixels)");
}

#[test]
fn a_large_roadmap_is_faint_and_under_the_paths() {
    let scenario = r#"world {
  bounds (0, 0) (20, 20)
  rect a (5, 0) (6, 15)
  rect b (12, 5) (13, 20)
}
robot p point
plan many prm p {
  start (1, 1)
  goal (19, 19)
  seed 1
  stop limit
  limit iterations 2500
}
"#;
    let t = Test::new()
        .file("prm.scen", scenario)
        .args(&["run", "-q", "--svg", "out.svg", "prm.scen"]);
    t.run();
    let svg = std::fs::read_to_string(t.dir().join("out.svg")).expect("out.svg");
    let layers: Vec<&str> = elements(&svg, "g", "class=\"layer\"");
    let graph: Vec<&&str> = layers
        .iter()
        .filter(|g| attr(g, "data-key") == Some("roadmap edges"))
        .collect();
    assert!(!graph.is_empty(), "no roadmap layer");
    for g in &graph {
        let opacity = num(g, "stroke-opacity");
        assert!(opacity < 0.2, "the roadmap is not faded: {g}");
        assert!(num(g, "stroke-width") <= 0.5, "{g}");
    }
    let last_layer = svg.rfind("<g class=\"layer\"").expect("layers");
    let path = svg.find("<polyline class=\"path\"").expect("a path");
    assert!(last_layer < path, "a layer drawn over the path");
    let keys = texts(group(&svg, "legend"), "class=\"key\"");
    assert!(
        keys.iter()
            .any(|(_, k)| k.starts_with("roadmap edges (") && k.ends_with(" drawn, faint)")),
        "{keys:?}"
    );
}

#[test]
fn a_picture_file_needs_its_extension_before_anything_runs() {
    for (args, flag) in [
        (
            vec!["run", "--svg", "out.png", "missing.scen"],
            "`--svg out.png`",
        ),
        (
            vec!["run", "--png", "out.svg", "missing.scen"],
            "`--png out.svg`",
        ),
        (
            vec!["bench", "--png", "plots.svg", "missing.scen"],
            "`--png plots.svg`",
        ),
        (
            vec!["bench", "--svg", "plots", "missing.scen"],
            "`--svg plots`",
        ),
    ] {
        let out = Test::new()
            .args(&args)
            .status(2)
            .stderr_contains(flag)
            .run();
        let stderr = String::from_utf8_lossy(&out.stderr);
        // Refused at once: the missing scenario was never opened.
        assert!(!stderr.contains("missing.scen"), "{stderr}");
    }
}

#[test]
fn bench_pictures_have_the_legend_right_of_the_plots_and_a_png() {
    let scenario = r#"world {
  bounds (0, 0) (20, 20)
  segment bottom (10, 2) (10, 8)
}
robot p point
plan walk potential p { start (7, 5) goal (15, 5) limit steps 20000 }
bench seeds {
  plans [walk]
  vary jump [2, 4, 10]
  runs 5
}
"#;
    let t = Test::new().file("b.scen", scenario).args(&[
        "bench",
        "-q",
        "--metrics",
        "length",
        "--svg",
        "plots.svg",
        "--png",
        "plots.png",
        "b.scen",
    ]);
    t.run();
    let svg = std::fs::read_to_string(t.dir().join("plots.svg")).expect("plots.svg");
    let root = svg.lines().find(|l| l.starts_with("<svg")).expect("<svg>");
    let (w, h) = (num(root, "width"), num(root, "height"));
    // Two panels of 620 pixels (boxes, lines), the legend right of them.
    // Plotters writes a text's content on a line of its own.
    let legend: Vec<f64> = svg
        .split("<text")
        .skip(1)
        .filter(|t| {
            let inner = t.split_once('>').map_or("", |(_, rest)| rest);
            inner.split("</text>").next().map(str::trim) == Some("walk")
        })
        .map(|t| num(t, "x"))
        .collect();
    assert_eq!(legend.len(), 1, "{svg}");
    assert!(
        legend[0] >= 1240.0,
        "the legend is over the plots: x = {}",
        legend[0]
    );
    assert!(svg.contains("band: 25–75 % of runs"));
    let image =
        Pixmap::decode_png(&std::fs::read(t.dir().join("plots.png")).expect("png")).expect("a PNG");
    assert_eq!(
        (image.width(), image.height()),
        ((2.0 * w) as u32, (2.0 * h) as u32)
    );
}

/// Issue 39: the success rate is a bar chart on a 0–100 % axis with the
/// 95 % Wilson interval as an error bar, its legend off the data; and no
/// median line by the varied key, which a rate does not have.
#[test]
fn the_success_rate_is_a_bar_chart_with_wilson_error_bars() {
    let scenario = r#"world {
  bounds (0, 0) (20, 20)
  segment bottom (10, 2) (10, 8)
}
robot p point
plan walk potential p { start (7, 5) goal (15, 5) limit steps 20000 }
bench seeds {
  plans [walk]
  vary jump [2, 4, 10]
  runs 5
}
"#;
    let t = Test::new().file("b.scen", scenario).args(&[
        "bench",
        "-q",
        "--metrics",
        "found",
        "--svg",
        "rate.svg",
        "b.scen",
    ]);
    t.run();
    let svg = std::fs::read_to_string(t.dir().join("rate.svg")).expect("rate.svg");
    let texts: Vec<String> = svg
        .split("<text")
        .skip(1)
        .filter_map(|t| {
            let inner = t.split_once('>')?.1;
            Some(inner.split("</text>").next()?.trim().to_string())
        })
        .collect();
    for wanted in [
        "seeds — success rate",
        "runs that found a path (%)",
        "error bar: its 95 % interval",
        "0",
        "100",
    ] {
        assert!(
            texts.iter().any(|t| t == wanted),
            "no `{wanted}`: {texts:?}"
        );
    }
    // No box-plot notes and no line panel for a rate.
    assert!(
        !svg.contains("whiskers") && !svg.contains("median found"),
        "{svg}"
    );
    let root = svg.lines().find(|l| l.starts_with("<svg")).expect("<svg>");
    assert_eq!(
        num(root, "width"),
        620.0 + 220.0,
        "one panel and the legend"
    );
}

/// Issue 39: a family's picture names its sample and what it drew.
#[test]
fn a_familys_picture_names_its_sample() {
    let family = "param gx = uniform(3, 7)\n\
        world {\n  bounds (0, 0) (10, 10)\n  rect wall (gx, 2) (gx + 1, 10)\n}\n\
        robot p point\n\
        plan a astar p { start (1, 5) goal (9, 5) }\n";
    let t = Test::new()
        .file("f.scen", family)
        .args(&["run", "-q", "--sample", "3", "--svg", "f.svg", "f.scen"]);
    t.run();
    let svg = std::fs::read_to_string(t.dir().join("f.svg")).expect("f.svg");
    let title = svg
        .split("<title>")
        .nth(1)
        .and_then(|t| t.split("</title>").next())
        .unwrap_or_default();
    assert!(
        title.starts_with("f.scen — sample 3 (family seed 0): gx = "),
        "{title}"
    );
}

/// A cart crossing the robot's corridor, then vanishing; the robot waits.
const CART: &str = r#"scenario "Cart"
world {
  bounds (0, 0) (10, 4)
  rect south_w (0, 0) (4, 2)
  rect south_e (5, 0) (10, 2)
  rect north_w (0, 3) (4, 4)
  rect north_e (5, 3) (10, 4)
  moving cart disk 0.5 { at 0s (4.5, 0.5) at 6s (4.5, 3.5) then vanish }
}
robot dot disk 0.3 speed 1
plan go sipp dot { start (0.5, 2.5) goal (9.5, 2.5) }
"#;

#[test]
fn a_moving_obstacle_is_drawn_with_its_route_times_and_the_robots_waits() {
    let t =
        Test::new()
            .file("cart.scen", CART)
            .args(&["run", "-q", "--svg", "out.svg", "cart.scen"]);
    t.run();
    let svg = std::fs::read_to_string(t.dir().join("out.svg")).expect("out.svg written");
    let (left, bottom, scale) = bounds_frame(&svg, (10.0, 4.0));
    let cart = group(&svg, "moving-cart");
    // Filled where it starts, at its first point and of its radius.
    let start = elements(cart, "circle", "fill-opacity");
    assert_eq!(start.len(), 1, "{cart}");
    assert!(
        (num(start[0], "cx") - (left + 4.5 * scale)).abs() < 0.01,
        "{}",
        start[0]
    );
    assert!(
        (num(start[0], "cy") - (bottom - 0.5 * scale)).abs() < 0.01,
        "{}",
        start[0]
    );
    assert!(
        (num(start[0], "r") - 0.5 * scale).abs() < 0.01,
        "{}",
        start[0]
    );
    // The route dashed; the end outlined and dotted, since it vanishes.
    let route = elements(cart, "polyline", "class=\"route\"");
    assert!(
        route.len() == 1 && route[0].contains("stroke-dasharray"),
        "{cart}"
    );
    let end = elements(cart, "circle", "fill=\"none\"");
    assert!(
        end.len() == 1 && end[0].contains("stroke-dasharray=\"2 3\""),
        "{cart}"
    );
    // The times, over the paths.
    let times: Vec<String> = texts(group(&svg, "moving-times"), "class=\"time\"")
        .into_iter()
        .map(|(_, text)| text)
        .collect();
    assert_eq!(times, ["0s", "6s", "gone"]);
    assert!(svg.find("id=\"moving-times\"") > svg.find("class=\"path\""));
    // The robot waits for the cart beside its way.
    let waits = texts(&svg, "class=\"wait\"");
    assert_eq!(waits.len(), 1, "{svg}");
    assert!(waits[0].1.starts_with("waits "), "{waits:?}");
}

/// A cart with a waypoint every 0.2 units: its times are thinned so that
/// no two labels overlap, the first and last always kept.
#[test]
fn a_dense_route_keeps_a_readable_subset_of_its_times() {
    let waypoints: Vec<String> = (0..=40)
        .map(|k| format!("at {}s ({}, 0.5)", k, 1.0 + 0.2 * k as f64))
        .collect();
    let scenario = format!(
        "scenario \"Dense\"\nworld {{\n  bounds (0, 0) (10, 4)\n  moving cart disk 0.3 {{ {} then stay }}\n}}\nrobot dot disk 0.3 speed 1\nplan go sipp dot {{ start (0.5, 3.5) goal (9.5, 3.5) }}\n",
        waypoints.join(" ")
    );
    let t = Test::new().file("dense.scen", &scenario).args(&[
        "run",
        "-q",
        "--svg",
        "out.svg",
        "dense.scen",
    ]);
    t.run();
    let svg = std::fs::read_to_string(t.dir().join("out.svg")).expect("out.svg written");
    let labels = texts(group(&svg, "moving-times"), "class=\"time\"");
    let times: Vec<&str> = labels.iter().map(|(_, t)| t.as_str()).collect();
    assert!(times.contains(&"0s") && times.contains(&"40s"), "{times:?}");
    assert!(times.len() > 2 && times.len() < 41, "{times:?}");
    // Along a straight route, the kept labels are far enough apart: each
    // at least its own width from the next.
    let xs: Vec<f64> = labels
        .iter()
        .map(|(open, _)| {
            let at = open.find(" x=\"").expect("x") + 4;
            open[at..at + open[at..].find('"').expect("\"")]
                .parse()
                .expect("a number")
        })
        .collect();
    let mut sorted = xs.clone();
    sorted.sort_by(f64::total_cmp);
    for pair in sorted.windows(2) {
        assert!(pair[1] - pair[0] >= 0.6 * 11.0 * 2.0 - 1e-9, "{xs:?}");
    }
}

/// The delay of each frame of the GIF at `path` (hundredths of a second),
/// after checking that the first frame fills the screen and every later
/// one (the rectangle that changed) lies inside it.
fn gif_delays(path: &std::path::Path) -> Vec<u16> {
    let file = std::fs::File::open(path).expect("the GIF written");
    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::Indexed);
    let mut decoder = options.read_info(file).expect("a GIF");
    let (width, height) = (decoder.width(), decoder.height());
    let mut delays = Vec::new();
    while let Some(frame) = decoder.read_next_frame().expect("a frame") {
        if delays.is_empty() {
            assert_eq!((frame.width, frame.height), (width, height));
        }
        assert!(frame.left + frame.width <= width && frame.top + frame.height <= height);
        delays.push(frame.delay);
    }
    delays
}

#[test]
fn a_gif_animates_the_cart_and_the_robot_at_25_frames_per_second() {
    let t =
        Test::new()
            .file("cart.scen", CART)
            .args(&["run", "-q", "--gif", "out.gif", "cart.scen"]);
    t.run();
    let delays = gif_delays(&t.dir().join("out.gif"));
    let frames = delays.len();
    // The robot waits for the cart and arrives at t ≈ 9.4 s (the cart
    // vanishes at 6 s): frames every 1/25 s to a second after that.
    let arrival: f64 = {
        let out = Test::new()
            .file("cart.scen", CART)
            .args(&["run", "--json", "cart.scen"])
            .run();
        let doc: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        doc["plans"]["go"]["metrics"]["arrival"].as_f64().unwrap()
    };
    assert_eq!(frames, ((arrival + 1.0) * 25.0).ceil() as usize + 1);
    assert!(delays.iter().all(|&d| d == 4), "{delays:?}");
    // Where nothing moves, nothing is written.
    Test::new()
        .file("disks.scen", DISKS)
        .args(&["run", "-q", "--gif", "out.gif", "disks.scen"])
        .stderr_contains("nothing moves")
        .status(2)
        .run();
    Test::new()
        .file("cart.scen", CART)
        .args(&["run", "-q", "--gif", "out.png", "cart.scen"])
        .stderr_contains("writes a GIF animation")
        .status(2)
        .run();

    // `--gif-speed 4`: a frame every 4/25 s of plan time, to a second of
    // the animation (4 s) after the arrival; still 4/100 s per frame.
    let fast = Test::new().file("cart.scen", CART).args(&[
        "run",
        "-q",
        "--gif",
        "fast.gif",
        "--gif-speed",
        "4",
        "cart.scen",
    ]);
    fast.run();
    let fast_delays = gif_delays(&fast.dir().join("fast.gif"));
    assert!(fast_delays.iter().all(|&d| d == 4), "{fast_delays:?}");
    let fast_frames = fast_delays.len();
    assert_eq!(
        fast_frames,
        ((arrival + 4.0) * 25.0 / 4.0).ceil() as usize + 1
    );
    assert!(fast_frames * 3 < frames, "{fast_frames} of {frames}");
    // The speed tunes `--gif` only, and is a positive number.
    for (args, says) in [
        (
            vec!["--gif-speed", "2"],
            "`--gif-speed` tunes `--gif`, which was not given",
        ),
        (
            vec!["--gif", "o.gif", "--gif-speed", "0"],
            "the speed is a number above 0",
        ),
        (
            vec!["--gif", "o.gif", "--gif-speed", "-2"],
            "the speed is a number above 0",
        ),
        (
            vec!["--gif", "o.gif", "--gif-speed", "fast"],
            "invalid value 'fast'",
        ),
    ] {
        let mut all = vec!["run", "-q"];
        all.extend(args);
        all.push("cart.scen");
        let t = Test::new()
            .file("cart.scen", CART)
            .args(&all)
            .stderr_contains(says)
            .status(2);
        t.run();
        assert!(!t.dir().join("o.gif").exists());
    }
}
