//! `holey batch`: one command on many files, several at once.
//!
//! Each supported command is a subcommand of `batch` whose arguments are
//! the command's own options (the same clap structs, flattened), the
//! inputs and batch's options; each file goes through the command's own
//! `run_file` (or `measure`, `find`), so a batch run and a single run
//! share one code path.

use std::collections::{BTreeMap, HashMap, HashSet};
use std::ffi::OsString;
use std::io::{IsTerminal, Write};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use anyhow::{Context, Result, anyhow};
use holey_io::Format;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rayon::prelude::*;

use crate::cmd::{
    MeshToFile, convert, cut, info, menger, remesh, resolve, selfint, sierpinski, subdivide, union,
    wireframe,
};
use crate::error::{bad_input, exit_status};

const AFTER_HELP: &str = "\
Runs COMMAND on every mesh file the INPUTs name, several files at once:

  holey batch COMMAND [COMMAND's options] INPUT... [--out DIR] [--jobs N] [--recursive]

COMMAND's options are those of `holey COMMAND` (see `holey batch COMMAND
--help`), and may come before or after the inputs.

Inputs: an INPUT is a file, a folder (the files in it whose extension
names a mesh format, as in `holey --help`; in its subfolders too with
--recursive) or a glob pattern such as 'scans/*.stl' or 'models/**/*.obj', which holey expands
itself (quote it, or let the shell expand it: both work). A file named
directly is always taken; folders and patterns give only files with a
mesh extension, in name order. A file named twice runs once, and every
INPUT must give at least one file.

Results: the commands that write a mesh (convert, subdivide, remesh,
wireframe, truncate, resolve, union, sierpinski, menger) write each file's result into DIR (--out,
created if missing) as <stem>.<ext>, the input's name with the extension
--format gives, or its own. Before any work the run is refused if two
inputs would write the same file (a.obj and b/a.obj; a.obj and a.ply
with --format stl), if a result would replace its input, or if DIR is a
file. Every file is written atomically. union runs on one file at a time:
the solid its surface encloses, self-intersections and inner shells
removed.

Reports: info and selfint print one JSON object per file, one line each
(JSON Lines; --json is implied), in the order of the inputs whatever
order the files finish in: {\"file\": \"models/a.obj\", ...the fields of
`holey COMMAND --json`...}, or {\"file\": ..., \"error\": \"...\"} for a
file that failed.

Options that name one output file (union's --report and --parity,
selfint's --curves) or print a report that does not say which file it is
about (union's -v) are refused, and so is --via-motion (it takes two
solids).

Failures: a file that fails is reported on stderr when it fails, and the
others go on. The run ends with a summary on stderr: files done, failed,
seconds. A progress bar shows on stderr when it is a terminal.

Exit status: 0 when every file succeeded; 2 when files failed on bad
input only (a malformed file, a mesh the command cannot take) or the run
was refused; 1 when a file failed for a system reason (disk,
permissions) or an internal error.

Examples:
  holey batch convert scans/ --format ply --out ply/
  holey batch subdivide --scheme catmull-clark -n 2 models/ --out smooth/
  holey batch remesh --scheme honeycomb models/ --out honeycomb/
  holey batch union 'repairs/**/*.stl' --out solid/ --jobs 4
  holey batch sierpinski -n 2 a.obj b.off --out sierpinski/ --format dlfl
  holey batch info models/ --recursive > counts.jsonl
  holey batch selfint 'scans/*.stl' | jq -c 'select(.intersecting_pairs > 0)'";

const WRITES: &str = "\
The options listed above --out are those of the command run alone; see
its own --help for what they do. Each result is written into DIR as <stem>.<ext>;
see `holey batch --help` for inputs, results, failures and exit status.";

const REPORTS: &str = "\
The options listed above --recursive are those of the command run alone;
see its own --help for what they do. Prints one JSON line per file (--json
is implied), in input order; see `holey batch --help` for inputs,
failures and exit status.";

#[derive(clap::Args)]
#[command(after_help = AFTER_HELP, subcommand_value_name = "COMMAND")]
pub struct Args {
    #[command(subcommand)]
    pub command: Batched,
}

/// The commands batch runs, each with its own options.
#[derive(clap::Subcommand)]
pub enum Batched {
    /// Convert each file (to the format --format names).
    Convert(Writing<convert::Options>),
    /// Catmull–Clark or Doo–Sabin smoothing of each file.
    Subdivide(Writing<subdivide::Options>),
    /// TopMod's remeshing schemes on each file.
    Remesh(Writing<remesh::Options>),
    /// The wireframe (or columns) of each file.
    Wireframe(Writing<wireframe::Options>),
    /// Truncation of each file's vertices (--all) or of the ones named.
    Truncate(Writing<cut::TruncateOptions>),
    /// Cut and glue each surface along its self-intersections.
    #[command(after_help = WRITES)]
    Resolve {
        #[command(flatten)]
        out: Outputs,
        #[command(flatten)]
        inputs: Inputs,
    },
    /// The solid each surface encloses (a union of one input).
    // The options batch refuses (see `Job::check`) are left out of its help.
    #[command(mut_arg("via_motion", |a| a.hide(true)), mut_arg("report", |a| a.hide(true)))]
    #[command(mut_arg("parity", |a| a.hide(true)), mut_arg("verbose", |a| a.hide(true)))]
    Union(Writing<union::Options>),
    /// Generalized Sierpinski polyhedra of each file.
    Sierpinski(Writing<sierpinski::Options>),
    /// Generalized Menger sponges of each file.
    Menger(Writing<menger::Options>),
    /// Measure each file: one JSON line per file.
    Info(Reporting<info::Options>),
    /// Exact self-intersections of each file: one JSON line per file.
    #[command(mut_arg("curves", |a| a.hide(true)))]
    Selfint(Reporting<selfint::Options>),
}

/// The arguments of a command that writes a mesh per file: its own
/// options, where the results go, the files.
#[derive(clap::Args)]
#[command(after_help = WRITES)]
pub struct Writing<O: clap::Args> {
    #[command(flatten)]
    options: O,
    #[command(flatten)]
    out: Outputs,
    #[command(flatten)]
    inputs: Inputs,
}

impl<O: clap::Args> Writing<O> {
    /// The job `job` makes of the options, the inputs, the outputs.
    fn split(self, job: impl FnOnce(O) -> Job) -> (Job, Inputs, Option<Outputs>) {
        (job(self.options), self.inputs, Some(self.out))
    }
}

/// The arguments of a command that reports on each file: its own options
/// and the files.
#[derive(clap::Args)]
#[command(after_help = REPORTS)]
pub struct Reporting<O: clap::Args> {
    #[command(flatten)]
    options: O,
    #[command(flatten)]
    inputs: Inputs,
}

/// The files to run on, and how many at once.
#[derive(clap::Args)]
pub struct Inputs {
    /// Mesh files, folders and glob patterns (see `holey batch --help`).
    #[arg(required = true, value_name = "INPUT")]
    pub inputs: Vec<String>,
    /// Also take the mesh files in the folders' subfolders, at any depth.
    #[arg(short, long)]
    pub recursive: bool,
    /// Files run at once [default: the number of cores].
    #[arg(short, long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub jobs: Option<u32>,
}

/// Where the results of a command that writes meshes go.
#[derive(clap::Args)]
pub struct Outputs {
    /// Folder the results are written into; created if missing.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// The results' format, as a file extension such as obj or ply
    /// [default: each input's own].
    #[arg(long, value_name = "EXT", value_parser = parse_format)]
    pub format: Option<Format>,
}

fn parse_format(s: &str) -> Result<Format, String> {
    let ext = s.strip_prefix('.').unwrap_or(s);
    Format::from_extension(ext)
        .ok_or_else(|| format!("{s:?} is not a mesh format (known: {})", known_extensions()))
}

/// The mesh extensions holey knows, for messages: `.obj, .off, ...`.
fn known_extensions() -> String {
    let all: Vec<String> = Format::ALL
        .iter()
        .map(|f| format!(".{}", f.extension()))
        .collect();
    all.join(", ")
}

/// A command and its options, as it runs on each file.
enum Job {
    Convert(convert::Options),
    Subdivide(subdivide::Options),
    Remesh(remesh::Options),
    Wireframe(wireframe::Options),
    Truncate(cut::TruncateOptions),
    Resolve,
    Union(union::Options),
    Sierpinski(sierpinski::Options),
    Menger(menger::Options),
    Info(info::Options),
    Selfint(selfint::Options),
}

impl Batched {
    /// The job, the inputs, and where results go (for commands that write).
    fn split(self) -> (Job, Inputs, Option<Outputs>) {
        match self {
            Batched::Convert(w) => w.split(Job::Convert),
            Batched::Subdivide(w) => w.split(Job::Subdivide),
            Batched::Remesh(w) => w.split(Job::Remesh),
            Batched::Wireframe(w) => w.split(Job::Wireframe),
            Batched::Truncate(w) => w.split(Job::Truncate),
            Batched::Resolve { out, inputs } => (Job::Resolve, inputs, Some(out)),
            Batched::Union(w) => w.split(Job::Union),
            Batched::Sierpinski(w) => w.split(Job::Sierpinski),
            Batched::Menger(w) => w.split(Job::Menger),
            Batched::Info(r) => (Job::Info(r.options), r.inputs, None),
            Batched::Selfint(r) => (Job::Selfint(r.options), r.inputs, None),
        }
    }
}

impl Job {
    fn name(&self) -> &'static str {
        match self {
            Job::Convert(_) => "convert",
            Job::Subdivide(_) => "subdivide",
            Job::Remesh(_) => "remesh",
            Job::Wireframe(_) => "wireframe",
            Job::Truncate(_) => "truncate",
            Job::Resolve => "resolve",
            Job::Union(_) => "union",
            Job::Sierpinski(_) => "sierpinski",
            Job::Menger(_) => "menger",
            Job::Info(_) => "info",
            Job::Selfint(_) => "selfint",
        }
    }

    /// Refuses, before any work, the options that cannot mean anything
    /// per file: one output file every file would overwrite, a report
    /// that does not say which file it is about, a motion of two solids.
    fn check(&self) -> Result<()> {
        match self {
            Job::Union(o) => {
                if o.via_motion {
                    return Err(bad_input(
                        "batch union runs on one file at a time; --via-motion takes two solids",
                    ));
                }
                if o.engine.report.is_some() || o.engine.parity.is_some() {
                    return Err(bad_input(
                        "--report and --parity name one file, which every file would overwrite: batch does not take them",
                    ));
                }
                if o.engine.verbose {
                    return Err(bad_input(
                        "-v prints a report that does not say which file it is about: batch does not take it",
                    ));
                }
                Ok(())
            }
            Job::Selfint(o) if o.curves.is_some() => Err(bad_input(
                "--curves names one file, which every file would overwrite: batch does not take it",
            )),
            _ => Ok(()),
        }
    }

    /// Runs the command on `input`, writing its result to `output` (for
    /// the commands that write meshes); returns the JSON object of a
    /// reporting command, serialized.
    fn run_file(&self, input: &str, output: Option<&str>) -> Result<Option<String>> {
        let out = || output.ok_or_else(|| anyhow!("no output path for {input}"));
        match self {
            Job::Convert(o) => o.run_file(input, out()?)?,
            Job::Subdivide(o) => o.run_file(input, out()?)?,
            Job::Remesh(o) => remesh::run_file(input, out()?, o)?,
            Job::Wireframe(o) => o.run_file(input, out()?)?,
            Job::Truncate(o) => cut::run_truncate_file(input, out()?, o)?,
            Job::Resolve => {
                // What -v would print; it does not name the file.
                let _summary = resolve::run_file(input, out()?)?;
            }
            Job::Union(o) => union::unite(&[input], out()?, o)?,
            Job::Sierpinski(o) => o.run_file(input, out()?)?,
            Job::Menger(o) => o.run_file(input, out()?)?,
            Job::Info(o) => return Ok(Some(serde_json::to_string(&info::measure(input, o)?)?)),
            Job::Selfint(o) => {
                let found = selfint::find(input)?;
                let json = selfint::report_json(input, &found, o.pairs);
                return Ok(Some(serde_json::to_string(&json)?));
            }
        }
        Ok(None)
    }
}

pub fn run(args: Args) -> Result<()> {
    let (job, inputs, outputs) = args.command.split();
    job.check()?;
    let files = collect_files(&inputs.inputs, inputs.recursive)?;
    let items = plan(files, outputs.as_ref())?;
    if let Some(o) = &outputs {
        std::fs::create_dir_all(&o.out)
            .with_context(|| format!("cannot create the folder {}", o.out.display()))?;
    }
    let jobs = match inputs.jobs {
        Some(n) => n as usize,
        None => std::thread::available_parallelism().map_or(1, std::num::NonZero::get),
    };
    // Every file's command would start its own spinner; the bar below
    // stands for them all.
    crate::progress::quiet();
    let start = Instant::now();
    let bar = progress_bar(items.len(), job.name());
    let tally = run_all(&job, &items, jobs, &bar);
    bar.finish_and_clear();
    let total = items.len();
    let mut summary = format!(
        "batch {}: {} done, {} failed, of {total} file{} in {:.2} s",
        job.name(),
        tally.done,
        tally.failed,
        if total == 1 { "" } else { "s" },
        start.elapsed().as_secs_f64()
    );
    if tally.skipped > 0 {
        summary += &format!(" ({} not run: stdout was closed)", tally.skipped);
    }
    eprintln!("{summary}");
    if let Some(e) = tally.stdout_error {
        return Err(anyhow::Error::new(e).context("cannot write to stdout"));
    }
    if tally.failed == 0 {
        Ok(())
    } else if tally.system_failures == 0 {
        Err(bad_input(format!(
            "{} of {total} files failed",
            tally.failed
        )))
    } else {
        Err(anyhow!(
            "{} of {total} files failed, {} of them not for their input",
            tally.failed,
            tally.system_failures
        ))
    }
}

/// The files the INPUT arguments name, in order, each once.
fn collect_files(args: &[String], recursive: bool) -> Result<Vec<PathBuf>> {
    let mut files = Vec::new();
    let mut seen = HashSet::new();
    for arg in args {
        let found = expand(arg, recursive)?;
        if found.is_empty() {
            return Err(bad_input(format!(
                "{arg}: no mesh files ({}) there",
                known_extensions()
            )));
        }
        for mut file in found {
            // The commands read a name starting with @ as a primitive.
            if file.as_os_str().as_encoded_bytes().starts_with(b"@") {
                file = Path::new(".").join(file);
            }
            // The same file reached by two paths (a folder and a pattern)
            // runs once; a path that cannot be resolved stands for itself.
            let key = std::fs::canonicalize(&file).unwrap_or_else(|_| file.clone());
            if seen.insert(key) {
                files.push(file);
            }
        }
    }
    Ok(files)
}

/// The files one INPUT names: itself, a folder's mesh files, or a
/// pattern's matches. A path that exists is taken literally, even if it
/// has pattern characters in its name.
fn expand(arg: &str, recursive: bool) -> Result<Vec<PathBuf>> {
    if arg.starts_with('@') && !Path::new(arg).exists() {
        return Err(bad_input(format!(
            "{arg}: batch runs on files; write the primitive to a file first (holey primitive {arg} FILE)"
        )));
    }
    let path = Path::new(arg);
    match std::fs::metadata(path) {
        Ok(m) if m.is_dir() => {
            let mut files = Vec::new();
            folder_files(path, recursive, &mut files)?;
            files.sort();
            Ok(files)
        }
        Ok(_) => Ok(vec![path.to_path_buf()]),
        Err(_) if arg.contains(['*', '?', '[']) => pattern_files(arg),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            Err(bad_input(format!("{arg}: no such file or folder")))
        }
        Err(e) => Err(anyhow::Error::new(e).context(format!("cannot read {arg}"))),
    }
}

/// Whether a path's extension names a mesh format.
fn is_mesh_file(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .and_then(Format::from_extension)
        .is_some()
        && path.is_file()
}

/// The mesh files in `folder` (and below it when `recursive`), appended
/// to `files`. Subfolders reached through symbolic links are not entered,
/// so a link to a parent cannot make the walk endless.
fn folder_files(folder: &Path, recursive: bool, files: &mut Vec<PathBuf>) -> Result<()> {
    let entries = std::fs::read_dir(folder)
        .with_context(|| format!("cannot list the folder {}", folder.display()))?;
    for entry in entries {
        let entry =
            entry.with_context(|| format!("cannot list the folder {}", folder.display()))?;
        let path = entry.path();
        let kind = entry
            .file_type()
            .with_context(|| format!("cannot read {}", path.display()))?;
        if kind.is_dir() {
            if recursive {
                folder_files(&path, recursive, files)?;
            }
        } else if is_mesh_file(&path) {
            files.push(path);
        }
    }
    Ok(())
}

/// The mesh files a glob pattern matches, in name order.
fn pattern_files(pattern: &str) -> Result<Vec<PathBuf>> {
    let matches = glob::glob(pattern)
        .map_err(|e| bad_input(format!("{pattern}: not a valid pattern: {e}")))?;
    let mut files = Vec::new();
    for m in matches {
        let path = m.with_context(|| format!("expanding {pattern}"))?;
        if is_mesh_file(&path) {
            files.push(path);
        }
    }
    Ok(files)
}

/// One file to run on.
struct Item {
    input: PathBuf,
    /// The input as shown in messages and in the JSON lines.
    name: String,
    /// Where the result goes, for the commands that write meshes.
    output: Option<PathBuf>,
}

/// Each file with its output path, checked before any work: the folder
/// must not be a file, no two results may share a path, and no result may
/// replace its input.
fn plan(files: Vec<PathBuf>, outputs: Option<&Outputs>) -> Result<Vec<Item>> {
    let name = |p: &Path| p.display().to_string();
    let Some(outputs) = outputs else {
        return Ok(files
            .into_iter()
            .map(|input| Item {
                name: name(&input),
                input,
                output: None,
            })
            .collect());
    };
    let dir = &outputs.out;
    let dir_exists = match std::fs::metadata(dir) {
        Ok(m) if m.is_dir() => true,
        Ok(_) => {
            return Err(bad_input(format!(
                "--out {}: exists and is not a folder",
                dir.display()
            )));
        }
        Err(_) => false,
    };
    let canonical_dir = if dir_exists {
        std::fs::canonicalize(dir).ok()
    } else {
        None
    };
    let mut items = Vec::with_capacity(files.len());
    let mut taken: HashMap<String, usize> = HashMap::new();
    let mut clashes = Vec::new();
    for input in files {
        let file_name = output_name(&input, outputs.format)?;
        let output = dir.join(&file_name);
        // Compared without case: on a case-insensitive file system A.obj
        // and a.obj are one file.
        let key = file_name.to_string_lossy().to_lowercase();
        if let Some(&first) = taken.get(&key) {
            let first: &Item = &items[first];
            clashes.push(format!(
                "{} and {} would both be written to {}",
                first.name,
                name(&input),
                output.display()
            ));
        } else {
            taken.insert(key, items.len());
        }
        if let Some(d) = &canonical_dir
            && std::fs::canonicalize(&input).is_ok_and(|i| i == d.join(&file_name))
        {
            return Err(bad_input(format!(
                "{}: its result would replace it; choose another --out folder",
                name(&input)
            )));
        }
        items.push(Item {
            name: name(&input),
            input,
            output: Some(output),
        });
    }
    if !clashes.is_empty() {
        return Err(bad_input(format!(
            "{}\n(rename the inputs, or run them into different folders)",
            clashes.join("\n")
        )));
    }
    Ok(items)
}

/// `<stem>.<ext>` for an input: the extension of `format`, or the input's own.
fn output_name(input: &Path, format: Option<Format>) -> Result<OsString> {
    let ext = match format {
        Some(f) => OsString::from(f.extension()),
        None => input.extension().map(OsString::from).ok_or_else(|| {
            bad_input(format!(
                "{}: no extension to name its result's format; give --format",
                input.display()
            ))
        })?,
    };
    let stem = input
        .file_stem()
        .ok_or_else(|| bad_input(format!("{}: not a file name", input.display())))?;
    let mut file_name = stem.to_os_string();
    file_name.push(".");
    file_name.push(ext);
    Ok(file_name)
}

/// The bar on stderr, drawn only when stderr is a terminal.
fn progress_bar(files: usize, command: &str) -> ProgressBar {
    let terminal = std::io::stderr().is_terminal();
    let target = if terminal {
        ProgressDrawTarget::stderr()
    } else {
        ProgressDrawTarget::hidden()
    };
    let bar = ProgressBar::with_draw_target(Some(files as u64), target);
    if let Ok(style) =
        ProgressStyle::with_template("{bar:40} {pos}/{len} files, {elapsed} (eta {eta}) {msg}")
    {
        bar.set_style(style.progress_chars("=> "));
    }
    bar.set_message(format!("holey batch {command}"));
    if terminal {
        bar.enable_steady_tick(Duration::from_millis(200));
    }
    bar
}

/// How one file went.
enum Outcome {
    /// Done, with the JSON object of a reporting command.
    Done(Option<String>),
    Failed(anyhow::Error),
    /// Not run: the run was stopped (stdout closed).
    Skipped,
}

/// What the run did, counted as files finish.
#[derive(Default)]
struct Tally {
    done: usize,
    failed: usize,
    /// Failures that were not the input's fault (exit status 1).
    system_failures: usize,
    skipped: usize,
    stdout_error: Option<std::io::Error>,
}

/// Runs `job` on every item, `jobs` at once on a pool of their own (so
/// that the commands' own parallel loops share those threads too), and
/// reports each file as it finishes. JSON lines are printed in input
/// order: a file finished early waits for those before it.
fn run_all(job: &Job, items: &[Item], jobs: usize, bar: &ProgressBar) -> Tally {
    let mut tally = Tally::default();
    let pool = match rayon::ThreadPoolBuilder::new().num_threads(jobs).build() {
        Ok(pool) => pool,
        Err(e) => {
            // Without threads nothing runs; say so for every file.
            tally.failed = items.len();
            tally.system_failures = items.len();
            eprintln!("error: cannot start {jobs} worker threads: {e}");
            return tally;
        }
    };
    let stop = AtomicBool::new(false);
    let (tx, rx) = mpsc::channel::<(usize, Outcome)>();
    std::thread::scope(|scope| {
        let stop = &stop;
        let pool = &pool;
        scope.spawn(move || {
            pool.install(|| {
                items
                    .par_iter()
                    .enumerate()
                    // One file per task: files differ in size by orders of
                    // magnitude, so rayon should not batch them.
                    .with_max_len(1)
                    .for_each_with(tx, |tx, (i, item)| {
                        let outcome = if stop.load(Ordering::Relaxed) {
                            Outcome::Skipped
                        } else {
                            run_guarded(job, item)
                        };
                        // The receiver outlives every sender.
                        let _ = tx.send((i, outcome));
                    });
            });
        });
        let mut waiting: BTreeMap<usize, Option<String>> = BTreeMap::new();
        let mut next = 0;
        let mut stdout = std::io::stdout().lock();
        for (i, outcome) in rx {
            bar.inc(1);
            let item = &items[i];
            let line = match outcome {
                Outcome::Done(json) => {
                    tally.done += 1;
                    json.map(|body| json_line(&item.name, &body))
                }
                Outcome::Failed(e) => {
                    tally.failed += 1;
                    if exit_status(&e) != 2 {
                        tally.system_failures += 1;
                    }
                    let message = format!("{e:#}");
                    bar.suspend(|| eprintln!("error: {}", with_file(&item.name, &message)));
                    let error = serde_json::json!({ "error": message }).to_string();
                    item.output.is_none().then(|| json_line(&item.name, &error))
                }
                Outcome::Skipped => {
                    tally.skipped += 1;
                    None
                }
            };
            waiting.insert(i, line);
            while let Some(line) = waiting.remove(&next) {
                next += 1;
                if let (Some(line), None) = (line, &tally.stdout_error)
                    && let Err(e) = writeln!(stdout, "{line}")
                {
                    // A closed pipe (`| head`): stop starting files.
                    stop.store(true, Ordering::Relaxed);
                    tally.stdout_error = Some(e);
                }
            }
        }
    });
    tally
}

/// Runs `job` on one item. A panic is caught here as a last line of
/// defence, so that one file hitting a bug fails alone instead of ending
/// the run; the commands themselves report bad input as errors.
fn run_guarded(job: &Job, item: &Item) -> Outcome {
    // The commands take their paths as text, as they came from the
    // command line.
    let Some(input) = item.input.to_str() else {
        return Outcome::Failed(bad_input("the file name is not UTF-8"));
    };
    let output = match &item.output {
        None => None,
        Some(o) => match o.to_str() {
            Some(o) => Some(o),
            None => return Outcome::Failed(bad_input("the output file name is not UTF-8")),
        },
    };
    match catch_unwind(AssertUnwindSafe(|| job.run_file(input, output))) {
        Ok(Ok(json)) => Outcome::Done(json),
        Ok(Err(e)) => Outcome::Failed(e),
        Err(payload) => {
            let message = payload
                .downcast_ref::<&str>()
                .copied()
                .or_else(|| payload.downcast_ref::<String>().map(String::as_str))
                .unwrap_or("no message");
            Outcome::Failed(anyhow!("internal error (a panic): {message}"))
        }
    }
}

/// `{"file": name, ...}`: the fields of `body` (a JSON object, serialized)
/// after the file's name, which comes first so that a reader sees it
/// first.
fn json_line(name: &str, body: &str) -> String {
    let file = serde_json::Value::from(name).to_string();
    match body.strip_prefix('{') {
        Some("}") => format!("{{\"file\":{file}}}"),
        Some(fields) => format!("{{\"file\":{file},{fields}"),
        None => format!("{{\"file\":{file},\"result\":{body}}}"),
    }
}

/// An error message led by the file's name, unless it already starts
/// with it (the file readers' messages do).
fn with_file(name: &str, message: &str) -> String {
    if message.starts_with(name) {
        message.to_owned()
    } else {
        format!("{name}: {message}")
    }
}
