//! `ilmr-lsp`: the ILMR language server, speaking LSP on stdin and stdout.

fn main() -> std::process::ExitCode {
    if std::env::args()
        .skip(1)
        .any(|a| a == "--version" || a == "-V")
    {
        println!("ilmr-lsp {}", env!("CARGO_PKG_VERSION"));
        return std::process::ExitCode::SUCCESS;
    }
    ilmr_lsp::server::run_stdio()
}
