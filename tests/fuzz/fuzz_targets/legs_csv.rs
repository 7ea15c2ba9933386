//! The leg-length CSV reader returns rows with statuses, or a message.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = linkage_examples::cli::legs_csv::read_from(data);
});
