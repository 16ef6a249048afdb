// The glTF metallic-roughness BRDF: Lambert + GGX (height-correlated Smith), with
// KHR_materials_specular's specularFactor scaling the dielectric specular lobe.
// With specular = 0 and metallic = 0 it is exactly base_color / π, and scenes without
// any specular lobe compile without the GGX code (#ifdef SPECULAR).
#include "common/math.wgsl"

// Roughness below ~0.032 behaves as 0.032: a true mirror is a delta lobe that light
// sampling could never hit, and α → 0 overflows D.
const MIN_ALPHA: f32 = 1e-3;

struct Brdf {
    base_color: vec3<f32>,
    metallic: f32,
    alpha: f32,     // GGX α = roughness²
    specular: f32,
}

struct BrdfSample {
    wi: vec3<f32>,
    pdf: f32,       // solid angle; 0 when the sample is invalid
}

fn make_brdf(base_color: vec3<f32>, metallic: f32, roughness: f32, specular: f32) -> Brdf {
    let r = clamp(roughness, 0.0, 1.0);
    return Brdf(base_color, clamp(metallic, 0.0, 1.0), max(r * r, MIN_ALPHA), max(specular, 0.0));
}

fn eval_diffuse(b: Brdf) -> vec3<f32> {
    return b.base_color * INV_PI;
}

#ifdef SPECULAR
fn schlick_weight(cos_theta: f32) -> f32 {
    let m = clamp(1.0 - cos_theta, 0.0, 1.0);
    let m2 = m * m;
    return m2 * m2 * m;
}

// Schlick's Fresnel of the dielectric interface (F0 = 0.04, ior 1.5) scaled by
// KHR_materials_specular's specularFactor: the specular lobe's F and the share of light a
// glass layer reflects instead of passing (material.wgsl's `Layer`).
fn dielectric_fresnel(specular: f32, cos_theta: f32) -> f32 {
    return specular * (0.04 + 0.96 * schlick_weight(cos_theta));
}

// D(h) = α² / (π ((n·h)²(α² − 1) + 1)²), the bracket written as (n·h)²α² + |n × h|²: near
// the peak of a sharp lobe n·h is within a few ULPs of 1, and 1 − (n·h)² by subtraction
// keeps only those ULPs (at α = 1e-3, D came in steps of ~10 % and integrated to 1.018
// instead of 1 in an f32 emulation: a light-sampled mirror reflection 2 % too bright). The
// cross product keeps every digit (0.99998, as in f64).
fn ggx_d(n: vec3<f32>, h: vec3<f32>, alpha: f32) -> f32 {
    let a2 = alpha * alpha;
    let n_dot_h = max(dot(n, h), 0.0);
    let c = cross(n, h);
    let d = n_dot_h * n_dot_h * a2 + dot(c, c);
    return a2 / (PI * d * d);
}

// Height-correlated Smith visibility G2 / (4 N·L N·V).
fn ggx_visibility(n_dot_l: f32, n_dot_v: f32, alpha: f32) -> f32 {
    let a2 = alpha * alpha;
    let gv = n_dot_l * sqrt(n_dot_v * n_dot_v * (1.0 - a2) + a2);
    let gl = n_dot_v * sqrt(n_dot_l * n_dot_l * (1.0 - a2) + a2);
    return 0.5 / max(gv + gl, 1e-20);
}

fn ggx_g1(n_dot_v: f32, alpha: f32) -> f32 {
    let a2 = alpha * alpha;
    return 2.0 * n_dot_v / (n_dot_v + sqrt(a2 + (1.0 - a2) * n_dot_v * n_dot_v));
}

// Visible-normal sampling (Heitz 2018) in the local frame where the normal is +Z.
fn sample_ggx_vndf(wo: vec3<f32>, alpha: f32, u: vec2<f32>) -> vec3<f32> {
    let vh = normalize(vec3<f32>(alpha * wo.x, alpha * wo.y, wo.z));
    let lensq = vh.x * vh.x + vh.y * vh.y;
    let t1 = select(vec3<f32>(1.0, 0.0, 0.0), vec3<f32>(-vh.y, vh.x, 0.0) * inverseSqrt(lensq), lensq > 1e-20);
    let t2 = cross(vh, t1);
    let r = sqrt(u.x);
    let phi = 2.0 * PI * u.y;
    let p1 = r * cos(phi);
    let s = 0.5 * (1.0 + vh.z);
    let p2 = (1.0 - s) * sqrt(max(1.0 - p1 * p1, 0.0)) + s * r * sin(phi);
    let nh = p1 * t1 + p2 * t2 + sqrt(max(0.0, 1.0 - p1 * p1 - p2 * p2)) * vh;
    return normalize(vec3<f32>(alpha * nh.x, alpha * nh.y, max(nh.z, 1e-6)));
}

