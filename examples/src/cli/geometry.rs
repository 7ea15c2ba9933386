//! The `--geometry` TOML file.

use serde::Deserialize;
use std::path::Path;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    base: Vec<[f64; 3]>,
    platform: Vec<[f64; 3]>,
    start: StartSection,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct StartSection {
    legs: Vec<f64>,
    pose: Option<Vec<f64>>,
}

/// A validated 6-6 geometry with its start.
pub struct Geometry {
    pub base: [[f64; 3]; 6],
    pub platform: [[f64; 3]; 6],
    pub legs: [f64; 6],
    pub pose: Option<[f64; 6]>,
}

fn six<T: Copy>(v: &[T], what: &str) -> Result<[T; 6], String> {
    v.try_into()
        .map_err(|_| format!("`{what}` needs 6 entries, found {}", v.len()))
}

/// The longest geometry file read, bytes: a geometry takes well under 1 KB, and a path to
/// something endless (`/dev/zero`) must not be read into memory until the allocator gives up.
const MAX_FILE: u64 = 1 << 20;

/// The file's text, at most [`MAX_FILE`] bytes.
fn read_text(path: &Path) -> Result<String, String> {
    use std::io::Read;
    let cannot = |e: std::io::Error| format!("cannot read {}: {e}", path.display());
    let mut text = String::new();
    std::fs::File::open(path)
        .map_err(cannot)?
        .take(MAX_FILE + 1)
        .read_to_string(&mut text)
        .map_err(cannot)?;
    if text.len() as u64 > MAX_FILE {
        return Err(format!(
            "{}: longer than {} MB: not a geometry file",
            path.display(),
            MAX_FILE >> 20
        ));
    }
    Ok(text)
}

pub fn load(path: &Path) -> Result<Geometry, String> {
    let text = read_text(path)?;
    parse(&text).map_err(|e| format!("{}: {e}", path.display()))
}

pub fn parse(text: &str) -> Result<Geometry, String> {
    let f: File = toml::from_str(text).map_err(|e| e.to_string().trim().replace('\n', " "))?;
    let g = Geometry {
        base: six(&f.base, "base")?,
        platform: six(&f.platform, "platform")?,
        legs: six(&f.start.legs, "start.legs")?,
        pose: f
            .start
            .pose
            .as_deref()
            .map(|p| six(p, "start.pose"))
            .transpose()?,
    };
    let values = g
        .base
        .iter()
        .flatten()
        .chain(g.platform.iter().flatten())
        .chain(&g.legs)
        .chain(g.pose.iter().flatten());
    if values.into_iter().any(|x| !x.is_finite()) {
        return Err("every geometry value must be a finite number".into());
    }
    if let Some(i) = g.legs.iter().position(|l| *l <= 0.0) {
        return Err(format!("start leg L{} must be positive", i + 1));
    }
    Ok(g)
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct JointsFile {
    base: Vec<[f64; 3]>,
    platform: Vec<[f64; 3]>,
    #[allow(dead_code)]
    start: Option<StartSection>,
}

/// Base and platform joint centres.
pub type Joints = ([[f64; 3]; 6], [[f64; 3]; 6]);

/// Only the joint centres, base and platform: for commands that need no start configuration
/// (`stewart modes`), the `[start]` section is optional (and ignored).
pub fn load_joints(path: &Path) -> Result<Joints, String> {
    let text = read_text(path)?;
    parse_joints(&text).map_err(|e| format!("{}: {e}", path.display()))
}

pub fn parse_joints(text: &str) -> Result<Joints, String> {
    let f: JointsFile =
        toml::from_str(text).map_err(|e| e.to_string().trim().replace('\n', " "))?;
    let (base, platform) = (six(&f.base, "base")?, six(&f.platform, "platform")?);
    if base
        .iter()
        .chain(&platform)
        .flatten()
        .any(|x| !x.is_finite())
    {
        return Err("every geometry value must be a finite number".into());
    }
    Ok((base, platform))
}
