//! Task files: check, render, lower, encode, run on both robots, and the same text as
//! an interactive line joining a running program.
fn main() {
    let target = ilmr_fuzz::targets::tasks::Tasks::load();
    ilmr_fuzz::fuzz(|input| target.feed(input));
}
