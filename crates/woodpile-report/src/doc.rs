//! The report as a list of blocks, rendered to Markdown and to a self-contained HTML page
//! (figures embedded as base64 data URIs: the SVG of each, or its PNG when there is no SVG).

use crate::Error;
use base64::Engine as _;
use std::fmt::Write as _;
use std::fs;
use std::path::{Path, PathBuf};

/// One block of the report.
#[derive(Debug, Clone)]
pub enum Block {
    /// Section heading (level 2 or 3) with its anchor.
    Heading(u8, String),
    /// Paragraph; `code` spans in backticks.
    Para(String),
    /// Bulleted list.
    List(Vec<String>),
    /// Table: header and rows.
    Table(Vec<String>, Vec<Vec<String>>),
    /// Figure: path relative to the report, caption.
    Figure(String, String),
    /// Preformatted text.
    Code(String),
}

/// The report being assembled, and the figures it names.
#[derive(Debug)]
pub struct Doc {
    /// The report's directory: figures are named relative to it.
    root: PathBuf,
    blocks: Vec<Block>,
    /// Number of figures it shows.
    pub figures: usize,
}

impl Doc {
    /// An empty report written into `root`.
    pub fn new(root: &Path) -> Self {
        Doc {
            root: root.to_path_buf(),
            blocks: Vec::new(),
            figures: 0,
        }
    }

    /// A section heading.
    pub fn h2(&mut self, t: impl Into<String>) {
        self.blocks.push(Block::Heading(2, t.into()));
    }
    /// A subsection heading.
    pub fn h3(&mut self, t: impl Into<String>) {
        self.blocks.push(Block::Heading(3, t.into()));
    }
    /// A paragraph (`code` in backticks).
    pub fn p(&mut self, t: impl Into<String>) {
        self.blocks.push(Block::Para(t.into()));
    }
    /// A bulleted list.
    pub fn list(&mut self, items: Vec<String>) {
        self.blocks.push(Block::List(items));
    }
    /// A table: its header and rows.
    pub fn table(&mut self, header: &[&str], rows: Vec<Vec<String>>) {
        self.blocks.push(Block::Table(
            header.iter().map(|s| s.to_string()).collect(),
            rows,
        ));
    }
    /// Preformatted text.
    pub fn code(&mut self, t: impl Into<String>) {
        self.blocks.push(Block::Code(t.into()));
    }
    /// A figure: `files` as returned by a plot function (the PNG is shown, the SVG linked).
    pub fn figure(&mut self, files: &[PathBuf], caption: impl Into<String>) {
        if let Some(png) = files
            .iter()
            .find(|f| f.extension().is_some_and(|e| e == "png"))
        {
            let rel = png.strip_prefix(&self.root).unwrap_or(png);
            let rel = rel.to_string_lossy().replace('\\', "/");
            self.figures += 1;
            self.blocks.push(Block::Figure(
                rel,
                format!("Figure {}. {}", self.figures, caption.into()),
            ));
        }
    }

    /// One figure per plot of `files` (as many as there are captions), each captioned
    /// `PREFIX: caption`.
    pub fn figures(
        &mut self,
        files: &[Vec<PathBuf>],
        prefix: &str,
        captions: impl IntoIterator<Item = String>,
    ) {
        for (f, caption) in files.iter().zip(captions) {
            self.figure(f, format!("{prefix}: {caption}"));
        }
    }

    fn anchor(title: &str) -> String {
        let mut a = String::new();
        for c in title.chars() {
            if c.is_ascii_alphanumeric() {
                a.push(c.to_ascii_lowercase());
            } else if !a.ends_with('-') && !a.is_empty() {
                a.push('-');
            }
        }
        a.trim_end_matches('-').to_string()
    }

    /// The report as Markdown under `title`, with a table of contents.
    pub fn markdown(&self, title: &str) -> String {
        let mut s = format!("# {title}\n\n## Contents\n\n");
        for b in &self.blocks {
            if let Block::Heading(2, t) = b {
                let _ = writeln!(s, "- [{t}](#{})", Self::anchor(t));
            }
        }
        s.push('\n');
        for b in &self.blocks {
            match b {
                Block::Heading(l, t) => {
                    let _ = writeln!(s, "{} {t}\n", "#".repeat(usize::from(*l)));
                }
                Block::Para(t) => {
                    let _ = writeln!(s, "{t}\n");
                }
                Block::List(items) => {
                    for i in items {
                        let _ = writeln!(s, "- {i}");
                    }
                    s.push('\n');
                }
                Block::Table(h, rows) => {
                    let _ = writeln!(s, "| {} |", h.join(" | "));
                    let _ = writeln!(s, "|{}", " --- |".repeat(h.len()));
                    for r in rows {
                        let cells: Vec<String> = r.iter().map(|c| c.replace('|', "\\|")).collect();
                        let _ = writeln!(s, "| {} |", cells.join(" | "));
                    }
                    s.push('\n');
                }
                Block::Figure(path, caption) => {
                    let svg = path.trim_end_matches(".png").to_string() + ".svg";
                    let _ = writeln!(s, "![{caption}]({path})\n\n*{caption}* ([SVG]({svg}))\n");
                }
                Block::Code(t) => {
                    let _ = writeln!(s, "```\n{t}\n```\n");
                }
            }
        }
        s
    }

