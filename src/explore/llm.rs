//! The prompts: asking an OpenAI-compatible chat endpoint "What are different types of
//! chair?" (the paper's query), reading the itemised answer, and picking from it.
//!
//! [`ask_kinds`] sends one `POST {URL}/chat/completions` and returns the items of the
//! answer's first choice; [`parse_items`] reads numbered (`1.`, `2)`) or bulleted (`-`,
//! `*`, `•`) lines, drops markdown emphasis and a description after a dash or colon, and
//! keeps each item once; [`pick`] takes the items `--pick` names (from 1) or the first
//! five, then the user's own prompts.

use super::net::{ServerError, agent, join, post_json};
use std::time::Duration;

/// How many items are taken when `--pick` is not given (the paper used five).
pub const DEFAULT_PICKS: usize = 5;

/// Where and how to ask.
#[derive(Debug, Clone, PartialEq)]
pub struct Llm {
    /// The API's base URL (`http://localhost:8080/v1`).
    pub url: String,
    pub model: String,
    /// Sent as a bearer token (`OPENAI_API_KEY`) when set.
    pub key: Option<String>,
    pub timeout: Duration,
}

/// The question the paper asks.
pub fn question(object: &str) -> String {
    format!("What are different types of {}?", object.trim())
}

/// Asks the endpoint for kinds of `object`; the items of its answer (in its order) and the
/// answer's text.
pub fn ask_kinds(llm: &Llm, object: &str) -> Result<(Vec<String>, String), ServerError> {
    let url = join(&llm.url, "chat/completions");
    let body = serde_json::json!({
        "model": llm.model,
        "messages": [{"role": "user", "content": question(object)}],
    });
    let answer = post_json(
        &agent(llm.timeout),
        &llm.url,
        &url,
        &body,
        llm.key.as_deref(),
    )?;
    let text = answer
        .pointer("/choices/0/message/content")
        .and_then(|c| c.as_str())
        .ok_or_else(|| {
            let what = format!("{url} answered without `choices[0].message.content`");
            ServerError::new(&llm.url, what, false)
        })?;
    let items = parse_items(text);
    if items.is_empty() {
        let what = format!("{url} answered with no numbered or bulleted list");
        return Err(ServerError::new(&llm.url, what, false));
    }
    Ok((items, text.to_string()))
}

/// The items of an itemised answer, each once, in order.
pub fn parse_items(text: &str) -> Vec<String> {
    let mut items: Vec<String> = Vec::new();
    for line in text.lines() {
        let Some(rest) = strip_marker(line.trim()) else {
            continue;
        };
        let item = name_of(rest);
        if !item.is_empty() && !items.iter().any(|i| i.eq_ignore_ascii_case(&item)) {
            items.push(item);
        }
    }
    items
}

/// The text after a list marker (`12.`, `3)`, `-`, `*`, `•`), or `None` for other lines.
fn strip_marker(line: &str) -> Option<&str> {
    for bullet in ["- ", "* ", "• ", "+ ", "– "] {
        if let Some(rest) = line.strip_prefix(bullet) {
            return Some(rest);
        }
    }
    let digits = line.chars().take_while(char::is_ascii_digit).count();
    if digits == 0 {
        return None;
    }
    let rest = &line[digits..];
    rest.strip_prefix(". ")
        .or_else(|| rest.strip_prefix(") "))
        .or_else(|| rest.strip_prefix(".\t"))
}

/// An item's name: emphasis removed, what follows a colon or a spaced dash dropped, and
/// trailing punctuation trimmed.
fn name_of(item: &str) -> String {
    let plain = item.replace("**", "").replace("__", "");
    let mut cut = plain.as_str();
    for sep in [":", " - ", " – ", " — ", " ("] {
        if let Some(i) = cut.find(sep) {
            cut = &cut[..i];
        }
    }
    cut.trim()
        .trim_end_matches(['.', ',', ';'])
        .trim_matches(['*', '_', '`', '"'])
        .trim()
        .to_string()
}

/// Parses `--pick` (`1,3,5`: positions from 1).
pub fn parse_pick(text: &str) -> Result<Vec<usize>, String> {
    text.split(',')
        .map(|t| match t.trim().parse::<usize>() {
            Ok(n) if n > 0 => Ok(n),
            _ => Err(format!(
                "`--pick {text}`: `{}` is not a position from 1",
                t.trim()
            )),
        })
        .collect()
}

/// The prompts to explore: the items `picks` names (from 1) or the first
/// [`DEFAULT_PICKS`], then `own` (the user's `--prompt`s), each once.
pub fn pick(
    items: &[String],
    picks: Option<&[usize]>,
    own: &[String],
) -> Result<Vec<String>, String> {
    let mut chosen: Vec<String> = match picks {
        Some(p) => p
            .iter()
            .map(|&n| {
                items
                    .get(n - 1)
                    .cloned()
                    .ok_or_else(|| format!("`--pick {n}`: the list has {} items", items.len()))
            })
            .collect::<Result<_, _>>()?,
        None => items.iter().take(DEFAULT_PICKS).cloned().collect(),
    };
    for p in own {
        let p = p.trim();
        if !p.is_empty() && !chosen.iter().any(|c| c.eq_ignore_ascii_case(p)) {
            chosen.push(p.to_string());
        }
    }
    Ok(chosen)
}

#[cfg(test)]
mod tests {
    use super::*;

    proptest::proptest! {
        /// Any answer gives items without panicking, each one non-empty and trimmed.
        #[test]
        fn any_answer_is_read(text in "(([0-9]{1,2}[.)] |[-*•+] )?[^\n]{0,30}\n){0,8}") {
            for item in parse_items(&text) {
                proptest::prop_assert!(!item.is_empty() && item.trim() == item);
            }
        }
    }

    #[test]
    fn numbered_lists_lose_their_descriptions() {
        let text = "Here are some types of chair:\n\n1. **Armchair**: a chair with arms.\n\
                    2. Rocking chair - rocks back and forth\n3) Bar stool — tall\n\
                    10. Bench (seats several)\nThat is all.";
        assert_eq!(
            parse_items(text),
            ["Armchair", "Rocking chair", "Bar stool", "Bench"]
        );
    }

    #[test]
    fn bulleted_lists_are_read_and_repeats_dropped() {
        let text = "- stool\n* Bench: long\n• stool\n+ recliner.\nnot an item";
        assert_eq!(parse_items(text), ["stool", "Bench", "recliner"]);
    }

    #[test]
    fn picks_are_positions_and_own_prompts_follow() {
        let items: Vec<String> = ["a", "b", "c", "d", "e", "f"].map(String::from).to_vec();
        assert_eq!(
            pick(&items, None, &["bench".into(), "a".into()]).unwrap(),
            ["a", "b", "c", "d", "e", "bench"]
        );
        assert_eq!(pick(&items, Some(&[2, 6]), &[]).unwrap(), ["b", "f"]);
        assert!(
            pick(&items, Some(&[7]), &[])
                .unwrap_err()
                .contains("6 items")
        );
        assert_eq!(parse_pick("1, 3,5").unwrap(), [1, 3, 5]);
        assert!(parse_pick("0").is_err() && parse_pick("x").is_err());
    }
}
