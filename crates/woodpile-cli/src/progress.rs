//! Progress on stderr, for `report`, `optimize` and long `simulate` runs: a bar with an ETA when
//! stderr is a terminal, and otherwise (logs, CI, a pipe) one plain line per stage, so a batch
//! job's log shows where it is without the bar's control characters.
//!
//! A line reads `report [3/15] 12.4 s, ETA 48 s: blast cases`: the label, the finished steps, the
//! elapsed time, an estimate of the time left (from the mean time per finished step; omitted
//! before the first step is done) and the stage. Frequent updates ([`Progress::detail`], e.g. a
//! GA's generations) are printed at most every [`DETAIL_INTERVAL`] as lines; on a bar they are
//! shown at once.

use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// Least time between two detail lines when stderr is not a terminal.
pub const DETAIL_INTERVAL: Duration = Duration::from_secs(5);

/// Where progress goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Display {
    /// Nothing (`--quiet`).
    Hidden,
    /// An indicatif bar with an ETA (stderr is a terminal).
    Bar,
    /// One line per stage on stderr (stderr is not a terminal).
    Lines,
}

impl Display {
    /// The display for this process: hidden when quiet, a bar on a terminal, lines otherwise.
    pub fn detect(quiet: bool) -> Self {
        if quiet {
            Display::Hidden
        } else if std::io::stderr().is_terminal() {
            Display::Bar
        } else {
            Display::Lines
        }
    }
}

/// Progress of one command over `len` steps.
#[derive(Debug)]
pub struct Progress {
    label: &'static str,
    len: u64,
    display: Display,
    bar: ProgressBar,
    started: Instant,
    /// The ETA is an upper bound ([`Progress::ending_early`]).
    ending_early: bool,
    lines: Mutex<Lines>,
}

#[derive(Debug, Default)]
struct Lines {
    position: u64,
    stage: String,
    last_detail: Option<Instant>,
    /// Where the ETA's rate is measured from (see [`Progress::rate_from_here`]).
    eta_origin: Option<(Instant, u64)>,
}

impl Progress {
    /// Progress labelled `label` over `len` steps, shown as [`Display::detect`] says.
    pub fn new(label: &'static str, len: u64, quiet: bool) -> Self {
        Self::with_display(label, len, Display::detect(quiet))
    }

    /// Progress of work that started at `started` (before the progress was shown), shown as
    /// [`Display::detect`] says: elapsed time and ETA count from `started`.
    pub fn since(label: &'static str, len: u64, quiet: bool, started: Instant) -> Self {
        let mut p = Self::with_display(label, len, Display::detect(quiet));
        p.started = started;
        p.bar = p.bar.with_elapsed(started.elapsed());
        p
    }

    /// Progress shown on a given display.
    pub fn with_display(label: &'static str, len: u64, display: Display) -> Self {
        let bar = if display == Display::Bar {
            let bar = ProgressBar::new(len);
            let template =
                format!("{label} {{pos}}/{{len}} [{{bar:25}}] {{elapsed}}, ETA {{eta}} | {{msg}}");
            if let Ok(style) = ProgressStyle::with_template(&template) {
                bar.set_style(style.progress_chars("=> "));
            }
            bar.enable_steady_tick(Duration::from_millis(200));
            bar
        } else {
            ProgressBar::hidden()
        };
        Progress {
            label,
            len,
            display,
            bar,
            started: Instant::now(),
            ending_early: false,
            lines: Mutex::new(Lines::default()),
        }
    }

    /// A new stage starts: shown on the bar, printed as a line.
    pub fn stage(&self, stage: impl Into<String>) {
        let stage = stage.into();
        match self.display {
            Display::Hidden => {}
            Display::Bar => self.bar.set_message(stage),
            Display::Lines => {
                let mut lines = self.lock();
                lines.stage = stage;
                self.print(&lines, None);
            }
        }
    }

