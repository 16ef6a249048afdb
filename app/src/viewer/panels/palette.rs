//! The debug views' colours for the legends: a mirror of the palettes in
//! shaders/display.wgsl (`source_color`, `reason_color`, `heatmap`), gi/view.wgsl and
//! pt/view.wgsl (the tests below read them from the WGSL). Those are linear
//! colours that the display pass sRGB-encodes; `egui::Rgba` is linear too, so the legend
//! swatches match the image exactly.

use egui::{Color32, Rgba};
use restir_render::pt::constants::PT_FAIL_REASON_COUNT;
use restir_render::shader_constants::{
    SOURCE_INITIAL, SOURCE_NAMES, SOURCE_SPATIAL, SOURCE_TEMPORAL,
};

fn linear(c: [f32; 3]) -> Color32 {
    Rgba::from_rgb(c[0], c[1], c[2]).into()
}

fn mix(a: [f32; 3], b: [f32; 3], t: f32) -> [f32; 3] {
    std::array::from_fn(|i| a[i] + (b[i] - a[i]) * t)
}

/// Selection source (null is black).
pub fn source_color(source: u32) -> Color32 {
    linear(match source {
        SOURCE_INITIAL => [0.15, 0.35, 1.0],
        SOURCE_TEMPORAL => [0.1, 0.85, 0.25],
        SOURCE_SPATIAL => [1.0, 0.55, 0.05],
        _ => [0.0; 3],
    })
}

/// Which strategy proposed the initial survivor (`PROPOSER_*`), as display_colors.wgsl.
const PROPOSER_PALETTE: [[f32; 3]; 6] = [
    [0.0, 0.0, 0.0],
    [1.0, 1.0, 1.0],
    [0.5, 0.5, 0.5],
    [0.15, 0.35, 1.0],
    [1.0, 0.55, 0.05],
    [0.1, 0.85, 0.25],
];

pub fn proposer_color(proposer: u32) -> Color32 {
    linear(PROPOSER_PALETTE[(proposer as usize).min(PROPOSER_PALETTE.len() - 1)])
}

/// The six surface and reservoir checks DI and GI share (bits 0..6), in both palettes.
const CHECK_COLOURS: [[f32; 3]; 6] = [
    [1.0, 0.0, 0.0],
    [1.0, 0.5, 0.0],
    [1.0, 0.0, 1.0],
    [0.0, 0.6, 1.0],
    [0.0, 1.0, 1.0],
    [1.0, 1.0, 0.0],
];

/// Bit `bit` of a palette that starts with the shared checks and goes on with `own`.
fn check_or_own(bit: u32, own: &[[f32; 3]; 3]) -> Color32 {
    let bit = bit as usize;
    let colour = match CHECK_COLOURS.get(bit) {
        Some(shared) => *shared,
        None => own[(bit - CHECK_COLOURS.len()).min(own.len() - 1)],
    };
    linear(colour)
}

/// Temporal rejection reason `bit` (0..REJECT_REASON_COUNT): the shared checks, then
/// target ≤ 0 brown, target ratio white, light gone green.
pub fn reason_color(bit: u32) -> Color32 {
    check_or_own(bit, &[[0.6, 0.3, 0.1], [1.0, 1.0, 1.0], [0.1, 0.9, 0.2]])
}

/// GI rejection reason `bit` (0..GI_REJECT_REASON_COUNT), as gi/view.wgsl draws it: the
/// shared checks, then reconnection violet, Jacobian white, occluded green.
pub fn gi_reason_color(bit: u32) -> Color32 {
    check_or_own(bit, &[[0.55, 0.0, 1.0], [1.0, 1.0, 1.0], [0.1, 0.9, 0.2]])
}

/// The Jacobian views' three anchors (gi-jacobian's and pt-jacobian's): |J| at the low
/// end, 1, the high end.
pub fn jacobian_colors() -> [Color32; 3] {
    [
        linear([0.1, 0.3, 1.0]),
        linear([1.0, 1.0, 1.0]),
        linear([1.0, 0.1, 0.05]),
    ]
}

