//! Progress of the shading stage, the one that takes long: points shaded out of the total,
//! reported to a caller's callback from the worker threads.

use std::sync::atomic::{AtomicUsize, Ordering};

/// A callback given (points shaded, total points); called from any worker thread.
pub type Progress<'a> = &'a (dyn Fn(usize, usize) + Sync);

/// Points between two reports.
pub const STEP: usize = 1024;

/// Counts shaded points and reports every [`STEP`] of them, and the last.
pub struct Counter<'a> {
    done: AtomicUsize,
    total: usize,
    report: Progress<'a>,
}

impl<'a> Counter<'a> {
    pub fn new(total: usize, report: Progress<'a>) -> Self {
        Self {
            done: AtomicUsize::new(0),
            total,
            report,
        }
    }

    /// One more point shaded.
    pub fn tick(&self) {
        let done = self.done.fetch_add(1, Ordering::Relaxed) + 1;
        if done.is_multiple_of(STEP) || done == self.total {
            (self.report)(done, self.total);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{Counter, STEP};
    use std::sync::Mutex;

    #[test]
    fn reports_every_step_and_the_last() {
        let seen = Mutex::new(Vec::new());
        let report = |done, total| seen.lock().unwrap().push((done, total));
        let total = 2 * STEP + 5;
        let counter = Counter::new(total, &report);
        (0..total).for_each(|_| counter.tick());
        let seen = seen.into_inner().unwrap();
        assert_eq!(seen, vec![(STEP, total), (2 * STEP, total), (total, total)]);
    }
}
