//! Streaming plumbing: where results go, and when they are flushed.
//!
//! Results are buffered, and flushed whenever the input is about to be read: a pipe or FIFO
//! gets each row before the program waits for the next input, while a file read in large
//! blocks costs one write per block, not one per row. A write error (a closed pipe, a full
//! disk) is kept and reported, never swallowed.

use std::cell::RefCell;
use std::io::{self, BufWriter, Read, Write};
use std::path::{Path, PathBuf};
use std::rc::Rc;

/// Where results are written: a file (created on first use) or standard output.
pub struct Sink {
    path: Option<PathBuf>,
    out: Option<BufWriter<Box<dyn Write>>>,
    /// The first write error, with what was being written.
    failed: Option<String>,
}

/// A [`Sink`] shared by the writer and the input's [`FlushBeforeRead`].
#[derive(Clone)]
pub struct SharedSink(Rc<RefCell<Sink>>);

impl SharedSink {
    /// `None` is standard output. Nothing is created until the first line: a bad input header
    /// leaves an existing output file alone.
    pub fn new(path: Option<&Path>) -> Self {
        SharedSink(Rc::new(RefCell::new(Sink {
            path: path.map(Path::to_path_buf),
            out: None,
            failed: None,
        })))
    }

    /// Appends one line (without its newline).
    pub fn write_line(&self, line: &str) -> Result<(), String> {
        let mut sink = self.0.borrow_mut();
        sink.check()?;
        let result = match sink.open() {
            Ok(out) => out
                .write_all(line.as_bytes())
                .and_then(|()| out.write_all(b"\n")),
            Err(e) => Err(e),
        };
        sink.record(result)
    }

    /// Writes out everything buffered.
    pub fn flush(&self) -> Result<(), String> {
        let mut sink = self.0.borrow_mut();
        sink.check()?;
        let result = match sink.out.as_mut() {
            Some(out) => out.flush(),
            None => Ok(()),
        };
        sink.record(result)
    }

    /// The first write error, if any.
    pub fn check(&self) -> Result<(), String> {
        self.0.borrow().check()
    }
}

impl Sink {
    fn name(&self) -> String {
        match &self.path {
            Some(p) => p.display().to_string(),
            None => "standard output".into(),
        }
    }

    fn open(&mut self) -> io::Result<&mut BufWriter<Box<dyn Write>>> {
        if self.out.is_none() {
            let w: Box<dyn Write> = match &self.path {
                Some(p) => Box::new(std::fs::File::create(p)?),
                None => Box::new(io::stdout()),
            };
            self.out = Some(BufWriter::with_capacity(64 * 1024, w));
        }
        Ok(self.out.as_mut().expect("just opened"))
    }

    fn check(&self) -> Result<(), String> {
        match &self.failed {
            Some(e) => Err(e.clone()),
            None => Ok(()),
        }
    }

    fn record(&mut self, result: io::Result<()>) -> Result<(), String> {
        if let Err(e) = result {
            self.failed = Some(format!(
                "cannot write {}: {e} (the results are incomplete)",
                self.name()
            ));
            // The buffer cannot be written either; dropping it must not try again.
            if let Some(out) = self.out.take() {
                let _ = out.into_parts();
            }
        }
        self.check()
    }
}

/// Input that flushes the results before each read: a reader that may block (a pipe, a FIFO,
/// a terminal) first hands over every result so far. A failed flush fails the read, and the
/// sink keeps the reason ([`SharedSink::check`]).
pub struct FlushBeforeRead<R> {
    inner: R,
    sink: SharedSink,
}

impl<R: Read> FlushBeforeRead<R> {
    pub fn new(inner: R, sink: SharedSink) -> Self {
        FlushBeforeRead { inner, sink }
    }
}

impl<R: Read> Read for FlushBeforeRead<R> {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        self.sink.flush().map_err(io::Error::other)?;
        self.inner.read(buf)
    }
}

