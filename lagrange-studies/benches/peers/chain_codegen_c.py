#!/usr/bin/env python3
"""Peer baseline: SymPy -> cse -> C (gcc) against lagrange's generated code,
on the same N-link pendulum chain.

Model (identical to the project's lagrange-studies/examples/scaling/chain.rs, indexed form):
N point masses on massless rods, absolute angles theta_i from the downward
vertical, runtime parameters m[i], l[i] (symbols on both sides), g = 9.81 a
compile-time constant:

    x_i = sum_{j<=i} l_j sin(theta_j),   y_i = -sum_{j<=i} l_j cos(theta_j)
    T = sum_i m_i/2 (xdot_i^2 + ydot_i^2),   V = sum_i m_i g y_i
    M = d2L/dqdot2,   f = dL/dq - (d2L/dqdot dq) qdot          (M qddot = f)

SymPy side, two derivations an expert might pick (each per N in a child
process with a time limit):
  * "EL": plain sympy symbols, Euler-Lagrange written out on T and V above
    (diff / hessian; no simplification);
  * "LM": sympy.physics.mechanics.LagrangesMethod (one frame per link,
    Particle, Lagrangian, form_lagranges_equations, mass_matrix / forcing),
    the idiomatic route; q(t), q'(t) replaced by plain symbols afterwards.
Both: sympy.cse jointly on [M upper triangle, f] (default options), then C
via sympy.printing.c.ccode, one function

    void mf(const double* q, const double* qd, const double* m,
            const double* l, double* M, double* f)   /* M row-major, full */

compiled by gcc -O3 -march=native with and without -ffast-math into an
object file, linked to a driver compiled separately (-O2, no LTO: the call
is opaque, as from a static library).

lagrange side: the generated `mass_matrix_and_forcing` of the same model in
a tiny crate per N (lagrange by path, cargo build --release, defaults), called
through an #[inline(never)] wrapper so that both sides pay one call.

Timing loop, identical in C and Rust: K = 64 precomputed states
    q_i = 0.3 + 0.9 sin(1.7 i + k),  qdot_i = 0.5 cos(1.3 i - 0.7 k),
    m_i = 1 + 0.1 i,  l_i = 1 - 0.5 i / N   (as lagrange-studies/examples/scaling/template)
call k = it mod 64, acc += M[it mod N^2] + f[it mod N]; ITERS calls per
repetition (>= 1e6), best of 5 repetitions per process, processes
alternated between the implementations (ROUNDS rounds), best overall.

Agreement: M and f at 6 states from C (both flag sets) and Rust, max |C - R|
over max |R|, separately for M and f, worst over the states.

Operation count, one convention for both texts (count_ops below): parse the
emitted function body (C from ccode, Rust pretty-printed from
lagrange_engine::derive(..).tokens()), drop `let`/`const` bindings never
referenced (dead code), then count every binary + - * /, every call of a math
function (sin, cos, pow, powi, sqrt, ...), pow(x, 2) counting as one, and
each call of the generated code's local multiply-add `fma(a, b, c)` as a
multiply and an add (as `a*b + c` counts in C; the helper itself is not
counted), a sin(x) and a cos(x) of the same argument as one call (gcc and
LLVM compile them to one sincos; lagrange writes one sin_cos(x), or one
sin_cos_array([x, y, ...]) for several angles, counted as one call per
angle); unary
minus is counted apart (`neg`) and not in the total; a constant written
`(1.0/2.0)` is a literal, not a division; constants and array reads are free.
The engine's own count (Derived::op_counts, what BENCHMARKS.md reports) and
sympy.count_ops of the cse output are given beside it.

Usage (a Python with sympy, and gcc; from the project's root, or pass --lagrange):
    python chain_codegen_c.py [--ns 2,5,10,20] [--lagrange PATH] [--out DIR] [--work DIR]
Writes DIR/chain_codegen_c.txt and .json (default: target/peers in the
checkout); scratch in --work (default: lgbench/ in the system's temporary
directory, or $LAGRANGE_PEERS_WORK). `cargo bench -p lagrange-studies --bench peers` runs it
(lagrange-studies/benches/peers.rs); the generated code is printed by the engine's example
`peers_chain` (lagrange-engine/examples/peers_chain.rs), built here.
"""
import argparse
import json
import os
import platform
import re
import shutil
import signal
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
import tempfile  # noqa: E402
LAGRANGE = os.environ.get("LAGRANGE_CHECKOUT", os.getcwd())
RESULTS = os.path.join(LAGRANGE, "target", "peers")
WORK = GEN_DIR = C_DIR = RUST_DIR = RUST_TARGET = None


def set_work(work):
    """Scratch directories under `work` (children inherit it by environment)."""
    global WORK, GEN_DIR, C_DIR, RUST_DIR, RUST_TARGET
    WORK = os.path.abspath(work)
    os.environ["LAGRANGE_PEERS_WORK"] = WORK
    GEN_DIR = os.path.join(WORK, "gen")  # target dir of the example that prints the generated code
    C_DIR = os.path.join(WORK, "c")
    RUST_DIR = os.path.join(WORK, "rust")
    RUST_TARGET = os.path.join(RUST_DIR, "target")


set_work(os.environ.get("LAGRANGE_PEERS_WORK") or os.path.join(tempfile.gettempdir(), "lgbench"))
G = 9.81
K_STATES = 64
CHECK_STATES = [0, 1, 2, 3, 17, 42]
NICE = ["nice", "-n", "10"]

CFLAGS = {
    "O3": ["-O3", "-march=native"],
    "O3fm": ["-O3", "-march=native", "-ffast-math"],
}
DRIVER_FLAGS = ["-O2"]


# --------------------------------------------------------------------------
# operation counter, shared by the C and the Rust text
# --------------------------------------------------------------------------
MATH_FUNCS = {"sin", "cos", "sin_cos", "tan", "exp", "log", "sqrt", "pow", "powi", "powf",
              "atan2", "asin", "acos", "atan", "sinh", "cosh", "tanh", "abs", "fabs",
              "cbrt", "exp2", "log2", "log10", "hypot"}
