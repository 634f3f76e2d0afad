//! The module import graph of each crate, and its cycles.
//!
//! Every `.rs` file under a crate's `src/` is a module (`a/b.rs` and
//! `a/b/mod.rs` are `crate::a::b`; `lib.rs` and `main.rs` the root). A module
//! imports another when it names it in a `use` statement (brace groups
//! expanded) or in a qualified path in code: `crate::a::b`, `super::x`,
//! `self::x`, or `child::x` for a module it declares with `mod child;`.
//! Inline modules (`mod tests { ... }`) are part of their file's module but
//! resolve `super` and `self` from themselves. Each path names the longest
//! module it starts with; paths into other crates are ignored. Comments and
//! literals are skipped by a small tokenizer.
//!
//! The project rule is that no module imports one that imports it back: any
//! strongly connected component of more than one module is a cycle, and
//! `cargo xtask modules` fails on it.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};

/// A module's path below the crate root (empty for the root).
type Module = Vec<String>;

/// Checks every `crates/*/src` and `xtask/src`, printing per crate the
/// module, edge and cycle counts (and with `verbose` the edges), and fails
/// when any crate has a cycle.
pub(crate) fn run(verbose: bool) -> Result<()> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("xtask lives in the workspace");
    let mut total = 0;
    for src in source_dirs(root)? {
        let sources = read_sources(&root.join(&src))?;
        let graph = Graph::new(&sources);
        if verbose {
            for (from, to) in &graph.edges {
                let mut to: Vec<String> = to.iter().map(|m| name(m)).collect();
                to.sort();
                println!("{} -> {}", name(from), to.join(", "));
            }
        }
        let cycles = graph.cycles();
        for cycle in &cycles {
            let names: Vec<String> = cycle.iter().map(|m| name(m)).collect();
            println!("CYCLE: {}", names.join(" <-> "));
        }
        let edges: usize = graph.edges.values().map(BTreeSet::len).sum();
        println!(
            "{}: {} modules, {edges} edges, {} cycles",
            src.display(),
            graph.modules.len(),
            cycles.len()
        );
        total += cycles.len();
    }
    if total > 0 {
        // The cycles are printed above; an error would only repeat them
        // (with a backtrace when RUST_BACKTRACE is set).
        eprintln!("modules: {total} cycle(s): a module imports one that imports it back");
        std::process::exit(1);
    }
    Ok(())
}

/// `crates/*/src` by name, then `xtask/src`, relative to the workspace root.
fn source_dirs(root: &Path) -> Result<Vec<PathBuf>> {
    let crates = root.join("crates");
    let mut dirs = Vec::new();
    for entry in std::fs::read_dir(&crates).with_context(|| format!("reading {}", crates.display()))? {
        let name = entry?.file_name();
        let src = Path::new("crates").join(name).join("src");
        if root.join(&src).is_dir() {
            dirs.push(src);
        }
    }
    dirs.sort();
    dirs.push(Path::new("xtask").join("src"));
    Ok(dirs)
}

/// The `.rs` files below `src`, keyed by their path relative to it (with
/// `/` separators).
fn read_sources(src: &Path) -> Result<BTreeMap<String, String>> {
    fn walk(dir: &Path, rel: &str, out: &mut BTreeMap<String, String>) -> Result<()> {
        for entry in std::fs::read_dir(dir).with_context(|| format!("reading {}", dir.display()))? {
            let path = entry?.path();
            let file = path.file_name().and_then(|n| n.to_str()).context("non-UTF-8 file name")?;
            let rel = if rel.is_empty() { file.to_string() } else { format!("{rel}/{file}") };
            if path.is_dir() {
                walk(&path, &rel, out)?;
            } else if file.ends_with(".rs") {
                let text =
                    std::fs::read_to_string(&path).with_context(|| format!("reading {}", path.display()))?;
                out.insert(rel, text);
            }
        }
        Ok(())
    }
    let mut out = BTreeMap::new();
    walk(src, "", &mut out)?;
    Ok(out)
}

/// `crate::a::b` for `[a, b]`.
fn name(module: &[String]) -> String {
    std::iter::once("crate").chain(module.iter().map(String::as_str)).collect::<Vec<_>>().join("::")
}

