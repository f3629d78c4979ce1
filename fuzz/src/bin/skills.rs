//! Skill files, checked in full and as a `--skills` library, called from a task.
fn main() {
    let target = ilmr_fuzz::targets::skills::Skills::load();
    ilmr_fuzz::fuzz(|input| target.feed(input));
}
