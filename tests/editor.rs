//! The editor's tests: its static files and the regions picture over HTTP, and the page
//! itself driven in Debian's headless Chromium through chromedriver (WebDriver, with
//! `fantoccini`) against the real server, as a person uses it: pointer down, move and up,
//! keys, buttons. `bash scripts/test` installs Chromium when it is missing; a missing
//! browser fails these tests with a message saying so, never skips them.
#![allow(clippy::unwrap_used, clippy::expect_used)]

/// The service's allocator (src/main.rs): the service under test runs in this process, and
/// its drag timings are the binary's.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

#[path = "api/helpers.rs"]
#[allow(dead_code)]
mod helpers;

mod editor {
    pub mod api_key;
    pub mod browser;
    pub mod curve_tools;
    pub mod drag;
    pub mod families;
    pub mod gestures;
    pub mod layout;
    pub mod page;
    pub mod picture;
    pub mod precision;
    pub mod regions;
    pub mod resilience;
    pub mod space;
    pub mod static_files;
    pub mod steps;
    pub mod third_release;
    pub mod timing;
    pub mod view;
}
