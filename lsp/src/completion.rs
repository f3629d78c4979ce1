//! Completion that knows where it is: statements get commands (with snippets of their
//! parameters), skills and block keywords; an argument list gets only what its grammar
//! allows at that argument; conditions and expressions get variables and constants.

use std::collections::{BTreeMap, HashSet};

use ilmr_compiler::check::Resolved;
use ilmr_compiler::diagnostic::FileId;
use ilmr_model::RobotModel;
use ilmr_stdlib::{
    CATALOGUE, CommandSpec, ModelNames, NameSpace, Occurs, ParamKind, Syntax, VarKind,
};
use tower_lsp_server::ls_types::{
    CompletionItem, CompletionItemKind, CompletionList, CompletionTextEdit, Documentation,
    InsertTextFormat, MarkupContent, MarkupKind, TextEdit,
};

use crate::analysis::Program;
use crate::context::{self, Context};
use crate::docs;
use crate::line_index::LineIndex;

/// Groups order the list: what the grammar asks for first, then names, then the rest.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Group {
    Keyword,
    Setting,
    ModelName,
    Variable,
    Constant,
    Command,
    Skill,
    Block,
}

pub struct Request<'a> {
    pub program: &'a Program,
    pub model: &'a RobotModel,
    pub file: FileId,
    pub index: &'a LineIndex,
    pub offset: usize,
    pub snippets: bool,
}

struct Items<'a> {
    req: &'a Request<'a>,
    /// By label, so that a name offered twice (a keyword of two forms) appears once.
    /// Each with its group and its rank in the group (variables: nearest first).
    items: BTreeMap<String, (Group, usize, CompletionItem)>,
}

/// Variables offered in one list at most. A task of 100,000 lines binds some 26,000;
/// past this many the list is marked incomplete, so the editor asks again as the
/// name is typed, and the list holds those that begin with what is typed, then those
/// that contain it, each the nearest bound above the cursor first.
pub const MAX_VARIABLE_ITEMS: usize = 100;

pub fn complete(req: &Request<'_>) -> CompletionList {
    let text = req.program.text(req.file);
    let line = req.index.line_of(req.offset);
    let line_start = req.index.line_span(text, line).start as usize;
    let cursor = context::at(text, line_start, req.offset);
    let mut items = Items {
        req,
        items: BTreeMap::new(),
    };
    let typed = text
        .get(cursor.word.start as usize..cursor.word.end as usize)
        .unwrap_or("");
    let (vars, incomplete) = variables(req.program, req.file, req.offset, line_start, typed);
    match &cursor.context {
        Context::Nothing => {}
        Context::Statement => {
            items.commands();
            items.skills();
            items.blocks();
            items.variables(&vars, |_| true);
        }
        Context::AfterAssign => {
            items.commands();
            items.skills();
            items.while_loop();
            items.variables(&vars, |_| true);
            items.constants(true);
        }
        Context::Priority => items.keyword("highest", "the block runs alone: everything else ends"),
        Context::Condition => {
            items.variables(&vars, |_| true);
            items.constants(true);
        }
        Context::Expression => {
            items.variables(&vars, |k| k.numeric_field().is_some());
            items.constants(true);
        }
        Context::Args {
            name,
            previous,
            setting,
            ..
        } => {
            let Some(spec) = context::command(name) else {
                // A skill with parameters: the parameter at this argument.
                if let Some(id) = req.program.analysis().skills.find(name) {
                    let info = req.program.analysis().skills.get(id);
                    if let Some(p) = info.params.get(previous.len()) {
                        if p.words.is_empty() {
                            items.variables(&vars, |k| k.numeric_field().is_some());
                            items.constants(true);
                        } else {
                            let doc = format!("`{}` of skill `{}`", p.name, info.name);
                            for w in &p.words {
                                items.keyword(w, &doc);
                            }
                        }
                    }
                }
                return items.finish(req, text, cursor.word, incomplete);
            };
            if setting.is_some() {
                items.variables(&vars, |k| k.numeric_field().is_some());
                items.constants(false);
            } else {
                for slot in context::slots(spec, previous) {
                    let param = slot.param(spec);
                    items.param(&param.kind, param.doc, &vars, false);
                }
            }
        }
    }
    items.finish(req, text, cursor.word, incomplete)
}