/// The module a source file (path relative to `src/`, `/` separators) is.
fn module_of(file: &str) -> Module {
    let mut parts: Module = file.trim_end_matches(".rs").split('/').map(str::to_string).collect();
    if parts.last().is_some_and(|p| p == "lib" || p == "main" || p == "mod") {
        parts.pop();
    }
    parts
}

/// The modules of a crate and which modules each imports (never itself).
struct Graph {
    modules: BTreeSet<Module>,
    edges: BTreeMap<Module, BTreeSet<Module>>,
}

impl Graph {
    /// The graph of a crate's sources: file path relative to `src/` → text.
    fn new(sources: &BTreeMap<String, String>) -> Graph {
        // `lib.rs` and `main.rs` are both the root: their tokens are joined.
        let mut files: BTreeMap<Module, Vec<Token>> = BTreeMap::new();
        for (file, text) in sources {
            files.entry(module_of(file)).or_default().extend(tokenize(text));
        }
        let modules: BTreeSet<Module> = files.keys().cloned().collect();
        let mut edges: BTreeMap<Module, BTreeSet<Module>> = BTreeMap::new();
        for (module, tokens) in &files {
            let file = FileScan::new(tokens);
            for (scope, path) in file.paths() {
                let Some(full) = absolute(module, &scope, &file.children, &path) else { continue };
                let target = longest_module(&modules, &full);
                if &target != module {
                    edges.entry(module.clone()).or_default().insert(target);
                }
            }
        }
        Graph { modules, edges }
    }

    /// The strongly connected components of more than one module (Tarjan),
    /// each sorted by name, in order of their first module's name.
    fn cycles(&self) -> Vec<Vec<Module>> {
        struct Tarjan<'a> {
            graph: &'a Graph,
            index: BTreeMap<&'a Module, usize>,
            low: BTreeMap<&'a Module, usize>,
            stack: Vec<&'a Module>,
            on_stack: BTreeSet<&'a Module>,
            sccs: Vec<Vec<Module>>,
        }
        impl<'a> Tarjan<'a> {
            fn strong(&mut self, v: &'a Module) {
                let n = self.index.len();
                self.index.insert(v, n);
                self.low.insert(v, n);
                self.stack.push(v);
                self.on_stack.insert(v);
                for w in self.graph.edges.get(v).into_iter().flatten() {
                    if !self.index.contains_key(w) {
                        self.strong(w);
                        let low = self.low[v].min(self.low[w]);
                        self.low.insert(v, low);
                    } else if self.on_stack.contains(w) {
                        let low = self.low[v].min(self.index[w]);
                        self.low.insert(v, low);
                    }
                }
                if self.low[v] == self.index[v] {
                    let mut component = Vec::new();
                    loop {
                        let w = self.stack.pop().expect("v is on the stack");
                        self.on_stack.remove(w);
                        component.push(w.clone());
                        if w == v {
                            break;
                        }
                    }
                    if component.len() > 1 {
                        component.sort_by_key(|m| name(m));
                        self.sccs.push(component);
                    }
                }
            }
        }
        let mut tarjan = Tarjan {
            graph: self,
            index: BTreeMap::new(),
            low: BTreeMap::new(),
            stack: Vec::new(),
            on_stack: BTreeSet::new(),
            sccs: Vec::new(),
        };
        for v in &self.modules {
            if !tarjan.index.contains_key(v) {
                tarjan.strong(v);
            }
        }
        let mut sccs = tarjan.sccs;
        sccs.sort_by_key(|c| name(&c[0]));
        sccs
    }
}

/// The module `path` (as written, from a file of `module` inside its inline
/// module `scope`) starts from, followed by the rest of the path; `None` for
/// paths into other crates.
fn absolute(
    module: &Module,
    scope: &[String],
    children: &BTreeSet<String>,
    path: &[String],
) -> Option<Module> {
    let here = || module.iter().chain(scope).cloned().collect::<Module>();
    let first = path.first()?;
    let (mut base, rest) = match first.as_str() {
        "crate" => (Module::new(), &path[1..]),
        "self" => (here(), &path[1..]),
        "super" => {
            let mut base = here();
            let supers = path.iter().take_while(|p| *p == "super").count();
            base.truncate(base.len().saturating_sub(supers));
            (base, &path[supers..])
        }
        child if children.contains(child) => (module.clone(), path),
        _ => return None,
    };
    base.extend(rest.iter().cloned());
    Some(base)
}

