//! Reading leg lengths from CSV, one row at a time.
//!
//! Rows are read as bytes and only the six `L1`…`L6` fields are decoded: a stray byte in a
//! column nobody reads must not cost a valid row, and a bad byte in a leg field costs that row
//! alone (`invalid_number`).

use std::io::Read;

/// One input row: its leg lengths, or why it cannot be solved.
pub type Row = Result<[f64; 6], &'static str>;

/// A streaming reader of leg-length rows: constant memory whatever the input's length.
pub struct LegRows<R: Read> {
    reader: csv::Reader<R>,
    columns: [usize; 6],
    record: csv::ByteRecord,
}

impl<R: Read> LegRows<R> {
    /// Reads the header. A missing, repeated or unreadable `L1`…`L6` column is an error: with
    /// two `L1` columns no one can say which holds the leg length.
    pub fn new(source: R) -> Result<Self, String> {
        let mut reader = csv::ReaderBuilder::new()
            .trim(csv::Trim::All)
            .flexible(true)
            .from_reader(source);
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
            reader,
            columns,
            record: csv::ByteRecord::new(),
        })
    }

    /// The next row, `None` at the end of the input; a read error is an error (the rows that
    /// follow cannot be numbered), a bad row is a row status.
    pub fn next_row(&mut self) -> Result<Option<Row>, String> {
        match self.reader.read_byte_record(&mut self.record) {
            Ok(false) => Ok(None),
            Ok(true) => Ok(Some(parse_row(&self.record, &self.columns))),
            Err(e) => Err(format!("cannot read the input: {e}")),
        }
    }
}

impl<R: Read> Iterator for LegRows<R> {
    type Item = Result<Row, String>;

    fn next(&mut self) -> Option<Self::Item> {
        self.next_row().transpose()
    }
}

/// Reads every row of a file into memory (for `bench`, which replays them).
pub fn read(path: &std::path::Path) -> Result<Vec<Row>, String> {
    let file =
        std::fs::File::open(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    read_from(file).map_err(|e| format!("{}: {e}", path.display()))
}

/// Reads every row from any reader; a missing or repeated `L1`…`L6` column, an unreadable
/// header or a read error is an error, a bad row is a row status.
pub fn read_from<R: Read>(source: R) -> Result<Vec<Row>, String> {
    LegRows::new(source)?.collect()
}

fn parse_row(r: &csv::ByteRecord, columns: &[usize; 6]) -> Row {
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
