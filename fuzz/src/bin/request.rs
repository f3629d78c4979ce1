//! `serve` request lines through the protocol parser and every answer as one JSON line.
fn main() {
    ilmr_fuzz::fuzz(ilmr_fuzz::targets::requests::feed);
}