FMA_FUNCS = {"fma", "fma_", "fma__"}
TOKEN_RE = re.compile(r"""
    (?P<num>(?:\d+\.\d*|\.\d+|\d+)(?:[eE][+-]?\d+)?(?:f64|f32|usize|i32|u32)?)
  | (?P<id>[A-Za-z_][A-Za-z_0-9]*)
  | (?P<op>::|->|=>|==|!=|<=|>=|&&|\|\||[-+*/=;,()\[\]{}<>:&.!#%?|])
  | (?P<ws>\s+)
""", re.X)
CONST_DIV_RE = re.compile(r"\(\s*\d+(?:\.\d*)?\s*/\s*\d+(?:\.\d*)?\s*\)")


def tokenize(text):
    out = []
    pos = 0
    while pos < len(text):
        mt = TOKEN_RE.match(text, pos)
        if not mt:
            raise ValueError("cannot tokenize at %r" % text[pos:pos + 40])
        pos = mt.end()
        if mt.lastgroup != "ws":
            out.append(mt.group())
    return out


def count_tokens(toks):
    """Binary + - * /, math calls, unary minus, in a token list."""
    c = {"add": 0, "sub": 0, "mul": 0, "div": 0, "call": 0, "neg": 0}
    operand_end = False   # previous token ends an operand (ident, number, ')', ']')
    for i, t in enumerate(toks):
        if t in ("+", "-", "*", "/"):
            if operand_end:
                c[{"+": "add", "-": "sub", "*": "mul", "/": "div"}[t]] += 1
            elif t == "-":
                c["neg"] += 1
            operand_end = False
            continue
        if t in MATH_FUNCS and i + 1 < len(toks) and toks[i + 1] == "(":
            c["call"] += 1
        if t == "sin_cos_array" and i + 1 < len(toks) and toks[i + 1] == "(":
            # lagrange's kernel on K angles at once: K calls, one per angle,
            # as K sin_cos(x) would count
            c["call"] += array_len(toks, i + 2)
        if t in FMA_FUNCS and i + 1 < len(toks) and toks[i + 1] == "(":
            # lagrange's local multiply-add: a multiply and an add, as `a*b + c` in C
            c["mul"] += 1
            c["add"] += 1
        operand_end = bool(re.match(r"[A-Za-z_0-9.]", t)) or t in (")", "]")
    c["total"] = c["add"] + c["sub"] + c["mul"] + c["div"] + c["call"]
    return c


def array_len(toks, i):
    """Elements of the array literal opening at toks[i] ('['); a trailing
    comma (as prettyplease writes a long one) opens none."""
    assert toks[i] == "[", toks[i:i + 3]
    depth, n = 0, 1
    for k, t in enumerate(toks[i:], i):
        if t in ("(", "[", "{"):
            depth += 1
        elif t in (")", "]", "}"):
            depth -= 1
            if depth == 0:
                return n
        elif t == "," and depth == 1 and toks[k + 1] != "]":
            n += 1
    raise ValueError("unclosed array")


def sin_cos_pairs(token_lists):
    """Arguments of which the text takes both sin(x) and cos(x) as two calls:
    compilers make them one sincos call (gcc and LLVM alike), so each pair
    counts as one call, as lagrange's sin_cos(x) does."""
    seen = {"sin": set(), "cos": set()}
    for toks in token_lists:
        for i in range(len(toks) - 3):
            if toks[i] in seen and toks[i + 1] == "(" and toks[i + 3] == ")":
                seen[toks[i]].add(toks[i + 2])
    return len(seen["sin"] & seen["cos"])


def split_statements(body):
    """Top-level statements of a function body, split at ';' outside brackets."""
    stmts, depth, cur = [], 0, []
    for ch in body:
        if ch in "([{":
            depth += 1
        elif ch in ")]}":
            depth -= 1
        if ch == ";" and depth == 0:
            stmts.append("".join(cur).strip())
            cur = []
        else:
            cur.append(ch)
    rest = "".join(cur).strip()
    if rest:
        stmts.append(rest)
    return stmts


BIND_RE = re.compile(r"^(?:let|const\s+double)\s+([A-Za-z_][A-Za-z_0-9]*)\s*(?::\s*S\s*)?=\s*(.*)$", re.S)


def count_ops(body):
    """Ops of a straight-line function body (C or Rust), dead bindings dropped."""
    body = CONST_DIV_RE.sub("1.0", body)
    stmts = split_statements(body)
    binds = {}
    others = []
    for s in stmts:
        mt = BIND_RE.match(s)
        if mt and not s.startswith("let ("):
            binds[mt.group(1)] = tokenize(mt.group(2))
        else:
            others.append(tokenize(s))
    # dead-binding elimination (iterated)
    live_tokens = [t for toks in others for t in toks]
    while True:
        # a binding is dead if no other statement references it
        refs = {}
        for name, toks in binds.items():
            for t in toks:
                refs[t] = refs.get(t, 0) + 1
        for t in live_tokens:
            refs[t] = refs.get(t, 0) + 1
        dead = [n for n in binds if refs.get(n, 0) == 0]
        if not dead:
            break
        for n in dead:
            del binds[n]
    total = {"add": 0, "sub": 0, "mul": 0, "div": 0, "call": 0, "neg": 0}
    for toks in list(binds.values()) + others:
        c = count_tokens(toks)
        for k in total:
            total[k] += c[k]
    total["call"] -= sin_cos_pairs(list(binds.values()) + others)
    total["total"] = total["add"] + total["sub"] + total["mul"] + total["div"] + total["call"]
    total["bindings"] = len(binds)
    return total


def count_ops_all(body):
    """The same without dead-binding elimination (the text exactly as written)."""
    body = CONST_DIV_RE.sub("1.0", body)
    total = {"add": 0, "sub": 0, "mul": 0, "div": 0, "call": 0, "neg": 0}
    lists = []
    for s in split_statements(body):
        mt = BIND_RE.match(s)
        toks = tokenize(mt.group(2) if (mt and not s.startswith("let (")) else s)
        lists.append(toks)
        c = count_tokens(toks)
        for k in total:
            total[k] += c[k]
    total["call"] -= sin_cos_pairs(lists)
    total["total"] = total["add"] + total["sub"] + total["mul"] + total["div"] + total["call"]
    return total


