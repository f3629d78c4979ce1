//! Every ILMR program in the repository (task and skill files under `examples/`,
//! `tests/`, `stdlib/` and `robots/`), as (path, text), in a fixed order: the inputs the
//! parser's and the checker's agreement tests run over.

pub fn repository_programs() -> Vec<(String, String)> {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut out = Vec::new();
    let mut dirs = vec![
        root.join("examples"),
        root.join("tests"),
        root.join("stdlib"),
        root.join("robots"),
    ];
    while let Some(dir) = dirs.pop() {
        let Ok(entries) = std::fs::read_dir(&dir) else {
            continue;
        };
        let mut paths: Vec<_> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
        paths.sort();
        for path in paths {
            if path.is_dir() {
                dirs.push(path);
            } else if path.extension().is_some_and(|e| e == "ilmr" || e == "ilms")
                && let Ok(text) = std::fs::read_to_string(&path)
            {
                out.push((path.display().to_string(), text));
            }
        }
    }
    out
}