/// The longest prefix of `path` that is a module (the root at least).
fn longest_module(modules: &BTreeSet<Module>, path: &[String]) -> Module {
    let mut target = Module::new();
    for part in path {
        target.push(part.clone());
        if !modules.contains(&target) {
            target.pop();
            break;
        }
    }
    target
}

#[derive(Clone, Debug, PartialEq)]
enum Token {
    /// An identifier or keyword (`r#` removed).
    Ident(String),
    /// `::`.
    PathSep,
    /// Any other punctuation character.
    Punct(char),
    /// A string, character or number literal, or a lifetime.
    Literal,
}

/// Rust source as tokens, without comments; literals are not looked into.
fn tokenize(text: &str) -> Vec<Token> {
    let c: Vec<char> = text.chars().collect();
    let at = |i: usize| c.get(i).copied().unwrap_or('\0');
    let is_ident_start = |ch: char| ch == '_' || ch.is_alphabetic();
    let is_ident = |ch: char| ch == '_' || ch.is_alphanumeric();
    let mut tokens = Vec::new();
    let mut i = 0;
    while i < c.len() {
        let ch = c[i];
        if ch.is_whitespace() {
            i += 1;
        } else if ch == '/' && at(i + 1) == '/' {
            while i < c.len() && c[i] != '\n' {
                i += 1;
            }
        } else if ch == '/' && at(i + 1) == '*' {
            // Block comments nest.
            let mut depth = 0;
            while i < c.len() {
                if c[i] == '/' && at(i + 1) == '*' {
                    depth += 1;
                    i += 2;
                } else if c[i] == '*' && at(i + 1) == '/' {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    i += 1;
                }
            }
        } else if let Some(end) = raw_string_end(&c, i) {
            tokens.push(Token::Literal);
            i = end;
        } else if ch == '"' || (matches!(ch, 'b' | 'c') && at(i + 1) == '"') {
            i += if ch == '"' { 1 } else { 2 };
            while i < c.len() && c[i] != '"' {
                i += if c[i] == '\\' { 2 } else { 1 };
            }
            tokens.push(Token::Literal);
            i += 1;
        } else if ch == '\'' || (ch == 'b' && at(i + 1) == '\'') {
            i += if ch == '\'' { 1 } else { 2 };
            if at(i) == '\\' || at(i + 1) == '\'' {
                // A character: `'x'`, `'\n'`, `'\u{1F600}'`, `'\''`.
                i += if at(i) == '\\' { 2 } else { 1 };
                while i < c.len() && c[i] != '\'' {
                    i += 1;
                }
                i += 1;
            } else {
                // A lifetime or label: `'a`.
                while i < c.len() && is_ident(c[i]) {
                    i += 1;
                }
            }
            tokens.push(Token::Literal);
        } else if ch == 'r' && at(i + 1) == '#' && is_ident_start(at(i + 2)) {
            let start = i + 2;
            i = start;
            while i < c.len() && is_ident(c[i]) {
                i += 1;
            }
            tokens.push(Token::Ident(c[start..i].iter().collect()));
        } else if is_ident_start(ch) {
            let start = i;
            while i < c.len() && is_ident(c[i]) {
                i += 1;
            }
            tokens.push(Token::Ident(c[start..i].iter().collect()));
        } else if ch.is_ascii_digit() {
            while i < c.len() && is_ident(c[i]) {
                i += 1;
            }
            tokens.push(Token::Literal);
        } else if ch == ':' && at(i + 1) == ':' {
            tokens.push(Token::PathSep);
            i += 2;
        } else {
            tokens.push(Token::Punct(ch));
            i += 1;
        }
    }
    tokens
}