def rust_body(text):
    """Body of the pretty-printed `mass_matrix_and_forcing`."""
    start = text.index("fn mass_matrix_and_forcing")
    brace = text.index("{", text.index(") -> ", start))
    depth, i = 0, brace
    while True:
        if text[i] == "{":
            depth += 1
        elif text[i] == "}":
            depth -= 1
            if depth == 0:
                break
        i += 1
    body = strip_fma_helper(text[brace + 1:i])
    # the destructuring of q, qdot and self, and constant conversions are free
    stmts = []
    for s in split_statements(body):
        if (s.startswith("let (") and "sin_cos" not in s) or s.startswith("let [") or s.startswith("let Self"):
            continue
        if "convert::<" in s:
            continue
        stmts.append(s)
    return ";\n".join(stmts)


def strip_fma_helper(body):
    """The body without the local `fn fma` item (its `a * b + c` is counted at each call)."""
    mt = re.search(r"#\[inline\(always\)\]\s*fn\s+fma_*\s*<", body)
    if not mt:
        return body
    i = body.index("{", body.index(") -> ", mt.end()))
    depth = 0
    while True:
        if body[i] == "{":
            depth += 1
        elif body[i] == "}":
            depth -= 1
            if depth == 0:
                break
        i += 1
    return body[:mt.start()] + body[i + 1:]


def c_body(text):
    start = text.index("{", text.index("void mf("))
    end = text.rindex("}")
    stmts = [s for s in split_statements(text[start + 1:end])
             if not re.match(r"const double (q|u|m|l)\d+ = ", s)]
    return ";\n".join(stmts)


# --------------------------------------------------------------------------
# SymPy derivations (child process)
# --------------------------------------------------------------------------
def derive_el(n):
    import sympy as sm
    q = sm.symbols("q0:%d" % n)
    u = sm.symbols("u0:%d" % n)
    m = sm.symbols("m0:%d" % n)
    l = sm.symbols("l0:%d" % n)
    g = sm.Float(G)
    xd = [sm.Add(*[l[j] * sm.cos(q[j]) * u[j] for j in range(i + 1)]) for i in range(n)]
    yd = [sm.Add(*[l[j] * sm.sin(q[j]) * u[j] for j in range(i + 1)]) for i in range(n)]
    y = [-sm.Add(*[l[j] * sm.cos(q[j]) for j in range(i + 1)]) for i in range(n)]
    T = sm.Add(*[m[i] / 2 * (xd[i] ** 2 + yd[i] ** 2) for i in range(n)])
    V = sm.Add(*[m[i] * g * y[i] for i in range(n)])
    L = T - V
    p = [sm.diff(L, u[i]) for i in range(n)]
    M = sm.Matrix(n, n, lambda i, j: sm.diff(p[i], u[j]))
    f = sm.Matrix([sm.diff(L, q[i]) - sm.Add(*[sm.diff(p[i], q[j]) * u[j] for j in range(n)])
                   for i in range(n)])
    return M, f, (q, u, m, l)


def derive_lm(n):
    import sympy as sm
    import sympy.physics.mechanics as me
    qt = me.dynamicsymbols("q0:%d" % n)
    qdt = [qi.diff(me.dynamicsymbols._t) for qi in qt]
    m = sm.symbols("m0:%d" % n)
    l = sm.symbols("l0:%d" % n)
    g = sm.Float(G)
    N = me.ReferenceFrame("N")
    O = me.Point("O")
    O.set_vel(N, 0)
    prev = O
    particles = []
    for i in range(n):
        A = N.orientnew("A%d" % i, "Axis", [qt[i], N.z])
        A.set_ang_vel(N, qdt[i] * N.z)
        P = prev.locatenew("P%d" % i, -l[i] * A.y)
        P.v2pt_theory(prev, N, A)
        Pa = me.Particle("Pa%d" % i, P, m[i])
        Pa.potential_energy = m[i] * g * P.pos_from(O).dot(N.y)
        particles.append(Pa)
        prev = P
    L = me.Lagrangian(N, *particles)
    LM = me.LagrangesMethod(L, qt)
    LM.form_lagranges_equations()
    M, f = LM.mass_matrix, LM.forcing
    q = sm.symbols("q0:%d" % n)
    u = sm.symbols("u0:%d" % n)
    sub = dict(zip(qdt, u))
    M = M.xreplace(sub).xreplace(dict(zip(qt, q)))
    f = f.xreplace(sub).xreplace(dict(zip(qt, q)))
    return M, f, (q, u, m, l)


def emit_c(n, repl, reduced, syms):
    from sympy.printing.c import C99CodePrinter
    pr = C99CodePrinter()
    q, u, m, l = syms
    lines = ["/* generated by peers/chain_codegen_c.py: %d-link chain, sympy.cse + ccode */" % n,
             "#include <math.h>",
             "void mf(const double* q, const double* qd, const double* m, const double* l,",
             "        double* M, double* f)",
             "{"]
    for i in range(n):
        lines.append("    const double q%d = q[%d];" % (i, i))
        lines.append("    const double u%d = qd[%d];" % (i, i))
        lines.append("    const double m%d = m[%d];" % (i, i))
        lines.append("    const double l%d = l[%d];" % (i, i))
    for s, e in repl:
        lines.append("    const double %s = %s;" % (s, pr.doprint(e)))
    k = 0
    for i in range(n):
        for j in range(i, n):
            lines.append("    M[%d] = %s;" % (i * n + j, pr.doprint(reduced[k])))
            if j != i:
                lines.append("    M[%d] = M[%d];" % (j * n + i, i * n + j))
            k += 1
    for i in range(n):
        lines.append("    f[%d] = %s;" % (i, pr.doprint(reduced[k])))
        k += 1
    lines.append("}")
    return "\n".join(lines) + "\n"


class StepTimeout(Exception):
    pass


def _alarm(signum, frame):
    raise StepTimeout()