// Solid-angle pdf of a reflected direction under VNDF sampling: D · G1(wo) / (4 N·V).
fn ggx_vndf_pdf(n: vec3<f32>, h: vec3<f32>, n_dot_v: f32, alpha: f32) -> f32 {
    return ggx_d(n, h, alpha) * ggx_g1(n_dot_v, alpha) / (4.0 * n_dot_v);
}

fn eval_specular_lobes(b: Brdf, n: vec3<f32>, wo: vec3<f32>, wi: vec3<f32>) -> vec3<f32> {
    let n_dot_l = dot(n, wi);
    let n_dot_v = dot(n, wo);
    let h = normalize(wo + wi);
    let v_dot_h = max(dot(wo, h), 0.0);
    let fw = schlick_weight(v_dot_h);
    let dielectric_f = dielectric_fresnel(b.specular, v_dot_h);
    let diffuse = (1.0 - b.metallic) * (1.0 - dielectric_f) * eval_diffuse(b);
    let spec_color = (1.0 - b.metallic) * vec3<f32>(dielectric_f) + b.metallic * (b.base_color + (1.0 - b.base_color) * fw);
    let spec = spec_color * ggx_d(n, h, b.alpha) * ggx_visibility(n_dot_l, n_dot_v, b.alpha);
    return diffuse + spec;
}
#endif

// fr(wo, wi) without the cosine. Zero below either hemisphere.
fn eval_brdf(b: Brdf, n: vec3<f32>, wo: vec3<f32>, wi: vec3<f32>) -> vec3<f32> {
    if dot(n, wi) <= 0.0 || dot(n, wo) <= 0.0 {
        return vec3<f32>(0.0);
    }
#ifdef SPECULAR
    return eval_specular_lobes(b, n, wo, wi);
#else
    return eval_diffuse(b);
#endif
}

// Probability of sampling the diffuse lobe; exactly 1 when there is no specular lobe and
// 0 when the diffuse lobe is black (a glass layer's reflection, layer_walk.wgsl: every
// sample then lands in the specular lobe, so a smooth pane's highlight is noise-free).
fn diffuse_lobe_probability(b: Brdf) -> f32 {
#ifdef SPECULAR
    let w_spec = b.metallic + (1.0 - b.metallic) * b.specular * 0.25;
    let diffuse_luminance = luminance(b.base_color);
    let w_diff = (1.0 - b.metallic) * select(0.0, max(diffuse_luminance, 0.05), diffuse_luminance > 0.0);
    if w_spec <= 0.0 {
        return 1.0;
    }
    return w_diff / (w_diff + w_spec);
#else
    return 1.0;
#endif
}

fn brdf_pdf(b: Brdf, n: vec3<f32>, wo: vec3<f32>, wi: vec3<f32>) -> f32 {
    let n_dot_l = dot(n, wi);
    let n_dot_v = dot(n, wo);
    if n_dot_l <= 0.0 || n_dot_v <= 0.0 {
        return 0.0;
    }
    let pd = diffuse_lobe_probability(b);
    var pdf = pd * n_dot_l * INV_PI;
#ifdef SPECULAR
    if pd < 1.0 {
        let h = normalize(wo + wi);
        pdf += (1.0 - pd) * ggx_vndf_pdf(n, h, n_dot_v, b.alpha);
    }
#endif
    return pdf;
}

fn sample_brdf(b: Brdf, n: vec3<f32>, wo: vec3<f32>, u: vec3<f32>) -> BrdfSample {
    let frame_m = basis_from_normal(n);
    let pd = diffuse_lobe_probability(b);
    var wi: vec3<f32>;
    if u.z < pd {
        // Cosine-weighted hemisphere.
        let r = sqrt(u.x);
        let phi = 2.0 * PI * u.y;
        let local = vec3<f32>(r * cos(phi), r * sin(phi), sqrt(max(0.0, 1.0 - u.x)));
        wi = frame_m * local;
    } else {
#ifdef SPECULAR
        let wo_local = transpose(frame_m) * wo;
        let h = frame_m * sample_ggx_vndf(wo_local, b.alpha, u.xy);
        wi = reflect(-wo, h);
#else
        wi = n;
#endif
    }
    return BrdfSample(wi, brdf_pdf(b, n, wo, wi));
}
