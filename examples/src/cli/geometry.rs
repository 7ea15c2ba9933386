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

pub fn load(path: &Path) -> Result<Geometry, String> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
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
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
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
