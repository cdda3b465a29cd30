//! The repository stands on its own: every relative link of every Markdown file resolves to a
//! file inside the repository (and a `#fragment` into a Markdown file to one of its headings),
//! every `curl … -d @examples/…` line posts a file that `tests/api/examples.rs` posts to the
//! same route, and no source comment cites a document outside the repository.
//!
//! Markdown is read the way GitHub renders it, as far as links go: fenced code blocks, code
//! spans and HTML comments hold no links; links are inline (`[text](dest)`, `![alt](dest)`),
//! reference definitions (`[label]: dest`) and HTML `href`/`src` attributes. Heading anchors
//! follow GitHub's rule: the heading's text, lower-cased, spaces turned into `-`, every other
//! character that is not a letter, digit, `-` or `_` dropped; a repeated anchor gets `-1`,
//! `-2`, ….
//!
//! One file of about 550 lines: the Markdown reading (`lines`, `without_code_spans`,
//! `link_destinations`, `anchors`) is written here because no Markdown parser is among the
//! dependencies; with `pulldown-cmark` as a dev-dependency it would shrink to an event loop.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

const ROOT: &str = env!("CARGO_MANIFEST_DIR");

/// Directories never searched for Markdown files (build output, git's own data).
const SKIPPED_DIRS: [&str; 2] = ["target", ".git"];

/// Texts that a comment in `src/` must not cite: the background documents that are not part
/// of the repository.
const OUTSIDE_DOCUMENTS: [&str; 3] = ["MATH.md", "API.md", "shared/docs"];

// ------------------------------------------------------------------- files --

/// Every file under `dir` whose name ends with `.{extension}`, sorted, skipping
/// [`SKIPPED_DIRS`].
fn files_with_extension(dir: &Path, extension: &str) -> Vec<PathBuf> {
    let mut found = Vec::new();
    let mut pending = vec![dir.to_path_buf()];
    while let Some(dir) = pending.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            if path.is_dir() {
                if !SKIPPED_DIRS.contains(&name.as_str()) {
                    pending.push(path);
                }
            } else if path.extension().is_some_and(|e| e == extension) {
                found.push(path);
            }
        }
    }
    found.sort();
    found
}

fn markdown_files() -> Vec<PathBuf> {
    let files = files_with_extension(Path::new(ROOT), "md");
    assert!(
        files.iter().any(|f| f.ends_with("README.md")),
        "no README.md found under {ROOT}"
    );
    files
}

fn relative(path: &Path) -> String {
    path.strip_prefix(ROOT)
        .unwrap_or(path)
        .display()
        .to_string()
}

// ---------------------------------------------------------------- markdown --

/// One line of a Markdown text: its number (from 1), its text without HTML comments, and
/// whether it is inside a fenced code block (or is a fence).
struct Line {
    number: usize,
    text: String,
    in_code: bool,
}

/// The lines of `markdown`, with HTML comments removed (also across lines) and fenced code
/// blocks (``` or ~~~, closed by a fence of the same character at least as long) marked.
fn lines(markdown: &str) -> Vec<Line> {
    let mut out = Vec::new();
    let mut fence: Option<(char, usize)> = None;
    let mut in_comment = false;
    for (index, raw) in markdown.lines().enumerate() {
        let trimmed = raw.trim_start();
        let indent = raw.len() - trimmed.len();
        let fence_char = trimmed.chars().next().filter(|c| *c == '`' || *c == '~');
        let fence_len = fence_char.map_or(0, |c| trimmed.chars().take_while(|&d| d == c).count());
        if !in_comment && indent <= 3 && fence_len >= 3 {
            let c = fence_char.unwrap();
            match fence {
                None => fence = Some((c, fence_len)),
                Some((open, len)) if open == c && fence_len >= len => fence = None,
                Some(_) => {}
            }
            out.push(Line {
                number: index + 1,
                text: raw.to_owned(),
                in_code: true,
            });
            continue;
        }
        if fence.is_some() {
            out.push(Line {
                number: index + 1,
                text: raw.to_owned(),
                in_code: true,
            });
            continue;
        }
        let mut text = String::new();
        let mut rest = raw;
        loop {
            if in_comment {
                match rest.find("-->") {
                    Some(end) => {
                        rest = &rest[end + 3..];
                        in_comment = false;
                    }
                    None => break,
                }
            } else {
                match rest.find("<!--") {
                    Some(start) => {
                        text.push_str(&rest[..start]);
                        rest = &rest[start + 4..];
                        in_comment = true;
                    }
                    None => {
                        text.push_str(rest);
                        break;
                    }
                }
            }
        }
        out.push(Line {
            number: index + 1,
            text,
            in_code: false,
        });
    }
    out
}