def child(n, variant, limit):
    import sympy as sm
    rec = {"n": n, "variant": variant}
    signal.signal(signal.SIGALRM, _alarm)
    signal.alarm(limit)
    try:
        t0 = time.perf_counter()
        M, f, syms = (derive_el if variant == "EL" else derive_lm)(n)
        rec["derive_s"] = time.perf_counter() - t0
        if variant == "LMs":
            # the usual next step: trigsimp every entry (closed form, sin(q_i - q_j))
            t0 = time.perf_counter()
            M = M.applyfunc(sm.trigsimp)
            f = f.applyfunc(sm.trigsimp)
            rec["simplify_s"] = time.perf_counter() - t0
        # 1.0*x factors that trigsimp leaves (g is a Float) are no operations
        one = {sm.Float(1.0): sm.Integer(1), sm.Float(-1.0): sm.Integer(-1)}
        M = M.xreplace(one)
        f = f.xreplace(one)
        exprs = [M[i, j] for i in range(n) for j in range(i, n)] + [f[i] for i in range(n)]
        t0 = time.perf_counter()
        repl, reduced = sm.cse(exprs)
        rec["cse_s"] = time.perf_counter() - t0
        rec["cse_count_ops"] = int(sum(sm.count_ops(e) for _, e in repl) + sum(sm.count_ops(e) for e in reduced))
        rec["cse_replacements"] = len(repl)
        t0 = time.perf_counter()
        src = emit_c(n, repl, reduced, syms)
        rec["ccode_s"] = time.perf_counter() - t0
    except StepTimeout:
        rec["error"] = "timeout > %d s" % limit
        return rec
    finally:
        signal.alarm(0)
    path = os.path.join(C_DIR, "mf_%s_%d.c" % (variant, n))
    with open(path, "w") as fh:
        fh.write(src)
    rec["c_file"] = path
    rec["c_bytes"] = len(src)
    return rec


# --------------------------------------------------------------------------
# C driver and Rust bench crate
# --------------------------------------------------------------------------
C_DRIVER = r"""
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#ifndef NN
#error NN
#endif
#define K 64
void mf(const double* q, const double* qd, const double* m, const double* l, double* M, double* f);
static double now(void) { struct timespec ts; clock_gettime(CLOCK_MONOTONIC, &ts); return ts.tv_sec + 1e-9 * ts.tv_nsec; }
static double qs[K][NN], qds[K][NN];
int main(int argc, char** argv) {
    double m[NN], l[NN], M[NN * NN], f[NN];
    for (int i = 0; i < NN; i++) { m[i] = 1.0 + 0.1 * i; l[i] = 1.0 - 0.5 * i / (double)NN; }
    for (int k = 0; k < K; k++) for (int i = 0; i < NN; i++) {
        qs[k][i] = 0.3 + 0.9 * sin(1.7 * i + k); qds[k][i] = 0.5 * cos(1.3 * i - 0.7 * k); }
    if (argc > 1 && argv[1][0] == 'v') {
        int ks[] = {CHECK_STATES};
        for (unsigned s = 0; s < sizeof ks / sizeof ks[0]; s++) {
            mf(qs[ks[s]], qds[ks[s]], m, l, M, f);
            printf("state %d\n", ks[s]);
            for (int i = 0; i < NN * NN; i++) printf("M %.17e\n", M[i]);
            for (int i = 0; i < NN; i++) printf("f %.17e\n", f[i]);
        }
        return 0;
    }
    long iters = atol(argv[2]);
    double best = 1e300, acc = 0.0;
    for (int rep = 0; rep < 5; rep++) {
        double t0 = now();
        for (long it = 0; it < iters; it++) {
            long k = it & (K - 1);
            mf(qs[k], qds[k], m, l, M, f);
            acc += M[it % (NN * NN)] + f[it % NN];
        }
        double dt = (now() - t0) / iters * 1e9;
        if (dt < best) best = dt;
    }
    printf("ns %.4f\nacc %.6e\n", best, acc);
    return 0;
}
"""

C_FLOOR = r"""
/* The trigonometric floor (peers/chain_codegen_c.py): the NN sincos calls
   that both the SymPy C (gcc merges its sin and cos) and lagrange's code
   make, their results stored, nothing else; same driver. */
#define _GNU_SOURCE
#include <math.h>
void mf(const double* q, const double* qd, const double* m, const double* l, double* M, double* f)
{
    for (int i = 0; i < NN; i++) {
        double s, c;
        sincos(q[i], &s, &c);
        f[i] = s;
        M[i] = c;
    }
}
"""

RUST_MAIN = r"""//! Times lagrange's generated mass_matrix_and_forcing for the __N__-link chain
//! (peers/chain_codegen_c.py). `values` prints M (row-major) and f at fixed
//! states; `time ITERS` prints the best of 5 ns per call.
use lagrange::lagrangian;
use lagrange::nalgebra::{SMatrix, SVector};
use std::hint::black_box;

pub const N: usize = __N__;
const K: usize = 64;

lagrangian! {
__MODEL__
}

#[inline(never)]
fn mf(model: &Chain<f64>, q: &SVector<f64, N>, qd: &SVector<f64, N>) -> (SMatrix<f64, N, N>, SVector<f64, N>) {
    model.mass_matrix_and_forcing(0.0, q, qd)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let m: [f64; N] = core::array::from_fn(|i| 1.0 + 0.1 * i as f64);
    let l: [f64; N] = core::array::from_fn(|i| 1.0 - 0.5 * i as f64 / N as f64);
    let model = Chain::new(m, l);
    let qs: Vec<SVector<f64, N>> = (0..K)
        .map(|k| SVector::from_fn(|i, _| 0.3 + 0.9 * (1.7 * i as f64 + k as f64).sin()))
        .collect();
    let qds: Vec<SVector<f64, N>> = (0..K)
        .map(|k| SVector::from_fn(|i, _| 0.5 * (1.3 * i as f64 - 0.7 * k as f64).cos()))
        .collect();
    if args.len() > 1 && args[1] == "values" {
        for &k in &[__CHECK__] {
            let (mm, ff) = mf(&model, &qs[k], &qds[k]);
            println!("state {k}");
            for i in 0..N {
                for j in 0..N {
                    println!("M {:.17e}", mm[(i, j)]);
                }
            }
            for i in 0..N {
                println!("f {:.17e}", ff[i]);
            }
        }
        return;
    }
    let iters: usize = args[2].parse().unwrap();
    let mut best = f64::INFINITY;
    let mut acc = 0.0;
    for _ in 0..5 {
        let t0 = std::time::Instant::now();
        for it in 0..iters {
            let k = it & (K - 1);
            let (mm, ff) = mf(black_box(&model), &qs[k], &qds[k]);
            acc += mm.as_slice()[it % (N * N)] + ff[it % N];
        }
        let dt = t0.elapsed().as_secs_f64() / iters as f64 * 1e9;
        best = best.min(dt);
    }
    println!("ns {best:.4}");
    println!("acc {:.6e}", black_box(acc));
}
"""

