//! The in-process executor: one task after another on this process's threads (fewer when
//! a task's description asks for fewer, `task::run_one`). Nothing is started anew, so a
//! task stopped from outside stops the whole process: there is nothing to retry.

use super::{in_rounds, BatchState, Executor, Progress};
use crate::batch::{Batch, TaskReport};
use crate::manifest::Program;
use crate::task::{run_one, Execute};
use anyhow::Result;
use std::sync::atomic::{AtomicBool, Ordering};

pub struct InProcess<'a> {
    pub program: Program<'a>,
    pub execute: Execute<'a>,
}

impl Executor for InProcess<'_> {
    fn describe(&self) -> String {
        format!("in this process, {} threads", rayon::current_num_threads())
    }

    fn run(&self, batch: &Batch, stop: &AtomicBool, progress: Progress) -> Result<Vec<TaskReport>> {
        in_rounds(batch, 0, stop, |tasks, _| {
            for (done, &i) in tasks.iter().enumerate() {
                if stop.load(Ordering::Relaxed) {
                    break;
                }
                progress(&BatchState {
                    done: batch.len - tasks.len() + done,
                    all: batch.len,
                    running: 1,
                    waiting: tasks.len() - done - 1,
                });
                let task = batch.task(i);
                // a task error is in its manifest, which the report reads
                let _ = run_one(self.program, &task.description(), &task.0, self.execute);
            }
            progress(&BatchState {
                done: batch.len,
                all: batch.len,
                running: 0,
                waiting: 0,
            });
            Ok(())
        })
    }
}
