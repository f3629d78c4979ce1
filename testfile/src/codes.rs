//! The stable codes of `ilmrc test`: problems in a test file (`A01xx`), in an
//! assertion (`A02xx`), and a test's failures (`A03xx`). Never renumber: tools match on
//! them. docs/testing.md lists them, kept in step by `src/testing/tests.rs`.

macro_rules! codes {
    ($($variant:ident = $code:literal, $title:literal;)*) => {
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub enum Code { $($variant,)* }

        impl Code {
            /// Every code, for the test that keeps docs/testing.md in step.
            pub const ALL: &'static [Code] = &[$(Code::$variant,)*];

            pub fn as_str(self) -> &'static str {
                match self { $(Code::$variant => $code,)* }
            }

            /// A few words naming the problem.
            pub fn title(self) -> &'static str {
                match self { $(Code::$variant => $title,)* }
            }
        }
    };
}

codes! {
    NotToml = "A0101", "the test file is not TOML";
    UnknownKey = "A0102", "unknown key";
    WrongType = "A0103", "value of the wrong type";
    MissingKey = "A0104", "missing key";
    BadValue = "A0105", "value out of place";
    MissingFile = "A0106", "file not found";
    DuplicateName = "A0107", "two tests of one name";
    Syntax = "A0201", "assertion syntax error";
    UnknownLine = "A0202", "no statement on that line";
    UnknownCommand = "A0203", "no statement of that text";
    UnknownVariable = "A0204", "no such variable";
    UnknownObject = "A0205", "no such object in the world";
    NotTraced = "A0206", "not recorded in the trace";
    NeedsRobot = "A0207", "not known of this test's robot";
    Failed = "A0301", "assertion failed";
    TaskRejected = "A0302", "the task does not check";
    RunFailed = "A0303", "the run did not start";
    SnapshotDiffers = "A0304", "the trace is not its snapshot";
}