# `articulated = false`: the generated M and f are compared, which from 10
# coordinates the chain would otherwise not have (formed at run time from
# the links' parts; lagrange-studies/benches/articulated.rs times that).
MODEL = """#[lagrange(articulated = false)]
pub struct Chain {{
    const N = {n};
    coordinates: theta[N];
    parameters: m[N], l[N];
    constants: g = 9.81;
    let x[i in 0..N] = sum(j in 0..=i, l[j]*sin(theta[j]));
    let y[i in 0..N] = -sum(j in 0..=i, l[j]*cos(theta[j]));
    kinetic: sum(i in 0..N, m[i]/2*(dot(x[i])^2 + dot(y[i])^2));
    potential: sum(i in 0..N, m[i]*g*y[i]);
}}"""


def write_rust_crate(n):
    d = os.path.join(RUST_DIR, "chain%d" % n)
    os.makedirs(os.path.join(d, "src"), exist_ok=True)
    with open(os.path.join(d, "Cargo.toml"), "w") as fh:
        fh.write('[package]\nname = "chain%d"\nversion = "0.0.0"\nedition = "2021"\npublish = false\n\n'
                 '[dependencies]\nlagrange = { path = "%s" }\n\n[workspace]\n' % (n, LAGRANGE))
    lock = os.path.join(d, "Cargo.lock")
    if not os.path.exists(lock):
        shutil.copy(os.path.join(LAGRANGE, "Cargo.lock"), lock)
    src = (RUST_MAIN.replace("__N__", str(n)).replace("__MODEL__", MODEL.format(n=n))
           .replace("__CHECK__", ", ".join(map(str, CHECK_STATES))))
    with open(os.path.join(d, "src", "main.rs"), "w") as fh:
        fh.write(src)
    return d


def cargo_build(d, jobs, target=None, rustflags=None):
    env = dict(os.environ)
    env["CARGO_TARGET_DIR"] = target or RUST_TARGET
    if rustflags:
        env["RUSTFLAGS"] = rustflags
    t0 = time.perf_counter()
    cp = subprocess.run(NICE + ["cargo", "build", "--release", "--offline", "-j", str(jobs),
                                "--manifest-path", os.path.join(d, "Cargo.toml")],
                        capture_output=True, text=True, env=env)
    dt = time.perf_counter() - t0
    if cp.returncode != 0:
        raise RuntimeError("cargo build failed in %s:\n%s" % (d, cp.stderr[-3000:]))
    return dt


def touch(path):
    with open(path, "rb") as fh:
        data = fh.read()
    with open(path, "wb") as fh:
        fh.write(data)


def parse_values(text):
    Ms, fs = [], []
    for line in text.splitlines():
        if line.startswith("state"):
            Ms.append([])
            fs.append([])
        elif line.startswith("M "):
            Ms[-1].append(float(line[2:]))
        elif line.startswith("f "):
            fs[-1].append(float(line[2:]))
    return Ms, fs


def rel_diff(a, b):
    """max over states of max|a-b| / max|b|."""
    worst = 0.0
    for x, y in zip(a, b):
        scale = max(abs(v) for v in y)
        worst = max(worst, max(abs(p - r) for p, r in zip(x, y)) / scale)
    return worst


def run_timed(cmd):
    cp = subprocess.run(NICE + cmd, capture_output=True, text=True)
    if cp.returncode != 0:
        raise RuntimeError("%s failed: %s" % (cmd, cp.stderr[-2000:]))
    for line in cp.stdout.splitlines():
        if line.startswith("ns "):
            return float(line[3:])
    raise RuntimeError("no timing from %s" % cmd)


def iters_for(n):
    return {2: 10_000_000, 5: 2_000_000}.get(n, 1_000_000)


