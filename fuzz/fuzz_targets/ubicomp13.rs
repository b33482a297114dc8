#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| pdr_fuzz::ubicomp13(data));
