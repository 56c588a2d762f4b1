//! Expressions, with mathematical precedence:
//!
//! ```text
//! sum     := product (('+' | '-') product)*
//! product := unary (('*' | '/') unary)*
//! unary   := '-' unary | power
//! power   := postfix ('^' unary)?
//! postfix := primary ('.' name '(' args ')')*
//! primary := number | name | name '[' sum ']' | name '(' args ')'
//!          | 'sum' '(' name 'in' sum ('..' | '..=') sum ',' sum ')' | '(' sum ')'
//! ```
//!
//! The parser descends recursively, and so do lowering and the engine after
//! it: an expression may nest at most [`MAX_NESTING`] levels (parentheses,
//! calls, brackets, sums, unary minuses, exponents, method calls), far
//! below what overflows a stack. Sums and products are chains, not nested,
//! so `x + x + ... + x` may have any number of terms.

use super::plain_name;
use crate::ast::{BinOp, Expr, IndexRange, SpanRange};
use syn::parse::ParseStream;
use syn::{Ident, LitFloat, LitInt, Token, bracketed, parenthesized};

/// The deepest an expression may nest. A textbook model nests a few levels.
/// At this depth parsing and lowering take at most about 1.5 MiB of stack in
/// a debug build of the engine (opt-level 0), 0.3 MiB optimized; rustc runs
/// a proc macro on a thread of 8 MiB.
pub const MAX_NESTING: usize = 128;

/// `depth + 1`, or the error on the next token (the operator or the group)
/// that would nest too deep.
fn deeper(input: ParseStream, depth: usize) -> syn::Result<usize> {
    if depth >= MAX_NESTING {
        return Err(too_deep(input.span()));
    }
    Ok(depth + 1)
}

pub(super) fn too_deep(span: proc_macro2::Span) -> syn::Error {
    syn::Error::new(
        span,
        format!(
            "this expression nests more than {MAX_NESTING} levels deep (parentheses, calls, unary minuses, \
             exponents or method calls): write it in steps with `let`s"
        ),
    )
}

/// `[expr]` after a name, if there: the expression and the closing span.
pub(super) fn parse_bracket(input: ParseStream) -> syn::Result<Option<(Expr, proc_macro2::Span)>> {
    bracket(input, 0)
}

fn bracket(input: ParseStream, depth: usize) -> syn::Result<Option<(Expr, proc_macro2::Span)>> {
    if !input.peek(syn::token::Bracket) {
        return Ok(None);
    }
    let depth = deeper(input, depth)?;
    let inner;
    let bracket = bracketed!(inner in input);
    if inner.is_empty() {
        return Err(syn::Error::new(
            bracket.span.join(),
            "empty brackets: expected an index or a length inside `[]`",
        ));
    }
    let e = drain_on_error(&inner, |inner| {
        let e = expr(inner, depth)?;
        if !inner.is_empty() {
            return Err(inner.error("expected an operator or `]`"));
        }
        Ok(e)
    })?;
    Ok(Some((e, bracket.span.close())))
}

/// `var in lo..hi` or `var in lo..=hi`.
pub(super) fn parse_index_range(input: ParseStream) -> syn::Result<IndexRange> {
    index_range(input, 0)
}

fn index_range(input: ParseStream, depth: usize) -> syn::Result<IndexRange> {
    let var = plain_name(input)?;
    if !input.peek(Token![in]) {
        return Err(input.error(format!(
            "expected `in`: an index is written `{var} in 0..N` or `{var} in 0..=i`"
        )));
    }
    input.parse::<Token![in]>()?;
    let lo = expr(input, depth)?;
    let inclusive = if input.peek(Token![..=]) {
        input.parse::<Token![..=]>()?;
        true
    } else if input.peek(Token![..]) {
        input.parse::<Token![..]>()?;
        false
    } else {
        return Err(input.error("expected `..` or `..=`: a range is written `0..N` or `0..=i`"));
    };
    let hi = expr(input, depth)?;
    Ok(IndexRange {
        range: SpanRange::single(var.span()).to(hi.range()),
        var,
        lo: Box::new(lo),
        hi: Box::new(hi),
        inclusive,
    })
}

