//! The shape that keeps first frames fast on a CPU driver (docs/src/compile-time.md):
//! lavapipe inlines every call before LLVM compiles a pass, and LLVM's time grows faster
//! than the inlined size, so the traversal and the texture lookup, the largest functions,
//! are called from as few places as possible. These budgets count their inlined copies in
//! each pass for the general effect set (every code path compiled in). A budget is raised
//! only with a `bench-load` measurement beside it. No GPU needed.

use std::collections::{BTreeMap, HashMap};

use naga::{Block, Function, Handle, Statement};
use restir_render::effects::EffectSet;
use restir_render::shader_source::compose;

/// How many copies of each function the entry point holds once every call is inlined.
fn inlined_copies(module: &naga::Module) -> BTreeMap<String, usize> {
    fn calls(block: &Block, out: &mut Vec<Handle<Function>>) {
        for statement in block.iter() {
            match statement {
                Statement::Call { function, .. } => out.push(*function),
                Statement::Block(b) => calls(b, out),
                Statement::If { accept, reject, .. } => {
                    calls(accept, out);
                    calls(reject, out);
                }
                Statement::Switch { cases, .. } => cases.iter().for_each(|c| calls(&c.body, out)),
                Statement::Loop {
                    body, continuing, ..
                } => {
                    calls(body, out);
                    calls(continuing, out);
                }
                _ => {}
            }
        }
    }
    let callees: HashMap<Handle<Function>, Vec<Handle<Function>>> = module
        .functions
        .iter()
        .map(|(h, f)| {
            let mut out = Vec::new();
            calls(&f.body, &mut out);
            (h, out)
        })
        .collect();
    fn visit(
        h: Handle<Function>,
        callees: &HashMap<Handle<Function>, Vec<Handle<Function>>>,
        copies: &mut HashMap<Handle<Function>, usize>,
    ) {
        *copies.entry(h).or_default() += 1;
        for &c in &callees[&h] {
            visit(c, callees, copies);
        }
    }
    let mut copies = HashMap::new();
    let mut top = Vec::new();
    calls(&module.entry_points[0].function.body, &mut top);
    for h in top {
        visit(h, &callees, &mut copies);
    }
    copies
        .into_iter()
        .map(|(h, n)| (module.functions[h].name.clone().unwrap_or_default(), n))
        .collect()
}

fn copies_in(pass_shader: &str, function: &str) -> usize {
    let source = compose(pass_shader, &EffectSet::all().defines()).unwrap();
    let module = naga::front::wgsl::parse_str(&source).unwrap();
    inlined_copies(&module).get(function).copied().unwrap_or(0)
}

/// (shader, copies of `trace`, copies of `sample_texture`) for the general effect set,
/// counted before the driver folds constants (a copy in a branch a pass never takes still
/// counts). Making the shapes one call site each cut bench-load's compile of StainedGlassLamp
/// from minutes to about half a minute (docs/src/measured/compile-and-load.md "Compile time",
/// with the data).
const BUDGETS: &[(&str, usize, usize)] = &[
    ("gbuffer_resolve.wgsl", 3, 32),
    ("lights/presample_lights.wgsl", 0, 1),
    ("di/initial.wgsl", 2, 13),
    ("di/temporal.wgsl", 1, 9),
    ("di/spatial.wgsl", 1, 7),
    ("di/shade.wgsl", 1, 5),
    ("di/mutation.wgsl", 1, 7),
    ("reference.wgsl", 5, 48),
    ("gi/initial.wgsl", 2, 19),
    ("gi/temporal.wgsl", 2, 8),
    ("gi/spatial.wgsl", 2, 8),
    ("pt/initial.wgsl", 3, 33),
    ("pt/temporal.wgsl", 5, 45),
    ("pt/spatial.wgsl", 5, 45),
    ("ray_bench.wgsl", 2, 9),
];

#[test]
fn each_pass_inlines_the_traversal_and_texture_lookup_within_its_budget() {
    let mut over = Vec::new();
    for &(shader, traces, lookups) in BUDGETS {
        let t = copies_in(shader, "trace");
        let l = copies_in(shader, "sample_texture");
        if t > traces || l > lookups {
            over.push(format!(
                "{shader}: {t} traversals (budget {traces}), {l} texture lookups (budget {lookups})"
            ));
        }
    }
    assert!(over.is_empty(), "over budget:\n{}", over.join("\n"));
    // Every pass that traces rays is budgeted.
    for pass in restir_render::passes::ALL {
        if copies_in(pass.shader, "trace") > 0 {
            assert!(
                BUDGETS.iter().any(|b| b.0 == pass.shader),
                "{} traces rays but has no budget here",
                pass.shader
            );
        }
    }
}

/// The counter has power: a second call site is a second copy, a loop around one call site
/// is still one (planted: the shape the passes had before, one trace per branch).
#[test]
fn the_counter_counts_call_sites_not_calls() {
    let module = |body: &str| {
        let src = format!(
            "fn leaf(x: f32) -> f32 {{ return x * 2.0; }}\n\
             fn mid(x: f32) -> f32 {{ return leaf(x) + leaf(x + 1.0); }}\n\
             @compute @workgroup_size(1) fn main() {{ var a = 0.0; {body} }}"
        );
        naga::front::wgsl::parse_str(&src).unwrap()
    };
    let one_site = module("for (var i = 0u; i < 4u; i++) { a += mid(a); }");
    assert_eq!(inlined_copies(&one_site)["mid"], 1);
    assert_eq!(inlined_copies(&one_site)["leaf"], 2);
    let planted = module("if a > 0.0 { a = mid(a); } else { a = mid(-a); }");
    assert_eq!(inlined_copies(&planted)["mid"], 2);
    assert_eq!(inlined_copies(&planted)["leaf"], 4);
}
