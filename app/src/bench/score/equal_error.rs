//! Equal-error cost (docs/src/measured/how-the-bench-measures.md, "Equal error"): with `--knob
//! NAME=V1,V2,...` every configuration runs once per value of its quality knob (light
//! candidates, say), giving a curve of per-frame error against cost. The cost at which each
//! curve reaches a target error, read off the curve, compares configurations where "MSE × ms"
//! cannot: a denoised image whose error stops falling (a bias or blur floor) does not trade
//! error for time at the 1/time rate that product assumes. Costs are stated twice: lavapipe's
//! (or the GPU's) milliseconds, and a hardware-neutral count (shadow rays and light candidates
//! per pixel). The error is the estimator's: the reference's own noise σ comes out in
//! quadrature (a frame scored against a noisy reference reads √(RMSE² + σ²)). The files and the
//! results.md section are written by write/cost_curves.rs.

use super::result::ConfigResult;

/// One run of a configuration at one knob value.
#[derive(Clone, Debug, PartialEq)]
pub struct CostPoint {
    pub knob: String,
    /// Median frame time: the mean of the seeds' medians where there are several.
    pub ms: f64,
    /// Each seed's median frame time, in seed order (empty where unknown: one seed, or a
    /// `cost_curves.csv` written before they were kept).
    pub seed_ms: Vec<f64>,
    pub rays_per_pixel: f64,
    pub candidates_per_pixel: f64,
    /// Per-frame luma RMSE (mean over seeds where there are several), the reference's own
    /// noise taken out; NaN where that noise is as large as the error (no reading).
    pub rmse: f64,
    /// Its 95 % half-width over the seeds (infinite with one seed).
    pub rmse_ci95: f64,
}

/// Where a curve meets the target error.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Reach {
    /// Between two measured points: the costs there, interpolated in log-log.
    At(Cost),
    /// The cheapest point is already at or below the target: at most its cost.
    AtMost(Cost),
    /// No point reaches the target: more than the dearest point's cost.
    Beyond(Cost),
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cost {
    pub ms: f64,
    pub rays_per_pixel: f64,
    pub candidates_per_pixel: f64,
}

impl Reach {
    pub fn cost(&self) -> Cost {
        match *self {
            Reach::At(c) | Reach::AtMost(c) | Reach::Beyond(c) => c,
        }
    }

    /// The `reach` column of `equal_error.csv` and `map.csv`.
    pub fn code(&self) -> &'static str {
        match self {
            Reach::At(_) => "interpolated",
            Reach::AtMost(_) => "at_most",
            Reach::Beyond(_) => "beyond",
        }
    }
}

fn cost_of(p: &CostPoint) -> Cost {
    Cost {
        ms: p.ms,
        rays_per_pixel: p.rays_per_pixel,
        candidates_per_pixel: p.candidates_per_pixel,
    }
}

/// The points of a curve in its own order: by knob value where every value is a number
/// (each knob the bench sweeps buys quality with work as it grows), else as given (the
/// `--knob` order). Not by measured time: on a loaded machine two neighbouring values'
/// times can swap, and a curve read in time order then meets the target elsewhere (two
/// identical runs read `≤ 1.00×` and `1.00×`).
pub fn in_knob_order<'a>(points: impl IntoIterator<Item = &'a CostPoint>) -> Vec<&'a CostPoint> {
    let mut ordered: Vec<&CostPoint> = points.into_iter().collect();
    let values: Option<Vec<f64>> = ordered.iter().map(|p| p.knob.trim().parse().ok()).collect();
    if values.is_some() {
        // A stable sort: equal values keep their order.
        ordered.sort_by(|a, b| {
            let v = |p: &CostPoint| p.knob.trim().parse::<f64>().unwrap_or(f64::NAN);
            v(a).total_cmp(&v(b))
        });
    }
    ordered
}

