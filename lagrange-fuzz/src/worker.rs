//! The worker process: expands inputs one by one, each on a fresh thread
//! with an 8 MiB stack (what rustc gives a proc macro), under a memory
//! limit, and reports each outcome as one line on stdout. A stack overflow
//! or a failed allocation kills the process; the supervisor sees the death
//! (and the `!oom` line written first by the allocator) and starts another.
//!
//! Protocol, supervisor → worker: `E <len>\n` or `D <len>\n` (expand twice
//! and compare, for the determinism check) followed by `len` bytes of
//! source. Worker → supervisor: one [`Outcome`] line per input.

use std::alloc::{GlobalAlloc, Layout, System};
use std::io::{BufRead, Read, Write};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};
use std::time::Instant;

use proc_macro2::{TokenStream, TokenTree};

/// The stack rustc's main thread has, on which proc macros run.
pub const STACK: usize = 8 << 20;

/// Live heap bytes, their peak since the input began, and the limit.
static CURRENT: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);
static LIMIT: AtomicUsize = AtomicUsize::new(usize::MAX);

/// The system allocator, counting live bytes: the per-input peak is
/// measured exactly, and the memory limit is the same on every machine
/// (address-space limits also count fragmentation and thread stacks).
pub struct Counting;

fn reserve(n: usize) -> bool {
    let now = CURRENT.fetch_add(n, Relaxed) + n;
    if now > LIMIT.load(Relaxed) {
        CURRENT.fetch_sub(n, Relaxed);
        out_of_memory();
        return false;
    }
    // Not a `fetch_max`: one thread allocates at a time, and a read-modify-
    // write on every allocation costs the engine a tenth of its time.
    if now > PEAK.load(Relaxed) {
        PEAK.store(now, Relaxed);
    }
    true
}

/// Tells the supervisor before the process aborts; allocates nothing.
fn out_of_memory() {
    const LINE: &[u8] = b"!oom\n";
    // SAFETY: writes a static buffer to the process's stdout descriptor.
    unsafe { libc::write(1, LINE.as_ptr().cast(), LINE.len()) };
}

// SAFETY: every call is forwarded to `System` with the same layout; the
// counters only decide whether to forward an allocation at all.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if !reserve(layout.size()) {
            return std::ptr::null_mut();
        }
        // SAFETY: the caller's layout, as `GlobalAlloc::alloc` requires.
        let p = unsafe { System.alloc(layout) };
        if p.is_null() {
            CURRENT.fetch_sub(layout.size(), Relaxed);
            out_of_memory();
        }
        p
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if !reserve(layout.size()) {
            return std::ptr::null_mut();
        }
        // SAFETY: the caller's layout, as `GlobalAlloc::alloc_zeroed` requires.
        let p = unsafe { System.alloc_zeroed(layout) };
        if p.is_null() {
            CURRENT.fetch_sub(layout.size(), Relaxed);
            out_of_memory();
        }
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: `ptr` came from `System` with this layout (every
        // allocation above is forwarded to it).
        unsafe { System.dealloc(ptr, layout) };
        CURRENT.fetch_sub(layout.size(), Relaxed);
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let old = layout.size();
        if new_size > old && !reserve(new_size - old) {
            return std::ptr::null_mut();
        }
        // SAFETY: `ptr` came from `System` with this layout, as above.
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if p.is_null() {
            if new_size > old {
                CURRENT.fetch_sub(new_size - old, Relaxed);
            }
            out_of_memory();
        } else if new_size < old {
            CURRENT.fetch_sub(old - new_size, Relaxed);
        }
        p
    }
}

/// What became of one input.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Class {
    /// Items only: the model derived.
    Expansion,
    /// A `compile_error!` (with the stub).
    CompileError,
    /// Not Rust tokens: a generator bug, never given to the engine (rustc
    /// never passes such input to a macro).
    Unlexable,
    /// Output that is not a sequence of Rust items.
    Malformed,
    /// The same model expanded to different bytes.
    Nondeterministic,
    Panic,
    /// Stack overflow or any other death of the process.
    Abort,
    OverTime,
    OverMemory,
}