# --------------------------------------------------------------------------
# main
# --------------------------------------------------------------------------
def main():
    global LAGRANGE, RESULTS
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--ns", default="2,5,10,20")
    ap.add_argument("--lagrange", default=None, help="the lagrange checkout (default: the current directory)")
    ap.add_argument("--out", default=None, help="results directory (default: target/peers in the checkout)")
    ap.add_argument("--work", default=None, help="scratch directory (default: $LAGRANGE_PEERS_WORK or lgbench/ in /tmp)")
    ap.add_argument("--variants", default="EL,LM,LMs")
    ap.add_argument("--derive-limit", type=int, default=600, help="s per SymPy derivation+cse")
    ap.add_argument("--rounds", type=int, default=3, help="process rounds per implementation")
    ap.add_argument("--lms-max", type=int, default=10, help="largest N for the LMs (trigsimp) variant")
    ap.add_argument("--native-rust", action="store_true",
                    help="also time Rust built with RUSTFLAGS='-C target-cpu=native' (own target dir)")
    ap.add_argument("--build-times", default="10,20", help="N whose model crate build is re-timed (-j 2)")
    ap.add_argument("--retime-only", action="store_true",
                    help="only re-time the binaries of the last full run (read from the .json), "
                         "and append the table to the .txt")
    ap.add_argument("--child", default=None, help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.lagrange:
        LAGRANGE = os.path.abspath(args.lagrange)
        os.environ["LAGRANGE_CHECKOUT"] = LAGRANGE  # children inherit it
        RESULTS = os.path.join(LAGRANGE, "target", "peers")
    if args.out:
        RESULTS = os.path.abspath(args.out)
    if args.work:
        set_work(args.work)

    if args.retime_only:
        retime(args)
        return

    if args.child:
        n, variant = args.child.split(":")
        rec = child(int(n), variant, args.derive_limit)
        sys.stdout.write("RESULT " + json.dumps(rec) + "\n")
        return

    t_start = time.time()
    ns = [int(x) for x in args.ns.split(",")]
    variants = args.variants.split(",")
    os.makedirs(C_DIR, exist_ok=True)
    os.makedirs(RESULTS, exist_ok=True)
    import sympy
    log = lambda *a: print("[chain_codegen_c]", *a, file=sys.stderr, flush=True)
    with open("/proc/loadavg") as fh:
        load_start = fh.read().split()[:3]

    rows = {n: {"n": n, "sympy": {}} for n in ns}
    notes = []

    # ---- A: SymPy derivation, cse, C source --------------------------------
    for n in ns:
        for v in variants:
            if v == "LMs" and n > args.lms_max:
                notes.append("n=%d LMs: not run (trigsimp of f takes 25 s at N=5 and grows steeply; --lms-max %d)"
                             % (n, args.lms_max))
                continue
            log("sympy %s n=%d" % (v, n))
            t0 = time.time()
            try:
                cp = subprocess.run(NICE + [sys.executable, os.path.abspath(__file__), "--child", "%d:%s" % (n, v),
                                            "--derive-limit", str(args.derive_limit)],
                                    capture_output=True, text=True, timeout=args.derive_limit + 120)
                rec = None
                for line in cp.stdout.splitlines():
                    if line.startswith("RESULT "):
                        rec = json.loads(line[7:])
                if rec is None:
                    rec = {"error": "child failed rc=%s: %s" % (cp.returncode, cp.stderr[-800:])}
            except subprocess.TimeoutExpired:
                rec = {"error": "child exceeded %d s" % (args.derive_limit + 120)}
            rec["child_wall_s"] = time.time() - t0
            log(json.dumps(rec))
            rows[n]["sympy"][v] = rec
            if "error" in rec:
                notes.append("n=%d %s: %s" % (n, v, rec["error"]))

    # ---- B: gcc ---------------------------------------------------------------
    for n in ns:
        drv_c = os.path.join(C_DIR, "driver.c")
        with open(drv_c, "w") as fh:
            fh.write(C_DRIVER.replace("CHECK_STATES", ", ".join(map(str, CHECK_STATES))))
        drv_o = os.path.join(C_DIR, "driver_%d.o" % n)
        subprocess.run(["gcc"] + DRIVER_FLAGS + ["-DNN=%d" % n, "-c", drv_c, "-o", drv_o], check=True)
        # the floor: the N sincos calls both sides make, and nothing else
        floor_c = os.path.join(C_DIR, "sincos_floor.c")
        with open(floor_c, "w") as fh:
            fh.write(C_FLOOR)
        floor_o = os.path.join(C_DIR, "sincos_floor_%d.o" % n)
        subprocess.run(["gcc"] + CFLAGS["O3"] + ["-DNN=%d" % n, "-c", floor_c, "-o", floor_o], check=True)
        rows[n]["floor_exe"] = os.path.join(C_DIR, "sincos_floor_%d" % n)
        subprocess.run(["gcc", drv_o, floor_o, "-o", rows[n]["floor_exe"], "-lm"], check=True)
        for v, rec in rows[n]["sympy"].items():
            if "c_file" not in rec:
                continue
            with open(rec["c_file"]) as fh:
                rec["ops_counter"] = count_ops(c_body(fh.read()))
            rec["gcc_s"] = {}
            rec["exe"] = {}
            for tag, flags in CFLAGS.items():
                obj = os.path.join(C_DIR, "mf_%s_%d_%s.o" % (v, n, tag))
                exe = os.path.join(C_DIR, "bench_%s_%d_%s" % (v, n, tag))
                t0 = time.perf_counter()
                subprocess.run(NICE + ["gcc"] + flags + ["-c", rec["c_file"], "-o", obj], check=True)
                rec["gcc_s"][tag] = time.perf_counter() - t0
                subprocess.run(["gcc", drv_o, obj, "-o", exe, "-lm"], check=True)
                rec["exe"][tag] = exe
            log("gcc n=%d %s: %s ops %s" % (n, v, rec["gcc_s"], rec["ops_counter"]))

    # ---- C: lagrange: generated text, op counts, crates -------------------
    env = dict(os.environ, CARGO_TARGET_DIR=os.path.join(GEN_DIR, "target"))
    subprocess.run(NICE + ["cargo", "build", "--release", "--offline", "-p", "lagrange-engine",
                           "--example", "peers_chain", "--manifest-path", os.path.join(LAGRANGE, "Cargo.toml")],
                   check=True, env=env)
    gen = os.path.join(GEN_DIR, "target", "release", "examples", "peers_chain")
    rustc_v = subprocess.run(["rustc", "--version"], capture_output=True, text=True).stdout.strip()
    os.makedirs(RUST_DIR, exist_ok=True)
    for n in ns:
        text = subprocess.run([gen, str(n)], capture_output=True, text=True, check=True).stdout
        with open(os.path.join(RUST_DIR, "generated_%d.rs" % n), "w") as fh:
            fh.write(text)
        eng = re.search(r"engine_shared_ops (\d+) (\d+) (\d+)", text)
        rows[n]["ours"] = {
            "engine_ops": int(eng.group(3)),
            "ops_counter": count_ops(rust_body(text)),
            "ops_counter_as_written": count_ops_all(rust_body(text)),
            "engine_derive_emit_s": float(re.search(r"derive_emit_s (\S+)", text).group(1)),
        }
        log("ours n=%d %s" % (n, rows[n]["ours"]))
    for n in ns:
        d = write_rust_crate(n)
        log("cargo build chain%d (first build may compile dependencies, -j 1)" % n)
        rows[n]["ours"]["first_build_s"] = cargo_build(d, 1)
        rows[n]["ours"]["exe"] = os.path.join(RUST_TARGET, "release", "chain%d" % n)
        if args.native_rust:
            cargo_build(d, 1, target=RUST_TARGET + "-native", rustflags="-C target-cpu=native")
            rows[n]["ours"]["exe_native"] = os.path.join(RUST_TARGET + "-native", "release", "chain%d" % n)
    build_ns = [int(x) for x in args.build_times.split(",") if x and int(x) in ns]
    for n in build_ns:
        d = os.path.join(RUST_DIR, "chain%d" % n)
        times = []
        for _ in range(2):
            touch(os.path.join(d, "src", "main.rs"))
            times.append(cargo_build(d, 2))
        rows[n]["ours"]["build_s"] = min(times)
        log("cargo build chain%d after touch: %s" % (n, times))

    # ---- D: agreement ---------------------------------------------------------
    for n in ns:
        ref = subprocess.run([rows[n]["ours"]["exe"], "values"], capture_output=True, text=True, check=True).stdout
        RM, Rf = parse_values(ref)
        if "exe_native" in rows[n]["ours"]:
            nat = subprocess.run([rows[n]["ours"]["exe_native"], "values"], capture_output=True, text=True,
                                 check=True).stdout
            NM, Nf = parse_values(nat)
            rows[n]["ours"]["agree_native"] = {"M": rel_diff(NM, RM), "f": rel_diff(Nf, Rf)}
        for v, rec in rows[n]["sympy"].items():
            if "exe" not in rec:
                continue
            rec["agree"] = {}
            for tag, exe in rec["exe"].items():
                out = subprocess.run([exe, "v"], capture_output=True, text=True, check=True).stdout
                CM, Cf = parse_values(out)
                rec["agree"][tag] = {"M": rel_diff(CM, RM), "f": rel_diff(Cf, Rf)}
            log("agree n=%d %s %s" % (n, v, rec["agree"]))

    # ---- E: timing -------------------------------------------------------------
    for n in ns:
        it = iters_for(n)
        jobs = [("ours", rows[n]["ours"]["exe"]), ("sincos_floor", rows[n]["floor_exe"])]
        if args.native_rust:
            jobs.append(("ours_native", rows[n]["ours"]["exe_native"]))
        for v, rec in rows[n]["sympy"].items():
            for tag, exe in rec.get("exe", {}).items():
                jobs.append(("%s_%s" % (v, tag), exe))
        best = {}
        for r in range(args.rounds):
            for name, exe in (jobs if r % 2 == 0 else list(reversed(jobs))):
                t = run_timed([exe, "time", str(it)])
                best[name] = min(best.get(name, 1e300), t)
        rows[n]["ns"] = best
        rows[n]["iters"] = it
        log("timing n=%d: %s" % (n, best))

    with open("/proc/loadavg") as fh:
        load_end = fh.read().split()[:3]
    gcc_v = subprocess.run(["gcc", "--version"], capture_output=True, text=True).stdout.splitlines()[0]
    write_report(rows, ns, variants, notes, {
        "python": platform.python_version(), "sympy": sympy.__version__, "gcc": gcc_v, "rustc": rustc_v,
        "cores": os.cpu_count(), "load_start": load_start, "load_end": load_end,
        "wall_s": time.time() - t_start, "rounds": args.rounds, "native_rust": args.native_rust,
        "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
    })


def retime(args):
    """Phase E again on the binaries of the last run (e.g. when the machine is quieter)."""
    path = os.path.join(RESULTS, "chain_codegen_c.json")
    with open(path) as fh:
        data = json.load(fh)
    with open("/proc/loadavg") as fh:
        load_start = fh.read().split()[:3]
    t_start = time.time()
    ns = [int(x) for x in args.ns.split(",")]
    out = {}
    for n in ns:
        r = data["rows"][str(n)]
        jobs = [("ours", r["ours"]["exe"])]
        if "floor_exe" in r:
            jobs.append(("sincos_floor", r["floor_exe"]))
        if "exe_native" in r["ours"]:
            jobs.append(("ours_native", r["ours"]["exe_native"]))
        for v, rec in r["sympy"].items():
            for tag, exe in rec.get("exe", {}).items():
                jobs.append(("%s_%s" % (v, tag), exe))
        best = {}
        it = iters_for(n)
        for k in range(args.rounds):
            for name, exe in (jobs if k % 2 == 0 else list(reversed(jobs))):
                best[name] = min(best.get(name, 1e300), run_timed([exe, "time", str(it)]))
        out[n] = best
        print("[retime] n=%d %s" % (n, best), file=sys.stderr, flush=True)
    with open("/proc/loadavg") as fh:
        load_end = fh.read().split()[:3]
    names = []
    for n in ns:
        for k in out[n]:
            if k not in names:
                names.append(k)
    L = ["", "## Re-timing (--retime-only), %s, %d rounds, load %s at start, %s at end, %.0f s" % (
        time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()), args.rounds, "/".join(load_start),
        "/".join(load_end), time.time() - t_start), ""]
    L.append("ns per call (best); ours = cargo --release defaults, ours_native = -C target-cpu=native; "
             "X_O3 = gcc -O3 -march=native, X_O3fm = the same + -ffast-math.")
    L.append("")
    L.append("| N | " + " | ".join(names) + " | ours / best C -O3 | ours / best C -ffast-math | ours_native / best C -O3 | ours_native / best C -ffast-math |")
    L.append("|---:|" + "---:|" * (len(names) + 4))
    for n in ns:
        b = out[n]
        c3 = min([v for k, v in b.items() if k.endswith("_O3")] or [None])
        cf = min([v for k, v in b.items() if k.endswith("_O3fm")] or [None])
        row = [f1(b.get(k), 1) for k in names]
        ratios = [f1(b["ours"] / c3), f1(b["ours"] / cf),
                  f1(b["ours_native"] / c3) if "ours_native" in b else "-",
                  f1(b["ours_native"] / cf) if "ours_native" in b else "-"]
        L.append("| %d | %s | %s |" % (n, " | ".join(row), " | ".join(ratios)))
    L.append("")
    L.extend(summary({n: data["rows"][str(n)] for n in ns}, ns, out))
    text = "\n".join(L) + "\n"
    print(text)
    with open(os.path.join(RESULTS, "chain_codegen_c.txt"), "a") as fh:
        fh.write(text)
    data.setdefault("retime", []).append({"load_start": load_start, "load_end": load_end, "rounds": args.rounds,
                                          "ns": {str(n): out[n] for n in ns}})
    with open(path, "w") as fh:
        json.dump(data, fh, indent=1)


