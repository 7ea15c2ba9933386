//! The `--geometry` reader returns a geometry or a message.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = linkage_examples::cli::geometry::parse(&String::from_utf8_lossy(data));
});
