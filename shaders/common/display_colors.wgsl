// Colours shared by the display pass and the GI views: sRGB encoding, tonemapping with
// the display uniform's exposure (the including shader binds `display: Display`), the
// viridis heatmap and the selection-source palette.
#include "common/math.wgsl"

fn linear_to_srgb(c: vec3<f32>) -> vec3<f32> {
    let x = clamp(c, vec3<f32>(0.0), vec3<f32>(1.0));
    return select(1.055 * pow(x, vec3<f32>(1.0 / 2.4)) - 0.055, x * 12.92, x <= vec3<f32>(0.0031308));
}

// ACES filmic fit (Narkowicz 2015).
fn aces(x: vec3<f32>) -> vec3<f32> {
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), vec3<f32>(0.0), vec3<f32>(1.0));
}

fn tonemap(c: vec3<f32>) -> vec3<f32> {
    let x = max(c * display.exposure, vec3<f32>(0.0));
    switch display.tonemapper {
        case TONEMAP_ACES: { return aces(x); }
        case TONEMAP_REINHARD: { return x / (1.0 + luminance(x)); }
        default: { return x; }
    }
}

// Writes a display colour (a palette entry, or an image already tonemapped) to the view's
// output texture: only the sRGB encoding is left to apply. Every pass that includes this
// file binds `output`, the RGBA8 display texture.
fn store_display_color(pixel: vec2<u32>, color: vec3<f32>) {
    textureStore(output, vec2<i32>(pixel), vec4<f32>(linear_to_srgb(color), 1.0));
}

// Viridis, 5-stop piecewise linear: dark purple (0) → yellow (1).
fn heatmap(t_in: f32) -> vec3<f32> {
    let t = clamp(t_in, 0.0, 1.0) * 4.0;
    let c0 = vec3<f32>(0.267, 0.005, 0.329);
    let c1 = vec3<f32>(0.229, 0.322, 0.546);
    let c2 = vec3<f32>(0.128, 0.567, 0.551);
    let c3 = vec3<f32>(0.369, 0.789, 0.383);
    let c4 = vec3<f32>(0.993, 0.906, 0.144);
    if t < 1.0 { return mix(c0, c1, t); }
    if t < 2.0 { return mix(c1, c2, t - 1.0); }
    if t < 3.0 { return mix(c2, c3, t - 2.0); }
    return mix(c3, c4, t - 3.0);
}

// The six surface and reservoir checks DI's and GI's rejection masks share (bits
// 0..SHARED_REJECT_CHECKS), in both rejection palettes.
fn check_color(bit: u32) -> vec3<f32> {
    var palette = array<vec3<f32>, SHARED_REJECT_CHECKS>(
        vec3<f32>(1.0, 0.0, 0.0),   // off-screen: red
        vec3<f32>(1.0, 0.5, 0.0),   // previous surface invalid: orange
        vec3<f32>(1.0, 0.0, 1.0),   // material: magenta
        vec3<f32>(0.0, 0.6, 1.0),   // normal: blue
        vec3<f32>(0.0, 1.0, 1.0),   // depth / position: cyan
        vec3<f32>(1.0, 1.0, 0.0),   // reservoir null: yellow
    );
    return palette[min(bit, SHARED_REJECT_CHECKS - 1u)];
}

// Which strategy proposed the initial survivor (PROPOSER_*; none is black).
fn proposer_color(proposer: u32) -> vec3<f32> {
    var palette = array<vec3<f32>, 6>(
        vec3<f32>(0.0, 0.0, 0.0),    // none: black
        vec3<f32>(1.0, 1.0, 1.0),    // BSDF ray: white
        vec3<f32>(0.5, 0.5, 0.5),    // power table: grey
        vec3<f32>(0.15, 0.35, 1.0),  // light tile: blue
        vec3<f32>(1.0, 0.55, 0.05),  // ReGIR slot: orange
        vec3<f32>(0.1, 0.85, 0.25),  // light BVH: green
    );
    return palette[min(proposer, 5u)];
}

fn source_color(source: u32) -> vec3<f32> {
    switch source {
        case SOURCE_INITIAL: { return vec3<f32>(0.15, 0.35, 1.0); }
        case SOURCE_TEMPORAL: { return vec3<f32>(0.1, 0.85, 0.25); }
        case SOURCE_SPATIAL: { return vec3<f32>(1.0, 0.55, 0.05); }
        default: { return vec3<f32>(0.0); }
    }
}

// log2 |J| over ±span: blue (J small) through white (1) to red (J large), the Jacobian
// views' ramp (gi-jacobian, pt-jacobian; the legends: app/src/viewer/panels/palette.rs).
fn log_jacobian_color(j: f32, span: f32) -> vec3<f32> {
    let t = clamp(log2(max(j, 1e-30)) / span, -1.0, 1.0);
    if t < 0.0 {
        return mix(vec3<f32>(1.0), vec3<f32>(0.1, 0.3, 1.0), -t);
    }
    return mix(vec3<f32>(1.0), vec3<f32>(1.0, 0.1, 0.05), t);
}
