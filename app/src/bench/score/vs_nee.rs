//! Each configuration against `nee`, when it ran: its median frame time, its per-frame luma
//! MSE and, in equal-time mode, its running average's MSE, each as a ratio to `nee`'s.

use super::result::ConfigResult;

/// Time and MSE ratios relative to `nee` (when it ran).
pub fn compare_with_nee(results: &mut [ConfigResult]) {
    let Some(nee) = results.iter().find(|r| r.config.name == "nee").cloned() else {
        return;
    };
    let nee_ms = nee.median_frame_ms();
    let nee_frame_rmse = nee.scores.as_ref().map(|s| s.mean_luma_rmse);
    for r in results.iter_mut() {
        r.time_vs_nee = match (r.median_frame_ms(), nee_ms) {
            (Some(a), Some(b)) if b > 0.0 => Some(a / b),
            _ => None,
        };
        r.frame_mse_vs_nee = mse_ratio(r.scores.as_ref().map(|s| s.mean_luma_rmse), nee_frame_rmse);
        if r.budget.is_some() {
            r.budget_mse_vs_nee =
                mse_ratio(r.final_accumulated_rmse(), nee.final_accumulated_rmse());
        }
    }
}

/// `(error / error_of_nee)²`: the MSE ratio relative to `nee` (None without `nee` or
/// when `nee`'s error is 0).
pub fn mse_ratio(error: Option<f64>, nee_error: Option<f64>) -> Option<f64> {
    let (e, n) = (error?, nee_error?);
    (n > 0.0).then(|| (e / n).powi(2))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bench_mse_ratio_is_relative_to_nee() {
        assert_eq!(mse_ratio(Some(0.5), Some(1.0)), Some(0.25));
        assert_eq!(mse_ratio(Some(0.5), None), None);
        assert_eq!(mse_ratio(Some(0.5), Some(0.0)), None);
    }
}
