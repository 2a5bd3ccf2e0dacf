//! Warnings while loading: one line per kind of problem, with a count.
//!
//! A file may hold 100,000 images that are all missing: that is one line,
//! `100,000 images missing; ... (first: image 0: ...)`, not 100,000 lines. Kinds are found in
//! a hash map, so recording costs the same for the first problem and the millionth.

use std::collections::HashMap;

/// Collects warnings, one line per kind, in the order each kind first occurred.
#[derive(Default)]
pub(crate) struct Warnings {
    kinds: HashMap<String, usize>,
    lines: Vec<Line>,
}

struct Line {
    /// The first problem of the kind, as it reads alone.
    single: String,
    /// For problems with one of many items: what several of them are called, and the first
    /// item.
    items: Option<(String, String)>,
    count: usize,
}

impl Warnings {
    /// Records a problem of kind `kind`. The first message of a kind is kept; with more of
    /// the kind the line reads `"{message} ({count} occurrences)"`.
    pub(crate) fn warn(&mut self, kind: &str, message: impl FnOnce() -> String) {
        self.record(kind, || (message(), None));
    }

    /// Records a problem with one of many items (an image, a light, a texture). Alone the
    /// line reads `single(item)`; with more of the kind it reads
    /// `"{count} {plural} (first: {item})"`.
    pub(crate) fn warn_item(
        &mut self,
        kind: &str,
        plural: &str,
        item: impl FnOnce() -> String,
        single: impl FnOnce(&str) -> String,
    ) {
        self.record(kind, || {
            let item = item();
            (single(&item), Some((plural.to_string(), item)))
        });
    }

    fn record(&mut self, kind: &str, first: impl FnOnce() -> (String, Option<(String, String)>)) {
        match self.kinds.get(kind) {
            Some(&i) => self.lines[i].count += 1,
            None => {
                let (single, items) = first();
                self.kinds.insert(kind.to_string(), self.lines.len());
                self.lines.push(Line {
                    single,
                    items,
                    count: 1,
                });
            }
        }
    }

    /// The lines, one per kind.
    pub(crate) fn finish(self) -> Vec<String> {
        self.lines
            .into_iter()
            .map(|line| match (line.count, line.items) {
                (1, _) => line.single,
                (n, Some((plural, item))) => {
                    format!("{} {plural} (first: {item})", thousands(n as u64))
                }
                (n, None) => format!("{} ({} occurrences)", line.single, thousands(n as u64)),
            })
            .collect()
    }
}

/// `n` with a comma between each group of three digits: `12,345`.
pub(crate) fn thousands(n: u64) -> String {
    let digits = n.to_string();
    let mut out = String::with_capacity(digits.len() + digits.len() / 3);
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i) % 3 == 0 {
            out.push(',');
        }
        out.push(c);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thousands_groups_digits() {
        let cases = [
            (0u64, "0"),
            (999, "999"),
            (1000, "1,000"),
            (123456, "123,456"),
        ];
        for (n, want) in cases {
            assert_eq!(thousands(n), want);
        }
        assert_eq!(thousands(u64::MAX), "18,446,744,073,709,551,615");
    }

    #[test]
    fn one_line_per_kind_in_first_seen_order() {
        let mut w = Warnings::default();
        w.warn("b", || "plain".into());
        for i in 0..1234u32 {
            w.warn_item(
                "a",
                "images missing",
                || format!("image {i}"),
                |item| format!("{item} is missing"),
            );
        }
        w.warn("b", || unreachable!("only the first message is made"));
        w.warn_item(
            "c",
            "lights skipped",
            || "light 9".into(),
            |item| format!("{item} is skipped"),
        );
        assert_eq!(
            w.finish(),
            [
                "plain (2 occurrences)",
                "1,234 images missing (first: image 0)",
                "light 9 is skipped",
            ]
        );
    }
}