def summary(rows, ns, timings):
    """The comparison in one table: SymPy's idiomatic route (LM) for the
    operations, the fastest C of any variant for each flag set."""
    L = ["## Summary", "",
         "ops: the counter on both texts (SymPy LM + cse, the idiomatic route); C: the fastest SymPy variant's "
         "code per flag set; ours: cargo --release defaults; ours native: RUSTFLAGS='-C target-cpu=native'; "
         "N sincos alone: the same driver around the N sincos calls both sides make and nothing else "
         "(a floor for both); ns per call, best.", "",
         "| N | ops SymPy LM + cse | ops ours | ops ours / SymPy | C -O3 -march=native ns | C -O3 -ffast-math ns "
         "| ours ns | ours / C -O3 | ours native ns | ours native / C -ffast-math | N sincos alone ns "
         "| ours native vs ours, rel. diff M, f |",
         "|---:|" + "---:|" * 11]
    for n in ns:
        r = rows[n]
        lm = r["sympy"].get("LM", {}).get("ops_counter", {}).get("total")
        us_ops = r.get("ours", {}).get("ops_counter", {}).get("total")
        t = timings.get(n, {})
        c3 = min([v for k, v in t.items() if k.endswith("_O3")] or [None]) if t else None
        cf = min([v for k, v in t.items() if k.endswith("_O3fm")] or [None]) if t else None
        us, nat = t.get("ours"), t.get("ours_native")
        ag = r.get("ours", {}).get("agree_native")
        L.append("| %d | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            n, lm if lm is not None else "-", us_ops if us_ops is not None else "-",
            f1(us_ops / lm if lm and us_ops else None), f1(c3, 1), f1(cf, 1), f1(us, 1),
            f1(us / c3 if us and c3 else None), f1(nat, 1), f1(nat / cf if nat and cf else None),
            f1(t.get("sincos_floor"), 1), "%.1e / %.1e" % (ag["M"], ag["f"]) if ag else "-"))
    L.append("")
    return L


