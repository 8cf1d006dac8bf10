//! The preview's own thread: it renders the newest job it is given, the
//! quick pass at once and then the finer pass in windows of rows, and
//! drops a job as soon as a newer one comes (between two windows), so that
//! a drag's many edits cost one quick pass each and the window never
//! waits. The port's.

use std::sync::mpsc::{channel, Receiver, Sender, TryRecvError};
use std::thread::JoinHandle;

use super::preview::{render_rows, Job, Pass, FINE, QUICK, ROWS_A_WINDOW};
use crate::raster::Raster;

/// A finished pass of the job of `revision`.
#[derive(Clone, Debug, PartialEq)]
pub struct Done {
    pub revision: u64,
    pub pass: Pass,
    pub result: Result<Raster, String>,
}

/// The preview thread, and the channels to it and back.
pub struct Worker {
    jobs: Option<Sender<(u64, Job)>>,
    done: Receiver<Done>,
    thread: Option<JoinHandle<()>>,
}

impl Worker {
    /// Starts the thread, rendering `passes` in order for each job (the
    /// editor's: [`QUICK`] then [`FINE`]).
    pub fn start(passes: Vec<Pass>) -> Worker {
        let (jobs, inbox) = channel::<(u64, Job)>();
        let (outbox, done) = channel();
        let thread = std::thread::spawn(move || serve(&inbox, &outbox, &passes));
        Worker {
            jobs: Some(jobs),
            done,
            thread: Some(thread),
        }
    }

    /// The editor's worker: the quick pass, then the finer one.
    pub fn editor() -> Worker {
        Worker::start(vec![QUICK, FINE])
    }

    /// Asks for the job of `revision` (a newer one replaces it).
    pub fn submit(&self, revision: u64, job: Job) {
        if let Some(jobs) = &self.jobs {
            // A thread that ended has nothing to render with; the window
            // shows the last preview.
            let _ = jobs.send((revision, job));
        }
    }

    /// The passes finished since the last call, in order.
    pub fn finished(&self) -> Vec<Done> {
        self.done.try_iter().collect()
    }

    /// Waits for the next finished pass (for tests and tools).
    pub fn wait(&self) -> Option<Done> {
        self.done.recv().ok()
    }
}

impl Drop for Worker {
    fn drop(&mut self) {
        // Closing the channel ends the thread after its current window.
        self.jobs = None;
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

/// The thread's loop: the newest job, its passes, until the channel closes.
fn serve(inbox: &Receiver<(u64, Job)>, outbox: &Sender<Done>, passes: &[Pass]) {
    let Ok(mut next) = inbox.recv() else { return };
    loop {
        let newest = |mut job: (u64, Job)| {
            while let Ok(newer) = inbox.try_recv() {
                job = newer;
            }
            job
        };
        let (revision, job) = newest(next);
        let mut newer = None;
        for &pass in passes {
            match render_pass(&job, pass, inbox) {
                Ok(result) => {
                    if outbox.send(Done { revision, pass, result }).is_err() {
                        return;
                    }
                }
                Err(Stop::Newer(j)) => {
                    newer = Some(*j);
                    break;
                }
                Err(Stop::Closed) => return,
            }
        }
        next = match newer {
            Some(j) => j,
            None => match inbox.recv() {
                Ok(j) => j,
                Err(_) => return,
            },
        };
    }
}

/// Why a pass stopped before its end.
enum Stop {
    Newer(Box<(u64, Job)>),
    Closed,
}

/// One pass in windows of rows, looking for a newer job between them.
fn render_pass(job: &Job, pass: Pass, inbox: &Receiver<(u64, Job)>) -> Result<Result<Raster, String>, Stop> {
    let prepared = match job.prepare(pass) {
        Ok(p) => p,
        Err(e) => return Ok(Err(e)),
    };
    let img = &prepared.scene().image;
    let mut raster = Raster {
        width: img.width,
        height: 0,
        pixels: Vec::with_capacity(img.width * img.height),
    };
    let mut row = 0;
    while row < img.height {
        match inbox.try_recv() {
            Ok(j) => return Err(Stop::Newer(Box::new(j))),
            Err(TryRecvError::Disconnected) => return Err(Stop::Closed),
            Err(TryRecvError::Empty) => {}
        }
        let end = (row + ROWS_A_WINDOW).min(img.height);
        match render_rows(&prepared, row..end) {
            Ok(part) => raster.pixels.extend(part.pixels),
            Err(e) => return Ok(Err(e)),
        }
        raster.height = end;
        row = end;
    }
    Ok(Ok(raster))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::editor::document::Document;
    use crate::options::Fidelity;
    use crate::run::DeckInput;

    fn job() -> Job {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("legacy_pascal/decks/fig5_6.deck");
        let doc = Document::open(DeckInput::read(&path).unwrap(), "star", Fidelity::Thesis).unwrap();
        Job::new(&doc, &doc.original, 0.0)
    }

    #[test]
    fn each_pass_comes_back_in_order_and_equals_a_whole_render() {
        let small = Pass {
            long_side: 24,
            mask: Some(1),
        };
        let finer = Pass {
            long_side: 40,
            mask: None,
        };
        let w = Worker::start(vec![small, finer]);
        w.submit(7, job());
        let a = w.wait().unwrap();
        let b = w.wait().unwrap();
        assert_eq!((a.revision, a.pass, b.revision, b.pass), (7, small, 7, finer));
        let whole = super::super::preview::render_pass(&job(), finer).unwrap();
        assert_eq!(b.result.unwrap(), whole, "windows of rows make the whole picture");
        assert_eq!(a.result.unwrap().width, 24);
    }

    #[test]
    fn the_newest_job_wins() {
        let small = Pass {
            long_side: 16,
            mask: Some(1),
        };
        let (jobs, inbox) = channel();
        let (outbox, done) = channel();
        for r in 1..=5 {
            jobs.send((r, job())).unwrap();
        }
        // The five wait before the thread starts: it renders the newest.
        let thread = std::thread::spawn(move || serve(&inbox, &outbox, &[small]));
        assert_eq!(
            done.recv().unwrap().revision,
            5,
            "the jobs waiting behind a newer one are dropped"
        );
        drop(jobs);
        thread.join().unwrap();
        assert!(done.try_recv().is_err());
    }
}
