//! Scenarios through the reader, and the scripted robot built from each accepted one,
//! driven by the VM with the scenario's lines.
fn main() {
    ilmr_fuzz::targets::scenarios::load();
    ilmr_fuzz::fuzz(ilmr_fuzz::targets::scenarios::feed);
}
