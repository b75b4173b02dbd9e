//! TOML syntax and type errors as one bounded line: where (line, column), what (toml's
//! message) and a short excerpt of the offending line. toml's own `Display` prints the
//! whole line, so a file of one long line (a speed table written out, nesting thousands
//! deep) put hundreds of kB into one message.

/// Most characters of the offending line a message quotes, centred on the column.
pub const MAX_EXCERPT: usize = 80;

/// `e`, raised while parsing `text`, as "line L, column C: message (near `…excerpt…`)";
/// toml's message alone when it carries no position.
pub fn describe(text: &str, e: &toml::de::Error) -> String {
    let msg = e.message().trim().replace('\n', " ");
    let Some(span) = e.span() else {
        return msg;
    };
    let mut at = span.start.min(text.len());
    while !text.is_char_boundary(at) {
        at -= 1;
    }
    let before = &text[..at];
    let line = before.matches('\n').count() + 1;
    let start = before.rfind('\n').map_or(0, |i| i + 1);
    let end = text[at..].find('\n').map_or(text.len(), |i| at + i);
    let col = text[start..at].chars().count();
    let skip = col.saturating_sub(MAX_EXCERPT / 2);
    let full = text[start..end].trim_end_matches('\r');
    let shown: String = full.chars().skip(skip).take(MAX_EXCERPT).collect();
    let cut_after = full.chars().count() > skip + MAX_EXCERPT;
    format!(
        "line {line}, column {}: {msg} (near `{}{}{}`)",
        col + 1,
        if skip > 0 { "…" } else { "" },
        shown.trim(),
        if cut_after { "…" } else { "" }
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(text: &str) -> String {
        describe(text, &toml::from_str::<toml::Value>(text).unwrap_err())
    }

    #[test]
    fn a_long_line_is_quoted_only_near_the_error() {
        let row = "[0.0, 10.0], ".repeat(20_000);
        let text = format!("a = 1\nt = [{row} oops]\n");
        let m = err(&text);
        assert!(m.starts_with("line 2, column "), "{m}");
        assert!(m.contains("oops") && m.contains('…'), "{m}");
        assert!(m.chars().count() < MAX_EXCERPT + 200, "{} chars", m.len());
        // The column is the error's, counted in characters from 1.
        let col: usize = m["line 2, column ".len()..]
            .split(':')
            .next()
            .unwrap()
            .parse()
            .unwrap();
        assert_eq!(
            col,
            text.lines().nth(1).unwrap().find("oops").unwrap() + 1,
            "{m}"
        );
    }

    #[test]
    fn deep_nesting_gives_a_short_message() {
        let text = format!("a = {}1{}", "[".repeat(5_000), "]".repeat(5_000));
        let m = err(&text);
        assert!(m.len() < 400, "{m}");
    }

    #[test]
    fn a_short_line_is_quoted_whole_and_multibyte_text_is_safe() {
        let m = err("name = \"é\"\nx = 1 2\n");
        assert!(m.starts_with("line 2, column "), "{m}");
        assert!(m.contains("(near `x = 1 2`)"), "{m}");
        let m = err("é = [ é");
        assert!(m.starts_with("line 1, column "), "{m}");
    }
}