def f1(x, d=2):
    return "-" if x is None else ("%.*f" % (d, x))


def write_report(rows, ns, variants, notes, meta):
    L = []
    L.append("# N-link chain: SymPy -> cse -> C (gcc) vs lagrange's generated Rust (peers/chain_codegen_c.py)")
    L.append("# %s; python %s, sympy %s; %s; %s; %d cores, load %s at start, %s at end; wall %.0f s" % (
        meta["date"], meta["python"], meta["sympy"], meta["gcc"], meta["rustc"], meta["cores"],
        "/".join(meta["load_start"]), "/".join(meta["load_end"]), meta["wall_s"]))
    L.append("# model: absolute angles, m[i], l[i] runtime inputs on both sides, g = 9.81 constant; "
             "M full (row-major in C), f; M qdd = f.")
    L.append("# ops: one counter on both texts (binary + - * /, math calls incl. pow; unary minus apart; "
             "dead bindings dropped); 'engine' = Derived::op_counts (BENCHMARKS.md); 'sympy co' = count_ops of cse output.")
    L.append("# ns/call: best of 5 reps x %d process rounds, reps of >= 1e6 calls over 64 varying states; "
             "C: gcc -O3 -march=native [-ffast-math], separate object; Rust: cargo --release defaults, #[inline(never)] wrapper."
             % meta["rounds"])
    L.append("")
    L.extend(summary(rows, ns, {n: rows[n].get("ns", {}) for n in ns}))
    for v in variants:
        L.append("## SymPy variant %s (%s)" % (v, {
            "EL": "plain symbols, Euler-Lagrange on T, V, no simplification",
            "LM": "sympy.physics.mechanics.LagrangesMethod, no simplification",
            "LMs": "LagrangesMethod, then trigsimp of every entry of M and f; 'derive' includes trigsimp"}[v]))
        L.append("")
        hdr = ("| N | SymPy derive s | cse s | gcc -O3 s | ops SymPy+cse (counter) | sympy co | ops ours (counter) "
               "| ours engine | C ns -O3 | C ns -O3 -ffast-math | ours ns | ours/C-O3 | ours/C-fm | rel.diff M, f vs ours |")
        L.append(hdr)
        L.append("|" + "---:|" * (hdr.count("|") - 1))
        for n in ns:
            r = rows[n]
            s = r["sympy"].get(v, {})
            o = r.get("ours", {})
            t = r.get("ns", {})
            c3, cf, us = t.get("%s_O3" % v), t.get("%s_O3fm" % v), t.get("ours")
            ag = s.get("agree", {})
            agtxt = ", ".join("%s %.1e/%.1e" % (k, a["M"], a["f"]) for k, a in ag.items()) or s.get("error", "-")
            L.append("| %d | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
                n, f1((s.get("derive_s") or 0) + s.get("simplify_s", 0) if "derive_s" in s else None), f1(s.get("cse_s")), f1(s.get("gcc_s", {}).get("O3")),
                s.get("ops_counter", {}).get("total", "-"), s.get("cse_count_ops", "-"),
                o.get("ops_counter", {}).get("total", "-"), o.get("engine_ops", "-"),
                f1(c3, 1), f1(cf, 1), f1(us, 1),
                f1(us / c3 if us and c3 else None), f1(us / cf if us and cf else None), agtxt))
        L.append("")
    if meta.get("native_rust"):
        L.append("Rust with RUSTFLAGS='-C target-cpu=native' (ns/call): " + ", ".join(
            "N=%d %s" % (n, f1(rows[n].get("ns", {}).get("ours_native"), 1)) for n in ns))
        L.append("")
    L.append("## Time from T, V to runnable code")
    L.append("")
    L.append("| N | variant | SymPy derive + cse + ccode + gcc -O3 (s) | ours: engine derive+emit (s) | ours: cargo build --release -j 2 after touch (s) |")
    L.append("|---:|---|---:|---:|---:|")
    for n in ns:
        for v in variants:
            s = rows[n]["sympy"].get(v, {})
            tot = None
            if "gcc_s" in s:
                tot = s["derive_s"] + s.get("simplify_s", 0) + s["cse_s"] + s["ccode_s"] + s["gcc_s"]["O3"]
            o = rows[n].get("ours", {})
            L.append("| %d | %s | %s | %s | %s |" % (n, v, f1(tot), f1(o.get("engine_derive_emit_s"), 3),
                                                    f1(o.get("build_s"))))
    L.append("")
    L.append("## Operation breakdown (same counter)")
    L.append("")
    L.append("| N | side | add | sub | mul | div | calls | total | unary neg | bindings |")
    L.append("|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for n in ns:
        for name, c in ([("SymPy %s" % v, rows[n]["sympy"][v].get("ops_counter")) for v in variants
                         if v in rows[n]["sympy"]] + [("ours", rows[n].get("ours", {}).get("ops_counter")),
                                                      ("ours, text as written (dead lets kept)",
                                                       rows[n].get("ours", {}).get("ops_counter_as_written"))]):
            if not c:
                continue
            L.append("| %d | %s | %d | %d | %d | %d | %d | %d | %d | %s |" % (
                n, name, c["add"], c["sub"], c["mul"], c["div"], c["call"], c["total"], c["neg"],
                c.get("bindings", "-")))
    if notes:
        L.append("")
        L.append("notes:")
        L.extend("  - " + x for x in notes)
    out = "\n".join(L) + "\n"
    print(out)
    with open(os.path.join(RESULTS, "chain_codegen_c.txt"), "w") as fh:
        fh.write(out)
    slim = {}
    for n in ns:
        r = json.loads(json.dumps(rows[n]))
        slim[str(n)] = r
    with open(os.path.join(RESULTS, "chain_codegen_c.json"), "w") as fh:
        json.dump({"meta": meta, "rows": slim, "notes": notes}, fh, indent=1)


if __name__ == "__main__":
    main()
