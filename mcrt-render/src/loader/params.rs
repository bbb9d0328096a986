//! `$name` substitution with `<default>` parameters and `-D` defines, in time linear in the
//! text read and written, and bounded: no attribute may grow past [`MAX_ATTRIBUTE`] bytes
//! and no file past [`MAX_SUBSTITUTED`] bytes of substituted text, so that defaults that
//! repeat earlier defaults cannot expand exponentially.
//!
//! Mitsuba 3 replaces `$name` for every known parameter, longest names first. Since names
//! hold no `$` and a default's value is substituted when it is declared, that is the same
//! as replacing each `$` by the longest parameter name that follows it, which a trie of the
//! names finds in one pass.
//!
//! A define must be one of the scene's parameters: a name a `<default>` declares or a
//! `$name` uses. [`Params::unused_defines`] lists the others, which the loader refuses (as the
//! render example refuses an unknown define for its built-in scene), so a misspelt `-D`
//! never goes unnoticed.

use std::collections::HashMap;

/// Largest attribute value after substitution, in bytes (1 MiB).
pub(crate) const MAX_ATTRIBUTE: usize = 1 << 20;

/// Largest total of substituted attribute text in one file, in bytes (64 MiB).
pub(crate) const MAX_SUBSTITUTED: usize = 1 << 26;

/// Why a substitution failed (the caller adds file, line and element).
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) enum SubstError {
    /// A `$` not followed by a known name.
    Undefined,
    /// The attribute, or the file's total, would exceed its bound.
    TooLarge(String),
}

/// The known parameters: defines first (they win), then defaults in file order.
pub(crate) struct Params {
    values: Vec<String>,
    /// Per value: whether a `$name` used it, and whether a `<default>` declared its name.
    used: Vec<bool>,
    declared: Vec<bool>,
    /// The defines' names (their values come first in `values`).
    define_names: Vec<String>,
    /// The names `<default>` elements declared, in file order.
    default_names: Vec<String>,
    /// Trie of the names: `(node, char) → child`; node 0 is the root.
    edges: HashMap<(u32, char), u32>,
    /// For every trie node, the parameter whose name ends there.
    ends: Vec<Option<u32>>,
    /// Substituted bytes written so far.
    written: usize,
}

impl Params {
    /// The parameters given by `defines` (`-D name=value`); a repeated name keeps its first
    /// value.
    pub fn new(defines: &[(String, String)]) -> Self {
        let mut p = Self {
            values: Vec::new(),
            used: Vec::new(),
            declared: Vec::new(),
            define_names: Vec::new(),
            default_names: Vec::new(),
            edges: HashMap::new(),
            ends: vec![None],
            written: 0,
        };
        for (n, v) in defines {
            if p.add(n, v) {
                p.define_names.push(n.clone());
            }
        }
        p
    }

    /// A `<default>`: adds `name = value` unless a define or an earlier default gave
    /// `name`, and marks the name as declared either way.
    pub fn declare(&mut self, name: &str, value: &str) {
        self.add(name, value);
        // `add` left `name` known; its first declaration records it (a lookup in the trie,
        // not a scan of the names, so that n defaults load in linear time).
        if let Some(i) = self.find(name) {
            if !self.declared[i] {
                self.declared[i] = true;
                self.default_names.push(name.to_string());
            }
        }
    }

    /// The value index of parameter `name`.
    fn find(&self, name: &str) -> Option<usize> {
        let mut node = 0u32;
        for c in name.chars() {
            node = *self.edges.get(&(node, c))?;
        }
        self.ends[node as usize].map(|v| v as usize)
    }

    /// The defines that no `<default>` declared and no `$name` used, in the order given.
    pub fn unused_defines(&self) -> Vec<&str> {
        self.define_names
            .iter()
            .enumerate()
            .filter(|&(i, _)| !self.used[i] && !self.declared[i])
            .map(|(_, n)| n.as_str())
            .collect()
    }

    /// The names `<default>` elements declared, in file order.
    pub fn default_names(&self) -> &[String] {
        &self.default_names
    }

