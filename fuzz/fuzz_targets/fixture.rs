//! libFuzzer target: any bytes as fixture text through parsing,
//! validation, the database build and a tiny render. Bad input must be an
//! error; a panic or a non-finite pixel is a crash.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        if let vstf::fuzz::Outcome::Failed(why) = vstf::fuzz::one(text) {
            panic!("{why}");
        }
    }
});
