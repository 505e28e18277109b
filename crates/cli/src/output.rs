//! Writing results as one set (docs/conventions.md §5, DESIGN.md §9): every command stages
//! its whole output in a hidden folder beside `--out`, and swaps it in only when every file is
//! on disk, so after a kill or a full disk `--out` holds the previous complete set or the new
//! complete set, never a mix, and the error names the file that could not be written.
//!
//! 1. [`OutDir::create`] checks that `--out` is absent, empty, or an earlier output of the same
//!    command (its record lists every file in it), and refuses anything else: a folder made by
//!    another command, or holding files of its own, is never merged into or thrown away. It
//!    removes what killed runs left beside it, and makes the stage `.NAME.staging-PID`.
//! 2. [`OutDir::write`] puts each file in the stage.
//! 3. [`OutDir::finish`] writes the record `<command>.json` (with a `"files"` list), syncs
//!    the stage, and swaps it with `--out` in one step (Linux `renameat2(RENAME_EXCHANGE)`; a
//!    plain rename where there is nothing to replace), then deletes the old set.
//!
//! A stage that is dropped unfinished (an error) is deleted; one left by `kill -9` is deleted
//! by the next run into the same folder.

use anyhow::{Context, Result, bail};
use serde_json::{Value, json};
use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};

/// An output set being written: files go to a stage beside the final folder.
pub struct OutDir {
    /// The final folder (`--out`).
    root: PathBuf,
    /// The hidden stage beside it.
    stage: PathBuf,
    /// The command whose set this is: its record is `<command>.json`.
    command: &'static str,
    /// Files written so far, relative to the folder.
    files: Vec<String>,
    finished: bool,
}

/// Hidden siblings of an output folder: `.NAME.staging-PID`.
const STAGE_MARK: &str = ".staging-";

impl OutDir {
    /// Begins a new set for `command` that will replace `root` (see the module documentation).
    pub fn create(root: &Path, command: &'static str) -> Result<Self> {
        let root = absolute(root)?;
        let parent = root
            .parent()
            .context("--out names no folder")?
            .to_path_buf();
        fs::create_dir_all(&parent)
            .with_context(|| format!("cannot create output folder {}", parent.display()))?;
        check_replaceable(&root, command)?;
        remove_abandoned_stages(&root);
        let stage = stage_path(&root, std::process::id());
        if stage.exists() {
            fs::remove_dir_all(&stage)
                .with_context(|| format!("cannot remove {}", stage.display()))?;
        }
        fs::create_dir(&stage).with_context(|| {
            format!(
                "cannot create output folder {} (its stage {})",
                root.display(),
                stage.display()
            )
        })?;
        Ok(Self {
            root,
            stage,
            command,
            files: Vec::new(),
            finished: false,
        })
    }

    /// Where `name` will be once the set is in place (for messages).
    pub fn final_path(&self, name: &str) -> PathBuf {
        self.root.join(name)
    }

    /// Writes `bytes` to `name` (which may hold `/`, for a subfolder) in the stage.
    pub fn write(&mut self, name: &str, bytes: &[u8]) -> Result<PathBuf> {
        let shown = self.final_path(name);
        let path = self.stage.join(name);
        if let Some(dir) = path.parent() {
            fs::create_dir_all(dir).with_context(|| format!("cannot write {}", shown.display()))?;
        }
        write_synced(&path, bytes).with_context(|| format!("cannot write {}", shown.display()))?;
        if !self.files.iter().any(|f| f == name) {
            self.files.push(name.to_string());
        }
        Ok(shown)
    }

    /// Writes `value` as pretty JSON to `name`.
    pub fn write_json(&mut self, name: &str, value: &Value) -> Result<PathBuf> {
        let bytes = json_bytes(value)?;
        self.write(name, &bytes)
    }