impl Items<'_> {
    /// The list as the editor gets it: ordered by group and rank, each item replacing
    /// the word at the cursor.
    fn finish(
        self,
        req: &Request<'_>,
        text: &str,
        at: ilmr_compiler::span::Span,
        incomplete: bool,
    ) -> CompletionList {
        let word = req.index.range(text, at);
        let mut out: Vec<(Group, usize, CompletionItem)> = self.items.into_values().collect();
        out.sort_by(|a, b| (a.0, a.1, &a.2.label).cmp(&(b.0, b.1, &b.2.label)));
        let items = out
            .into_iter()
            .enumerate()
            .map(|(i, (_, _, mut item))| {
                item.sort_text = Some(format!("{i:04}"));
                let new_text = item
                    .insert_text
                    .take()
                    .unwrap_or_else(|| item.label.clone());
                item.text_edit = Some(CompletionTextEdit::Edit(TextEdit::new(word, new_text)));
                item
            })
            .collect();
        CompletionList {
            is_incomplete: incomplete,
            items,
        }
    }
}

/// The variables visible at `offset` whose names contain `typed` (any case): in a
/// task, those bound on a line above; in a skill, every variable of the program,
/// since skills share the task's records. At most [`MAX_VARIABLE_ITEMS`]: names that
/// begin with `typed` first, each group the nearest binding above the cursor first;
/// `true` when some were left out.
pub fn variables(
    program: &Program,
    file: FileId,
    offset: usize,
    line_start: usize,
    typed: &str,
) -> (Vec<(String, VarKind)>, bool) {
    let typed = typed.to_lowercase();
    // Where `typed` begins in a name (any case), without a copy of the name when
    // nothing is typed: the usual case, with every variable to rank.
    let found_at = |spelling: &str| -> Option<usize> {
        if typed.is_empty() {
            Some(0)
        } else {
            spelling.to_lowercase().find(&typed)
        }
    };
    // (does not begin with `typed`, bytes from the nearest binding above to the
    // cursor), the spelling and the kind.
    type Ranked<'a> = ((bool, usize), &'a str, VarKind);
    let mut ranked: Vec<Ranked<'_>> = Vec::new();
    match program.unit_at(file, offset) {
        // A unit's variables are one per name already.
        Some(unit) if unit.skill.is_none() => {
            for (_, var) in unit.vars.iter() {
                let nearest = var
                    .defs
                    .iter()
                    .filter(|(f, s)| *f == file && (s.end as usize) <= line_start)
                    .map(|(_, s)| line_start - s.end as usize)
                    .min();
                if let (Some(distance), Some(at)) = (nearest, found_at(&var.spelling)) {
                    ranked.push(((at != 0, distance), &var.spelling, var.kind));
                }
            }
        }
        // Every unit's, once per name (the first unit's spelling and kind).
        _ => {
            let mut seen = HashSet::new();
            for unit in &program.analysis().units {
                for (_, var) in unit.vars.iter().filter(|(_, v)| !v.defs.is_empty()) {
                    if let Some(at) = found_at(&var.spelling)
                        && seen.insert(var.spelling.to_lowercase())
                    {
                        ranked.push(((at != 0, 0), &var.spelling, var.kind));
                    }
                }
            }
        }
    }
    let order = |a: &Ranked<'_>, b: &Ranked<'_>| a.0.cmp(&b.0).then_with(|| a.1.cmp(b.1));
    let incomplete = ranked.len() > MAX_VARIABLE_ITEMS;
    if incomplete {
        ranked.select_nth_unstable_by(MAX_VARIABLE_ITEMS, order);
        ranked.truncate(MAX_VARIABLE_ITEMS);
    }
    ranked.sort_by(order);
    let vars = ranked
        .into_iter()
        .map(|(_, name, kind)| (name.to_string(), kind))
        .collect();
    (vars, incomplete)
}