/// An expression at the top level of a section.
pub fn parse_expr(input: ParseStream) -> syn::Result<Expr> {
    expr(input, 0)
}

/// `sum := product (('+' | '-') product)*`, at nesting `depth`.
fn expr(input: ParseStream, depth: usize) -> syn::Result<Expr> {
    let mut lhs = product(input, depth)?;
    loop {
        let op = if input.peek(Token![+]) {
            input.parse::<Token![+]>()?;
            BinOp::Add
        } else if input.peek(Token![-]) {
            input.parse::<Token![-]>()?;
            BinOp::Sub
        } else {
            return Ok(lhs);
        };
        let rhs = product(input, depth)?;
        lhs = lhs.then(op, rhs);
    }
}

/// `product := unary (('*' | '/') unary)*`
fn product(input: ParseStream, depth: usize) -> syn::Result<Expr> {
    let mut lhs = unary(input, depth)?;
    loop {
        let op = if input.peek(Token![*]) {
            input.parse::<Token![*]>()?;
            BinOp::Mul
        } else if input.peek(Token![/]) {
            input.parse::<Token![/]>()?;
            BinOp::Div
        } else {
            return Ok(lhs);
        };
        let rhs = unary(input, depth)?;
        lhs = lhs.then(op, rhs);
    }
}

/// `unary := '-' unary | power`
fn unary(input: ParseStream, depth: usize) -> syn::Result<Expr> {
    if input.peek(Token![-]) {
        let depth = deeper(input, depth)?;
        let minus = input.parse::<Token![-]>()?;
        let inner = unary(input, depth)?;
        return Ok(Expr::Neg {
            range: SpanRange::single(minus.span).to(inner.range()),
            inner: Box::new(inner),
        });
    }
    power(input, depth)
}

/// `power := postfix ('^' unary)?` — right-associative through `unary`.
fn power(input: ParseStream, depth: usize) -> syn::Result<Expr> {
    let base = postfix(input, depth)?;
    if input.peek(Token![^]) {
        let depth = deeper(input, depth)?;
        input.parse::<Token![^]>()?;
        let exponent = unary(input, depth)?;
        return Ok(Expr::Power {
            range: base.range().to(exponent.range()),
            base: Box::new(base),
            exponent: Box::new(exponent),
        });
    }
    Ok(base)
}

/// `postfix := primary ('.' name '(' args ')')*`; each call nests the
/// receiver one level deeper.
fn postfix(input: ParseStream, depth: usize) -> syn::Result<Expr> {
    let mut e = primary(input, depth)?;
    let mut depth = depth;
    while input.peek(Token![.]) && !input.peek(Token![..]) {
        input.parse::<Token![.]>()?;
        let method: Ident = input.parse()?;
        if depth >= MAX_NESTING {
            return Err(too_deep(method.span()));
        }
        if !input.peek(syn::token::Paren) {
            return Err(syn::Error::new(
                method.span(),
                format!(
                    "expected `(` after `.{method}`: only method calls such as `x.sin()` or `x.powi(2)` may follow a `.`"
                ),
            ));
        }
        let (mut args, close) = call_args(input, depth)?;
        depth += 1;
        args.insert(0, e);
        e = Expr::Call {
            range: args[0].range().to(SpanRange::single(close)),
            func: method,
            args,
        };
    }
    Ok(e)
}

fn call_args(input: ParseStream, depth: usize) -> syn::Result<(Vec<Expr>, proc_macro2::Span)> {
    let depth = deeper(input, depth)?;
    let inner;
    let paren = parenthesized!(inner in input);
    let args = drain_on_error(&inner, |inner| {
        let mut args = Vec::new();
        while !inner.is_empty() {
            args.push(expr(inner, depth)?);
            if inner.is_empty() {
                break;
            }
            if !inner.peek(Token![,]) {
                return Err(inner.error("expected an operator, `,` or `)`"));
            }
            inner.parse::<Token![,]>()?;
        }
        Ok(args)
    })?;
    Ok((args, paren.span.close()))
}

