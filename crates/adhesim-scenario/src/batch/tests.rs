//! The engine on cases that succeed, fail and panic: markers, resume, retry, hashes, shards.

use super::*;
use std::sync::atomic::{AtomicUsize, Ordering};

/// A case whose run writes `out.txt`, fails or panics, and counts its runs.
struct TestCase {
    id: String,
    hash: String,
    behaviour: &'static str,
    runs: AtomicUsize,
}

fn case(id: &str, behaviour: &'static str) -> TestCase {
    TestCase {
        id: id.into(),
        hash: format!("hash-of-{id}"),
        behaviour,
        runs: AtomicUsize::new(0),
    }
}

impl BatchCase for TestCase {
    fn id(&self) -> &str {
        &self.id
    }
    fn hash(&self) -> &str {
        &self.hash
    }
    fn run(&self, folder: &Path) -> Result<()> {
        self.runs.fetch_add(1, Ordering::SeqCst);
        match self.behaviour {
            "ok" => Ok(std::fs::write(folder.join("out.txt"), &self.id)?),
            "error" => bail!("no convergence in case {}", self.id),
            _ => panic!("boom in case {}", self.id),
        }
    }
}

fn ids<C: BatchCase>(cases: &[&C]) -> Vec<String> {
    let mut ids: Vec<String> = cases.iter().map(|c| c.id().to_string()).collect();
    ids.sort();
    ids
}

#[test]
fn failures_and_panics_are_cases_of_their_own_and_finished_cases_are_kept() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [case("a", "ok"), case("b", "error"), case("c", "panic")];
    let batch = Batch::open(dir.path(), Shard::ALL).unwrap();
    let pending = batch.pending(&cases, false).unwrap();
    assert_eq!(pending.todo.len(), 3);
    let outcome = batch.execute(pending, 2, 1, &|_, _| {}).unwrap();
    let mut failed = outcome.failed_now.clone();
    failed.sort();
    assert_eq!(failed, ["b", "c"]);
    let folder = |id: &str| dir.path().join("cases").join(id);
    assert_eq!(std::fs::read_to_string(folder("a").join("out.txt")).unwrap(), "a");
    assert_eq!(
        case_state(dir.path(), "a", "hash-of-a"),
        CaseState::Finished { ok: true }
    );
    assert_eq!(
        case_state(dir.path(), "c", "hash-of-c"),
        CaseState::Finished { ok: false }
    );
    let error = std::fs::read_to_string(folder("c").join("error.txt")).unwrap();
    assert!(error.contains("panic: boom in case c"), "{error}");
    let error = std::fs::read_to_string(folder("b").join("error.txt")).unwrap();
    assert!(error.contains("no convergence in case b"), "{error}");
    let message = outcome.failure_status(dir.path(), "cases").unwrap_err().to_string();
    assert!(message.starts_with("2 of 3 cases failed; 2 in this run"), "{message}");
    // No temporary folder is left behind.
    assert_eq!(std::fs::read_dir(dir.path().join("tmp")).unwrap().count(), 0);

    // Resume: nothing runs again; the failures are kept unless retried.
    let pending = batch.pending(&cases, false).unwrap();
    assert!(pending.todo.is_empty());
    assert_eq!(pending.kept_failures.len(), 2);
    let pending = batch.pending(&cases, true).unwrap();
    assert_eq!(ids(&pending.todo), ["b", "c"]);
    assert_eq!(ids(&pending.finished), ["a"]);
    assert_eq!(cases[0].runs.load(Ordering::SeqCst), 1);
}

#[test]
fn another_hash_or_a_broken_folder_is_redone_and_shards_split_by_position() {
    let dir = tempfile::tempdir().unwrap();
    let mut cases = vec![case("a", "ok"), case("b", "ok"), case("c", "ok")];
    let batch = Batch::open(dir.path(), Shard::ALL).unwrap();
    let pending = batch.pending(&cases, false).unwrap();
    batch.execute(pending, 1, 1, &|_, _| {}).unwrap();
    // Another scenario or results revision under the same id; a folder whose marker is gone
    // (as if written by hand).
    cases[0].hash = "another".into();
    std::fs::remove_file(dir.path().join("cases/b/done")).unwrap();
    let pending = batch.pending(&cases, false).unwrap();
    assert_eq!(ids(&pending.todo), ["a", "b"]);
    assert!(!dir.path().join("cases/b").exists(), "the broken folder is removed");
    drop(batch);
    // Shard 1 of 2 holds the cases at odd positions only.
    let batch = Batch::open(dir.path(), Shard { index: 1, count: 2 }).unwrap();
    let pending = batch.pending(&cases, false).unwrap();
    assert_eq!(pending.selected, 1);
    assert_eq!(ids(&pending.todo), ["b"]);
}

#[test]
fn shard_arguments_are_checked() {
    let shard = parse_shard(Some("2/3")).unwrap();
    assert_eq!((shard.index, shard.count), (2, 3));
    for bad in ["3/3", "1/0", "x/2", "1"] {
        let message = parse_shard(Some(bad)).err().unwrap().to_string();
        assert!(message.contains(bad), "{message}");
    }
}