/// The cost at which `points` first reach `target` along the curve, from its cheapest
/// knob value to its dearest (`in_knob_order`): between the last point above and the first
/// at or below it, log(error) linear in log(ms) (error falls as a power of the work on such
/// curves, a straight line there), the neutral costs interpolated at the same place. None
/// without a usable point or target.
pub fn cost_at(points: &[CostPoint], target: f64) -> Option<Reach> {
    // Points without a reading (an error the reference's noise swallows, no time) are
    // left out.
    let curve = in_knob_order(
        points
            .iter()
            .filter(|p| p.ms > 0.0 && p.rmse > 0.0 && p.ms.is_finite() && p.rmse.is_finite()),
    );
    if curve.is_empty() || !(target > 0.0 && target.is_finite()) {
        return None;
    }
    if curve[0].rmse <= target {
        return Some(Reach::AtMost(cost_of(curve[0])));
    }
    for pair in curve.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        if b.rmse <= target && a.rmse > target {
            let t = (target.ln() - a.rmse.ln()) / (b.rmse.ln() - a.rmse.ln());
            let lerp = |x: f64, y: f64| x + t * (y - x);
            return Some(Reach::At(Cost {
                ms: (lerp(a.ms.ln(), b.ms.ln())).exp(),
                rays_per_pixel: lerp(a.rays_per_pixel, b.rays_per_pixel),
                candidates_per_pixel: lerp(a.candidates_per_pixel, b.candidates_per_pixel),
            }));
        }
    }
    Some(Reach::Beyond(cost_of(curve[curve.len() - 1])))
}

/// A configuration's curve: its name without the knob, and its points in `--knob` order.
pub struct Curve {
    pub name: String,
    pub points: Vec<CostPoint>,
}

/// The estimator's error from one measured against a reference of per-pixel noise
/// `noise`: √(RMSE² − σ²); NaN where the noise is not smaller than the error.
pub fn without_reference_noise(rmse: f64, noise: f64) -> f64 {
    let d = rmse * rmse - noise * noise;
    if d > 0.0 { d.sqrt() } else { f64::NAN }
}

/// Groups the results of a `--knob` bench into curves: `CONFIG[NAME=V]` → curve CONFIG;
/// `noise[i]` is the own noise of result i's reference.
pub fn curves(results: &[ConfigResult], noise: &[f64], knob_name: &str) -> Vec<Curve> {
    let mut curves: Vec<Curve> = Vec::new();
    for (r, &noise) in results.iter().zip(noise) {
        let Some((name, knob)) = split_knob(&r.config.name, knob_name) else {
            continue;
        };
        let (rmse, rmse_ci95) = match (&r.over_seeds, &r.scores) {
            (Some(f), _) => (f.frame_luma_rmse.mean, f.frame_luma_rmse.half_width),
            (None, Some(s)) => (s.mean_luma_rmse, f64::INFINITY),
            _ => continue,
        };
        let seed_ms = if r.seed_frame_ms.len() > 1 {
            r.seed_frame_ms.clone()
        } else {
            Vec::new()
        };
        let ms = if seed_ms.is_empty() {
            r.median_frame_ms().unwrap_or(f64::NAN)
        } else {
            seed_ms.iter().sum::<f64>() / seed_ms.len() as f64
        };
        let point = CostPoint {
            knob,
            ms,
            seed_ms,
            rays_per_pixel: r.times.shadow_rays_per_pixel_total,
            candidates_per_pixel: r.times.light_candidates_per_pixel,
            rmse: without_reference_noise(rmse, noise),
            rmse_ci95,
        };
        match curves.iter_mut().find(|c| c.name == name) {
            Some(c) => c.points.push(point),
            None => curves.push(Curve {
                name,
                points: vec![point],
            }),
        }
    }
    curves
}

/// `CONFIG[a=1;NAME=V;b=2]` → (`CONFIG[a=1;b=2]`, `V`): a point's curve and knob value.
pub fn split_knob(config: &str, knob_name: &str) -> Option<(String, String)> {
    let open = config.find('[')?;
    let inner = config[open + 1..].strip_suffix(']')?;
    let mut value = None;
    let rest: Vec<&str> = inner
        .split(';')
        .filter(|a| match a.split_once('=') {
            Some((k, v)) if k.trim() == knob_name => {
                value = Some(v.trim().to_string());
                false
            }
            _ => true,
        })
        .collect();
    let base = &config[..open];
    let name = if rest.is_empty() {
        base.to_string()
    } else {
        format!("{base}[{}]", rest.join(";"))
    };
    Some((name, value?))
}

