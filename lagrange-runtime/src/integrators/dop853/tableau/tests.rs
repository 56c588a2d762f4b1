use super::*;

/// A rooted tree, as the list of the subtrees hanging from its root.
#[derive(Clone, Debug)]
struct Tree(Vec<Tree>);

impl Tree {
    fn order(&self) -> usize {
        1 + self.0.iter().map(Tree::order).sum::<usize>()
    }

    /// `γ(t)`: the condition for tree `t` reads `Σ b_i Φ_i(t) = 1/γ(t)`.
    fn density(&self) -> f64 {
        self.order() as f64 * self.0.iter().map(Tree::density).product::<f64>()
    }

    /// The elementary weights `Φ_i(t)` for the stages of `a`.
    fn weights(&self, a: &[[f64; 16]; 16]) -> [f64; 16] {
        let mut phi = [1.0; 16];
        for child in &self.0 {
            let inner = child.weights(a);
            for (phi_i, a_i) in phi.iter_mut().zip(a) {
                *phi_i *= a_i.iter().zip(&inner).map(|(a, p)| a * p).sum::<f64>();
            }
        }
        phi
    }
}

/// All rooted trees with 1 to `max` vertices, grouped by order.
fn trees_up_to(max: usize) -> Vec<Vec<Tree>> {
    /// Extends `current` by multisets of `smaller[start..]` (taken in
    /// non-decreasing index order, so each multiset once) of total order
    /// `remaining`.
    fn extend(
        smaller: &[Tree],
        start: usize,
        remaining: usize,
        current: &mut Vec<Tree>,
        found: &mut Vec<Tree>,
    ) {
        if remaining == 0 {
            found.push(Tree(current.clone()));
            return;
        }
        for (i, tree) in smaller.iter().enumerate().skip(start) {
            if tree.order() <= remaining {
                current.push(tree.clone());
                extend(smaller, i, remaining - tree.order(), current, found);
                current.pop();
            }
        }
    }
    let mut by_order = vec![vec![Tree(vec![])]];
    for order in 2..=max {
        let smaller: Vec<Tree> = by_order.iter().flatten().cloned().collect();
        let mut found = Vec::new();
        extend(&smaller, 0, order - 1, &mut Vec::new(), &mut found);
        by_order.push(found);
    }
    by_order
}

fn full_a(absolute: bool) -> [[f64; 16]; 16] {
    let mut a = [[0.0; 16]; 16];
    for (row, coefficients) in a.iter_mut().zip(A) {
        for (a, &c) in row.iter_mut().zip(coefficients) {
            *a = if absolute { c.abs() } else { c };
        }
    }
    a
}

fn padded(weights: &[f64]) -> [f64; 16] {
    let mut w = [0.0; 16];
    w[..weights.len()].copy_from_slice(weights);
    w
}

/// `Σ w_i Φ_i(t) − target` over the trees of the given orders, each with
/// the largest value rounding can explain: every coefficient carries up
/// to ε/2 from its decimal, each term of `Σ w_i Φ_i` is a product of at
/// most 8 of them, and `Φ` sums at most 16 terms at each of at most 7
/// levels, so |rounding| ≤ (8/2 + 16·7 + 16) ε Σ |w_i| Φ_i(|A|) ≲ 132 ε·M
/// (M at least 1, for the rounding of the target 1/γ ≤ 1 itself). We
/// allow 200 ε·M: a coefficient off by 1e-12 relative already fails.
fn check(
    what: &str,
    w: &[f64; 16],
    orders: std::ops::RangeInclusive<usize>,
    target: impl Fn(&Tree) -> f64,
) {
    let (a, a_abs) = (full_a(false), full_a(true));
    for tree in trees_up_to(*orders.end()).iter().flatten() {
        if !orders.contains(&tree.order()) {
            continue;
        }
        let phi = tree.weights(&a);
        let phi_abs = tree.weights(&a_abs);
        let value: f64 = w.iter().zip(&phi).map(|(w, p)| w * p).sum();
        let magnitude: f64 = w.iter().zip(&phi_abs).map(|(w, p)| w.abs() * p).sum();
        let residual = value - target(tree);
        let bound = 200.0 * f64::EPSILON * magnitude.max(1.0);
        assert!(
            residual.abs() <= bound,
            "{what}: tree {tree:?} (order {}) misses by {residual:e} (rounding bound {bound:e})",
            tree.order()
        );
    }
}

