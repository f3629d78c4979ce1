fn main() {
    let path = std::env::args().nth(1).unwrap();
    let src = std::fs::read_to_string(path).unwrap();
    let p = ilmr_compiler::parser::parse(&src, ilmr_compiler::FileId(0));
    print!("{}", ilmr_compiler::tree::render(&p.file));
    for d in p.diagnostics {
        println!("{:?} {:?} {} | {}", d.code, d.span, d.message, d.label);
    }
}
