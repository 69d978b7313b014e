//! `slideline post`: the reports a results file gives again, printed at once.

use super::PostArgs;
use slideline::io::reader::ResultsReader;
use slideline::Error;

/// `slideline post`: without options the summary and the history; each option adds its report.
/// Everything is checked before anything is written, and the text goes out at the end, once:
/// a reader that closes the pipe early (`| head`) ends it quietly, as `cat` does.
pub fn post(args: &PostArgs) -> Result<(), Error> {
    use slideline::post;
    let r = ResultsReader::open(&args.file)?;
    if let Some(verdict) = slideline::dba::read(&args.file)?.filter(|_| !r.has_mesh()) {
        return verdict_file(&r, &verdict, args);
    }
    r.notes()?.iter().for_each(|note| eprintln!("note: {note}"));
    if args.increment.is_some() && args.field.is_none() && args.linearize.is_empty() {
        return Err(Error::input("--increment goes with --field or --linearize (the other reports cover every increment)"));
    }
    if args.force && args.compare.is_none() {
        return Err(Error::input("--force goes with --compare"));
    }
    let plot = args.plot.as_ref().map(|p| p.clone().unwrap_or_else(|| post::default_plot_path(&r)));
    for path in args.csv.iter().chain(&plot).chain(&args.report) {
        slideline::output_path::check_output_path(path, Some((&args.file, "the results file")))?;
    }
    let increment = args.increment.as_deref().unwrap_or("last");
    let detail = args.field.is_some()
        || args.node.is_some()
        || args.set.is_some()
        || args.compare.is_some()
        || args.csv.is_some()
        || plot.is_some()
        || args.deck
        || args.assessment
        || args.report.is_some()
        || !args.linearize.is_empty();
    let heat = r.heat_steps()?;
    if !heat.is_empty()
        && (args.field.is_some() || args.node.is_some() || args.set.is_some() || args.csv.is_some() || plot.is_some() || !args.linearize.is_empty())
    {
        return Err(Error::input(format!(
            "{}: a heat-conduction run has no increments; its fields are /heat/{}/temperature and .../flux (h5py), or the sidecar {}_{}.xmf in ParaView",
            args.file.display(),
            heat[0].0,
            args.file.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default(),
            heat[0].0
        )));
    }
    let mut out = String::new();
    if let Some(path) = &args.report {
        if slideline::bellows::forming::is_forming_file(&r)? {
            return Err(Error::input(format!(
                "{}: a `bellows --form` run's file: it has no design report yet (`slideline post FILE` prints its tables)",
                args.file.display()
            )));
        }
        let closing = slideline::bellows::report::closing_table_from_file(&r)?;
        if closing.is_none() {
            return Err(Error::input(format!("{}: not a `slideline bellows` run's file: it has no design report", args.file.display())));
        }
        slideline::bellows::report::html::write_design_report(&r, closing.as_deref(), path)?;
        out += &format!("report: {}\n", path.display());
    }
    if !detail {
        out += &format!("{}\n{}", post::summary(&r)?, post::history_table(&r, args.verbose)?);
        // a bellows run's closing table, as the run printed it
        // (what a damaged file cannot give again is said, not fatal: post reads what is left)
        match slideline::bellows::report::closing_table_from_file(&r) {
            Ok(Some(table)) => out += &format!("\n{table}"),
            Ok(None) => {}
            Err(e) => out += &format!("\nnote: the closing table cannot be printed again: {e}\n"),
        }
        // and the tables after it (flexibility, stability, frequencies), word for word
        match r.printed_tables() {
            Ok(tables) => tables.iter().for_each(|(_, table)| out += &format!("{table}\n")),
            Err(e) => out += &format!("\nnote: the tables after the closing one cannot be printed again: {e}\n"),
        }
    }
    if args.deck {
        out += &format!("{}\n", r.text_attr("deck")?);
    }
    if args.assessment {
        match r.assessment()? {
            Some(check) => {
                out += &slideline::bellows::report::code_section(&check);
                if let Some((fe, life)) = r.finite_element_assessment()? {
                    out += &slideline::bellows::report::assessment_section(&check, &fe, life.as_ref());
                }
            }
            None => return Err(Error::input(format!("{}: no code check in the file (`slideline bellows` writes one)", args.file.display()))),
        }
    }
    if let Some(path) = &args.csv {
        std::fs::write(path, post::history_csv(&r)?).map_err(|e| Error::Output { path: path.clone(), message: e.to_string() })?;
        out += &format!("history written to {}\n", path.display());
    }
    if let Some(name) = &args.field {
        out += &post::field(&r, name, post::increment_number(&r, increment)?)?;
    }
    if let Some(id) = args.node {
        out += &post::node_series(&r, id)?;
    }
    if let Some(set) = &args.set {
        out += &post::set_series(&r, set)?;
    }
    if let Some(other) = &args.compare {
        out += &post::compare(&r, &ResultsReader::open(other)?, args.force)?;
    }
    if let Some(path) = &plot {
        out += &format!("picture: {}\n", post::plot(&r, path)?.display());
    }
    if !args.linearize.is_empty() {
        out += &post::sections::linearize(&r, &args.linearize, post::increment_number(&r, increment)?)?;
    }
    print_quietly_on_closed_pipe(&out)
}

/// Writes `text` to standard output; a closed pipe (the reader has what it wanted) is no error.
fn print_quietly_on_closed_pipe(text: &str) -> Result<(), Error> {
    use std::io::Write as _;
    let mut stdout = std::io::stdout().lock();
    match stdout.write_all(text.as_bytes()).and_then(|_| stdout.flush()) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(Error::Output { path: "standard output".into(), message: e.to_string() }),
        _ => Ok(()),
    }
}

/// `post` of a design-by-analysis verdict file (`slideline check`, `bellows --dba`): its table
/// again, and with `--report` the design report; its checks' analyses are files of their own.
fn verdict_file(r: &ResultsReader, verdict: &slideline::dba::Verdict, args: &PostArgs) -> Result<(), Error> {
    let asked_of_a_run = args.field.is_some()
        || args.node.is_some()
        || args.set.is_some()
        || args.compare.is_some()
        || args.csv.is_some()
        || args.plot.is_some()
        || args.deck
        || !args.linearize.is_empty()
        || args.increment.is_some();
    if asked_of_a_run {
        let files = verdict.files.iter().map(|(_, f)| f.display().to_string()).collect::<Vec<_>>().join(", ");
        return Err(Error::input(format!(
            "{}: a design-by-analysis verdict file has no fields or history of its own; post its checks' files ({files})",
            args.file.display()
        )));
    }
    let mut out = String::new();
    if let Some(path) = &args.report {
        slideline::bellows::report::html::write_design_report(r, None, path)?;
        out += &format!("report: {}\n", path.display());
    }
    out += &slideline::dba::table(verdict, &args.file.display().to_string());
    print_quietly_on_closed_pipe(&out)
}
