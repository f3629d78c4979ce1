//! `seeds DIR`: writes each target's seed corpus to `DIR/TARGET/` and its dictionary to
//! `DIR/TARGET.dict`, from the same sources as the seeded loop.
fn main() {
    let Some(dir) = std::env::args_os().nth(1) else {
        eprintln!("usage: seeds DIR");
        std::process::exit(2);
    };
    if let Err(e) = ilmr_fuzz::engine::on_compiler_stack(|| ilmr_fuzz::seeds::write(dir.as_ref())) {
        eprintln!("seeds: {e}");
        std::process::exit(1);
    }
}
