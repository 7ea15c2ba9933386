//! The file readers on mangled input: an error, never a panic. A stable, deterministic cousin
//! of the cargo-fuzz targets in `tests/fuzz`; the generator's half is
//! `macros/codegen/tests/front_end_robustness.rs`.

use linkage_examples::cli::{geometry, legs_csv};
use linkage_tests::Rng;

#[test]
fn the_file_readers_survive_mangled_input() {
    let toml = "base = [[0,0,0],[1,0,0],[2,0,0],[3,0,0],[4,0,0],[5,0,0]]\nplatform = [[0,0,0],[1,0,0],[2,0,0],[3,0,0],[4,0,0],[5,0,0]]\n[start]\nlegs = [1,1,1,1,1,1]\npose = [0,0,0,0,0,1]\n";
    let csv = "t,L1,L2,L3,L4,L5,L6\n0,170,170,170,170,170,170\n1,\"a\",2,3,4,5,6\n";
    let mut rng = Rng::new(7);
    for _ in 0..3000 {
        for (text, is_toml) in [(toml, true), (csv, false)] {
            let mut bytes = text.as_bytes().to_vec();
            for _ in 0..1 + rng.next_u64() % 6 {
                let i = (rng.next_u64() as usize) % bytes.len();
                match rng.next_u64() % 3 {
                    0 => bytes[i] = (rng.next_u64() % 256) as u8,
                    1 => {
                        bytes.remove(i);
                    }
                    _ => bytes.insert(i, b"[],=\"\n-e9."[(rng.next_u64() % 10) as usize]),
                }
            }
            if is_toml {
                let _ = geometry::parse(&String::from_utf8_lossy(&bytes));
            } else {
                let _ = legs_csv::read_from(bytes.as_slice());
            }
        }
    }
}
