//! The supervisor's side of a worker process: send an input, wait for its
//! line within the time limit, and turn a death or a timeout into an
//! outcome. A dead or killed worker is replaced at the next input.

use std::io::{BufRead, BufReader, Read, Write};
use std::process::{Child, ChildStdin, Command, ExitStatus, Stdio};
use std::sync::mpsc::{self, Receiver, RecvTimeoutError};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use crate::worker::{Class, Outcome};

/// What one input may use.
#[derive(Clone, Copy, Debug)]
pub struct Limits {
    pub timeout: Duration,
    pub mem_mb: usize,
}

/// A worker process, started on first use and after each death.
pub struct Worker {
    limits: Limits,
    running: Option<Running>,
    /// Processes started so far.
    pub starts: usize,
}

struct Running {
    child: Child,
    stdin: ChildStdin,
    lines: Receiver<String>,
    stderr: Arc<Mutex<String>>,
    stderr_reader: JoinHandle<()>,
}

impl Worker {
    pub fn new(limits: Limits) -> Self {
        Worker {
            limits,
            running: None,
            starts: 0,
        }
    }

    fn start(&mut self) -> std::io::Result<&mut Running> {
        if self.running.is_none() {
            // This very binary, even if a rebuild has replaced it since.
            let proc_exe = std::path::Path::new("/proc/self/exe");
            let exe = if proc_exe.exists() {
                proc_exe.to_path_buf()
            } else {
                std::env::current_exe()?
            };
            let mut child = Command::new(exe)
                .args(["--worker", "--mem-mb", &self.limits.mem_mb.to_string()])
                .stdin(Stdio::piped())
                .stdout(Stdio::piped())
                .stderr(Stdio::piped())
                .spawn()?;
            let stdout = child.stdout.take().expect("piped stdout");
            let mut stderr_pipe = child.stderr.take().expect("piped stderr");
            let (send, lines) = mpsc::channel();
            std::thread::spawn(move || {
                for line in BufReader::new(stdout).lines() {
                    let Ok(line) = line else { break };
                    if send.send(line).is_err() {
                        break;
                    }
                }
            });
            let stderr = Arc::new(Mutex::new(String::new()));
            let tail = Arc::clone(&stderr);
            let stderr_reader = std::thread::spawn(move || {
                let mut buf = [0u8; 4096];
                while let Ok(n) = stderr_pipe.read(&mut buf) {
                    if n == 0 {
                        break;
                    }
                    let mut t = tail.lock().unwrap();
                    t.push_str(&String::from_utf8_lossy(&buf[..n]));
                    if t.len() > 8192 {
                        let cut = t.len() - 4096;
                        let cut = (cut..t.len()).find(|&i| t.is_char_boundary(i)).unwrap_or(0);
                        t.drain(..cut);
                    }
                }
            });
            self.starts += 1;
            self.running = Some(Running {
                stdin: child.stdin.take().expect("piped stdin"),
                child,
                lines,
                stderr,
                stderr_reader,
            });
        }
        Ok(self.running.as_mut().expect("just started"))
    }

    /// Expands `text` in the worker (`twice`: and again, comparing bytes).
    pub fn run(&mut self, text: &str, twice: bool) -> Outcome {
        let limits = self.limits;
        let frame = format!("{} {}\n", if twice { "D" } else { "E" }, text.len());
        let send = |w: &mut Worker| {
            w.start().and_then(|r| {
                r.stdin.write_all(frame.as_bytes())?;
                r.stdin.write_all(text.as_bytes())?;
                r.stdin.flush()
            })
        };
        if send(self).is_err() {
            // A worker gone between inputs (killed from outside): once more.
            self.stop();
            if let Err(e) = send(self) {
                eprintln!("lagrange-fuzz: could not start or reach a worker process: {e}");
                std::process::exit(3);
            }
        }
        let start = Instant::now();
        let mut oom = false;
        loop {
            let running = self.running.as_mut().expect("started above");
            let left = limits.timeout.saturating_sub(start.elapsed());
            match running.lines.recv_timeout(left) {
                Ok(line) if line == "!oom" => oom = true,
                Ok(line) => {
                    if let Some(o) = Outcome::parse(&line) {
                        if oom {
                            // The engine survived a failed allocation: the
                            // limit was still reached.
                            self.stop();
                            return over_memory(limits, start);
                        }
                        return o;
                    }
                }
                Err(RecvTimeoutError::Timeout) => {
                    self.stop();
                    if oom {
                        return over_memory(limits, start);
                    }
                    return outcome(
                        Class::OverTime,
                        limits.timeout.as_nanos() as u64,
                        format!("no result within {} ms", limits.timeout.as_millis()),
                    );
                }
                Err(RecvTimeoutError::Disconnected) => {
                    let (status, stderr) = self.reap();
                    if oom {
                        return over_memory(limits, start);
                    }
                    return outcome(
                        Class::Abort,
                        start.elapsed().as_nanos() as u64,
                        death(status, &stderr),
                    );
                }
            }
        }
    }

    /// Waits for a worker whose stdout closed: its exit status and stderr.
    fn reap(&mut self) -> (Option<ExitStatus>, String) {
        let Some(mut r) = self.running.take() else {
            return (None, String::new());
        };
        drop(r.stdin);
        let status = r.child.wait().ok();
        let _ = r.stderr_reader.join();
        let stderr = r.stderr.lock().unwrap().clone();
        (status, stderr)
    }

    /// Kills the worker (our own child, by its handle) and reaps it.
    fn stop(&mut self) {
        if let Some(r) = self.running.as_mut() {
            let _ = r.child.kill();
        }
        self.reap();
    }
}

impl Drop for Worker {
    fn drop(&mut self) {
        // Closing stdin ends the worker's loop.
        self.reap();
    }
}

fn outcome(class: Class, nanos: u64, message: String) -> Outcome {
    Outcome {
        class,
        nanos,
        peak: None,
        hash: None,
        message,
    }
}

fn over_memory(limits: Limits, start: Instant) -> Outcome {
    outcome(
        Class::OverMemory,
        start.elapsed().as_nanos() as u64,
        format!("allocation beyond the {} MiB limit", limits.mem_mb),
    )
}

/// `signal 6 (SIGABRT): thread '<unnamed>' has overflowed its stack`.
fn death(status: Option<ExitStatus>, stderr: &str) -> String {
    use std::os::unix::process::ExitStatusExt;
    let how = match status {
        Some(s) => match s.signal() {
            Some(6) => "signal 6 (SIGABRT)".to_string(),
            Some(11) => "signal 11 (SIGSEGV)".to_string(),
            Some(sig) => format!("signal {sig}"),
            None => format!("exit status {}", s.code().unwrap_or(-1)),
        },
        None => "unknown status".into(),
    };
    let last: Vec<&str> = stderr.lines().filter(|l| !l.trim().is_empty()).collect();
    let tail = last[last.len().saturating_sub(2)..].join(" / ");
    if tail.is_empty() {
        how
    } else {
        format!("{how}: {tail}")
    }
}
