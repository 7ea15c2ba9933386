//! Writes the stored start sets of `linkage_examples::start_sets` (monodromy, once).
//!
//! `cargo run --release --example start_sets` (from the workspace root).

use std::path::Path;

fn main() -> Result<(), String> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/start_sets");
    for (name, text) in linkage_examples::start_sets::generate().map_err(|e| e.to_string())? {
        let path = dir.join(name);
        std::fs::write(&path, text).map_err(|e| format!("{}: {e}", path.display()))?;
        println!("wrote {}", path.display());
    }
    Ok(())
}
