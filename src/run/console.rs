//! Where a run's words go besides its outputs (the check's diagnostics, notices,
//! rejected lines, the summary): `ilmrc run` prints them; `ilmrc test` runs several
//! tasks side by side and keeps each run's words for its own report.

pub enum Console {
    /// stdout and stderr, as `ilmrc run` has always printed them.
    Terminal,
    /// Both streams kept in order in one text.
    Kept(String),
}

impl Console {
    pub fn out(&mut self, text: &str) {
        match self {
            Console::Terminal => print!("{text}"),
            Console::Kept(s) => s.push_str(text),
        }
    }

    pub fn err(&mut self, text: &str) {
        match self {
            Console::Terminal => eprint!("{text}"),
            Console::Kept(s) => s.push_str(text),
        }
    }

    pub fn is_terminal(&self) -> bool {
        matches!(self, Console::Terminal)
    }
}