/// ReSTIR PT's depth palette (pt/view.wgsl `pt_depth_color`): the path length n of
/// pt-length and the reconnection vertex's depth k + 1 of pt-reconnection, 2 to 8.
const PT_DEPTH_COLOURS: [[f32; 3]; 7] = [
    [0.15, 0.35, 1.0],
    [0.1, 0.85, 0.25],
    [1.0, 0.9, 0.1],
    [1.0, 0.55, 0.05],
    [1.0, 0.1, 0.05],
    [0.6, 0.3, 0.1],
    [1.0, 1.0, 1.0],
];
/// The depths the PT palette tells apart (a path has at least two surface vertices).
pub const PT_DEPTHS: std::ops::RangeInclusive<u32> = 2..=8;

/// A path length or reconnection depth `d` (clamped into `PT_DEPTHS`, as the shader does).
pub fn pt_depth_color(d: u32) -> Color32 {
    let d = d.clamp(*PT_DEPTHS.start(), *PT_DEPTHS.end());
    linear(PT_DEPTH_COLOURS[(d - PT_DEPTHS.start()) as usize])
}

/// pt-reconnection where the path has no reconnection vertex (replayed whole): magenta.
const PT_PURE_REPLAY: [f32; 3] = [1.0, 0.0, 1.0];

pub fn pt_pure_replay_color() -> Color32 {
    linear(PT_PURE_REPLAY)
}

/// A shift's outcome (`PT_FAIL_*`), as pt-failure paints the commonest one (at full
/// brightness: the view dims it where fewer of the shifts failed).
const PT_FAILURE_COLOURS: [[f32; 3]; PT_FAIL_REASON_COUNT] = [
    [0.0, 0.35, 0.0],
    [1.0, 0.55, 0.05],
    [0.55, 0.0, 1.0],
    [0.1, 0.9, 0.2],
    [0.0, 0.8, 1.0],
    [1.0, 1.0, 0.0],
];

pub fn pt_failure_color(failure: u32) -> Color32 {
    linear(PT_FAILURE_COLOURS[(failure as usize).min(PT_FAIL_REASON_COUNT - 1)])
}

/// |J| at which pt-jacobian saturates: 2^`PT_JACOBIAN_SPAN` of pt/view.wgsl (its low end
/// is the reciprocal). Its colours are `jacobian_colors`, GI's.
pub const PT_JACOBIAN_SATURATION: f32 = 16.0;

/// The bias view's diverging ramp at t in [−1, 1] (darker blue, 0 white, brighter red), as
/// bias_view.wgsl's `bias_palette` draws it; t = 4 · (average − reference) / reference.
pub fn bias_color(t: f32) -> Color32 {
    let [darker, none, brighter] = BIAS_PALETTE;
    let x = t.clamp(-1.0, 1.0);
    linear(if x < 0.0 {
        mix(none, darker, -x)
    } else {
        mix(none, brighter, x)
    })
}

const BIAS_PALETTE: [[f32; 3]; 3] = [[0.1, 0.3, 1.0], [1.0, 1.0, 1.0], [1.0, 0.1, 0.05]];

/// The rejection view's spatial part: the fraction of neighbours rejected, black to grey.
pub fn spatial_count_color(fraction: f32) -> Color32 {
    linear([0.45 * fraction.clamp(0.0, 1.0); 3])
}

/// The 5-stop viridis ramp of the M, W and error views.
pub fn heatmap(t: f32) -> Color32 {
    const STOPS: [[f32; 3]; 5] = [
        [0.267, 0.005, 0.329],
        [0.229, 0.322, 0.546],
        [0.128, 0.567, 0.551],
        [0.369, 0.789, 0.383],
        [0.993, 0.906, 0.144],
    ];
    let t = t.clamp(0.0, 1.0) * 4.0;
    let i = (t.floor() as usize).min(3);
    linear(mix(STOPS[i], STOPS[i + 1], t - i as f32))
}

/// A filled square of `color` in the text line.
pub fn swatch(ui: &mut egui::Ui, color: Color32) -> egui::Response {
    let size = egui::vec2(
        ui.spacing().interact_size.y * 0.8,
        ui.spacing().interact_size.y * 0.8,
    );
    let (rect, response) = ui.allocate_exact_size(size, egui::Sense::hover());
    ui.painter().rect_filled(rect, 2.0, color);
    ui.painter().rect_stroke(
        rect,
        2.0,
        ui.visuals().widgets.noninteractive.bg_stroke,
        egui::StrokeKind::Inside,
    );
    response
}