/// The target error: `--target-rmse`, else the first curve's error at its middle knob
/// value (a level every configuration can be asked to reach within the sweep).
pub fn default_target(curves: &[Curve]) -> Option<f64> {
    let first = curves.first()?;
    first.points.get(first.points.len() / 2).map(|p| p.rmse)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(ms: f64, rmse: f64) -> CostPoint {
        CostPoint {
            knob: format!("{ms}"),
            ms,
            seed_ms: Vec::new(),
            rays_per_pixel: ms,
            candidates_per_pixel: 2.0 * ms,
            rmse,
            rmse_ci95: 0.0,
        }
    }

    #[test]
    fn the_cost_at_a_target_is_read_off_a_power_law_curve_exactly() {
        // rmse = ms^-1/2: a Monte Carlo curve. The target 0.25 is reached at 16 ms.
        let curve: Vec<CostPoint> = [1.0, 4.0, 64.0, 256.0]
            .iter()
            .map(|&ms: &f64| point(ms, ms.powf(-0.5)))
            .collect();
        let Some(Reach::At(c)) = cost_at(&curve, 0.25) else {
            panic!("{:?}", cost_at(&curve, 0.25));
        };
        assert!((c.ms - 16.0).abs() < 1e-9, "{}", c.ms);
        // Neutral costs interpolate at the same place: halfway in log between 4 and 64.
        assert!((c.rays_per_pixel - 34.0).abs() < 1e-9);
        assert!((c.candidates_per_pixel - 68.0).abs() < 1e-9);
        // Order of the points does not matter: they are read in knob order.
        let mut shuffled = curve.clone();
        shuffled.reverse();
        assert_eq!(cost_at(&shuffled, 0.25), cost_at(&curve, 0.25));
    }

    #[test]
    fn a_curve_is_read_in_knob_order_even_where_two_times_swapped() {
        // Knob 8, 16, 32; a loaded machine timed 16 slower than 32. Read in time order
        // (8, 32, 16) the curve crosses 0.2 between 8 and 32; along the knob it does so
        // between 16 and 32.
        let at = |knob: &str, ms: f64, rmse: f64| CostPoint {
            knob: knob.into(),
            ..point(ms, rmse)
        };
        let curve = vec![
            at("8", 80.0, 0.3),
            at("16", 100.0, 0.25),
            at("32", 90.0, 0.16),
        ];
        let Some(Reach::At(c)) = cost_at(&curve, 0.2) else {
            panic!("{:?}", cost_at(&curve, 0.2));
        };
        // log ms linear in log error between 16 (100 ms) and 32 (90 ms).
        let t = (0.2f64.ln() - 0.25f64.ln()) / (0.16f64.ln() - 0.25f64.ln());
        let expected = (100f64.ln() + t * (90f64.ln() - 100f64.ln())).exp();
        assert!((c.ms - expected).abs() < 1e-9, "{} vs {expected}", c.ms);
        // The file order does not matter either; a knob that is not a number keeps it.
        let mut reversed = curve.clone();
        reversed.reverse();
        assert_eq!(cost_at(&reversed, 0.2), cost_at(&curve, 0.2));
        let named: Vec<CostPoint> = ["low", "mid", "high"]
            .iter()
            .zip(&curve)
            .map(|(k, p)| CostPoint {
                knob: k.to_string(),
                ..p.clone()
            })
            .collect();
        assert_eq!(cost_at(&named, 0.2), cost_at(&curve, 0.2));
        // The dearest point is the curve's last, not the slowest measured.
        assert_eq!(
            cost_at(&curve, 0.1),
            Some(Reach::Beyond(cost_of(&curve[2])))
        );
    }

    #[test]
    fn targets_outside_the_curve_are_bounds_not_numbers() {
        let curve = vec![point(2.0, 0.5), point(8.0, 0.3)];
        assert_eq!(
            cost_at(&curve, 0.6),
            Some(Reach::AtMost(cost_of(&curve[0])))
        );
        // A floor: the error stops falling above the target (a denoiser's bias floor).
        assert_eq!(
            cost_at(&curve, 0.1),
            Some(Reach::Beyond(cost_of(&curve[1])))
        );
        assert_eq!(cost_at(&[], 0.1), None);
        assert_eq!(cost_at(&curve, 0.0), None);
        assert_eq!(cost_at(&[point(0.0, 0.2)], 0.1), None);
        // A point whose error the reference's noise swallows gives no reading.
        assert_eq!(cost_at(&[point(1.0, f64::NAN)], 0.1), None);
    }

    #[test]
    fn a_points_curve_is_its_name_without_the_knob() {
        let split = |c: &str| split_knob(c, "light_candidates");
        assert_eq!(
            split("ris+denoise[light_candidates=8]"),
            Some(("ris+denoise".into(), "8".into()))
        );
        assert_eq!(
            split("restir[m_cap=4;light_candidates=2]"),
            Some(("restir[m_cap=4]".into(), "2".into()))
        );
        assert_eq!(split("restir[m_cap=4]"), None);
        assert_eq!(split("restir"), None);
    }

    #[test]
    fn the_references_noise_comes_out_in_quadrature() {
        assert!((without_reference_noise(0.05, 0.03) - 0.04).abs() < 1e-12);
        assert!(without_reference_noise(0.03, 0.03).is_nan());
        assert_eq!(without_reference_noise(0.02, 0.0), 0.02);
    }
}
