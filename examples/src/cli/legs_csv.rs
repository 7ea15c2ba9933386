//! Reading leg lengths from CSV, one row at a time.
//!
//! Rows are read as bytes and only the six `L1`…`L6` fields are decoded: a stray byte in a
//! column nobody reads must not cost a valid row, and a bad byte in a leg field costs that row
//! alone (`invalid_number`). A row must have as many fields as the header: with one lost or
//! one added, every field after it moves to the next column, and the leg lengths read would be
//! other numbers than the ones written under `L1`…`L6` (`missing_value`, `extra_value`).

use std::io::Read;

/// One input row: its leg lengths, or why it cannot be solved.
pub type Row = Result<[f64; 6], &'static str>;

/// The longest line accepted, bytes. A row of six leg lengths takes well under 1 KB; without
/// a bound, one line with no end (`--input /dev/zero`, a file with its line breaks lost) would
/// be held in memory whole, until the allocator gave up and the program aborted.
pub const MAX_LINE: usize = 1 << 20;

/// A streaming reader of leg-length rows: constant memory whatever the input's length.
pub struct LegRows<R: Read> {
    reader: csv::Reader<LineLimit<R>>,
    columns: [usize; 6],
    /// The header's number of fields, which every row must have.
    fields: usize,
    record: csv::ByteRecord,
    /// Rows read so far, for the message of a read error.
    rows: u64,
}

/// Input whose lines may not exceed [`MAX_LINE`] bytes, and which may not end inside a quoted
/// field: either is a read error.
struct LineLimit<R> {
    inner: R,
    /// Bytes since the last line break (`\n` or `\r`).
    run: usize,
    /// Where the input is among the CSV parser's fields.
    quote: Quote,
    /// Line breaks read so far (the last byte read a CR: a LF after it ends no new line),
    /// and the line the open quoted field began on.
    lines: u64,
    after_cr: bool,
    opened: u64,
}

/// The CSV parser's view of quotes (the `csv` crate's defaults): a `"` opens a quoted field
/// only as a field's first byte, `""` inside one is a quote, and a lone `"` closes it. A
/// quoted field may hold line breaks, so one left open takes every line after it into one
/// field: the parser accepts that at the end of the input, and the rows it swallowed would be
/// lost without a word (one `missing_value` row for all of them).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Quote {
    /// At a field's first byte.
    FieldStart,
    /// In a field that did not start with a quote.
    Plain,
    /// In a quoted field.
    Open,
    /// Just after a quote in a quoted field: it closed the field, or starts `""`.
    Closing,
}

impl Quote {
    fn after(self, b: u8) -> Quote {
        let separator = matches!(b, b',' | b'\n' | b'\r');
        match self {
            Quote::FieldStart if b == b'"' => Quote::Open,
            Quote::Open if b == b'"' => Quote::Closing,
            Quote::Open => Quote::Open,
            Quote::Closing if b == b'"' => Quote::Open,
            _ if separator => Quote::FieldStart,
            _ => Quote::Plain,
        }
    }
}

impl<R: Read> Read for LineLimit<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buf)?;
        if n == 0 && self.quote == Quote::Open {
            return Err(std::io::Error::other(format!(
                "the input ends inside a quoted field: the `\"` on line {} is never closed, and \
                 every line after it would be read as part of that field",
                self.opened
            )));
        }
        for &b in &buf[..n] {
            let was = self.quote;
            self.quote = was.after(b);
            if b == b'\n' || b == b'\r' {
                // CRLF is one line break, as are a lone CR and a lone LF.
                self.lines += u64::from(b == b'\r' || !self.after_cr);
                self.after_cr = b == b'\r';
                self.run = 0;
            } else {
                self.after_cr = false;
                self.run += 1;
                if self.run > MAX_LINE {
                    return Err(std::io::Error::other(format!(
                        "a line longer than {} MB: not a CSV of leg lengths",
                        MAX_LINE >> 20
                    )));
                }
            }
            if was != Quote::Open && self.quote == Quote::Open {
                self.opened = self.lines + 1;
            }
        }
        Ok(n)
    }
}

