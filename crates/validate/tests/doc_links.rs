//! Every relative link in README.md and docs/ (the validation's page, its tables and the
//! departures it lists, which code comments cite by file) leads to a file that exists, and a
//! link to a heading of a Markdown file to a heading it has (GitHub's anchors). Code spans and
//! fenced blocks are not links; links with a scheme (https:, mailto:) are not checked.

use std::collections::HashSet;
use std::path::{Path, PathBuf};

fn repository() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The Markdown pages whose links are checked: README.md and every `.md` under docs/.
fn pages() -> Vec<PathBuf> {
    let mut pages = vec![repository().join("README.md")];
    let mut folders = vec![repository().join("docs")];
    while let Some(folder) = folders.pop() {
        for entry in std::fs::read_dir(&folder).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                folders.push(path);
            } else if path.extension().is_some_and(|e| e == "md") {
                pages.push(path);
            }
        }
    }
    pages
}

/// The page's lines with fenced code blocks blanked and inline code spans removed.
fn prose_lines(text: &str) -> Vec<String> {
    let mut in_fence = false;
    text.lines()
        .map(|line| {
            if line.trim_start().starts_with("```") {
                in_fence = !in_fence;
                return String::new();
            }
            if in_fence {
                return String::new();
            }
            line.split('`').step_by(2).collect()
        })
        .collect()
}

/// GitHub's anchor for a heading: lower case, letters, digits, `-` and `_` kept, spaces as `-`.
fn slug(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter_map(|c| match c {
            ' ' => Some('-'),
            c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c),
            _ => None,
        })
        .collect()
}

/// Every heading's anchor in a Markdown page, repeats numbered as GitHub numbers them.
fn anchors(page: &Path) -> HashSet<String> {
    let text = std::fs::read_to_string(page).unwrap();
    let mut found = HashSet::new();
    for line in prose_lines(&text) {
        let hashes = line.len() - line.trim_start_matches('#').len();
        if (1..=6).contains(&hashes) && line[hashes..].starts_with(' ') {
            let base = slug(line[hashes..].trim_end_matches('#'));
            let mut anchor = base.clone();
            let mut n = 0;
            while !found.insert(anchor.clone()) {
                n += 1;
                anchor = format!("{base}-{n}");
            }
        }
    }
    found
}

/// The targets of the `[text](target)` links on one line.
fn targets(line: &str) -> Vec<&str> {
    line.match_indices("](")
        .filter_map(|(at, _)| {
            let rest = &line[at + 2..];
            rest.find(')').map(|end| &rest[..end])
        })
        .filter(|target| !target.contains(' '))
        .collect()
}

/// What is wrong with one link from `page`, if anything.
fn broken(page: &Path, target: &str) -> Option<String> {
    let scheme = target.split_once(':').map(|(s, _)| s);
    if scheme.is_some_and(|s| !s.is_empty() && s.chars().all(|c| c.is_ascii_alphabetic())) {
        return None;
    }
    let (file, anchor) = target.split_once('#').unwrap_or((target, ""));
    let linked = if file.is_empty() {
        page.to_path_buf()
    } else {
        page.parent().unwrap().join(file)
    };
    if !linked.exists() {
        return Some(format!("{target}: no such file"));
    }
    let markdown = linked.extension().is_some_and(|e| e == "md");
    if !anchor.is_empty() && markdown && !anchors(&linked).contains(anchor) {
        return Some(format!("{target}: no such heading"));
    }
    None
}

fn broken_links_in(page: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(page).unwrap();
    let mut broken_links = Vec::new();
    for (number, line) in prose_lines(&text).iter().enumerate() {
        for target in targets(line) {
            if let Some(why) = broken(page, target) {
                broken_links.push(format!("{}:{}: {why}", page.display(), number + 1));
            }
        }
    }
    broken_links
}

#[test]
fn every_relative_link_in_the_docs_resolves() {
    let pages = pages();
    assert!(pages.len() > 30, "found only {} pages", pages.len());
    let broken_links: Vec<String> = pages
        .iter()
        .flat_map(|page| broken_links_in(page.as_path()))
        .collect();
    assert!(
        broken_links.is_empty(),
        "broken links:\n{}",
        broken_links.join("\n")
    );
}

/// The checker itself: a missing file and a missing heading are found, code spans ignored.
#[test]
fn the_checker_finds_what_is_broken() {
    let folder = std::env::temp_dir().join(format!("cuticle-doc-links-{}", std::process::id()));
    std::fs::create_dir_all(&folder).unwrap();
    let page = folder.join("page.md");
    std::fs::write(
        &page,
        "# Where each model stands (θ_i ≤ 1.1)\n\n[here](#where-each-model-stands-θ_i--11) \
         [gone](missing.md) [heading](page.md#nowhere) `[code](missing.md)` \
         [web](https://example.org)\n",
    )
    .unwrap();
    let found = broken_links_in(&page);
    std::fs::remove_dir_all(&folder).unwrap();
    assert_eq!(found.len(), 2, "{found:?}");
    assert!(found[0].ends_with("missing.md: no such file"), "{found:?}");
    assert!(
        found[1].ends_with("page.md#nowhere: no such heading"),
        "{found:?}"
    );
}