/// The input: a file, or standard input for `-`.
pub fn open_input(path: &Path) -> Result<Box<dyn Read>, String> {
    if path == Path::new("-") {
        return Ok(Box::new(io::stdin()));
    }
    let file =
        std::fs::File::open(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    Ok(Box::new(file))
}

/// Refuses to write results over a file the command still reads: an `--output` (or standard
/// output appended to a file, `>>`) that is the `--input` file would be truncated or grown
/// under the reader, which then reads its own results as rows: the rows not yet read are lost,
/// and the loop fills the disk. Also refused: an output over the `--geometry` file, which
/// would be destroyed. `None` is standard output, `-` standard input; the files are compared
/// by identity (device and inode: a symbolic or hard link is the same file). Only regular
/// files and named pipes (one FIFO both read and written feeds on itself) are compared:
/// `/dev/null`, anonymous pipes and terminals may be both.
pub fn refuse_overwriting(output: Option<&Path>, inputs: &[&Path]) -> Result<(), String> {
    let out_path = output.unwrap_or(Path::new("/dev/stdout"));
    let Some(out) = file_identity(out_path) else {
        return Ok(());
    };
    for input in inputs {
        let path = if *input == Path::new("-") {
            Path::new("/dev/stdin")
        } else {
            input
        };
        if file_identity(path) == Some(out) {
            let what = match output {
                Some(p) => format!("--output {}", p.display()),
                None => "standard output".into(),
            };
            let name = if *input == Path::new("-") {
                "standard input".into()
            } else {
                format!("the input file {}", input.display())
            };
            return Err(format!(
                "{what} is {name}: writing the results there would destroy the input (write them to another file)"
            ));
        }
    }
    Ok(())
}

/// A regular file's or a FIFO's device and inode, following links; `None` for anything else
/// or a path that does not exist (yet).
#[cfg(unix)]
fn file_identity(path: &Path) -> Option<(u64, u64)> {
    use std::os::unix::fs::{FileTypeExt, MetadataExt};
    let meta = std::fs::metadata(path).ok()?;
    (meta.is_file() || meta.file_type().is_fifo()).then(|| (meta.dev(), meta.ino()))
}

/// Elsewhere: the canonical path of a regular file.
#[cfg(not(unix))]
fn file_identity(path: &Path) -> Option<PathBuf> {
    let meta = std::fs::metadata(path).ok()?;
    meta.is_file()
        .then(|| std::fs::canonicalize(path).ok())
        .flatten()
}

/// Whether standard output was closed when the program started (`stewart … >&-`).
///
/// The Rust runtime then puts /dev/null, opened read-write, in its place, so every result
/// would vanish and the exit code would still be 0. A shell's `> /dev/null` opens it
/// write-only: that is a choice, and is respected. (A parent that hands over /dev/null opened
/// read-write looks the same as a closed descriptor; `--output /dev/null` says it plainly.)
/// Linux only (`/proc`); elsewhere `false`.
pub fn stdout_was_closed() -> bool {
    let Ok(target) = std::fs::read_link("/proc/self/fd/1") else {
        return false;
    };
    if target != Path::new("/dev/null") {
        return false;
    }
    let Ok(info) = std::fs::read_to_string("/proc/self/fdinfo/1") else {
        return false;
    };
    info.lines()
        .find_map(|l| l.strip_prefix("flags:"))
        .and_then(|f| u32::from_str_radix(f.trim(), 8).ok())
        // O_ACCMODE = 0o3; O_RDWR = 0o2.
        .is_some_and(|flags| flags & 0o3 == 0o2)
}

/// Writes `text` to standard output: a closed pipe or a full disk is an error to report, not
/// a panic (as `println!` would make it).
pub fn print(text: &str) -> Result<(), String> {
    let mut out = io::stdout().lock();
    out.write_all(text.as_bytes())
        .and_then(|()| out.flush())
        .map_err(|e| format!("cannot write standard output: {e}"))
}
