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

/// A line with no end (`--input /dev/zero`, a file whose line breaks were lost) was read into
/// memory whole: the program aborted when the allocator gave up (`memory allocation of
/// 536870912 bytes failed` under a 400 MB limit). A line beyond 1 MB, or a geometry file
/// beyond 1 MB, is now an error that says so, naming the last row read.
#[test]
fn an_endless_line_or_file_is_an_error_not_all_of_memory() {
    use std::io::Read;
    let rows = &b"L1,L2,L3,L4,L5,L6\n170,170,170,170,170,170\n"[..];
    let endless_row = rows.chain(std::io::repeat(b'1').take(64 << 20));
    let err = legs_csv::read_from(endless_row).unwrap_err();
    assert!(
        err.contains("after row 1") && err.contains("longer than 1 MB"),
        "{err}"
    );
    let endless_header = std::io::repeat(0).take(64 << 20);
    let err = legs_csv::read_from(endless_header).unwrap_err();
    assert!(err.contains("longer than 1 MB"), "{err}");
    // Long files of ordinary lines are no problem.
    let mut many = b"L1,L2,L3,L4,L5,L6\n".to_vec();
    many.extend(b"170,170,170,170,170,170\n".repeat(100_000));
    assert_eq!(legs_csv::read_from(many.as_slice()).unwrap().len(), 100_000);

    let path = std::env::temp_dir().join(format!("linkage-long-{}.toml", std::process::id()));
    let mut text = "# ".to_string();
    text.push_str(&"x".repeat(2 << 20));
    std::fs::write(&path, &text).unwrap();
    let err = geometry::load(&path).err().unwrap();
    assert!(err.contains("longer than 1 MB"), "{err}");
    let err = geometry::load_joints(&path).unwrap_err();
    assert!(err.contains("longer than 1 MB"), "{err}");
    std::fs::remove_file(&path).unwrap();
}