/// Parses a delimited group; on error, consumes the rest of it. Tokens left
/// in a group make syn fail the whole macro input with its own "unexpected
/// token", which would replace our error and lose the stub.
pub(super) fn drain_on_error<T>(
    inner: ParseStream,
    f: impl FnOnce(ParseStream) -> syn::Result<T>,
) -> syn::Result<T> {
    f(inner).inspect_err(|_| {
        let _ = inner.step(|cursor| {
            let mut rest = *cursor;
            while let Some((_, next)) = rest.token_tree() {
                rest = next;
            }
            Ok(((), rest))
        });
    })
}

/// `primary := number | name | name '(' args ')' | '(' sum ')'`
fn primary(input: ParseStream, depth: usize) -> syn::Result<Expr> {
    if input.peek(LitInt) {
        let lit: LitInt = input.parse()?;
        let value = lit
            .base10_digits()
            .parse::<f64>()
            .map_err(|_| syn::Error::new(lit.span(), "this number is not a real number"))?;
        return Ok(Expr::Num {
            value,
            span: lit.span(),
        });
    }
    if input.peek(LitFloat) {
        let lit: LitFloat = input.parse()?;
        let value = lit
            .base10_digits()
            .parse::<f64>()
            .map_err(|_| syn::Error::new(lit.span(), "this number is not a real number"))?;
        return Ok(Expr::Num {
            value,
            span: lit.span(),
        });
    }
    if input.peek(syn::token::Paren) {
        let depth = deeper(input, depth)?;
        let inner;
        let paren = parenthesized!(inner in input);
        if inner.is_empty() {
            return Err(syn::Error::new(
                paren.span.join(),
                "empty parentheses: expected an expression inside `()`",
            ));
        }
        return drain_on_error(&inner, |inner| {
            let e = expr(inner, depth)?;
            if !inner.is_empty() {
                return Err(inner.error("expected an operator or `)`"));
            }
            Ok(e)
        });
    }
    if input.peek(syn::Ident) {
        let name: Ident = plain_name(input)?;
        if name == "sum" && input.peek(syn::token::Paren) {
            return sum(input, name, depth);
        }
        if let Some((index, close)) = bracket(input, depth)? {
            return Ok(Expr::Index {
                range: SpanRange::single(name.span()).to(SpanRange::single(close)),
                base: name,
                index: Box::new(index),
            });
        }
        if input.peek(syn::token::Paren) {
            let (args, close) = call_args(input, depth)?;
            return Ok(Expr::Call {
                range: SpanRange::single(name.span()).to(SpanRange::single(close)),
                func: name,
                args,
            });
        }
        return Ok(Expr::Name(name));
    }
    if input.is_empty() || input.peek(Token![;]) || input.peek(Token![,]) {
        return Err(input.error("expected an expression here"));
    }
    Err(input.error("expected an expression: a number, a name, a function call or `(`"))
}

/// `sum(j in a..b, body)`.
fn sum(input: ParseStream, keyword: Ident, depth: usize) -> syn::Result<Expr> {
    let depth = deeper(input, depth)?;
    let inner;
    let paren = parenthesized!(inner in input);
    let (index, body) = drain_on_error(&inner, |inner| {
        if inner.is_empty() {
            return Err(inner
                .error("expected an index and a term: a sum is written `sum(i in 0..N, term)`"));
        }
        let index = index_range(inner, depth)?;
        if !inner.peek(Token![,]) {
            return Err(
                inner.error("expected `,` and the term: a sum is written `sum(i in 0..N, term)`")
            );
        }
        inner.parse::<Token![,]>()?;
        let body = expr(inner, depth)?;
        if inner.peek(Token![,]) {
            inner.parse::<Token![,]>()?;
        }
        if !inner.is_empty() {
            return Err(inner.error("expected an operator or `)`"));
        }
        Ok((index, body))
    })?;
    Ok(Expr::Sum {
        range: SpanRange::single(keyword.span()).to(SpanRange::single(paren.span.close())),
        index,
        body: Box::new(body),
    })
}