/// The selection sources in palette order, each a swatch and `text(name)`, two per row
/// (a grid, not a wrapped row: a wrapped row of groups overflows and widens the panel).
pub fn source_legend(ui: &mut egui::Ui, text: impl Fn(&str) -> String) {
    egui::Grid::new(ui.next_auto_id())
        .num_columns(2)
        .show(ui, |ui| {
            for (i, name) in SOURCE_NAMES.iter().enumerate() {
                ui.horizontal(|ui| {
                    swatch(ui, source_color(i as u32));
                    ui.label(text(name));
                });
                if i % 2 == 1 {
                    ui.end_row();
                }
            }
        });
}

/// A horizontal heatmap ramp with labels at both ends.
pub fn ramp(ui: &mut egui::Ui, low: &str, high: &str) {
    ramp_of(ui, low, high, heatmap);
}

/// The rejection view's spatial grey ramp.
pub fn spatial_count_ramp(ui: &mut egui::Ui, low: &str, high: &str) {
    ramp_of(ui, low, high, spatial_count_color);
}

fn ramp_of(ui: &mut egui::Ui, low: &str, high: &str, color: fn(f32) -> Color32) {
    ui.horizontal(|ui| {
        ui.label(low);
        let (rect, _) = ui.allocate_exact_size(egui::vec2(140.0, 12.0), egui::Sense::hover());
        let steps = 28;
        let w = rect.width() / steps as f32;
        for s in 0..steps {
            let x = rect.left() + s as f32 * w;
            let cell = egui::Rect::from_min_size(
                egui::pos2(x, rect.top()),
                egui::vec2(w + 0.5, rect.height()),
            );
            ui.painter()
                .rect_filled(cell, 0.0, color((s as f32 + 0.5) / steps as f32));
        }
        ui.label(high);
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use restir_render::shader_constants::{
        GI_REJECT_REASON_COUNT, REJECT_REASON_COUNT, SHARED_REJECT_CHECKS,
    };

    #[test]
    fn palette_matches_the_shader_in_srgb() {
        // display.wgsl writes linear_to_srgb(colour): initial (0.15, 0.35, 1.0) → (108, 160, 255).
        assert_eq!(
            source_color(SOURCE_INITIAL),
            Color32::from_rgb(108, 160, 255)
        );
        assert_eq!(source_color(0), Color32::BLACK);
        assert_eq!(reason_color(0), Color32::from_rgb(255, 0, 0));
        // light_gone: (0.1, 0.9, 0.2) linear.
        assert_eq!(reason_color(8), linear([0.1, 0.9, 0.2]));
        assert_eq!(heatmap(1.0), linear([0.993, 0.906, 0.144]));
    }

    /// The `vec3<f32>(r, g, b)` entries of the palette array inside WGSL function `name`.
    fn wgsl_palette(source: &str, name: &str) -> Vec<[f32; 3]> {
        let body = &source[source.find(&format!("fn {name}(")).expect("the function")..];
        let start = body.find("array<").unwrap();
        let array = &body[start..start + body[start..].find(");").unwrap()];
        vec3_literals(array)
            .into_iter()
            .map(|numbers| [numbers[0], numbers[1], numbers[2]])
            .collect()
    }

    /// The numbers of each `vec3<f32>(…)` literal in `text`, in order.
    fn vec3_literals(text: &str) -> Vec<Vec<f32>> {
        text.split("vec3<f32>(")
            .skip(1) // what comes before the first literal
            .map(|entry| {
                entry[..entry.find(')').unwrap()]
                    .split(',')
                    .map(|n| n.trim().parse().unwrap())
                    .collect()
            })
            .collect()
    }

    /// The text of WGSL function `name`, up to its closing brace.
    fn wgsl_function<'a>(source: &'a str, name: &str) -> &'a str {
        let body = &source[source.find(&format!("fn {name}(")).expect("the function")..];
        &body[..body.find("\n}").expect("its end")]
    }

    /// The value of WGSL constant `name` (the text between `=` and `;`).
    fn wgsl_const<'a>(source: &'a str, name: &str) -> &'a str {
        let decl = &source[source
            .find(&format!("const {name}:"))
            .expect("the constant")..];
        decl[decl.find('=').unwrap() + 1..decl.find(';').unwrap()].trim()
    }

    /// The legends' colours are the shaders' colours, read from the WGSL itself.
    #[test]
    fn rejection_palettes_match_the_shaders() {
        let display = include_str!("../../../../shaders/display.wgsl");
        let gi_view = include_str!("../../../../shaders/gi/view.wgsl");
        let colours = include_str!("../../../../shaders/common/display_colors.wgsl");
        let shared = wgsl_palette(colours, "check_color");
        assert_eq!(shared.len(), SHARED_REJECT_CHECKS as usize);
        let di = [shared.clone(), wgsl_palette(display, "reason_color")].concat();
        let gi = [shared, wgsl_palette(gi_view, "gi_reason_color")].concat();
        assert_eq!(di.len(), REJECT_REASON_COUNT);
        assert_eq!(gi.len(), GI_REJECT_REASON_COUNT);
        for (bit, colour) in di.into_iter().enumerate() {
            assert_eq!(reason_color(bit as u32), linear(colour), "DI bit {bit}");
        }
        for (bit, colour) in gi.into_iter().enumerate() {
            assert_eq!(gi_reason_color(bit as u32), linear(colour), "GI bit {bit}");
        }
    }

    #[test]
    fn the_proposer_legend_matches_the_shader() {
        let colours = include_str!("../../../../shaders/common/display_colors.wgsl");
        let palette = wgsl_palette(colours, "proposer_color");
        assert_eq!(palette, PROPOSER_PALETTE.to_vec());
        assert_eq!(
            palette.len(),
            restir_render::shader_constants::PROPOSER_NAMES.len()
        );
    }

    #[test]
    fn the_bias_legend_matches_the_shader() {
        let shader = include_str!("../../../../shaders/bias_view.wgsl");
        let stops = wgsl_palette(shader, "bias_palette");
        assert_eq!(stops, BIAS_PALETTE.to_vec());
        assert_eq!(bias_color(-1.0), linear(BIAS_PALETTE[0]));
        assert_eq!(bias_color(0.0), Color32::WHITE);
        assert_eq!(bias_color(7.0), linear(BIAS_PALETTE[2]));
    }

    /// The PT legends' colours are pt/view.wgsl's: its depth and failure palettes, the
    /// pure replay's magenta, and a Jacobian ramp with GI's ends saturating at 1/16 and 16.
    #[test]
    fn the_pt_palettes_match_the_shader() {
        let pt_view = include_str!("../../../../shaders/pt/view.wgsl");
        let depths = wgsl_palette(pt_view, "pt_depth_color");
        assert_eq!(depths.len(), PT_DEPTHS.count());
        for (d, colour) in PT_DEPTHS.zip(depths) {
            assert_eq!(pt_depth_color(d), linear(colour), "depth {d}");
        }
        let failures = wgsl_palette(pt_view, "pt_failure_color");
        assert_eq!(failures.len(), PT_FAIL_REASON_COUNT);
        for (f, colour) in failures.into_iter().enumerate() {
            assert_eq!(pt_failure_color(f as u32), linear(colour), "failure {f}");
        }
        let replay = vec3_literals(wgsl_const(pt_view, "PT_PURE_REPLAY"));
        assert_eq!(replay, vec![PT_PURE_REPLAY.to_vec()]);
        let span: f32 = wgsl_const(pt_view, "PT_JACOBIAN_SPAN").parse().unwrap();
        assert_eq!(span.exp2(), PT_JACOBIAN_SATURATION);
        // Both Jacobian views draw one ramp: mix(white, low, -t) below 1, mix(white, high,
        // t) above.
        let [low, one, high] = jacobian_colors();
        assert_eq!(one, Color32::WHITE);
        let shader = include_str!("../../../../shaders/common/display_colors.wgsl");
        let literals = vec3_literals(wgsl_function(shader, "log_jacobian_color"));
        let colours: Vec<Color32> = literals
            .iter()
            .filter(|n| n.len() == 3)
            .map(|n| linear([n[0], n[1], n[2]]))
            .collect();
        assert_eq!(colours, vec![low, high]);
        assert!(
            literals.iter().all(|n| n.len() == 3 || n == &[1.0]),
            "white is vec3(1.0)"
        );
    }
}
