//! Line and column of byte offsets, in linear time over a whole load: offsets asked for in
//! increasing order (document order) continue from the previous answer instead of
//! rescanning the text from its start.

/// A cursor over the text that turns byte offsets into 1-based (line, column in
/// characters).
pub(crate) struct Positions<'x> {
    text: &'x str,
    /// Byte offset, line and column of the last answer.
    offset: usize,
    line: usize,
    column: usize,
}

impl<'x> Positions<'x> {
    /// A cursor at the start of `text`.
    pub fn new(text: &'x str) -> Self {
        Self {
            text,
            offset: 0,
            line: 1,
            column: 1,
        }
    }

    /// The 1-based line and column of byte `offset` (clamped to the text, rounded down to a
    /// character boundary).
    pub fn at(&mut self, offset: usize) -> (u32, u32) {
        let mut offset = offset.min(self.text.len());
        while !self.text.is_char_boundary(offset) {
            offset -= 1;
        }
        if offset < self.offset {
            // Backwards (rare: only for errors out of document order): start over.
            *self = Self::new(self.text);
        }
        for c in self.text[self.offset..offset].chars() {
            if c == '\n' {
                self.line += 1;
                self.column = 1;
            } else {
                self.column += 1;
            }
        }
        self.offset = offset;
        (clamp_u32(self.line), clamp_u32(self.column))
    }
}

fn clamp_u32(x: usize) -> u32 {
    u32::try_from(x).unwrap_or(u32::MAX)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn forward_and_backward() {
        let t = "ab\ncé\n\nx";
        let mut p = Positions::new(t);
        assert_eq!(p.at(0), (1, 1));
        assert_eq!(p.at(1), (1, 2));
        assert_eq!(p.at(3), (2, 1));
        // 'é' is two bytes: offset 6 is the newline after it, column 3.
        assert_eq!(p.at(6), (2, 3));
        assert_eq!(p.at(8), (4, 1));
        assert_eq!(p.at(1), (1, 2));
        assert_eq!(p.at(5), (2, 2), "inside 'é' rounds down");
        assert_eq!(p.at(1000), (4, 2));
    }
}
