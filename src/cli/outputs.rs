//! How a command ended, as the exit status. (The checks of its outputs are the library's,
//! `facetlab::io::guard`.)

/// How a command ended, as the process's exit code.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Exit {
    /// Done (0).
    Ok,
    /// Done, outputs written, but the photon tracer disagreed with the beam tracer beyond the
    /// tolerance (1).
    Disagreement,
    /// Stopped by Ctrl-C or SIGTERM after writing what was found (130).
    Interrupted,
}

impl Exit {
    /// The process exit code. Bad input is 2 (an `Err`, not an `Exit`).
    pub fn code(self) -> i32 {
        match self {
            Exit::Ok => 0,
            Exit::Disagreement => 1,
            Exit::Interrupted => 130,
        }
    }
}

pub use facetlab::io::guard::refuse_overwrite;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_exit_has_its_code() {
        assert_eq!(
            [Exit::Ok, Exit::Disagreement, Exit::Interrupted].map(Exit::code),
            [0, 1, 130]
        );
    }
}
