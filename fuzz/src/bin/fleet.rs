//! Fleet files through `ilmrc fleet`'s reader.
fn main() {
    ilmr_fuzz::fuzz(ilmr_fuzz::targets::fleets::feed);
}