impl Items<'_> {
    fn add(&mut self, group: Group, item: CompletionItem) {
        self.add_ranked(group, 0, item);
    }

    fn add_ranked(&mut self, group: Group, rank: usize, item: CompletionItem) {
        self.items
            .entry(item.label.to_lowercase())
            .or_insert((group, rank, item));
    }

    fn keyword(&mut self, word: &str, doc: &str) {
        self.add(
            Group::Keyword,
            CompletionItem {
                label: word.to_string(),
                kind: Some(CompletionItemKind::KEYWORD),
                detail: Some(doc.to_string()),
                ..Default::default()
            },
        );
    }

    fn commands(&mut self) {
        for spec in CATALOGUE.iter().filter(|s| s.syntax == Syntax::Call) {
            let (insert, format) = if self.req.snippets {
                (snippet(spec), InsertTextFormat::SNIPPET)
            } else {
                (spec.name.to_string(), InsertTextFormat::PLAIN_TEXT)
            };
            self.add(
                Group::Command,
                CompletionItem {
                    label: spec.name.to_string(),
                    kind: Some(CompletionItemKind::FUNCTION),
                    detail: Some(spec.grammar.lines().next().unwrap_or("").to_string()),
                    documentation: Some(markdown(docs::command(spec, self.req.model))),
                    insert_text: Some(insert),
                    insert_text_format: Some(format),
                    ..Default::default()
                },
            );
        }
    }

    fn skills(&mut self) {
        let program = self.req.program;
        for (_, info) in program.analysis().skills.iter() {
            let place = match program.uri(info.file) {
                Some(uri) => format!("skill in {}", uri.rsplit('/').next().unwrap_or(uri)),
                None => "built-in skill".to_string(),
            };
            let (detail, insert, format) = if info.params.is_empty() {
                (place, None, None)
            } else {
                // `Corner(${1:d}, ${2|left,right|})`: a number's name to type over, a
                // word to choose.
                let insert = if self.req.snippets {
                    let slots: Vec<String> = info
                        .params
                        .iter()
                        .enumerate()
                        .map(|(i, p)| {
                            if p.words.is_empty() {
                                format!("${{{}:{}}}", i + 1, p.name)
                            } else {
                                format!("${{{}|{}|}}", i + 1, p.words.join(","))
                            }
                        })
                        .collect();
                    (
                        format!("{}({})", info.name, slots.join(", ")),
                        InsertTextFormat::SNIPPET,
                    )
                } else {
                    (format!("{}(", info.name), InsertTextFormat::PLAIN_TEXT)
                };
                (
                    format!(
                        "{}, {place}",
                        ilmr_compiler::check::params::signature(&info.name, &info.params)
                    ),
                    Some(insert.0),
                    Some(insert.1),
                )
            };
            self.add(
                Group::Skill,
                CompletionItem {
                    label: info.name.clone(),
                    kind: Some(CompletionItemKind::METHOD),
                    detail: Some(detail),
                    insert_text: insert,
                    insert_text_format: format,
                    ..Default::default()
                },
            );
        }
    }

    fn blocks(&mut self) {
        let blocks: [(&str, &str, &str); 8] = [
            (
                "if",
                "if(${1:condition})\n\t$0\nendif",
                "a guard: runs its body once, when the condition becomes true",
            ),
            ("while", "while(${1:condition})\n\t$0\nendwhile", "a loop"),
            (
                "check",
                "check\n\t$0\ncheckend",
                "statements that are validated, never run",
            ),
            ("endif", "endif", "closes `if`"),
            ("endwhile", "endwhile", "closes `while`"),
            ("checkend", "checkend", "closes `check`"),
            (
                "break",
                "break(${1:pattern})",
                "ends the commands whose text contains the pattern; bare `break` stops everything",
            ),
            (
                "priority",
                "priority = highest",
                "first in a block: when the block starts, everything else ends",
            ),
        ];
        for (label, body, doc) in blocks {
            self.structural(label, body, doc);
        }
    }

    fn while_loop(&mut self) {
        self.structural(
            "while",
            "while(${1:condition})\n\t$0\nendwhile",
            "a loop; the variable's status becomes 1 when it ends",
        );
    }

    fn structural(&mut self, label: &str, body: &str, doc: &str) {
        let (insert, format) = if self.req.snippets {
            (body.to_string(), InsertTextFormat::SNIPPET)
        } else {
            (label.to_string(), InsertTextFormat::PLAIN_TEXT)
        };
        self.add(
            Group::Block,
            CompletionItem {
                label: label.to_string(),
                kind: Some(CompletionItemKind::SNIPPET),
                detail: Some(doc.to_string()),
                insert_text: Some(insert),
                insert_text_format: Some(format),
                ..Default::default()
            },
        );
    }

    fn variables(&mut self, vars: &[(String, VarKind)], keep: impl Fn(VarKind) -> bool) {
        for (rank, (name, kind)) in vars.iter().filter(|(_, k)| keep(*k)).enumerate() {
            self.add_ranked(
                Group::Variable,
                rank,
                CompletionItem {
                    label: name.clone(),
                    kind: Some(CompletionItemKind::VARIABLE),
                    detail: Some(format!("variable: {}", kind.describe())),
                    ..Default::default()
                },
            );
        }
    }

    /// `[PARAMETERS]`, `[IDENTIFIERS]` and `[COLORS]`: numbers usable in any expression.
    /// Where a command wants a quantity, identifiers and colours (codes, not amounts)
    /// would only crowd the list, so `all` is false there.
    fn constants(&mut self, all: bool) {
        let model = self.req.model;
        let codes = model
            .identifiers
            .iter()
            .map(|v| (v, "identifier"))
            .chain(model.colors.iter().map(|v| (v, "color")))
            .filter(|_| all);
        let values = model
            .parameters
            .iter()
            .map(|v| (v, "parameter"))
            .chain(codes);
        for (v, what) in values {
            self.add(
                Group::Constant,
                CompletionItem {
                    label: v.name.clone(),
                    kind: Some(CompletionItemKind::CONSTANT),
                    detail: Some(format!("{what} of robot `{}` = {}", model.name, v.value)),
                    ..Default::default()
                },
            );
        }
    }

    fn model_names(&mut self, names: ModelNames) {
        let model = self.req.model;
        let devices = matches!(names, ModelNames::Device | ModelNames::Service);
        if devices {
            for d in &model.devices {
                self.add(
                    Group::ModelName,
                    CompletionItem {
                        label: d.name.clone(),
                        kind: Some(CompletionItemKind::MODULE),
                        detail: Some(format!(
                            "device {}: {} … {}, {} reading(s)",
                            d.id, d.min, d.max, d.readings
                        )),
                        ..Default::default()
                    },
                );
            }
        }
        if names == ModelNames::Object {
            for o in &model.objects {
                self.add(
                    Group::ModelName,
                    CompletionItem {
                        label: o.name.clone(),
                        kind: Some(CompletionItemKind::CLASS),
                        detail: Some(format!("object: {}", o.params.join(" "))),
                        ..Default::default()
                    },
                );
            }
        }
        if names == ModelNames::Service {
            for v in &model.identifiers {
                self.add(
                    Group::ModelName,
                    CompletionItem {
                        label: v.name.clone(),
                        kind: Some(CompletionItemKind::MODULE),
                        detail: Some(format!("identifier = {}", v.value)),
                        ..Default::default()
                    },
                );
            }
        }
    }

    fn paths(&mut self) {
        let program = self.req.program;
        for unit in &program.analysis().units {
            let text = program.text(unit.file);
            for (span, r) in &unit.refs {
                if *r == Resolved::Path {
                    self.add(
                        Group::Variable,
                        CompletionItem {
                            label: span.slice(text).to_string(),
                            kind: Some(CompletionItemKind::FILE),
                            detail: Some("path".to_string()),
                            ..Default::default()
                        },
                    );
                }
            }
        }
    }

    fn param(&mut self, kind: &ParamKind, doc: &str, vars: &[(String, VarKind)], in_choice: bool) {
        match *kind {
            ParamKind::Keyword { words } => {
                for w in words {
                    self.keyword(w, doc);
                }
            }
            ParamKind::Mode { words, .. } => {
                for w in words
                    .iter()
                    .filter(|w| self.req.model.identifier(w).is_some())
                {
                    self.keyword(w, doc);
                }
            }
            ParamKind::Setting { key, .. } => {
                let label = format!("{key}=");
                self.add(
                    Group::Setting,
                    CompletionItem {
                        label: label.clone(),
                        kind: Some(CompletionItemKind::PROPERTY),
                        detail: Some(docs::kind(kind, self.req.model)),
                        documentation: Some(markdown(doc.to_string())),
                        insert_text: Some(label),
                        ..Default::default()
                    },
                );
            }
            // Inside a choice a number is one alternative among words; listing every
            // numeric variable there would bury the words.
            ParamKind::Value { .. } if in_choice => {}
            ParamKind::Value { .. } => {
                self.variables(vars, |k| k.numeric_field().is_some());
                self.constants(false);
            }
            ParamKind::Model { names } => self.model_names(names),
            ParamKind::Position => self.variables(vars, VarKind::is_position),
            ParamKind::Variable => self.variables(vars, |_| true),
            ParamKind::Name {
                space: NameSpace::Path,
            } => self.paths(),
            ParamKind::Name {
                space: NameSpace::SavedPosition,
            } => {}
            ParamKind::OneOf { kinds } => {
                for k in kinds {
                    self.param(k, doc, vars, true);
                }
            }
        }
    }
}

