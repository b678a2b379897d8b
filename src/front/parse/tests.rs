use super::*;

fn deep_cases(n: usize) -> Vec<(&'static str, String)> {
    vec![
        (
            "parens",
            format!("x = {}1{};", "(".repeat(n), ")".repeat(n)),
        ),
        (
            "brackets",
            format!("x = {}1{};", "[".repeat(n), "]".repeat(n)),
        ),
        (
            "calls",
            format!("x = {}1{};", "f(".repeat(n), ")".repeat(n)),
        ),
        ("ternary", format!("x = {}1;", "a ? b : ".repeat(n))),
        ("lets", format!("x = {}1;", "let (a = 1) ".repeat(n))),
        (
            "instances",
            format!("{}cube();", "translate([1,0,0]) ".repeat(n)),
        ),
        (
            "elseif",
            format!("{}cube();", "if (a) cube(); else ".repeat(n)),
        ),
        ("blocks", format!("{}{}", "{".repeat(n), "}".repeat(n))),
        ("lc_for", format!("x = [{}1];", "for (i = a) ".repeat(n))),
        ("sum", format!("x = 1{};", "+1".repeat(n))),
        ("modules", format!("{} cube();", "module m() ".repeat(n))),
    ]
}

#[test]
fn explore_stack() {
    for n in [490, 100000] {
        let handle = std::thread::Builder::new()
            .stack_size(2 << 20)
            .spawn(move || {
                for (name, src) in deep_cases(n) {
                    let t = std::time::Instant::now();
                    let r = parse_program(0, &src);
                    println!(
                        "n={n} {name}: {} in {:?}",
                        match &r {
                            Ok(_) => "ok".to_string(),
                            Err(e) => e.message.clone(),
                        },
                        t.elapsed()
                    );
                }
            })
            .unwrap();
        handle.join().unwrap();
    }
}
