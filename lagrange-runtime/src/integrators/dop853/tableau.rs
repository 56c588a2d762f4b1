//! The coefficients of DOP853 (Dormand & Prince 1980, as in Hairer's
//! `dop853.f`, version of 2002), kept apart from the stepping logic because
//! they are long and only ever read.
//!
//! The digits are Hairer's, unchanged, so that each one can be checked
//! against `dop853.f`; the tests below check them all anyway, against the
//! order conditions. Stages are numbered from 1 as in the Fortran: 1–12 are
//! the step, stage 13 is `f` at the new state (its row of `A` is `B`, so the
//! dense output can refer to it like any stage), 14–16 are the extra stages
//! of the seventh-order continuous extension.
// Hairer's 30 digits, not rounded to what f64 keeps: the literals stay
// comparable with the source character by character.
#![allow(clippy::excessive_precision)]

/// The nodes `c_i` of the 16 stages.
pub(super) const C: [f64; 16] = [
    0.0,
    0.526001519587677318785587544488e-1,
    0.789002279381515978178381316732e-1,
    0.118350341907227396726757197510,
    0.281649658092772603273242802490,
    0.333333333333333333333333333333,
    0.25,
    0.307692307692307692307692307692,
    0.651282051282051282051282051282,
    0.6,
    0.857142857142857142857142857142,
    1.0,
    1.0,
    0.1,
    0.2,
    0.777777777777777777777777777778,
];

/// Row `i` holds `a_ij` for `j < i` (zeros included, so that columns line
/// up with stage numbers).
pub(super) const A: [&[f64]; 16] = [
    &[],
    // Stage 2.
    &[5.26001519587677318785587544488e-2],
    // Stage 3.
    &[
        1.97250569845378994544595329183e-2,
        5.91751709536136983633785987549e-2,
    ],
    // Stage 4.
    &[
        2.95875854768068491816892993775e-2,
        0.0,
        8.87627564304205475450678981324e-2,
    ],
    // Stage 5.
    &[
        2.41365134159266685502369798665e-1,
        0.0,
        -8.84549479328286085344864962717e-1,
        9.24834003261792003115737966543e-1,
    ],
    // Stage 6.
    &[
        3.7037037037037037037037037037e-2,
        0.0,
        0.0,
        1.70828608729473871279604482173e-1,
        1.25467687566822425016691814123e-1,
    ],
    // Stage 7.
    &[
        3.7109375e-2,
        0.0,
        0.0,
        1.70252211019544039314978060272e-1,
        6.02165389804559606850219397283e-2,
        -1.7578125e-2,
    ],
    // Stage 8.
    &[
        3.70920001185047927108779319836e-2,
        0.0,
        0.0,
        1.70383925712239993810214054705e-1,
        1.07262030446373284651809199168e-1,
        -1.53194377486244017527936158236e-2,
        8.27378916381402288758473766002e-3,
    ],
    // Stage 9.
    &[
        6.24110958716075717114429577812e-1,
        0.0,
        0.0,
        -3.36089262944694129406857109825,
        -8.68219346841726006818189891453e-1,
        2.75920996994467083049415600797e1,
        2.01540675504778934086186788979e1,
        -4.34898841810699588477366255144e1,
    ],
    // Stage 10.
    &[
        4.77662536438264365890433908527e-1,
        0.0,
        0.0,
        -2.48811461997166764192642586468,
        -5.90290826836842996371446475743e-1,
        2.12300514481811942347288949897e1,
        1.52792336328824235832596922938e1,
        -3.32882109689848629194453265587e1,
        -2.03312017085086261358222928593e-2,
    ],
    // Stage 11.
    &[
        -9.3714243008598732571704021658e-1,
        0.0,
        0.0,
        5.18637242884406370830023853209,
        1.09143734899672957818500254654,
        -8.14978701074692612513997267357,
        -1.85200656599969598641566180701e1,
        2.27394870993505042818970056734e1,
        2.49360555267965238987089396762,
        -3.0467644718982195003823669022,
    ],
    // Stage 12.
    &[
        2.27331014751653820792359768449,
        0.0,
        0.0,
        -1.05344954667372501984066689879e1,
        -2.00087205822486249909675718444,
        -1.79589318631187989172765950534e1,
        2.79488845294199600508499808837e1,
        -2.85899827713502369474065508674,
        -8.87285693353062954433549289258,
        1.23605671757943030647266201528e1,
        6.43392746015763530355970484046e-1,
    ],
    // Stage 13.
    &[
        5.42937341165687622380535766363e-2,
        0.0,
        0.0,
        0.0,
        0.0,
        4.45031289275240888144113950566,
        1.89151789931450038304281599044,
        -5.8012039600105847814672114227,
        3.1116436695781989440891606237e-1,
        -1.52160949662516078556178806805e-1,
        2.01365400804030348374776537501e-1,
        4.47106157277725905176885569043e-2,
    ],
    // Stage 14.
    &[
        5.61675022830479523392909219681e-2,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        2.53500210216624811088794765333e-1,
        -2.46239037470802489917441475441e-1,
        -1.24191423263816360469010140626e-1,
        1.5329179827876569731206322685e-1,
        8.20105229563468988491666602057e-3,
        7.56789766054569976138603589584e-3,
        -8.298e-3,
    ],
    // Stage 15.
    &[
        3.18346481635021405060768473261e-2,
        0.0,
        0.0,
        0.0,
        0.0,
        2.83009096723667755288322961402e-2,
        5.35419883074385676223797384372e-2,
        -5.49237485713909884646569340306e-2,
        0.0,
        0.0,
        -1.08347328697249322858509316994e-4,
        3.82571090835658412954920192323e-4,
        -3.40465008687404560802977114492e-4,
        1.41312443674632500278074618366e-1,
    ],
    // Stage 16.
    &[
        -4.28896301583791923408573538692e-1,
        0.0,
        0.0,
        0.0,
        0.0,
        -4.69762141536116384314449447206,
        7.68342119606259904184240953878,
        4.06898981839711007970213554331,
        3.56727187455281109270669543021e-1,
        0.0,
        0.0,
        0.0,
        -1.39902416515901462129418009734e-3,
        2.9475147891527723389556272149,
        -9.15095847217987001081870187138,
    ],
];

