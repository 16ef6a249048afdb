//! The formula language against a small CSV, and the glob matcher.

use super::eval::glob;
use super::*;
use crate::data::Tables;

fn eval_in(csv: &str, formula: &str) -> Result<Vec<Vec<f64>>, String> {
    let dir = std::env::temp_dir().join(format!("figures-expr-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join(format!("t{}.csv", formula.len()));
    std::fs::write(&file, csv).unwrap();
    let mut tables = Tables::default();
    let mut scope = Scope {
        tables: &mut tables,
        file,
        row: None,
    };
    parse(formula)?
        .iter()
        .map(|e| scope.eval(e).map_err(|e| e.to_string()))
        .collect()
}

const CSV: &str = "config,scene,ms,rmse\nris,a,10,0.2\nrestir,a,30,0.05\nris,b,12,\n\
                   x[1],b,5,0.1\n";

#[test]
fn figures_formulas_select_rows_and_do_arithmetic() {
    let v = eval_in(CSV, "(rmse[config=restir]/rmse[config=ris, scene=a])^2").unwrap();
    assert!((v[0][0] - 0.0625).abs() < 1e-12);
    let v = eval_in(CSV, "min(ms[scene=a]), max(ms), count(ms[config!=ris])").unwrap();
    assert_eq!(v, vec![vec![10.0], vec![30.0], vec![2.0]]);
    let v = eval_in(CSV, "sum(ms[config=r*] > 11)").unwrap();
    assert_eq!(v, vec![vec![2.0]]);
    let v = eval_in(CSV, "ms[config='x[1]']").unwrap();
    assert_eq!(v, vec![vec![5.0]]);
    let v = eval_in(
        CSV,
        "first(rmse[config=ris, scene=b], ms[config=ris, scene=b]), count(ms[config=nee])",
    )
    .unwrap();
    assert_eq!(v, vec![vec![12.0], vec![0.0]]);
}

#[test]
fn figures_formulas_name_what_is_missing() {
    let e = eval_in(CSV, "rmse[config=ris, scene=b]").unwrap_err();
    assert!(e.contains("line 4, column `rmse`: empty"), "{e}");
    let e = eval_in(CSV, "rmse[config=nee]").unwrap_err();
    assert!(e.contains("no row where config=nee"), "{e}");
    let e = eval_in(CSV, "time").unwrap_err();
    assert!(
        e.contains("no column `time`") && e.contains("config, scene, ms, rmse"),
        "{e}"
    );
    assert!(parse("ms[config=ris").is_err());
    assert!(parse("ms + ").is_err());
}

#[test]
fn figures_globs_match_runs_of_characters() {
    assert!(glob("con*-static", "concourse-384x256-static"));
    assert!(!glob("con*-static", "concourse-384x256-pan"));
    assert!(glob("*", ""));
    assert!(glob("a*b*c", "aXbYc"));
}