/// `text` without its code spans (`` `…` ``, also with longer backtick runs); an unclosed run
/// of backticks stays as it is.
fn without_code_spans(text: &str) -> String {
    let mut out = String::new();
    let mut rest = text;
    while let Some(start) = rest.find('`') {
        let run = rest[start..].chars().take_while(|&c| c == '`').count();
        let after = &rest[start + run..];
        let closing = "`".repeat(run);
        let mut search = 0;
        let mut end = None;
        while let Some(found) = after[search..].find(&closing) {
            let at = search + found;
            let longer = after[at + run..].starts_with('`');
            if !longer {
                end = Some(at);
                break;
            }
            search = at + after[at..].chars().take_while(|&c| c == '`').count();
        }
        out.push_str(&rest[..start]);
        match end {
            Some(end) => rest = &after[end + run..],
            None => {
                out.push_str(&rest[start..start + run]);
                rest = after;
            }
        }
    }
    out.push_str(rest);
    out
}

/// The link destinations of one prose line (code spans already removed): inline links and
/// images, a reference definition, and HTML `href`/`src` attributes.
fn link_destinations(text: &str) -> Vec<String> {
    let mut found = Vec::new();
    let mut rest = text;
    while let Some(at) = rest.find("](") {
        let after = &rest[at + 2..];
        let destination = if let Some(angled) = after.strip_prefix('<') {
            angled.split('>').next().unwrap_or("").to_owned()
        } else {
            // Up to the closing parenthesis (balanced) or the title after a space.
            let mut depth = 0usize;
            let mut end = after.len();
            for (i, c) in after.char_indices() {
                match c {
                    '(' => depth += 1,
                    ')' if depth == 0 => {
                        end = i;
                        break;
                    }
                    ')' => depth -= 1,
                    c if c.is_whitespace() => {
                        end = i;
                        break;
                    }
                    _ => {}
                }
            }
            after[..end].to_owned()
        };
        found.push(destination);
        rest = after;
    }
    let trimmed = text.trim_start();
    let definition = (text.len() - trimmed.len() <= 3 && trimmed.starts_with('['))
        .then(|| trimmed.find("]:"))
        .flatten()
        .filter(|&close| !trimmed[1..close].contains(']'));
    if let Some(close) = definition {
        let destination = trimmed[close + 2..].split_whitespace().next().unwrap_or("");
        found.push(
            destination
                .trim_matches(|c| c == '<' || c == '>')
                .to_owned(),
        );
    }
    for attribute in ["href=\"", "src=\""] {
        let mut rest = text;
        while let Some(at) = rest.find(attribute) {
            let after = &rest[at + attribute.len()..];
            found.push(after.split('"').next().unwrap_or("").to_owned());
            rest = after;
        }
    }
    found
}

/// A heading's text as GitHub renders it for its anchor: link texts without their
/// destinations, code spans without backticks, no emphasis stars.
fn heading_text(raw: &str) -> String {
    let mut text = String::new();
    let mut rest = raw;
    while let Some(open) = rest.find('[') {
        let Some(close) = rest[open..].find("](").map(|c| open + c) else {
            break;
        };
        let Some(end) = rest[close..].find(')').map(|e| close + e) else {
            break;
        };
        text.push_str(&rest[..open]);
        text.push_str(&rest[open + 1..close]);
        rest = &rest[end + 1..];
    }
    text.push_str(rest);
    text.replace(['`', '*'], "")
}

/// GitHub's anchor of a heading text (module docs).
fn slug(text: &str) -> String {
    let mut out = String::new();
    for c in heading_text(text).trim().chars() {
        if c.is_alphanumeric() || c == '-' || c == '_' {
            out.extend(c.to_lowercase());
        } else if c == ' ' {
            out.push('-');
        }
    }
    out
}

/// Every anchor a Markdown text defines: its ATX headings' slugs (repeats numbered) and
/// explicit `id="…"` / `name="…"` attributes.
fn anchors(markdown: &str) -> BTreeSet<String> {
    let mut seen: BTreeMap<String, usize> = BTreeMap::new();
    let mut out = BTreeSet::new();
    for line in lines(markdown).into_iter().filter(|l| !l.in_code) {
        let trimmed = line.text.trim_start();
        let hashes = trimmed.chars().take_while(|&c| c == '#').count();
        let after = &trimmed[hashes..];
        let is_heading = line.text.len() - trimmed.len() <= 3
            && (1..=6).contains(&hashes)
            && (after.is_empty() || after.starts_with([' ', '\t']));
        if is_heading {
            let title = after.trim().trim_end_matches('#').trim_end();
            let base = slug(title);
            let count = seen.entry(base.clone()).or_insert(0);
            out.insert(if *count == 0 {
                base.clone()
            } else {
                format!("{base}-{count}")
            });
            *count += 1;
        }
        for attribute in ["id=\"", "name=\""] {
            let mut rest = line.text.as_str();
            while let Some(at) = rest.find(attribute) {
                let after = &rest[at + attribute.len()..];
                out.insert(after.split('"').next().unwrap_or("").to_owned());
                rest = after;
            }
        }
    }
    out
}

