//! World files through the loader, and a simulated MoRo running Figure 52 in each
//! world it accepts.
fn main() {
    ilmr_fuzz::targets::worlds::load();
    ilmr_fuzz::fuzz(ilmr_fuzz::targets::worlds::feed);
}