    /// The report as one self-contained HTML page under `title` (figures embedded).
    pub fn html(&self, title: &str) -> Result<String, Error> {
        let mut s =
            String::from("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n");
        let _ = writeln!(s, "<title>{}</title>", escape(title));
        s.push_str(STYLE);
        s.push_str("</head>\n<body>\n<nav>\n<h2>Contents</h2>\n<ol>\n");
        for b in &self.blocks {
            if let Block::Heading(2, t) = b {
                let _ = writeln!(
                    s,
                    "<li><a href=\"#{}\">{}</a></li>",
                    Self::anchor(t),
                    inline(t)
                );
            }
        }
        s.push_str("</ol>\n</nav>\n<main>\n");
        let _ = writeln!(s, "<h1>{}</h1>", escape(title));
        for b in &self.blocks {
            match b {
                Block::Heading(l, t) => {
                    let _ = writeln!(s, "<h{l} id=\"{}\">{}</h{l}>", Self::anchor(t), inline(t));
                }
                Block::Para(t) => {
                    let _ = writeln!(s, "<p>{}</p>", inline(t));
                }
                Block::List(items) => {
                    s.push_str("<ul>\n");
                    for i in items {
                        let _ = writeln!(s, "<li>{}</li>", inline(i));
                    }
                    s.push_str("</ul>\n");
                }
                Block::Table(h, rows) => {
                    s.push_str("<div class=\"table\"><table>\n<thead><tr>");
                    for c in h {
                        let _ = write!(s, "<th>{}</th>", inline(c));
                    }
                    s.push_str("</tr></thead>\n<tbody>\n");
                    for r in rows {
                        s.push_str("<tr>");
                        for c in r {
                            let _ = write!(s, "<td>{}</td>", inline(c));
                        }
                        s.push_str("</tr>\n");
                    }
                    s.push_str("</tbody></table></div>\n");
                }
                Block::Figure(path, caption) => {
                    // The SVG beside the PNG when there is one: vector lines and text stay sharp
                    // at any zoom, and it is a tenth of the 300 dpi PNG's size (maps carry their
                    // cells as one image either way).
                    let png = self.root.join(path);
                    let svg = png.with_extension("svg");
                    let (file, mime) = if svg.is_file() {
                        (svg, "image/svg+xml")
                    } else {
                        (png, "image/png")
                    };
                    let bytes = fs::read(&file).map_err(|e| Error::Read {
                        path: file.clone(),
                        source: e,
                    })?;
                    let data = base64::engine::general_purpose::STANDARD.encode(bytes);
                    let _ = writeln!(
                        s,
                        "<figure data-file=\"{path}\"><img src=\"data:{mime};base64,{data}\" alt=\"{}\"><figcaption>{} <span class=\"file\">({path})</span></figcaption></figure>",
                        escape(caption),
                        inline(caption)
                    );
                }
                Block::Code(t) => {
                    let _ = writeln!(s, "<pre>{}</pre>", escape(t));
                }
            }
        }
        s.push_str("</main>\n</body>\n</html>\n");
        Ok(s)
    }
}

const STYLE: &str = "<style>
body { font-family: -apple-system, 'Segoe UI', Helvetica, Arial, sans-serif; margin: 0; color: #222; line-height: 1.5; }
nav { position: fixed; top: 0; left: 0; width: 16rem; height: 100vh; overflow-y: auto; background: #f4f5f7; border-right: 1px solid #ddd; padding: 1rem; box-sizing: border-box; font-size: 0.9rem; }
nav h2 { font-size: 1rem; margin-top: 0; }
nav ol { padding-left: 1.2rem; }
main { margin-left: 17rem; max-width: 70rem; padding: 1rem 2rem 4rem; }
h1 { border-bottom: 2px solid #2b5797; padding-bottom: .3rem; }
h2 { border-bottom: 1px solid #ccc; padding-bottom: .2rem; margin-top: 2.5rem; }
code, pre { font-family: 'DejaVu Sans Mono', Menlo, Consolas, monospace; background: #f1f1f1; border-radius: 3px; }
code { padding: 0 .25rem; }
pre { padding: .6rem; overflow-x: auto; }
div.table { overflow-x: auto; }
table { border-collapse: collapse; margin: 1rem 0; font-size: 0.9rem; }
th, td { border: 1px solid #ccc; padding: .3rem .6rem; text-align: left; vertical-align: top; }
th { background: #e8ecf3; }
tr:nth-child(even) td { background: #fafafa; }
figure { margin: 1.5rem 0; }
figure img { max-width: 100%; border: 1px solid #ddd; }
figcaption { font-size: 0.9rem; color: #444; }
figcaption .file { color: #888; }
@media (max-width: 60rem) { nav { position: static; width: auto; height: auto; } main { margin-left: 0; } }
</style>
";

fn escape(t: &str) -> String {
    t.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Escapes and turns `code` spans into `<code>`.
fn inline(t: &str) -> String {
    escape(t)
        .split('`')
        .enumerate()
        .map(|(i, part)| {
            if i % 2 == 1 {
                format!("<code>{part}</code>")
            } else {
                part.to_string()
            }
        })
        .collect()
}