    /// A detail of the current stage (e.g. a GA's generation): shown on the bar at once, printed
    /// as a line at most every [`DETAIL_INTERVAL`].
    pub fn detail(&self, detail: impl Into<String>) {
        match self.display {
            Display::Hidden => {}
            Display::Bar => self.bar.set_message(detail.into()),
            Display::Lines => {
                let mut lines = self.lock();
                let now = Instant::now();
                if lines
                    .last_detail
                    .is_none_or(|t| now.duration_since(t) >= DETAIL_INTERVAL)
                {
                    lines.last_detail = Some(now);
                    self.print(&lines, Some(&detail.into()));
                }
            }
        }
    }

    /// `n` more steps are done.
    pub fn inc(&self, n: u64) {
        self.bar.inc(n);
        self.lock().position += n;
    }

    /// `position` steps are done.
    pub fn set_position(&self, position: u64) {
        self.bar.set_position(position);
        self.lock().position = position;
    }

    /// The work may end before its last step (a GA that stalls): the ETA is shown as an upper
    /// bound, "at most 36 s left".
    pub fn ending_early(mut self) -> Self {
        self.ending_early = true;
        if self.display == Display::Bar {
            let template = format!(
                "{} {{pos}}/{{len}} [{{bar:25}}] {{elapsed}}, at most {{eta}} left | {{msg}}",
                self.label
            );
            if let Ok(style) = ProgressStyle::with_template(&template) {
                self.bar.set_style(style.progress_chars("=> "));
            }
        }
        self
    }

    /// Measures the ETA's rate from now on: the steps so far are not like the rest (a GA's
    /// generation 0 simulates every design of its population, later ones mostly hit the cache
    /// or stop runs early), so an ETA from their pace overestimates the time left several-fold.
    pub fn rate_from_here(&self) {
        self.bar.reset_eta();
        let mut lines = self.lock();
        lines.eta_origin = Some((Instant::now(), lines.position));
    }

    /// Steps done so far.
    pub fn position(&self) -> u64 {
        self.lock().position
    }

    /// Removes the bar (lines stay as printed).
    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }

    /// Time since the progress was created.
    pub fn elapsed(&self) -> Duration {
        self.started.elapsed()
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Lines> {
        // A panic while printing leaves nothing half-updated that matters: keep going.
        self.lines.lock().unwrap_or_else(|e| e.into_inner())
    }

    fn print(&self, lines: &Lines, detail: Option<&str>) {
        let (since, done) = lines.eta_origin.map_or((self.started, 0), |(t, p)| {
            (t, lines.position - p.min(lines.position))
        });
        let eta = (done > 0 && lines.position < self.len).then(|| {
            since
                .elapsed()
                .mul_f64((self.len - lines.position) as f64 / done as f64)
        });
        let text = line_with_eta(
            self.label,
            lines.position,
            self.len,
            self.elapsed(),
            eta.map(|e| (e, self.ending_early)),
            &lines.stage,
            detail,
        );
        // Progress is best effort: a closed stderr must not fail the command.
        crate::out::eprintln(text);
    }
}

/// One progress line: `label [pos/len] 12.4 s, ETA 48 s: stage (detail)`.
pub fn line(
    label: &str,
    position: u64,
    len: u64,
    elapsed: Duration,
    stage: &str,
    detail: Option<&str>,
) -> String {
    let eta = (position > 0 && position < len)
        .then(|| elapsed.mul_f64((len - position) as f64 / position as f64));
    line_with_eta(
        label,
        position,
        len,
        elapsed,
        eta.map(|e| (e, false)),
        stage,
        detail,
    )
}

/// [`line()`] with the ETA given (None: none shown), and whether it is an upper bound (shown as
/// "at most 36 s left").
pub fn line_with_eta(
    label: &str,
    position: u64,
    len: u64,
    elapsed: Duration,
    eta: Option<(Duration, bool)>,
    stage: &str,
    detail: Option<&str>,
) -> String {
    let secs = elapsed.as_secs_f64();
    let eta = match eta {
        None => String::new(),
        Some((e, false)) => format!(", ETA {:.0} s", e.as_secs_f64()),
        Some((e, true)) => format!(", at most {:.0} s left", e.as_secs_f64()),
    };
    let what = match (stage, detail) {
        ("", Some(d)) => d.to_string(),
        (s, Some(d)) => format!("{s} ({d})"),
        (s, None) => s.to_string(),
    };
    format!("{label} [{position}/{len}] {secs:.1} s{eta}: {what}")
}