/// Where the raw string (`r"…"`, `r#"…"#`, `br"…"`, `cr"…"`) starting at `i`
/// ends, if one does.
fn raw_string_end(c: &[char], i: usize) -> Option<usize> {
    let mut j = i;
    if matches!(c.get(j), Some('b' | 'c')) {
        j += 1;
    }
    if c.get(j) != Some(&'r') {
        return None;
    }
    j += 1;
    let hashes = c[j..].iter().take_while(|&&ch| ch == '#').count();
    j += hashes;
    if c.get(j) != Some(&'"') {
        return None;
    }
    j += 1;
    while j < c.len() {
        if c[j] == '"' && c[j + 1..].iter().take(hashes).filter(|&&ch| ch == '#').count() == hashes {
            return Some(j + 1 + hashes);
        }
        j += 1;
    }
    Some(c.len())
}

/// One file's tokens, each with the inline module it is in, and the child
/// modules the file declares (`mod child;`).
struct FileScan {
    tokens: Vec<(Token, Module)>,
    children: BTreeSet<String>,
}

impl FileScan {
    fn new(tokens: &[Token]) -> FileScan {
        let ident = |i: usize| match tokens.get(i) {
            Some(Token::Ident(s)) => Some(s.as_str()),
            _ => None,
        };
        let mut scoped = Vec::with_capacity(tokens.len());
        let mut children = BTreeSet::new();
        // The inline modules around the current token, each with the brace
        // depth inside it.
        let mut scope: Vec<(String, usize)> = Vec::new();
        let mut depth = 0;
        for (i, token) in tokens.iter().enumerate() {
            let names = scope.iter().map(|(n, _)| n.clone()).collect();
            scoped.push((token.clone(), names));
            match token {
                Token::Punct('{') => {
                    depth += 1;
                    if ident(i.wrapping_sub(2)) == Some("mod") {
                        if let Some(name) = ident(i - 1) {
                            scope.push((name.to_string(), depth));
                        }
                    }
                }
                Token::Punct('}') => {
                    if scope.last().is_some_and(|&(_, d)| d == depth) {
                        scope.pop();
                    }
                    depth = depth.saturating_sub(1);
                }
                Token::Punct(';') if scope.is_empty() && ident(i.wrapping_sub(2)) == Some("mod") => {
                    if let Some(name) = ident(i - 1) {
                        children.insert(name.to_string());
                    }
                }
                _ => {}
            }
        }
        FileScan { tokens: scoped, children }
    }

    fn ident(&self, i: usize) -> Option<&str> {
        match self.tokens.get(i) {
            Some((Token::Ident(s), _)) => Some(s),
            _ => None,
        }
    }

    /// The path `a::b::c` starting at token `i` (at least two segments),
    /// and the index after it.
    fn qualified(&self, i: usize) -> Option<(Vec<String>, usize)> {
        let mut path = vec![self.ident(i)?.to_string()];
        let mut j = i + 1;
        while matches!(self.tokens.get(j), Some((Token::PathSep, _))) {
            let Some(next) = self.ident(j + 1) else { break };
            path.push(next.to_string());
            j += 2;
        }
        (path.len() > 1).then_some((path, j))
    }

    /// Every path the file names, with the inline module it is named in:
    /// those of `use` statements, and the qualified paths starting with
    /// `crate`, `super`, `self` or a child module.
    fn paths(&self) -> Vec<(Module, Vec<String>)> {
        let mut out = Vec::new();
        for (i, (token, scope)) in self.tokens.iter().enumerate() {
            if *token == Token::Ident("use".into()) {
                let end = (i..self.tokens.len())
                    .find(|&j| self.tokens[j].0 == Token::Punct(';'))
                    .unwrap_or(self.tokens.len());
                let tree: Vec<Token> = self.tokens[i + 1..end].iter().map(|(t, _)| t.clone()).collect();
                out.extend(expand(&tree).into_iter().map(|p| (scope.clone(), p)));
            }
        }
        let starts = ["crate", "super", "self"];
        // Each kind of start is matched left to right without overlap, as a
        // search for `\bstart(::\w+)+` would.
        let mut kinds: Vec<Vec<&str>> = vec![starts.to_vec()];
        kinds.extend(self.children.iter().map(|c| vec![c.as_str()]));
        for kind in kinds {
            let mut i = 0;
            while i < self.tokens.len() {
                match self.ident(i).filter(|s| kind.contains(s)).and_then(|_| self.qualified(i)) {
                    Some((path, next)) => {
                        out.push((self.tokens[i].1.clone(), path));
                        i = next;
                    }
                    None => i += 1,
                }
            }
        }
        out
    }
}