    /// Adds `name = value` unless `name` is already known; returns whether it was added.
    pub fn add(&mut self, name: &str, value: &str) -> bool {
        let mut node = 0u32;
        for c in name.chars() {
            let next = self.ends.len() as u32;
            node = *self.edges.entry((node, c)).or_insert(next);
            if node == next {
                self.ends.push(None);
            }
        }
        let slot = &mut self.ends[node as usize];
        if slot.is_some() {
            return false;
        }
        *slot = Some(self.values.len() as u32);
        self.values.push(value.to_string());
        self.used.push(false);
        self.declared.push(false);
        true
    }

    /// The parameter with the longest name that starts `text`: that name's length and the
    /// parameter's index.
    fn longest_prefix(&self, text: &str) -> Option<(usize, usize)> {
        let (mut node, mut best) = (0u32, None);
        for (i, c) in text.char_indices() {
            match self.edges.get(&(node, c)) {
                Some(&n) => node = n,
                None => break,
            }
            if let Some(v) = self.ends[node as usize] {
                best = Some((i + c.len_utf8(), v as usize));
            }
        }
        best
    }

    /// `value` with every `$name` replaced.
    pub fn substitute(&mut self, value: &str) -> Result<String, SubstError> {
        if !value.contains('$') {
            return Ok(value.to_string());
        }
        let mut out = String::new();
        let mut rest = value;
        while let Some(k) = rest.find('$') {
            out.push_str(&rest[..k]);
            let after = &rest[k + 1..];
            // No name holds `$`, so the match cannot reach past the next one.
            let region = &after[..after.find('$').unwrap_or(after.len())];
            let (len, i) = self.longest_prefix(region).ok_or(SubstError::Undefined)?;
            self.used[i] = true;
            let v = &self.values[i];
            self.charge(out.len() + v.len())?;
            out.push_str(v);
            rest = &after[len..];
        }
        out.push_str(rest);
        self.charge(out.len())?;
        self.written += out.len();
        Ok(out)
    }

    /// Fails if an attribute of `len` bytes exceeds a bound.
    fn charge(&self, len: usize) -> Result<(), SubstError> {
        if len > MAX_ATTRIBUTE {
            return Err(SubstError::TooLarge(format!(
                "substitution makes an attribute longer than {MAX_ATTRIBUTE} bytes"
            )));
        }
        if self.written.saturating_add(len) > MAX_SUBSTITUTED {
            return Err(SubstError::TooLarge(format!(
                "substitution makes more than {MAX_SUBSTITUTED} bytes of attribute text \
                 in the file"
            )));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn params(kv: &[(&str, &str)]) -> Params {
        let mut p = Params::new(&[]);
        for (k, v) in kv {
            p.add(k, v);
        }
        p
    }

    #[test]
    fn longest_name_first_and_first_definition_wins() {
        let mut p = params(&[("a", "1"), ("ab", "2"), ("a", "9")]);
        assert_eq!(p.substitute("$a $ab $abc x$"), Err(SubstError::Undefined));
        assert_eq!(p.substitute("$a $ab $abc").as_deref(), Ok("1 2 2c"));
        assert_eq!(p.substitute("$$a"), Err(SubstError::Undefined));
        assert_eq!(p.substitute("plain").as_deref(), Ok("plain"));
        assert_eq!(p.substitute("é$aé").as_deref(), Ok("é1é"));
    }

    #[test]
    fn a_define_counts_if_declared_or_used() {
        let d = |n: &str| (n.to_string(), "1".to_string());
        let mut p = Params::new(&[d("spp"), d("res"), d("sp"), d("typo")]);
        p.declare("spp", "4");
        p.declare("max_depth", "-1");
        assert_eq!(p.substitute("$spp $res").as_deref(), Ok("1 1"));
        // `$spp` is the longest match, so `sp` is not used.
        assert_eq!(p.unused_defines(), ["sp", "typo"]);
        assert_eq!(p.default_names(), ["spp", "max_depth"]);
    }

    #[test]
    fn growth_is_bounded() {
        let mut p = params(&[("x", &"y".repeat(1000))]);
        let many = "$x".repeat(2000);
        assert!(matches!(p.substitute(&many), Err(SubstError::TooLarge(_))));
        let some = "$x".repeat(1000);
        let mut total = 0;
        let err = loop {
            match p.substitute(&some) {
                Ok(s) => total += s.len(),
                Err(e) => break e,
            }
        };
        assert!(matches!(err, SubstError::TooLarge(_)));
        assert!(total <= MAX_SUBSTITUTED && total > MAX_SUBSTITUTED / 2);
    }
}