impl<R: Read> LegRows<R> {
    /// Reads the header. A missing, repeated or unreadable `L1`…`L6` column is an error: with
    /// two `L1` columns no one can say which holds the leg length.
    pub fn new(source: R) -> Result<Self, String> {
        let mut reader = csv::ReaderBuilder::new()
            .trim(csv::Trim::All)
            .flexible(true)
            .from_reader(LineLimit {
                inner: source,
                run: 0,
                quote: Quote::FieldStart,
                lines: 0,
                after_cr: false,
                opened: 0,
            });
        let headers = reader.byte_headers().map_err(|e| e.to_string())?.clone();
        let mut columns = [0usize; 6];
        for (i, c) in columns.iter_mut().enumerate() {
            let name = format!("L{}", i + 1);
            let mut found = headers
                .iter()
                .enumerate()
                .filter(|(_, h)| *h == name.as_bytes())
                .map(|(k, _)| k);
            *c = found
                .next()
                .ok_or_else(|| format!("the header has no column `{name}` (it needs L1…L6)"))?;
            if let Some(again) = found.next() {
                return Err(format!(
                    "the header has column `{name}` twice (columns {} and {}): which one holds the leg length is ambiguous",
                    *c + 1,
                    again + 1
                ));
            }
        }
        Ok(LegRows {
            fields: headers.len(),
            reader,
            columns,
            record: csv::ByteRecord::new(),
            rows: 0,
        })
    }

    /// The next row, `None` at the end of the input; a read error is an error (the rows that
    /// follow cannot be numbered), a bad row is a row status.
    pub fn next_row(&mut self) -> Result<Option<Row>, String> {
        match self.reader.read_byte_record(&mut self.record) {
            Ok(false) => Ok(None),
            Ok(true) => {
                self.rows += 1;
                Ok(Some(parse_row(&self.record, &self.columns, self.fields)))
            }
            Err(e) => Err(format!(
                "cannot read the input after row {}: {e}",
                self.rows
            )),
        }
    }
}

impl<R: Read> Iterator for LegRows<R> {
    type Item = Result<Row, String>;

    fn next(&mut self) -> Option<Self::Item> {
        self.next_row().transpose()
    }
}

/// Reads every row of a file (`-`: standard input, as `solve` reads it) into memory (for
/// `bench`, which replays them, and `modes`).
pub fn read(path: &std::path::Path) -> Result<Vec<Row>, String> {
    let source = super::stream::open_input(path)?;
    read_from(source).map_err(|e| format!("{}: {e}", path.display()))
}

/// Reads every row from any reader; a missing or repeated `L1`…`L6` column, an unreadable
/// header or a read error is an error, a bad row is a row status.
pub fn read_from<R: Read>(source: R) -> Result<Vec<Row>, String> {
    LegRows::new(source)?.collect()
}

/// A row's leg lengths. Its fields are matched to the header's by position, so a row with a
/// field fewer or more than the header is refused whole: which field was lost or added cannot
/// be told, and every field after it would be read under the wrong name. Empty fields past
/// the header's (a trailing comma) add nothing and are allowed.
fn parse_row(r: &csv::ByteRecord, columns: &[usize; 6], fields: usize) -> Row {
    if r.len() < fields {
        return Err("missing_value");
    }
    if r.iter().skip(fields).any(|f| !f.is_empty()) {
        return Err("extra_value");
    }
    let mut x = [0.0; 6];
    for (j, &c) in columns.iter().enumerate() {
        let field = r.get(c).ok_or("missing_value")?;
        let text = std::str::from_utf8(field).map_err(|_| "invalid_number")?;
        x[j] = text.parse::<f64>().map_err(|_| "invalid_number")?;
        if !x[j].is_finite() {
            return Err("non_finite");
        }
    }
    Ok(x)
}