    /// Writes the record `<command>.json` (with `"files"`, every file of the set) and swaps the
    /// set in place of the folder.
    pub fn finish(mut self, mut record: Value) -> Result<PathBuf> {
        let name = record_name(self.command);
        let mut files = self.files.clone();
        files.push(name.clone());
        files.sort();
        record["files"] = json!(files);
        self.write_json(&name, &record)?;
        sync_dir(&self.stage).with_context(|| format!("cannot write {}", self.root.display()))?;
        check_replaceable(&self.root, self.command)?;
        swap_in(&self.stage, &self.root)?;
        self.finished = true;
        // The stage now holds the previous set, if there was one.
        let _ = fs::remove_dir_all(&self.stage);
        if let Some(parent) = self.root.parent() {
            let _ = sync_dir(parent);
        }
        Ok(self.root.join(name))
    }
}

impl Drop for OutDir {
    fn drop(&mut self) {
        if !self.finished {
            let _ = fs::remove_dir_all(&self.stage);
        }
    }
}

/// The record every command writes last: `<command>.json`.
pub fn record_name(command: &str) -> String {
    format!("{command}.json")
}

fn json_bytes(value: &Value) -> Result<Vec<u8>> {
    let mut text = serde_json::to_string_pretty(value)?;
    text.push('\n');
    Ok(text.into_bytes())
}

/// `path` made absolute, so that its parent and name are known (`.` has neither).
fn absolute(path: &Path) -> Result<PathBuf> {
    let abs = std::path::absolute(path)
        .with_context(|| format!("cannot resolve output folder {}", path.display()))?;
    // `a/b/..` and `a/.` name folders whose parent is not their lexical parent.
    let mut clean = PathBuf::new();
    for part in abs.components() {
        match part {
            std::path::Component::ParentDir => {
                clean.pop();
            }
            std::path::Component::CurDir => {}
            other => clean.push(other),
        }
    }
    if clean.file_name().is_none() {
        bail!(
            "--out {} is not a folder a set can be written to",
            path.display()
        );
    }
    Ok(clean)
}

fn stage_path(root: &Path, pid: u32) -> PathBuf {
    let name = root
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    root.with_file_name(format!(".{name}{STAGE_MARK}{pid}"))
}

/// Refuses a folder this command may not replace whole: one holding anything but an earlier
/// set of `command` (as its record lists it).
fn check_replaceable(root: &Path, command: &str) -> Result<()> {
    let meta = match fs::symlink_metadata(root) {
        Ok(m) => m,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(()),
        Err(e) => return Err(e).with_context(|| format!("cannot read {}", root.display())),
    };
    if !meta.is_dir() {
        bail!("--out {} exists and is not a folder", root.display());
    }
    let entries = entry_names(root)?;
    if entries.is_empty() {
        return Ok(());
    }
    let record = record_name(command);
    let listed = listed_files(&root.join(&record)).with_context(|| {
        format!(
            "--out {} is not an earlier output of `cuticle {command}` (it holds {}, and no {record}); \
             choose a new or empty folder",
            root.display(),
            entries[0]
        )
    })?;
    if let Some(stray) = entries
        .iter()
        .find(|e| !listed.iter().any(|f| top_level(f) == e.as_str()))
    {
        bail!(
            "--out {} holds {stray}, which no earlier `cuticle {command}` wrote there; \
             move it away or choose another folder (a set is replaced whole)",
            root.display()
        );
    }
    Ok(())
}

fn top_level(file: &str) -> &str {
    file.split('/').next().unwrap_or(file)
}

fn entry_names(dir: &Path) -> Result<Vec<String>> {
    let mut names = Vec::new();
    for entry in fs::read_dir(dir).with_context(|| format!("cannot read {}", dir.display()))? {
        let entry = entry.with_context(|| format!("cannot read {}", dir.display()))?;
        names.push(entry.file_name().to_string_lossy().into_owned());
    }
    names.sort();
    Ok(names)
}

/// The `"files"` of a record; for a record written before sets listed their files, every
/// plain file of the kinds commands write.
fn listed_files(record: &Path) -> Result<Vec<String>> {
    let text = fs::read_to_string(record)?;
    let value: Value = serde_json::from_str(&text)?;
    if let Some(files) = value.get("files") {
        let files: Vec<String> = serde_json::from_value(files.clone())?;
        return Ok(files);
    }
    let dir = record.parent().unwrap_or(Path::new("."));
    let kinds = ["exr", "png", "json", "csv", "svg", "md", "hair"];
    Ok(entry_names(dir)?
        .into_iter()
        .filter(|n| {
            dir.join(n).is_file()
                && Path::new(n)
                    .extension()
                    .is_some_and(|e| kinds.iter().any(|k| e == *k))
        })
        .collect())
}

