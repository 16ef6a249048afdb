// Small numeric helpers used by several modules.

const PI: f32 = 3.14159265358979;
const INV_PI: f32 = 0.318309886183791;
const FLT_MAX: f32 = 3.4e38;
const ONE_MINUS_EPSILON: f32 = 0.99999994;  // the largest f32 below 1

fn luminance(c: vec3<f32>) -> f32 {
    // Rec. 709, the same weights as render/src/image.rs.
    return dot(c, vec3<f32>(0.2126, 0.7152, 0.0722));
}

fn is_finite_f32(x: f32) -> bool {
    // NaN fails every comparison; infinities exceed FLT_MAX.
    return abs(x) <= FLT_MAX;
}

fn is_finite_vec3(v: vec3<f32>) -> bool {
    return is_finite_f32(v.x) && is_finite_f32(v.y) && is_finite_f32(v.z);
}

fn safe_normalize(v: vec3<f32>, fallback: vec3<f32>) -> vec3<f32> {
    let len2 = dot(v, v);
    if !(len2 > 1e-30) || !is_finite_f32(len2) {
        return fallback;
    }
    return v * inverseSqrt(len2);
}

// Octahedral unit-vector encoding into two snorm16 (Cigolle et al. 2014).
fn oct_encode(n: vec3<f32>) -> u32 {
    let l1 = abs(n.x) + abs(n.y) + abs(n.z);
    var p = n.xy / max(l1, 1e-20);
    if n.z < 0.0 {
        let s = select(vec2<f32>(-1.0), vec2<f32>(1.0), p >= vec2<f32>(0.0));
        p = (vec2<f32>(1.0) - abs(p.yx)) * s;
    }
    return pack2x16snorm(p);
}

fn oct_decode(e: u32) -> vec3<f32> {
    let p = unpack2x16snorm(e);
    var n = vec3<f32>(p, 1.0 - abs(p.x) - abs(p.y));
    let t = max(-n.z, 0.0);
    n.x += select(t, -t, n.x >= 0.0);
    n.y += select(t, -t, n.y >= 0.0);
    return normalize(n);
}

// Orthonormal basis around n (Duff et al. 2017).
fn basis_from_normal(n: vec3<f32>) -> mat3x3<f32> {
    let s = select(-1.0, 1.0, n.z >= 0.0);
    let a = -1.0 / (s + n.z);
    let b = n.x * n.y * a;
    let t = vec3<f32>(1.0 + s * n.x * n.x * a, s * b, -s * n.x);
    let bt = vec3<f32>(b, s + n.y * n.y * a, -n.y);
    return mat3x3<f32>(t, bt, n);
}

fn srgb_to_linear(c: vec3<f32>) -> vec3<f32> {
    let lo = c / 12.92;
    let hi = pow((c + 0.055) / 1.055, vec3<f32>(2.4));
    return select(hi, lo, c <= vec3<f32>(0.04045));
}
