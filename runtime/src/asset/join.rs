//! Two jobs at once where the platform has threads: the asset codec's only parallelism, from std
//! alone (the runtime brings no thread pool, and wasm32 has no threads).

/// Runs `a` and `b` and returns both results: `b` on a scoped thread when `parallel` and a thread
/// can be started, otherwise after `a` on this thread. A panic in either is resumed here.
pub(crate) fn join<RA, RB>(
    parallel: bool,
    a: impl FnOnce() -> RA,
    b: impl FnOnce() -> RB + Send,
) -> (RA, RB)
where
    RB: Send,
{
    if !parallel || cfg!(target_family = "wasm") {
        let ra = a();
        return (ra, b());
    }
    // `b` waits here until whichever thread runs it takes it: the spawned one, or this one when
    // no thread could be started.
    let slot = std::sync::Mutex::new(Some(b));
    let take = || slot.lock().ok().and_then(|mut b| b.take());
    std::thread::scope(|scope| {
        let spawned = std::thread::Builder::new()
            .spawn_scoped(scope, || take().map(|b| b()))
            .ok();
        let ra = a();
        let from_thread = spawned.and_then(|handle| {
            handle
                .join()
                .unwrap_or_else(|panic| std::panic::resume_unwind(panic))
        });
        let rb = from_thread
            .or_else(|| take().map(|b| b()))
            .expect("b is taken exactly once, by the thread or here");
        (ra, rb)
    })
}

#[cfg(test)]
mod tests {
    use super::join;

    #[test]
    fn both_jobs_run_once_in_either_mode() {
        for parallel in [false, true] {
            let (a, b) = join(parallel, || 1 + 1, || "b".repeat(3));
            assert_eq!((a, b.as_str()), (2, "bbb"));
        }
    }
}