/// Deletes the stages of runs into `root` that are no longer alive (killed mid-way).
fn remove_abandoned_stages(root: &Path) {
    let (Some(parent), Some(name)) = (root.parent(), root.file_name()) else {
        return;
    };
    let prefix = format!(".{}{STAGE_MARK}", name.to_string_lossy());
    let Ok(entries) = fs::read_dir(parent) else {
        return;
    };
    for entry in entries.flatten() {
        let file_name = entry.file_name().to_string_lossy().into_owned();
        let Some(pid) = file_name
            .strip_prefix(&prefix)
            .and_then(|p| p.parse::<u32>().ok())
        else {
            continue;
        };
        if pid != std::process::id() && !process_alive(pid) {
            let _ = fs::remove_dir_all(entry.path());
        }
    }
}

fn process_alive(pid: u32) -> bool {
    if cfg!(target_os = "linux") {
        Path::new("/proc").join(pid.to_string()).exists()
    } else {
        true
    }
}

/// Puts the stage in place of `root` in one step: an exchange when `root` exists (the stage
/// then holds the old set), a rename when it does not.
fn swap_in(stage: &Path, root: &Path) -> Result<()> {
    let context = || format!("cannot put the new output in place of {}", root.display());
    if !root.exists() {
        return fs::rename(stage, root).with_context(context);
    }
    match exchange(stage, root) {
        Ok(()) => Ok(()),
        Err(e)
            if e.raw_os_error() == Some(EXCHANGE_UNSUPPORTED)
                || e.kind() == std::io::ErrorKind::Unsupported =>
        {
            // A file system without an atomic exchange: two renames, the old set kept until
            // the new one is in place.
            let old = root.with_file_name(format!(
                "{}.old",
                stage.file_name().unwrap_or_default().to_string_lossy()
            ));
            fs::rename(root, &old).with_context(context)?;
            fs::rename(stage, root).with_context(context)?;
            fs::rename(&old, stage).with_context(context)
        }
        Err(e) => Err(e).with_context(context),
    }
}

#[cfg(target_os = "linux")]
const EXCHANGE_UNSUPPORTED: i32 = libc::EINVAL;
#[cfg(not(target_os = "linux"))]
const EXCHANGE_UNSUPPORTED: i32 = -1;

#[cfg(target_os = "linux")]
fn exchange(a: &Path, b: &Path) -> std::io::Result<()> {
    use std::ffi::CString;
    use std::os::unix::ffi::OsStrExt;
    let c = |p: &Path| {
        CString::new(p.as_os_str().as_bytes())
            .map_err(|_| std::io::Error::new(std::io::ErrorKind::InvalidInput, "NUL in path"))
    };
    let (a, b) = (c(a)?, c(b)?);
    // SAFETY: two valid NUL-terminated paths, relative to the working directory.
    let rc = unsafe {
        libc::renameat2(
            libc::AT_FDCWD,
            a.as_ptr(),
            libc::AT_FDCWD,
            b.as_ptr(),
            libc::RENAME_EXCHANGE,
        )
    };
    if rc == 0 {
        Ok(())
    } else {
        Err(std::io::Error::last_os_error())
    }
}

#[cfg(not(target_os = "linux"))]
fn exchange(_: &Path, _: &Path) -> std::io::Result<()> {
    Err(std::io::Error::from(std::io::ErrorKind::Unsupported))
}

/// Creates `path` with `bytes`, synced to the disk.
fn write_synced(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let mut file = fs::File::create(path)?;
    file.write_all(bytes)?;
    file.sync_all()
}

/// Makes a folder's entries durable (a no-op where folders cannot be opened).
fn sync_dir(dir: &Path) -> std::io::Result<()> {
    match fs::File::open(dir) {
        Ok(f) => f.sync_all().or(Ok(())),
        Err(_) => Ok(()),
    }
}

