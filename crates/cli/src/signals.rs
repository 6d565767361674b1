//! What a campaign says when a signal ends it (SIGINT, SIGTERM, SIGHUP). Its records are on
//! disk as each landing finishes (docs/campaigns.md, "Output"), so the process ends at once, as
//! the signal would have ended it, after one message saying what is kept and the command that
//! goes on from it. The message is written before the signal arrives: the handler only writes
//! those bytes and exits, which is all a signal handler may safely do.

use std::sync::OnceLock;

/// The message the handler writes to standard error.
static MESSAGE: OnceLock<Vec<u8>> = OnceLock::new();

/// From now on, SIGINT, SIGTERM and SIGHUP end the process with `message` on standard error
/// and the status a shell gives a process the signal ended (128 + its number). Set once: a
/// second call keeps the first message.
pub fn say_when_stopped(message: String) {
    if MESSAGE.set(message.into_bytes()).is_err() {
        return;
    }
    #[cfg(unix)]
    for signal in [libc::SIGINT, libc::SIGTERM, libc::SIGHUP] {
        // SAFETY: `stopped` only reads the message, set above and never changed after, and
        // calls the async-signal-safe `write` and `_exit`.
        unsafe {
            libc::signal(
                signal,
                stopped as extern "C" fn(libc::c_int) as libc::sighandler_t,
            );
        }
    }
}

/// The handler: the message, then the end of the process.
#[cfg(unix)]
extern "C" fn stopped(signal: libc::c_int) {
    if let Some(m) = MESSAGE.get() {
        // SAFETY: `m` is a live, initialised buffer of `m.len()` bytes.
        unsafe {
            libc::write(libc::STDERR_FILENO, m.as_ptr().cast(), m.len());
        }
    }
    // SAFETY: `_exit` ends the process without running anything else.
    unsafe { libc::_exit(128 + signal) }
}

/// The command line that continued this one: its own arguments with `--resume` (added if
/// missing), each quoted for a POSIX shell where it needs it.
pub fn resume_command() -> String {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    if !args.iter().any(|a| a == "--resume") {
        args.push("--resume".into());
    }
    let quoted = args.iter().map(|a| {
        if !a.is_empty()
            && a.chars()
                .all(|c| c.is_alphanumeric() || "-_./:=,@%+".contains(c))
        {
            a.clone()
        } else {
            format!("'{}'", a.replace('\'', r"'\''"))
        }
    });
    std::iter::once("touchdown".to_string())
        .chain(quoted)
        .collect::<Vec<_>>()
        .join(" ")
}