impl Class {
    pub const ALL: [Class; 9] = [
        Class::Expansion,
        Class::CompileError,
        Class::Unlexable,
        Class::Malformed,
        Class::Nondeterministic,
        Class::Panic,
        Class::Abort,
        Class::OverTime,
        Class::OverMemory,
    ];

    pub fn name(&self) -> &'static str {
        match self {
            Class::Expansion => "expansion",
            Class::CompileError => "compile_error",
            Class::Unlexable => "unlexable",
            Class::Malformed => "malformed",
            Class::Nondeterministic => "nondeterministic",
            Class::Panic => "panic",
            Class::Abort => "abort",
            Class::OverTime => "over_time",
            Class::OverMemory => "over_memory",
        }
    }

    pub fn parse(s: &str) -> Option<Class> {
        Class::ALL.into_iter().find(|c| c.name() == s)
    }

    /// A finding: the engine broke its contract on this input.
    pub fn is_failure(&self) -> bool {
        !matches!(
            self,
            Class::Expansion | Class::CompileError | Class::Unlexable
        )
    }
}

/// One input's result, as reported by the worker.
#[derive(Clone, Debug)]
pub struct Outcome {
    pub class: Class,
    /// Expansion time (for over-time: the limit).
    pub nanos: u64,
    /// Peak live heap during the input, if measured.
    pub peak: Option<usize>,
    /// FNV-1a 128 of the output's text, for `D` requests.
    pub hash: Option<u128>,
    /// The first compile error, the panic message, or why it died.
    pub message: String,
}

impl Outcome {
    pub fn line(&self) -> String {
        let hash = self.hash.map_or("-".into(), |h| format!("{h:032x}"));
        let peak = self.peak.map_or("-".into(), |p| p.to_string());
        let message = self.message.replace('\\', "\\\\").replace('\n', "\\n");
        format!(
            "{} {} {peak} {hash} {message}",
            self.class.name(),
            self.nanos
        )
    }

    pub fn parse(line: &str) -> Option<Outcome> {
        let mut parts = line.splitn(5, ' ');
        let class = Class::parse(parts.next()?)?;
        let nanos = parts.next()?.parse().ok()?;
        let peak = parts.next()?.parse().ok();
        let hash = u128::from_str_radix(parts.next()?, 16).ok();
        let message = unescape(parts.next().unwrap_or(""));
        Some(Outcome {
            class,
            nanos,
            peak,
            hash,
            message,
        })
    }
}

fn unescape(s: &str) -> String {
    let mut out = String::new();
    let mut chars = s.chars();
    while let Some(c) = chars.next() {
        if c == '\\' {
            match chars.next() {
                Some('n') => out.push('\n'),
                Some(other) => out.push(other),
                None => {}
            }
        } else {
            out.push(c);
        }
    }
    out
}

static PANIC: Mutex<Option<String>> = Mutex::new(None);

/// The worker's main loop; returns when stdin closes.
pub fn run(mem_mb: usize) {
    let limit = mem_mb << 20;
    LIMIT.store(limit, Relaxed);
    // A backstop for memory the allocator does not see.
    let backstop = (limit + (512 << 20)) as libc::rlim_t;
    let rlimit = libc::rlimit {
        rlim_cur: backstop,
        rlim_max: backstop,
    };
    // SAFETY: setrlimit reads a valid struct; failure only loses the backstop.
    unsafe { libc::setrlimit(libc::RLIMIT_AS, &rlimit) };
    std::panic::set_hook(Box::new(|info| {
        *PANIC.lock().unwrap_or_else(|e| e.into_inner()) = Some(info.to_string());
    }));
    let stdin = std::io::stdin();
    let mut input = stdin.lock();
    let mut header = String::new();
    loop {
        header.clear();
        if input.read_line(&mut header).unwrap_or(0) == 0 {
            return;
        }
        let mut parts = header.split_whitespace();
        let twice = parts.next() == Some("D");
        let len: usize = parts.next().and_then(|n| n.parse().ok()).unwrap_or(0);
        let mut text = vec![0; len];
        if input.read_exact(&mut text).is_err() {
            return;
        }
        let text = String::from_utf8_lossy(&text).into_owned();
        let outcome = std::thread::Builder::new()
            .stack_size(STACK)
            .spawn(move || expand_one(&text, twice))
            .expect("spawning the expansion thread")
            .join()
            .unwrap_or_else(|_| Outcome {
                class: Class::Panic,
                nanos: 0,
                peak: None,
                hash: None,
                message: "panic outside the expansion".into(),
            });
        let mut out = std::io::stdout().lock();
        let _ = writeln!(out, "{}", outcome.line());
        let _ = out.flush();
    }
}

