//! Any text given to `mechanism!` is either expanded or turned into `compile_error!`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        if let Ok(tokens) = text.parse::<proc_macro2::TokenStream>() {
            let _ = linkage_codegen::expand(tokens);
        }
    }
});