/// The eighth-order weights `b`, on stages 1–12.
pub(super) const B: [f64; 12] = [
    5.42937341165687622380535766363e-2,
    0.0,
    0.0,
    0.0,
    0.0,
    4.45031289275240888144113950566,
    1.89151789931450038304281599044,
    -5.8012039600105847814672114227,
    3.1116436695781989440891606237e-1,
    -1.52160949662516078556178806805e-1,
    2.01365400804030348374776537501e-1,
    4.47106157277725905176885569043e-2,
];

/// Hairer's `er`: the weights of the fifth-order error estimate
/// `h Σ er_i k_i`.
pub(super) const ER: [f64; 12] = [
    0.1312004499419488073250102996e-1,
    0.0,
    0.0,
    0.0,
    0.0,
    -0.1225156446376204440720569753e1,
    -0.4957589496572501915214079952,
    0.1664377182454986536961530415e1,
    -0.3503288487499736816886487290,
    0.3341791187130174790297318841,
    0.8192320648511571246570742613e-1,
    -0.2235530786388629525884427845e-1,
];

/// Hairer's `bhh`: a third-order solution on stages 1, 9 and 12; `b − bhh`
/// gives the third-order error estimate that tempers the fifth-order one.
pub(super) const BHH: [f64; 12] = [
    0.244094488188976377952755905512,
    0.0,
    0.0,
    0.0,
    0.0,
    0.0,
    0.0,
    0.0,
    0.733846688281611857341361741547,
    0.0,
    0.0,
    0.220588235294117647058823529412e-1,
];

/// Hairer's `d4`–`d7`: the four highest coefficients of the continuous
/// extension, on all 16 stages.
pub(super) const D: [[f64; 16]; 4] = [
    [
        -0.84289382761090128651353491142e1,
        0.0,
        0.0,
        0.0,
        0.0,
        0.56671495351937776962531783590,
        -0.30689499459498916912797304727e1,
        0.23846676565120698287728149680e1,
        0.21170345824450282767155149946e1,
        -0.87139158377797299206789907490,
        0.22404374302607882758541771650e1,
        0.63157877876946881815570249290,
        -0.88990336451333310820698117400e-1,
        0.18148505520854727256656404962e2,
        -0.91946323924783554000451984436e1,
        -0.44360363875948939664310572000e1,
    ],
    [
        0.10427508642579134603413151009e2,
        0.0,
        0.0,
        0.0,
        0.0,
        0.24228349177525818288430175319e3,
        0.16520045171727028198505394887e3,
        -0.37454675472269020279518312152e3,
        -0.22113666853125306036270938578e2,
        0.77334326684722638389603898808e1,
        -0.30674084731089398182061213626e2,
        -0.93321305264302278729567221706e1,
        0.15697238121770843886131091075e2,
        -0.31139403219565177677282850411e2,
        -0.93529243588444783865713862664e1,
        0.35816841486394083752465898540e2,
    ],
    [
        0.19985053242002433820987653617e2,
        0.0,
        0.0,
        0.0,
        0.0,
        -0.38703730874935176555105901742e3,
        -0.18917813819516756882830838328e3,
        0.52780815920542364900561016686e3,
        -0.11573902539959630126141871134e2,
        0.68812326946963000169666922661e1,
        -0.10006050966910838403183860980e1,
        0.77771377980534432092869265740,
        -0.27782057523535084065932004339e1,
        -0.60196695231264120758267380846e2,
        0.84320405506677161018159903784e2,
        0.11992291136182789328035130030e2,
    ],
    [
        -0.25693933462703749003312586129e2,
        0.0,
        0.0,
        0.0,
        0.0,
        -0.15418974869023643374053993627e3,
        -0.23152937917604549567536039109e3,
        0.35763911791061412378285349910e3,
        0.93405324183624310003907691704e2,
        -0.37458323136451633156875139351e2,
        0.10409964950896230045147246184e3,
        0.29840293426660503123344363579e2,
        -0.43533456590011143754432175058e2,
        0.96324553959188282948394950600e2,
        -0.39177261675615439165231486172e2,
        -0.14972683625798562581422125276e3,
    ],
];

/// The order conditions (Butcher's rooted trees), checked on the tableau as
/// transcribed: a wrong digit anywhere shows up as a violated condition.
#[cfg(test)]
mod tests {
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
                        + s1 * (r3
                            + theta * (r4 + s1 * (r5 + theta * (r6 + s1 * (r7 + theta * r8))))))
            });
            check(&format!("dense output at θ = {theta}"), &w, 1..=7, |t| {
                theta.powi(t.order() as i32) / t.density()
            });
        }
    }
}
