//! Reading leg lengths and writing results as CSV.

use std::io::Write;

/// One input row: its leg lengths, or why it cannot be solved.
pub type Row = Result<[f64; 6], &'static str>;

pub fn read(path: &std::path::Path) -> Result<Vec<Row>, String> {
    let file =
        std::fs::File::open(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    read_from(file).map_err(|e| format!("{}: {e}", path.display()))
}

/// Reads rows from any reader; a missing `L1`…`L6` column or an unreadable header is an error,
/// a bad row is a row status.
pub fn read_from<R: std::io::Read>(source: R) -> Result<Vec<Row>, String> {
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .flexible(true)
        .from_reader(source);
    let headers = reader.headers().map_err(|e| e.to_string())?.clone();
    let mut columns = [0usize; 6];
    for (i, c) in columns.iter_mut().enumerate() {
        let name = format!("L{}", i + 1);
        *c = headers
            .iter()
            .position(|h| h == name)
            .ok_or_else(|| format!("the header has no column `{name}` (it needs L1…L6)"))?;
    }
    let mut rows = Vec::new();
    for record in reader.records() {
        let row = match record {
            Err(_) => Err("malformed_row"),
            Ok(r) => parse_row(&r, &columns),
        };
        rows.push(row);
    }
    Ok(rows)
}

fn parse_row(r: &csv::StringRecord, columns: &[usize; 6]) -> Row {
    let mut x = [0.0; 6];
    for (j, &c) in columns.iter().enumerate() {
        let field = r.get(c).ok_or("missing_value")?;
        x[j] = field.parse::<f64>().map_err(|_| "invalid_number")?;
        if !x[j].is_finite() {
            return Err("non_finite");
        }
    }
    Ok(x)
}

/// The output header: row, status, the pose (Appendix B), v in the paper's order, and the
/// solve's account.
pub fn header() -> Vec<String> {
    let mut h: Vec<String> = ["row", "status", "yaw", "pitch", "roll", "x", "y", "z"]
        .map(String::from)
        .to_vec();
    h.extend((1..=18).map(|i| format!("v{i}")));
    h.push("error_estimate".into());
    h.push("steps".into());
    h
}

pub struct Output {
    writer: csv::Writer<Box<dyn Write>>,
}

impl Output {
    pub fn new(path: Option<&std::path::Path>) -> Result<Self, String> {
        let sink: Box<dyn Write> = match path {
            Some(p) => Box::new(
                std::fs::File::create(p)
                    .map_err(|e| format!("cannot write {}: {e}", p.display()))?,
            ),
            None => Box::new(std::io::stdout()),
        };
        let mut writer = csv::Writer::from_writer(sink);
        writer.write_record(header()).map_err(|e| e.to_string())?;
        Ok(Output { writer })
    }

    /// A row; `solution` is `None` when there is no pose to report.
    pub fn row(
        &mut self,
        row: usize,
        status: &str,
        solution: Option<(&[f64; 6], &[f64; 18])>,
        error: Option<f64>,
        steps: Option<u32>,
    ) -> Result<(), String> {
        let mut rec = vec![row.to_string(), status.to_string()];
        match solution {
            Some((pose, v)) => {
                rec.extend(pose.iter().map(|x| format!("{x:.12}")));
                rec.extend(v.iter().map(|x| format!("{x:.12}")));
            }
            None => rec.extend(std::iter::repeat_n(String::new(), 24)),
        }
        rec.push(error.map_or(String::new(), |e| format!("{e:.3e}")));
        rec.push(steps.map_or(String::new(), |s| s.to_string()));
        self.writer.write_record(rec).map_err(|e| e.to_string())
    }

    pub fn finish(mut self) -> Result<(), String> {
        self.writer.flush().map_err(|e| e.to_string())
    }
}