#[test]
fn tree_generator_finds_the_200_rooted_trees_up_to_order_8() {
    let counts: Vec<usize> = trees_up_to(8).iter().map(Vec::len).collect();
    assert_eq!(counts, [1, 1, 2, 4, 9, 20, 48, 115]);
}

#[test]
fn nodes_are_the_row_sums_of_a() {
    for (i, (row, c)) in A.iter().zip(C).enumerate().skip(1) {
        let sum: f64 = row.iter().sum();
        let magnitude: f64 = row.iter().map(|a| a.abs()).sum();
        // A sum of at most 15 rounded terms: ≤ 16 ε Σ |a_ij|.
        assert!(
            (sum - c).abs() <= 16.0 * f64::EPSILON * magnitude,
            "stage {}: Σ a = {sum}, c = {c}",
            i + 1
        );
    }
}

#[test]
fn weights_satisfy_all_200_conditions_of_order_8() {
    check("b", &padded(&B), 1..=8, |t| 1.0 / t.density());
}

#[test]
fn stage_13_is_the_new_state() {
    assert_eq!(A[12], B);
    assert_eq!(C[12], 1.0);
}

#[test]
fn fifth_order_estimate_vanishes_up_to_order_5_and_not_beyond() {
    // b − er is a fifth-order solution, so er annihilates every tree of
    // order ≤ 5 ...
    check("er", &padded(&ER), 1..=5, |_| 0.0);
    // ... and it estimates a sixth-order error, so not all of order 6.
    let a = full_a(false);
    let largest = trees_up_to(6)[5]
        .iter()
        .map(|t| {
            padded(&ER)
                .iter()
                .zip(t.weights(&a))
                .map(|(e, p)| e * p)
                .sum::<f64>()
        })
        .fold(0.0, |m: f64, r| m.max(r.abs()));
    assert!(largest > 1e-6, "er annihilates order 6 too ({largest:e})");
}

#[test]
fn third_order_weights_satisfy_the_conditions_of_order_3() {
    check("bhh", &padded(&BHH), 1..=3, |t| 1.0 / t.density());
}

#[test]
fn continuous_extension_is_of_order_7_across_the_step() {
    // Hairer's contd8 is y0 + θ(r2 + (1−θ)(r3 + θ(r4 + (1−θ)(r5 + θ(r6
    // + (1−θ)(r7 + θ r8)))))), with r2 = h Σ b k, r3 = h k1 − r2,
    // r4 = r2 − h k13 − r3 and r5..r8 = h Σ d k: per stage, weights
    // polynomial in θ. Order 7 means Σ w_i(θ) Φ_i(t) = θ^|t| / γ(t).
    let b = padded(&B);
    let e = |i: usize| {
        let mut e = [0.0; 16];
        e[i - 1] = 1.0;
        e
    };
    let (e1, e13) = (e(1), e(13));
    for theta in [0.1, 0.3, 0.5, 0.7, 0.9] {
        let s1 = 1.0 - theta;
        let w: [f64; 16] = std::array::from_fn(|i| {
            let (r2, r3) = (b[i], e1[i] - b[i]);
            let r4 = r2 - e13[i] - r3;
            let [r5, r6, r7, r8] = [D[0][i], D[1][i], D[2][i], D[3][i]];
            theta
                * (r2
                    + s1 * (r3 + theta * (r4 + s1 * (r5 + theta * (r6 + s1 * (r7 + theta * r8))))))
        });
        check(&format!("dense output at θ = {theta}"), &w, 1..=7, |t| {
            theta.powi(t.order() as i32) / t.density()
        });
    }
}
