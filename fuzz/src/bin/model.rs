//! ROBO.INI text: the loader, `to_ini` reading back, example tasks checked and lowered
//! against the model, and a simulated robot and VM configured from it.
fn main() {
    let target = ilmr_fuzz::targets::models::Models::load();
    ilmr_fuzz::fuzz(|input| target.feed(input));
}