/// Whether a destination leaves the repository by its nature (`https:`, `mailto:`, `//host`).
fn is_external(destination: &str) -> bool {
    if destination.starts_with("//") {
        return true;
    }
    match destination.find(':') {
        Some(colon) => {
            let scheme = &destination[..colon];
            !scheme.is_empty()
                && scheme
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || "+-.".contains(c))
        }
        None => false,
    }
}

/// `%xx` escapes decoded (a link to `a%20b.md` names `a b.md`).
fn percent_decoded(text: &str) -> String {
    let bytes = text.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        let hex = bytes
            .get(i + 1..i + 3)
            .and_then(|h| std::str::from_utf8(h).ok())
            .and_then(|h| u8::from_str_radix(h, 16).ok());
        match (bytes[i], hex) {
            (b'%', Some(byte)) => {
                out.push(byte);
                i += 3;
            }
            (byte, _) => {
                out.push(byte);
                i += 1;
            }
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// Checks one link destination of the Markdown file `file` against the repository at `root`:
/// a relative path must name an existing file or directory inside `root`, and a fragment
/// into a Markdown file one of its anchors. External links pass.
fn check_destination(root: &Path, file: &Path, destination: &str) -> Result<(), String> {
    if destination.is_empty() {
        return Err("empty link destination".to_owned());
    }
    if is_external(destination) {
        return Ok(());
    }
    let (path, fragment) = destination.split_once('#').unwrap_or((destination, ""));
    let path = percent_decoded(path.split('?').next().unwrap_or(""));
    let target = if path.is_empty() {
        file.to_path_buf()
    } else if let Some(from_root) = path.strip_prefix('/') {
        root.join(from_root)
    } else {
        file.parent().unwrap().join(&path)
    };
    let resolved = target
        .canonicalize()
        .map_err(|_| format!("`{destination}`: {} does not exist", target.display()))?;
    if !resolved.starts_with(root.canonicalize().unwrap()) {
        return Err(format!(
            "`{destination}` leaves the repository ({})",
            resolved.display()
        ));
    }
    let is_markdown = resolved.extension().is_some_and(|e| e == "md");
    if !fragment.is_empty() && is_markdown {
        let text = std::fs::read_to_string(&resolved).unwrap();
        if !anchors(&text).contains(fragment) {
            return Err(format!(
                "`{destination}`: no heading in {} has the anchor `{fragment}`",
                resolved.display()
            ));
        }
    }
    Ok(())
}

/// Every broken link of the Markdown file `file` (as `line N: why`).
fn broken_links(root: &Path, file: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(file).unwrap();
    let mut broken = Vec::new();
    for line in lines(&text).into_iter().filter(|l| !l.in_code) {
        for destination in link_destinations(&without_code_spans(&line.text)) {
            if let Err(why) = check_destination(root, file, &destination) {
                broken.push(format!("line {}: {why}", line.number));
            }
        }
    }
    broken
}

// ------------------------------------------------------------------- tests --

#[test]
fn every_relative_link_of_every_markdown_file_resolves() {
    let root = Path::new(ROOT);
    let mut broken = Vec::new();
    let files = markdown_files();
    for file in &files {
        for why in broken_links(root, file) {
            broken.push(format!("{}: {why}", relative(file)));
        }
    }
    assert!(
        broken.is_empty(),
        "broken links in {} Markdown files:\n{}",
        files.len(),
        broken.join("\n")
    );
}

#[test]
fn the_checker_finds_broken_links_and_anchors() {
    // A scratch repository: the checker must tell good links from bad ones.
    let scratch = std::env::temp_dir().join(format!("knotshape-doc-links-{}", std::process::id()));
    let root = scratch.join("repository");
    let docs = root.join("docs");
    std::fs::create_dir_all(&docs).unwrap();
    std::fs::write(scratch.join("outside.md"), "# Outside\n").unwrap();
    std::fs::write(
        docs.join("guide.md"),
        "# Guide\n\n## §3.1 Which knot moves\n\n## Ω1–Ω6: the `pairs`\n\n## Again\n\n## Again\n",
    )
    .unwrap();
    let readme = root.join("README.md");
    std::fs::write(
        &readme,
        "\
[fine](docs/guide.md#31-which-knot-moves) [fine](docs/guide.md#ω1ω6-the-pairs)
[fine](docs/guide.md#again-1) [fine](https://example.com/x.md) [fine](#top) ![p](docs/)
<!-- [hidden](missing.md) -->
`[code](missing.md)`
```text
[fenced](missing.md)
```
# Top
[gone](docs/missing.md) [bad anchor](docs/guide.md#which-knot-moves)
[outside](../outside.md)
[ref]: docs/nothing.md
<img src=\"docs/none.png\">
",
    )
    .unwrap();
    let broken = broken_links(&root, &readme);
    std::fs::remove_dir_all(&scratch).unwrap();
    let lines: Vec<&str> = broken
        .iter()
        .map(|b| b.split(':').next().unwrap())
        .collect();
    assert_eq!(
        lines,
        ["line 9", "line 9", "line 10", "line 11", "line 12"],
        "{broken:#?}"
    );
    assert!(broken[0].contains("does not exist"), "{broken:#?}");
    assert!(broken[1].contains("no heading"), "{broken:#?}");
    assert!(broken[2].contains("leaves the repository"), "{broken:#?}");
}

#[test]
fn curl_examples_post_the_files_the_example_test_posts() {
    // tests/api/examples.rs posts `examples/<group>-<endpoint>[-variant].json` to
    // `/v1/<group>/<endpoint>`; a Markdown curl line must post such a file to that route.
    let mut problems = Vec::new();
    let mut posted = 0;
    for file in markdown_files() {
        let text = std::fs::read_to_string(&file).unwrap();
        for line in lines(&text) {
            let Some(at) = line.text.find("@examples/") else {
                continue;
            };
            posted += 1;
            let name: String = line.text[at + 1..]
                .chars()
                .take_while(|c| !c.is_whitespace() && *c != '\'' && *c != '"')
                .collect();
            let place = format!("{}:{}", relative(&file), line.number);
            if !Path::new(ROOT).join(&name).is_file() {
                problems.push(format!("{place}: {name} does not exist"));
                continue;
            }
            let Some(route_at) = line.text.find("/v1/") else {
                problems.push(format!("{place}: no /v1/ route on the line of {name}"));
                continue;
            };
            let route: Vec<&str> = line.text[route_at + 4..]
                .split(|c: char| !(c.is_ascii_alphanumeric() || c == '-' || c == '/'))
                .next()
                .unwrap()
                .split('/')
                .collect();
            let stem = name
                .trim_start_matches("examples/")
                .trim_end_matches(".json");
            let expected = route.join("-");
            let matches =
                route.len() >= 2 && (stem == expected || stem.starts_with(&format!("{expected}-")));
            if !matches {
                problems.push(format!(
                    "{place}: {name} is posted to /v1/{}, but the example test posts it elsewhere",
                    route.join("/")
                ));
            }
        }
    }
    assert!(posted > 0, "no curl line posts an example file");
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn every_example_file_is_shown_in_the_docs() {
    let shown: String = markdown_files()
        .iter()
        .map(|f| std::fs::read_to_string(f).unwrap())
        .collect();
    let missing: Vec<String> = files_with_extension(&Path::new(ROOT).join("examples"), "json")
        .iter()
        .map(|f| format!("@examples/{}", f.file_name().unwrap().to_string_lossy()))
        .filter(|reference| !shown.contains(reference.as_str()))
        .collect();
    assert!(
        missing.is_empty(),
        "example files that no Markdown curl line posts (add them to README.md or docs/api.md): {missing:?}"
    );
}

#[test]
fn source_comments_cite_only_repository_files() {
    let mut citations = Vec::new();
    for file in files_with_extension(&Path::new(ROOT).join("src"), "rs") {
        let text = std::fs::read_to_string(&file).unwrap();
        for (index, line) in text.lines().enumerate() {
            if let Some(cited) = OUTSIDE_DOCUMENTS.iter().find(|d| line.contains(*d)) {
                citations.push(format!(
                    "{}:{}: cites {cited}: {}",
                    relative(&file),
                    index + 1,
                    line.trim()
                ));
            }
        }
    }
    assert!(
        citations.is_empty(),
        "comments in src/ must cite docs/method.md §… or the paper, not documents outside the \
         repository:\n{}",
        citations.join("\n")
    );
}