/// Writes one file that is not part of a set (a sweep's `sweep.json` beside its configuration
/// folders) atomically: a synced temporary sibling renamed over `path`. The error names `path`.
pub fn write_file_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let name = path.file_name().context("output path has no file name")?;
    let tmp = dir.join(format!(
        ".{}.tmp{}",
        name.to_string_lossy(),
        std::process::id()
    ));
    let result = write_synced(&tmp, bytes).and_then(|()| fs::rename(&tmp, path));
    if result.is_err() {
        let _ = fs::remove_file(&tmp);
    }
    result.with_context(|| format!("cannot write {}", path.display()))
}

/// [`write_file_atomic`] of pretty JSON.
pub fn write_json_atomic(path: &Path, value: &Value) -> Result<()> {
    write_file_atomic(path, &json_bytes(value)?)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(dir: &Path) -> Vec<String> {
        entry_names(dir).unwrap()
    }

    #[test]
    fn a_set_replaces_an_earlier_set_whole() {
        let tmp = tempfile::tempdir().unwrap();
        let root = tmp.path().join("out");
        let mut a = OutDir::create(&root, "lobes").unwrap();
        a.write("R.exr", b"old").unwrap();
        a.write("compare.png", b"old").unwrap();
        a.finish(json!({"run": 1})).unwrap();
        assert_eq!(names(&root), ["R.exr", "compare.png", "lobes.json"]);
        let mut b = OutDir::create(&root, "lobes").unwrap();
        b.write("R.exr", b"new").unwrap();
        // Until the set is finished, the folder holds the earlier one untouched.
        assert_eq!(fs::read(root.join("R.exr")).unwrap(), b"old");
        b.finish(json!({"run": 2})).unwrap();
        assert_eq!(
            names(&root),
            ["R.exr", "lobes.json"],
            "no file of the old set stays"
        );
        assert_eq!(fs::read(root.join("R.exr")).unwrap(), b"new");
        assert_eq!(names(tmp.path()), ["out"], "no stage is left beside it");
        let record: Value =
            serde_json::from_slice(&fs::read(root.join("lobes.json")).unwrap()).unwrap();
        assert_eq!(record["files"], json!(["R.exr", "lobes.json"]));
    }

    #[test]
    fn an_unfinished_set_leaves_the_folder_as_it_was() {
        let tmp = tempfile::tempdir().unwrap();
        let root = tmp.path().join("out");
        let mut a = OutDir::create(&root, "sim").unwrap();
        a.write("sim.exr", b"1").unwrap();
        a.finish(json!({})).unwrap();
        let mut b = OutDir::create(&root, "sim").unwrap();
        b.write("sim.exr", b"2").unwrap();
        drop(b);
        assert_eq!(fs::read(root.join("sim.exr")).unwrap(), b"1");
        assert_eq!(names(tmp.path()), ["out"]);
    }

    #[test]
    fn folders_of_other_commands_or_with_other_files_are_refused() {
        let tmp = tempfile::tempdir().unwrap();
        let root = tmp.path().join("out");
        OutDir::create(&root, "render")
            .unwrap()
            .finish(json!({}))
            .unwrap();
        let other = OutDir::create(&root, "lobes").err().unwrap().to_string();
        assert!(
            other.contains("not an earlier output of `cuticle lobes`"),
            "{other}"
        );
        fs::write(root.join("notes.txt"), b"mine").unwrap();
        let stray = OutDir::create(&root, "render").err().unwrap().to_string();
        assert!(stray.contains("holds notes.txt"), "{stray}");
        assert!(
            root.join("notes.txt").is_file(),
            "nothing of the user's is lost"
        );
        let file = tmp.path().join("file");
        fs::write(&file, b"").unwrap();
        assert!(OutDir::create(&file, "render").is_err());
    }

    #[test]
    fn stages_of_dead_runs_are_removed() {
        let tmp = tempfile::tempdir().unwrap();
        let root = tmp.path().join("out");
        // A pid above the kernel's pid_max is never alive.
        let dead = stage_path(&root, 4_194_305);
        fs::create_dir_all(&dead).unwrap();
        OutDir::create(&root, "sim")
            .unwrap()
            .finish(json!({}))
            .unwrap();
        assert_eq!(names(tmp.path()), ["out"]);
    }
}
