//! Test files through the reader as `ilmrc test` and the language server call it, and
//! the editor's completion and hover at places of what it read.
fn main() {
    ilmr_fuzz::fuzz(ilmr_fuzz::targets::testfiles::feed);
}
