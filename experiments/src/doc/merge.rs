//! The report is generated section by section, and keeps every section it does not
//! generate as it finds it in the existing file: people (and other tests' authors) add
//! sections to `docs/experiments.md` by hand, and regenerating must not lose them.
//!
//! A section runs from a `## ` heading to the next; the text before the first heading
//! is the introduction, which is generated.

/// A generated section: its heading starts with `key` (`## Test 1:`), and `text` is the
/// whole section, heading included.
pub struct Generated {
    pub key: String,
    pub text: String,
}

/// The existing file split into its introduction and `## ` sections.
fn sections(doc: &str) -> (String, Vec<String>) {
    let mut intro = String::new();
    let mut out: Vec<String> = Vec::new();
    let mut in_code = false;
    for line in doc.split_inclusive('\n') {
        if line.trim_start().starts_with("```") {
            in_code = !in_code;
        }
        if !in_code && line.starts_with("## ") {
            out.push(String::new());
        }
        match out.last_mut() {
            Some(s) => s.push_str(line),
            None => intro.push_str(line),
        }
    }
    (intro, out)
}

/// `intro` and `generated` in place of the existing file's introduction and generated
/// sections; the other sections kept where they are. A generated section the file
/// lacks goes after the generated one before it (first of all, after the
/// introduction).
pub fn merge(intro: &str, generated: &[Generated], existing: &str) -> String {
    let (_, old) = sections(existing);
    let which = |s: &str| generated.iter().position(|g| s.starts_with(&g.key));
    // Each entry: Ok(index of a generated section) or Err(kept text).
    let mut order: Vec<Result<usize, String>> = Vec::new();
    for s in old {
        match which(&s) {
            Some(i) if !order.contains(&Ok(i)) => order.push(Ok(i)),
            Some(_) => {}
            None => order.push(Err(s)),
        }
    }
    for i in 0..generated.len() {
        if order.contains(&Ok(i)) {
            continue;
        }
        let at = match i {
            0 => 0,
            _ => order
                .iter()
                .position(|e| *e == Ok(i - 1))
                .map_or(order.len(), |p| p + 1),
        };
        order.insert(at, Ok(i));
    }
    let mut out = intro.to_string();
    for e in order {
        let text = match e {
            Ok(i) => generated[i].text.as_str(),
            Err(ref kept) => kept.as_str(),
        };
        if !out.is_empty() && !out.ends_with("\n\n") {
            out.push_str(if out.ends_with('\n') { "\n" } else { "\n\n" });
        }
        out.push_str(text);
    }
    if !out.ends_with('\n') {
        out.push('\n');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn generated(keys: &[(&str, &str)]) -> Vec<Generated> {
        keys.iter()
            .map(|(k, t)| Generated {
                key: k.to_string(),
                text: t.to_string(),
            })
            .collect()
    }

    #[test]
    fn kept_sections_stay_where_they_were_and_generated_ones_are_replaced() {
        let existing = "# Old title\nold intro\n\n## Test 1: old\nold one\n\n## Notes\nby hand\n```sh\n## not a heading\n```\n\n## Test 2: old\nold two\n";
        let g = generated(&[
            ("## Test 1:", "## Test 1: new\none\n"),
            ("## Test 2:", "## Test 2: new\ntwo\n"),
        ]);
        let out = merge("# New title\n\n", &g, existing);
        assert_eq!(
            out,
            "# New title\n\n## Test 1: new\none\n\n## Notes\nby hand\n```sh\n## not a heading\n```\n\n## Test 2: new\ntwo\n"
        );
    }

    #[test]
    fn missing_generated_sections_follow_the_one_before_them() {
        let existing = "# T\n\n## Test 2: old\ntwo\n\n## Notes\nkept\n";
        let g = generated(&[
            ("## Test 1:", "## Test 1: a\n"),
            ("## Test 2:", "## Test 2: b\n"),
            ("## Test 3:", "## Test 3: c\n"),
        ]);
        let out = merge("# T\n\n", &g, existing);
        assert_eq!(
            out,
            "# T\n\n## Test 1: a\n\n## Test 2: b\n\n## Test 3: c\n\n## Notes\nkept\n"
        );
        // From nothing, the generated sections in order.
        assert_eq!(
            merge("# T\n\n", &g, ""),
            "# T\n\n## Test 1: a\n\n## Test 2: b\n\n## Test 3: c\n"
        );
    }

    #[test]
    fn merging_its_own_output_changes_nothing() {
        let g = generated(&[("## Test 1:", "## Test 1: a\nbody\n")]);
        let once = merge("# T\n\nintro\n", &g, "## Kept\ntext\n\n## Test 1: x\n");
        assert_eq!(merge("# T\n\nintro\n", &g, &once), once);
    }
}
