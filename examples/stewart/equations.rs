//! `stewart equations`: the generated Eq. 19 and Table A1.

use linkage::Mechanism;
use linkage_examples::cli::stream::print;
use linkage_examples::stewart::Stewart;

pub fn run(json: bool) -> Result<(), String> {
    if !json {
        return print(Stewart::LISTING);
    }
    let jacobian: Vec<serde_json::Value> = Stewart::PATTERN
        .iter()
        .zip(Stewart::JACOBIAN)
        .map(|(&(r, c), e)| serde_json::json!({ "row": r + 1, "col": c + 1, "expr": e }))
        .collect();
    let out = serde_json::json!({
        "unknowns": Stewart::UNKNOWNS,
        "inputs": Stewart::INPUTS,
        "equations": Stewart::EQUATIONS,
        "jacobian": jacobian,
    });
    print(&format!("{out}\n"))
}
