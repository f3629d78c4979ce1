//! Signature help: one signature per form of the command whose argument list holds the
//! cursor, the first form the arguments so far fit made active, and in it the parameter
//! the argument at the cursor fills.

use ilmr_model::RobotModel;
use ilmr_stdlib::{CommandSpec, Form, Occurs, ParamKind};
use tower_lsp_server::ls_types::{
    Documentation, MarkupContent, MarkupKind, ParameterInformation, ParameterLabel, SignatureHelp,
    SignatureInformation,
};

use crate::context::{self, ArgShape, Context};
use crate::docs;

pub fn help(
    text: &str,
    line_start: usize,
    offset: usize,
    model: &RobotModel,
) -> Option<SignatureHelp> {
    let cursor = context::at(text, line_start, offset);
    let Context::Args {
        name,
        previous,
        setting,
        ..
    } = cursor.context
    else {
        return None;
    };
    let spec = context::command(&name)?;
    let signatures: Vec<SignatureInformation> = spec
        .forms
        .iter()
        .map(|f| signature(spec, f, model))
        .collect();
    let word = cursor.word.slice(text).to_lowercase();
    let active = active_form(spec, &previous, &word);
    let param = active_param(
        spec,
        &spec.forms[active],
        &previous,
        setting.as_deref(),
        &word,
    );
    Some(SignatureHelp {
        signatures,
        active_signature: Some(active as u32),
        active_parameter: param.map(|p| p as u32),
    })
}

/// The form being written: one whose setting the half-typed word starts, else the first
/// that the arguments (with the word) fit.
fn active_form(spec: &'static CommandSpec, previous: &[ArgShape], word: &str) -> usize {
    let fitting = context::fitting_forms(spec, previous);
    if !word.is_empty() {
        let by_key = fitting.iter().copied().find(|&f| {
            spec.forms[f]
                .params
                .iter()
                .any(|p| matches!(p.kind, ParamKind::Setting { key, .. } if key.starts_with(word)))
        });
        let mut with_word = previous.to_vec();
        with_word.push(ArgShape::Word(word.to_string()));
        let by_word = context::fitting_forms(spec, &with_word).first().copied();
        if let Some(f) = by_key.or(by_word) {
            return f;
        }
    }
    fitting.first().copied().unwrap_or(0)
}

fn signature(spec: &CommandSpec, form: &Form, model: &RobotModel) -> SignatureInformation {
    let mut label = format!("{}(", spec.name);
    let mut params = Vec::new();
    for (i, p) in form.params.iter().enumerate() {
        if i > 0 {
            label.push(',');
        }
        let text = match p.kind {
            ParamKind::Setting { key, .. } => format!("{key}=…"),
            ParamKind::Keyword { words } if words.len() <= 3 => words.join("|"),
            _ => p.name.to_string(),
        };
        let text = match p.occurs {
            Occurs::One => text,
            Occurs::Optional => format!("[{text}]"),
            Occurs::Many | Occurs::Pairs => format!("{text}…"),
        };
        // Offsets count UTF-16 units; the labels are ASCII but for the ellipsis.
        let start: usize = label.encode_utf16().count();
        label.push_str(&text);
        let end: usize = label.encode_utf16().count();
        params.push(ParameterInformation {
            label: ParameterLabel::LabelOffsets([start as u32, end as u32]),
            documentation: Some(Documentation::MarkupContent(MarkupContent {
                kind: MarkupKind::Markdown,
                value: docs::param(p, model),
            })),
        });
    }
    label.push(')');
    SignatureInformation {
        label,
        documentation: Some(Documentation::MarkupContent(MarkupContent {
            kind: MarkupKind::Markdown,
            value: format!(
                "{} — a bound variable holds {}",
                form.label,
                form.produces.describe()
            ),
        })),
        parameters: Some(params),
        active_parameter: None,
    }
}

/// The parameter of `form` the argument at the cursor fills: the setting being written,
/// else the next positional parameter after those the previous arguments took.
fn active_param(
    spec: &'static CommandSpec,
    form: &Form,
    previous: &[ArgShape],
    setting: Option<&str>,
    word: &str,
) -> Option<usize> {
    let key_param = |key: &str| {
        form.params.iter().position(
            |p| matches!(p.kind, ParamKind::Setting { key: k, .. } if k.eq_ignore_ascii_case(key)),
        )
    };
    if let Some(key) = setting {
        return key_param(key);
    }
    let slots = context::slots(spec, previous);
    let mine: Vec<usize> = slots
        .iter()
        .filter(|s| std::ptr::eq(&spec.forms[s.form], form))
        .map(|s| s.param)
        .collect();
    // A half-typed word that starts a setting's key points at that setting.
    let by_key = mine.iter().copied().find(
        |&p| matches!(form.params[p].kind, ParamKind::Setting { key, .. } if key.starts_with(word)),
    );
    if let Some(p) = by_key.filter(|_| !word.is_empty()) {
        return Some(p);
    }
    mine.first().copied()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn active(line: &str) -> (u32, u32, String) {
        let model = RobotModel::builtin("moro").unwrap();
        let h = help(line, 0, line.len(), &model).unwrap();
        let sig = h.active_signature.unwrap();
        (
            sig,
            h.active_parameter.unwrap(),
            h.signatures[sig as usize].label.clone(),
        )
    }

    #[test]
    fn the_active_form_follows_the_arguments() {
        assert_eq!(active("turn(d=90,"), (0, 1, "turn(d=…,c=…)".to_string()));
        assert_eq!(active("turn(left"), (1, 0, "turn(left|right)".to_string()));
        assert_eq!(active("turn(c"), (0, 1, "turn(d=…,c=…)".to_string()));
        assert_eq!(
            active("followwall(left,"),
            (0, 1, "followwall(left|right|middle,[distance])".to_string())
        );
        assert_eq!(active("sensor(scanner,door,").0, 0);
        assert_eq!(
            active("sensor(battery,left,"),
            (1, 2, "sensor(sensor,[which],[forever])".to_string())
        );
    }
}
