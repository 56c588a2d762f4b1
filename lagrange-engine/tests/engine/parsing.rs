//! The expression parser on its own: precedence, indices and sums, method
//! syntax, as `show` prints the parsed tree with every grouping explicit.

use lagrange_engine::ast::{BinOp, Expr};
use lagrange_engine::parse::expression::parse_expr;
use syn::parse::Parser;

fn expr(src: &str) -> Expr {
    parse_expr.parse_str(src).unwrap()
}

fn show(e: &Expr) -> String {
    match e {
        Expr::Num { value, .. } => format!("{value}"),
        Expr::Name(n) => n.to_string(),
        Expr::Neg { inner, .. } => format!("(-{})", show(inner)),
        Expr::Chain { first, rest, .. } => {
            let mut out = show(first);
            for (op, x) in rest {
                let o = match op {
                    BinOp::Add => "+",
                    BinOp::Sub => "-",
                    BinOp::Mul => "*",
                    BinOp::Div => "/",
                };
                out = format!("({out} {o} {})", show(x));
            }
            out
        }
        Expr::Power { base, exponent, .. } => format!("({} ^ {})", show(base), show(exponent)),
        Expr::Call { func, args, .. } => {
            let a: Vec<String> = args.iter().map(show).collect();
            format!("{func}({})", a.join(", "))
        }
        Expr::Index { base, index, .. } => format!("{base}[{}]", show(index)),
        Expr::Sum { index, body, .. } => format!(
            "sum({} in {}{}{}, {})",
            index.var,
            show(&index.lo),
            if index.inclusive { "..=" } else { ".." },
            show(&index.hi),
            show(body)
        ),
    }
}

#[test]
fn power_binds_tighter_than_unary_minus_and_product() {
    assert_eq!(show(&expr("-x^2")), "(-(x ^ 2))");
    assert_eq!(show(&expr("a*b^2")), "(a * (b ^ 2))");
    assert_eq!(show(&expr("x^-1")), "(x ^ (-1))");
    assert_eq!(show(&expr("a^b^c")), "(a ^ (b ^ c))");
    assert_eq!(show(&expr("m1/2*(x + y)")), "((m1 / 2) * (x + y))");
    assert_eq!(show(&expr("a - b - c")), "((a - b) - c)");
}

#[test]
fn indices_and_sums() {
    assert_eq!(show(&expr("x[i-1]^2")), "(x[(i - 1)] ^ 2)");
    assert_eq!(
        show(&expr("sum(j in 0..=i, l[j]*sin(theta[j]))")),
        "sum(j in 0..=i, (l[j] * sin(theta[j])))"
    );
    assert_eq!(
        show(&expr("-sum(j in i+1..N, m[j])")),
        "(-sum(j in (i + 1)..N, m[j]))"
    );
}

#[test]
fn method_syntax_is_a_call_with_the_receiver_first() {
    assert_eq!(show(&expr("x.sin()")), "sin(x)");
    assert_eq!(show(&expr("(a - b).cos()")), "cos((a - b))");
    assert_eq!(show(&expr("x.powi(2) * 2.0")), "(powi(x, 2) * 2)");
    assert_eq!(show(&expr("y.atan2(x)")), "atan2(y, x)");
}