/// Lexes, expands and classifies one input, catching panics.
fn expand_one(text: &str, twice: bool) -> Outcome {
    PEAK.store(CURRENT.load(Relaxed), Relaxed);
    let base = CURRENT.load(Relaxed);
    let mut outcome = Outcome {
        class: Class::Unlexable,
        nanos: 0,
        peak: None,
        hash: None,
        message: String::new(),
    };
    let Ok(tokens) = text.parse::<TokenStream>() else {
        return outcome;
    };
    let again = twice.then(|| tokens.clone());
    let start = Instant::now();
    let result = catch_unwind(AssertUnwindSafe(|| {
        let output = lagrange_engine::expand(tokens);
        let nanos = start.elapsed().as_nanos() as u64;
        let (errors, first) = compile_errors(&output);
        let (class, message) = match syn::parse2::<syn::File>(output.clone()) {
            Err(e) => (Class::Malformed, format!("output is not Rust items: {e}")),
            Ok(_) if errors > 0 => (Class::CompileError, first),
            Ok(_) => (Class::Expansion, String::new()),
        };
        let mut hash = None;
        let mut class = class;
        if let Some(again) = again {
            let text = output.to_string();
            if lagrange_engine::expand(again).to_string() != text {
                class = Class::Nondeterministic;
            }
            hash = Some(fnv128(text.as_bytes()));
        }
        (class, message, nanos, hash)
    }));
    outcome.peak = Some(PEAK.load(Relaxed).saturating_sub(base));
    match result {
        Ok((class, message, nanos, hash)) => {
            outcome.class = class;
            outcome.message = message;
            outcome.nanos = nanos;
            outcome.hash = hash;
        }
        Err(payload) => {
            outcome.class = Class::Panic;
            outcome.nanos = start.elapsed().as_nanos() as u64;
            let hooked = PANIC.lock().unwrap_or_else(|e| e.into_inner()).take();
            outcome.message = hooked.unwrap_or_else(|| {
                payload
                    .downcast_ref::<&str>()
                    .map(|s| s.to_string())
                    .or_else(|| payload.downcast_ref::<String>().cloned())
                    .unwrap_or_else(|| "panic with a non-string payload".into())
            });
        }
    }
    outcome
}

/// How many `compile_error!`s the output holds, and the first one's message.
fn compile_errors(output: &TokenStream) -> (usize, String) {
    fn walk(stream: TokenStream, count: &mut usize, first: &mut String) {
        let mut previous_was_compile_error = false;
        for tt in stream {
            match &tt {
                TokenTree::Ident(id) => previous_was_compile_error = id == "compile_error",
                TokenTree::Punct(p) if p.as_char() == '!' && previous_was_compile_error => {
                    *count += 1;
                    previous_was_compile_error = false;
                    continue;
                }
                TokenTree::Group(g) => {
                    if *count == 1 && first.is_empty() {
                        if let Some(TokenTree::Literal(lit)) = g.stream().into_iter().next() {
                            *first = lit.to_string();
                        }
                    }
                    walk(g.stream(), count, first);
                    previous_was_compile_error = false;
                }
                _ => previous_was_compile_error = false,
            }
        }
    }
    let (mut count, mut first) = (0, String::new());
    walk(output.clone(), &mut count, &mut first);
    (count, first)
}

/// FNV-1a, 128 bits: a fingerprint of an expansion's bytes for comparing
/// expansions made in different processes.
pub fn fnv128(bytes: &[u8]) -> u128 {
    let mut h: u128 = 0x6c62272e07bb014262b821756295c58d;
    for &b in bytes {
        h ^= b as u128;
        h = h.wrapping_mul(0x0000000001000000000000000000013B);
    }
    h
}
