//! Loading from disk: missing files give the defaults, unreadable ones an
//! error, odd encodings a warning.

use std::path::PathBuf;

use ilmr_model::RobotModel;

/// A fresh directory per test, under the target dir so nothing leaks.
fn scratch(test: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("ilmr-model-{test}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch dir");
    dir
}

#[test]
fn a_missing_file_gives_the_defaults_and_one_warning() {
    let path = scratch("missing").join("ROBO.INI");
    let (model, warnings) = RobotModel::load(&path).expect("not an error");
    assert_eq!(model, RobotModel::defaults());
    assert_eq!(model.name, "default");
    assert_eq!(warnings.len(), 1);
    assert_eq!(warnings[0].line, None);
    assert_eq!(
        warnings[0].message,
        format!(
            "robot model file `{}` not found; the built-in defaults are used",
            path.display()
        )
    );
}

#[test]
fn a_file_is_named_after_its_stem_and_remembers_its_path() {
    let path = scratch("named").join("ROBO.INI");
    std::fs::write(&path, "[PARAMETERS]\nmax_speed 0.4\n[END]\n").expect("write");
    let (model, warnings) = RobotModel::load(&path).expect("readable");
    assert!(warnings.is_empty(), "{warnings:#?}");
    assert_eq!(model.name, "ROBO");
    assert_eq!(model.source.as_deref(), Some(path.as_path()));
    assert_eq!(model.max_speed(), 0.4);
}

#[test]
fn latin1_text_is_read_with_a_warning() {
    let path = scratch("latin1").join("robo.ini");
    // `ovi` comment in Latin-1: "; ovi = dörr" with ö as 0xF6.
    let mut bytes = b"[PARAMETERS]\nmax_speed 0.4\n; d".to_vec();
    bytes.push(0xF6);
    bytes.extend_from_slice(b"rr\n[END]\n");
    std::fs::write(&path, bytes).expect("write");
    let (model, warnings) = RobotModel::load(&path).expect("readable");
    let rendered: Vec<String> = warnings.iter().map(ToString::to_string).collect();
    assert_eq!(
        rendered,
        vec!["line 3: the file is not valid UTF-8; invalid bytes were replaced by U+FFFD"]
    );
    assert_eq!(model.max_speed(), 0.4);
}

#[test]
fn a_directory_is_an_io_error() {
    let dir = scratch("directory");
    assert!(RobotModel::load(&dir).is_err());
}