/// The paths of a use tree: `a::{b, c::{d, e}}` → `a::b`, `a::c::d`,
/// `a::c::e`; `x as y` → `x`; a glob `a::*` → `a`.
fn expand(tree: &[Token]) -> Vec<Vec<String>> {
    fn parse(tokens: &[Token], i: &mut usize, mut prefix: Vec<String>, out: &mut Vec<Vec<String>>) {
        while let Some(token) = tokens.get(*i) {
            match token {
                Token::Ident(s) if s == "as" => *i += 2,
                Token::Ident(s) => {
                    prefix.push(s.clone());
                    *i += 1;
                }
                Token::Punct('{') => {
                    *i += 1;
                    loop {
                        match tokens.get(*i) {
                            None => return,
                            Some(Token::Punct('}')) => {
                                *i += 1;
                                return;
                            }
                            Some(Token::Punct(',')) => *i += 1,
                            Some(_) => parse(tokens, i, prefix.clone(), out),
                        }
                    }
                }
                Token::Punct(',' | '}') => break,
                _ => *i += 1,
            }
        }
        if !prefix.is_empty() {
            out.push(prefix);
        }
    }
    let mut out = Vec::new();
    let mut i = 0;
    while i < tree.len() {
        parse(tree, &mut i, Vec::new(), &mut out);
        i += 1;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn graph(files: &[(&str, &str)]) -> Graph {
        Graph::new(&files.iter().map(|&(p, t)| (p.to_string(), t.to_string())).collect())
    }

    fn m(path: &str) -> Module {
        path.split("::").skip(1).map(str::to_string).collect()
    }

    fn edges(g: &Graph, from: &str) -> Vec<String> {
        g.edges.get(&m(from)).into_iter().flatten().map(|t| name(t)).collect()
    }

    fn words(path: &str) -> Vec<String> {
        path.split("::").map(str::to_string).collect()
    }

    #[test]
    fn two_modules_importing_each_other_are_a_cycle() {
        let g = graph(&[
            ("lib.rs", "mod a;\nmod b;\n"),
            ("a.rs", "use crate::b::B;\npub struct A;\n"),
            ("b.rs", "pub struct B(crate::a::A);\n"),
        ]);
        assert_eq!(edges(&g, "crate::a"), ["crate::b"]);
        assert_eq!(edges(&g, "crate::b"), ["crate::a"]);
        assert_eq!(g.cycles(), vec![vec![m("crate::a"), m("crate::b")]]);
    }

    #[test]
    fn a_longer_cycle_is_one_component() {
        let g = graph(&[
            ("lib.rs", "mod a; mod b; mod c; mod d;"),
            ("a.rs", "use super::b::X;"),
            ("b.rs", "use super::c::X;"),
            ("c.rs", "fn f() { crate::a::g() }"),
            ("d.rs", "use crate::a;"),
        ]);
        assert_eq!(g.cycles(), vec![vec![m("crate::a"), m("crate::b"), m("crate::c")]]);
    }

    #[test]
    fn a_parent_importing_its_child_is_no_cycle() {
        let g = graph(&[
            ("lib.rs", "mod tile;\npub use tile::Tile;\n"),
            ("tile/mod.rs", "mod kernel;\npub struct Tile;\nfn f() { kernel::run() }\n"),
            ("tile/kernel.rs", "use std::sync::Arc;\npub fn run() {}\n"),
        ]);
        assert_eq!(edges(&g, "crate"), ["crate::tile"]);
        assert_eq!(edges(&g, "crate::tile"), ["crate::tile::kernel"]);
        assert!(edges(&g, "crate::tile::kernel").is_empty(), "std is another crate");
        assert!(g.cycles().is_empty());
        // The child importing its parent back closes one.
        let g = graph(&[
            ("lib.rs", "mod tile;"),
            ("tile/mod.rs", "mod kernel;\npub struct Tile;\nfn f() { kernel::run() }\n"),
            ("tile/kernel.rs", "use super::Tile;\npub fn run() {}\n"),
        ]);
        assert_eq!(g.cycles(), vec![vec![m("crate::tile"), m("crate::tile::kernel")]]);
    }

    #[test]
    fn use_trees_are_expanded() {
        let tree = tokenize("crate::a::{b, c::{d, e as f}, g::*, self}");
        assert_eq!(
            expand(&tree),
            ["crate::a::b", "crate::a::c::d", "crate::a::c::e", "crate::a::g", "crate::a::self"].map(words)
        );
        assert_eq!(expand(&tokenize("{x::y, z}")), ["x::y", "z"].map(words));
        let g = graph(&[
            ("lib.rs", "mod a; mod x;"),
            ("a/mod.rs", "mod b; mod c;"),
            ("a/b.rs", ""),
            ("a/c/mod.rs", "mod d; mod e;"),
            ("a/c/d.rs", ""),
            ("a/c/e.rs", ""),
            ("x.rs", "use crate::a::{b, c::{d, e}};"),
        ]);
        // The path before the braces names `crate::a` too, as the reference
        // script's scan for `crate::\w+` paths does.
        assert_eq!(edges(&g, "crate::x"), ["crate::a", "crate::a::b", "crate::a::c::d", "crate::a::c::e"]);
    }

    #[test]
    fn super_super_resolves_two_levels_up() {
        let g = graph(&[
            ("lib.rs", "mod a; mod p;"),
            ("a.rs", ""),
            ("p/mod.rs", "mod q;"),
            ("p/q/mod.rs", "mod r;"),
            ("p/q/r.rs", "use super::super::X;\nfn f() { super::super::super::a::g() }"),
        ]);
        assert_eq!(edges(&g, "crate::p::q::r"), ["crate::a", "crate::p"]);
    }

    #[test]
    fn inline_modules_belong_to_their_file_and_resolve_super_from_themselves() {
        let g = graph(&[
            ("lib.rs", "mod a; mod b;"),
            (
                "a.rs",
                "fn f() {}\n#[cfg(test)]\nmod tests {\n    use super::*;\n    use super::super::b::B;\n}\n",
            ),
            ("b.rs", "mod inner { use self::deeper::X; mod deeper {} }\nuse self::Y;"),
        ]);
        assert_eq!(edges(&g, "crate::a"), ["crate::b"]);
        assert!(edges(&g, "crate::b").is_empty());
    }

    #[test]
    fn comments_and_literals_are_ignored() {
        let g = graph(&[
            ("lib.rs", "mod a; mod b;"),
            (
                "a.rs",
                "// use crate::b;\n/// See [`crate::b::B`].\n/* crate::b /* nested */ crate::b */\n\
                 const S: &str = \"crate::b::B; use crate::b;\";\nconst R: &str = r#\"crate::b\"#;\n\
                 const C: char = '\"'; fn f<'a>(x: &'a str) -> &'a str { x }\n",
            ),
            ("b.rs", "use crate::a; // crate::a again"),
        ]);
        assert!(edges(&g, "crate::a").is_empty());
        assert_eq!(edges(&g, "crate::b"), ["crate::a"]);
        assert!(g.cycles().is_empty());
    }

    #[test]
    fn paths_name_the_longest_existing_module() {
        let g = graph(&[
            ("lib.rs", "pub mod a; mod z;"),
            ("a/mod.rs", "pub mod b;"),
            ("a/b.rs", "pub struct T;"),
            ("z.rs", "fn f() -> crate::a::b::T { crate::a::b::T }\nfn g() { crate::a::h(); crate::i(); }"),
        ]);
        assert_eq!(edges(&g, "crate::z"), ["crate", "crate::a", "crate::a::b"]);
    }

    #[test]
    fn module_paths_of_files() {
        assert_eq!(module_of("lib.rs"), m("crate"));
        assert_eq!(module_of("main.rs"), m("crate"));
        assert_eq!(module_of("a/mod.rs"), m("crate::a"));
        assert_eq!(module_of("a/b.rs"), m("crate::a::b"));
    }
}