/// The command with placeholders for the required parameters of its first form.
pub fn snippet(spec: &CommandSpec) -> String {
    let Some(form) = spec.forms.first() else {
        return spec.name.to_string();
    };
    if spec.allows_bare() && form.params.is_empty() {
        return spec.name.to_string();
    }
    let mut parts = Vec::new();
    for p in form.params {
        let n = parts.len() + 1;
        let part = match p.kind {
            ParamKind::Setting { key, .. } => format!("{key}=${{{n}:{}}}", p.name),
            _ if p.occurs != Occurs::One => continue,
            ParamKind::Keyword { words } | ParamKind::Mode { words, .. } if words.len() > 1 => {
                format!("${{{n}|{}|}}", words.join(","))
            }
            _ => format!("${{{n}:{}}}", p.name),
        };
        parts.push(part);
    }
    if parts.is_empty() {
        format!("{}($1)$0", spec.name)
    } else {
        format!("{}({})$0", spec.name, parts.join(","))
    }
}

fn markdown(value: String) -> Documentation {
    Documentation::MarkupContent(MarkupContent {
        kind: MarkupKind::Markdown,
        value,
    })
}

#[cfg(test)]
mod tests {
    use ilmr_stdlib::Command;

    use super::snippet;

    #[test]
    fn snippets_hold_the_first_forms_required_parameters() {
        assert_eq!(snippet(Command::Turn.spec()), "turn(d=${1:d},c=${2:c})$0");
        assert_eq!(
            snippet(Command::FollowWall.spec()),
            "followwall(${1|left,right,middle|})$0"
        );
        assert_eq!(snippet(Command::Stop.spec()), "stop");
        assert_eq!(snippet(Command::Speed.spec()), "speed(${1:value})$0");
    }
}
