//! Reading a fuzzer's bytes front to back: small numbers, lengths and
//! slices, where a missing byte reads as zero and a slice as what is left,
//! so every input decodes to something and a mutation changes little.

/// The unread rest of an input.
#[derive(Clone, Debug)]
pub struct Cursor<'a> {
    rest: &'a [u8],
}

impl<'a> Cursor<'a> {
    /// A cursor at the start of `data`.
    pub fn new(data: &'a [u8]) -> Cursor<'a> {
        Cursor { rest: data }
    }

    /// Whether every byte has been read.
    pub fn is_empty(&self) -> bool {
        self.rest.is_empty()
    }

    /// The next byte (zero past the end).
    pub fn byte(&mut self) -> u8 {
        match self.rest.split_first() {
            Some((&b, rest)) => {
                self.rest = rest;
                b
            }
            None => 0,
        }
    }

    /// The next byte as a choice among `n` (`n > 0`).
    pub fn choice(&mut self, n: u8) -> u8 {
        self.byte() % n.max(1)
    }

    /// The next byte as a flag (its lowest bit).
    pub fn flag(&mut self) -> bool {
        self.byte() & 1 == 1
    }

    /// The next two bytes, little-endian.
    pub fn u16(&mut self) -> u16 {
        u16::from_le_bytes([self.byte(), self.byte()])
    }

    /// The next `len` bytes, or all that are left if fewer.
    pub fn take(&mut self, len: usize) -> &'a [u8] {
        let (taken, rest) = self.rest.split_at(len.min(self.rest.len()));
        self.rest = rest;
        taken
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reading_past_the_end_gives_zeros_and_short_slices() {
        let mut c = Cursor::new(&[7, 1, 2, 3]);
        assert_eq!(c.byte(), 7);
        assert_eq!(c.u16(), 0x0201);
        assert_eq!(c.take(10), &[3]);
        assert!(c.is_empty());
        assert_eq!((c.byte(), c.u16(), c.flag()), (0, 0, false));
        assert_eq!(c.take(5), &[] as &[u8]);
    }

    #[test]
    fn a_choice_is_always_in_range() {
        let mut c = Cursor::new(&[255, 9, 4]);
        assert_eq!(c.choice(4), 3);
        assert_eq!(c.choice(0), 0, "no choice at all reads as the first");
        assert!(!c.flag());
    }
}
