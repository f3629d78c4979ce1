use super::*;
use std::path::PathBuf;

/// A directory of its own for one test, emptied first.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("ilmr-files-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    dir
}

fn message(path: &Path, kind: Kind) -> String {
    match read(path, kind) {
        Ok(bytes) => panic!("read {} bytes of {}", bytes.len(), path.display()),
        Err(e) => e.to_string(),
    }
}

#[test]
fn a_regular_file_is_read_whole() {
    let dir = scratch("regular");
    let path = dir.join("task.ilmr");
    std::fs::write(&path, "speed(0.4)\n").unwrap_or_else(|e| panic!("{e}"));
    for kind in Kind::ALL {
        assert_eq!(read(&path, kind).ok(), Some(b"speed(0.4)\n".to_vec()));
    }
    assert_eq!(
        read_text(&path, Kind::Source).ok().as_deref(),
        Some("speed(0.4)\n")
    );
}

#[test]
fn missing_files_and_directories_say_so() {
    let dir = scratch("dirs");
    let e = read(&dir.join("absent"), Kind::World).err();
    assert!(e.as_ref().is_some_and(ReadError::is_not_found));
    assert_eq!(message(&dir.join("absent"), Kind::World), "no such file");
    assert_eq!(
        message(&dir, Kind::RobotModel),
        "it is a directory, not a file"
    );
}

#[cfg(unix)]
#[test]
fn devices_are_refused_before_a_byte_is_read() {
    for kind in Kind::ALL {
        assert_eq!(
            message(Path::new("/dev/zero"), kind),
            "it is a character device, not a regular file"
        );
    }
}

#[cfg(unix)]
#[test]
fn a_fifo_is_refused_without_waiting_for_a_writer() {
    let dir = scratch("fifo");
    let path = dir.join("pipe.ilmr");
    let c = std::ffi::CString::new(path.to_string_lossy().as_bytes()).unwrap_or_default();
    // SAFETY: `c` is a NUL-terminated path that lives across the call.
    assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
    assert_eq!(
        message(&path, Kind::Source),
        "it is a FIFO (named pipe), not a regular file"
    );
    // The open itself must not wait for a writer either (a FIFO swapped in after
    // the check).
    assert!(open(&path).is_ok());
}

#[test]
fn a_file_above_its_limit_is_refused_naming_the_limit() {
    let dir = scratch("large");
    let path = dir.join("ROBO.INI");
    let file = File::create(&path).unwrap_or_else(|e| panic!("{e}"));
    file.set_len(MAX_ROBOT_MODEL_BYTES + 1)
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        message(&path, Kind::RobotModel),
        "it is larger than 1 MiB, the limit for a robot model (MAX_ROBOT_MODEL_BYTES)"
    );
    // Exactly the limit is allowed.
    file.set_len(MAX_ROBOT_MODEL_BYTES)
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        read(&path, Kind::RobotModel).map(|b| b.len() as u64).ok(),
        Some(MAX_ROBOT_MODEL_BYTES)
    );
}

/// A file whose size says nothing of its content (as `/proc` files claim 0 bytes)
/// is still cut at the limit, by reading at most one byte more than it.
#[cfg(target_os = "linux")]
#[test]
fn what_is_read_stops_one_byte_past_the_limit() {
    let path = Path::new("/proc/self/maps");
    let size = std::fs::metadata(path).map(|m| m.len()).ok();
    assert_eq!(
        size,
        Some(0),
        "the test needs a file that claims to be empty"
    );
    assert!(matches!(read_limited(path, 16), Err(Problem::TooLarge)));
    assert!(read_limited(path, MAX_TRACE_BYTES).is_ok_and(|b| b.len() > 16));
}

#[test]
fn text_that_is_not_utf8_says_where() {
    let dir = scratch("utf8");
    let path = dir.join("bad.ilmr");
    std::fs::write(&path, b"ok\n\xc3\xa4\xff\n").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        read_text(&path, Kind::Source).err().map(|e| e.to_string()),
        Some("it is not UTF-8 text (invalid byte at line 2, column 2)".into())
    );
    assert!(matches!(
        read_text(&path, Kind::Source).map_err(|e| e.problem),
        Err(Problem::NotUtf8 {
            offset: 5,
            line: 2,
            column: 2
        })
    ));
    // Bytes are bytes: the module reader takes them.
    assert!(read(&path, Kind::Module).is_ok());
}

#[test]
fn io_errors_keep_their_kind_and_message() {
    let dir = scratch("io");
    let e: io::Error = read(&dir, Kind::World)
        .err()
        .map(Into::into)
        .unwrap_or_else(|| panic!("a directory was read"));
    assert_eq!(e.kind(), io::ErrorKind::IsADirectory);
    assert_eq!(e.to_string(), "it is a directory, not a file");
}

#[test]
fn every_limit_has_its_constant_name_and_whole_mebibytes() {
    for kind in Kind::ALL {
        assert!(kind.limit() % MIB == 0, "{kind:?}");
        assert!(kind.limit_name().starts_with("MAX_"), "{kind:?}");
    }
}
