//! Trace files and recorded inputs through the trace reader, every record written back.
fn main() {
    ilmr_fuzz::fuzz(ilmr_fuzz::targets::traces::feed);
}
