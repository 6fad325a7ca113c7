//! `vstf review`: the pending images one at a time, each accepted (it
//! becomes the golden image), rejected (dropped) or skipped, in the manner
//! of `cargo insta review`. Answers are read a line at a time from stdin,
//! so a review can also be scripted.

use std::io::{BufRead, Write};
use std::path::Path;
use vstf::error::Error;
use vstf::golden::{ci_is_set, slug, Pending, Store};
use vstf::project::Project;

/// What the person said to one pending image.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Answer {
    Accept,
    Reject,
    Skip,
    Quit,
}

fn answer(line: &str) -> Option<Answer> {
    match line.trim().to_ascii_lowercase().as_str() {
        "a" | "accept" | "y" | "yes" => Some(Answer::Accept),
        "r" | "reject" | "n" | "no" => Some(Answer::Reject),
        "s" | "skip" | "" => Some(Answer::Skip),
        "q" | "quit" => Some(Answer::Quit),
        _ => None,
    }
}

/// Prints one pending image: what it is, where it changed, its files.
fn show(p: &Pending, k: usize, n: usize) {
    let what = if p.replaces { "changed" } else { "new" };
    println!("[{k}/{n}] {what}: {} / {}", p.fixture, p.view);
    match p.change() {
        Some(c) => println!("  {c}"),
        None if p.replaces => println!("  (the golden has another size)"),
        None => println!("  no golden image yet"),
    }
    let dir = p.actual.parent().unwrap_or(Path::new("."));
    for f in ["actual.png", "expected.png", "diff.png"] {
        if dir.join(f).is_file() {
            println!("  {f:12} {}", dir.join(f).display());
        }
    }
}

/// Reviews every pending image; refused when CI is set.
pub fn run(root: Option<&Path>) -> Result<(), Error> {
    let store: Store = Project::locate(root)?.store();
    let pending = store.list_pending();
    if pending.is_empty() {
        println!("nothing pending");
        return Ok(());
    }
    if ci_is_set(std::env::var("CI").ok().as_deref()) {
        return Err(Error::Golden {
            message:
                "refusing to review golden images with CI set: review locally and commit the images"
                    .into(),
        });
    }
    let stdin = std::io::stdin();
    let mut lines = stdin.lock().lines();
    let (mut accepted, mut rejected, mut skipped) = (0, 0, 0);
    let n = pending.len();
    'images: for (k, p) in pending.iter().enumerate() {
        show(p, k + 1, n);
        let name = [format!("{}/{}", p.fixture, slug(&p.view))];
        let choice = loop {
            print!("  accept (a), reject (r), skip (s), quit (q)? ");
            std::io::stdout().flush().ok();
            let Some(line) = lines.next() else {
                println!();
                break Answer::Quit;
            };
            let line = line.map_err(|e| format!("cannot read the answer: {e}"))?;
            match answer(&line) {
                Some(a) => break a,
                None => println!("  {:?}: answer a, r, s or q", line.trim()),
            }
        };
        match choice {
            Answer::Accept => {
                store.approve(Some(&name), false)?;
                println!(
                    "  accepted: {}",
                    store.golden_path(&p.fixture, &p.view).display()
                );
                accepted += 1;
            }
            Answer::Reject => {
                store.reject(Some(&name))?;
                println!("  rejected (golden unchanged)");
                rejected += 1;
            }
            Answer::Skip => skipped += 1,
            Answer::Quit => {
                skipped += n - k;
                break 'images;
            }
        }
    }
    println!("review: {accepted} accepted, {rejected} rejected, {skipped} left pending");
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::{answer, Answer};

    #[test]
    fn answers_are_read_generously_and_nonsense_is_asked_again() {
        assert_eq!(answer(" A\n"), Some(Answer::Accept));
        assert_eq!(answer("reject"), Some(Answer::Reject));
        assert_eq!(answer(""), Some(Answer::Skip));
        assert_eq!(answer("q"), Some(Answer::Quit));
        assert_eq!(answer("maybe"), None);
    }
}
