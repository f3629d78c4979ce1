//! `.ilmb` files: decode, validate, disassemble, and run what validates on the
//! scripted robot for a bounded number of ticks.
fn main() {
    ilmr_fuzz::fuzz(ilmr_fuzz::targets::modules::feed);
}
