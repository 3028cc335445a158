//! A spinner on stderr for work that takes longer than about a second,
//! shown only when stderr is a terminal.

use std::io::IsTerminal;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// Set once spinners must stay hidden for the rest of the run.
static QUIET: AtomicBool = AtomicBool::new(false);

/// Hides every spinner from now on: `holey batch` draws one bar for the
/// whole run, which the spinners of the files it runs on at once would
/// draw over (and each would cost a thread sleeping for a second).
pub fn quiet() {
    QUIET.store(true, Ordering::Relaxed);
}

/// A spinner that appears after one second if the work is still running.
pub struct Progress {
    bar: ProgressBar,
}

impl Progress {
    pub fn start(message: impl Into<String>) -> Self {
        let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::hidden());
        bar.set_message(message.into());
        if let Ok(style) = ProgressStyle::with_template("{spinner} {msg} ({elapsed})") {
            bar.set_style(style);
        }
        if !QUIET.load(Ordering::Relaxed) && std::io::stderr().is_terminal() {
            let shown = bar.clone();
            std::thread::spawn(move || {
                std::thread::sleep(Duration::from_secs(1));
                if !shown.is_finished() {
                    shown.set_draw_target(ProgressDrawTarget::stderr());
                    shown.enable_steady_tick(Duration::from_millis(120));
                }
            });
        }
        Progress { bar }
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        self.bar.finish_and_clear();
    }
}
