//! The byte cursor of the Gmsh reader: ASCII tokens, binary values in either byte order,
//! and positions turned into messages (line for ASCII, byte for binary).

use crate::error::{Error, Result};
use std::path::Path;

/// Reads ASCII tokens and binary values from the file, and turns positions into messages.
pub(super) struct Cursor<'a> {
    pub(super) buf: &'a [u8],
    pub(super) pos: usize,
    pub(super) file: &'a Path,
    pub(super) binary: bool,
    pub(super) big_endian: bool,
    /// Bytes of a binary `size_t` (MSH 4.1 data-size).
    pub(super) size_t: usize,
}

impl Default for Cursor<'_> {
    fn default() -> Self {
        Cursor { buf: &[], pos: 0, file: Path::new(""), binary: false, big_endian: false, size_t: 8 }
    }
}

impl<'a> Cursor<'a> {
    pub(super) fn err(&self, at: usize, msg: impl Into<String>) -> Error {
        let at = at.min(self.buf.len());
        let at = if self.binary {
            format!("byte {at}")
        } else {
            format!("line {}", self.buf[..at].iter().filter(|&&c| c == b'\n').count() + 1)
        };
        Error::Parse { file: self.file.to_path_buf(), at, msg: msg.into() }
    }

    pub(super) fn remaining(&self) -> usize {
        self.buf.len() - self.pos
    }

    /// Capacity to reserve for `count` items of at least `min_bytes` each: never more than the
    /// rest of the input could hold, whatever the file claims.
    pub(super) fn cap(&self, count: u64, min_bytes: usize) -> usize {
        (self.remaining() / min_bytes.max(1)).min(usize::try_from(count).unwrap_or(usize::MAX))
    }

    pub(super) fn skip_ws(&mut self) {
        while self.pos < self.buf.len() && self.buf[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
    }

    /// Next whitespace-separated token and its position.
    pub(super) fn token(&mut self, what: &str) -> Result<(usize, &'a [u8])> {
        self.skip_ws();
        let start = self.pos;
        while self.pos < self.buf.len() && !self.buf[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
        if start == self.pos {
            return Err(self.err(start, format!("unexpected end of file, expected {what}")));
        }
        Ok((start, &self.buf[start..self.pos]))
    }

    pub(super) fn ascii<T: std::str::FromStr>(&mut self, what: &str) -> Result<T> {
        let (at, tok) = self.token(what)?;
        std::str::from_utf8(tok).ok().and_then(|s| s.parse().ok()).ok_or_else(|| {
            self.err(
                at,
                format!("expected {what}, found '{}'", String::from_utf8_lossy(&tok[..tok.len().min(40)])),
            )
        })
    }

    /// Ends the current text line: only blanks may remain before the newline. Binary data
    /// starts right after it, so no further whitespace may be skipped.
    pub(super) fn end_line(&mut self) -> Result<()> {
        while self.pos < self.buf.len() && matches!(self.buf[self.pos], b' ' | b'\t' | b'\r') {
            self.pos += 1;
        }
        match self.buf.get(self.pos) {
            Some(b'\n') => {
                self.pos += 1;
                Ok(())
            }
            None => Err(self.err(self.pos, "unexpected end of file, expected the end of the line")),
            Some(_) => Err(self.err(self.pos, "unexpected data at the end of the line")),
        }
    }

    pub(super) fn expect(&mut self, word: &str) -> Result<()> {
        let (at, tok) = self.token(word)?;
        if tok != word.as_bytes() {
            return Err(self.err(
                at,
                format!("expected {word}, found '{}'", String::from_utf8_lossy(&tok[..tok.len().min(40)])),
            ));
        }
        Ok(())
    }

    pub(super) fn bytes<const N: usize>(&mut self, what: &str) -> Result<[u8; N]> {
        let Some(b) = self.buf.get(self.pos..self.pos + N) else {
            return Err(self.err(self.pos, format!("unexpected end of file, expected {what} ({N} bytes)")));
        };
        self.pos += N;
        let mut a: [u8; N] = b.try_into().expect("slice of length N");
        if self.big_endian {
            a.reverse();
        }
        Ok(a)
    }

    pub(super) fn bin_i32(&mut self, what: &str) -> Result<i64> {
        Ok(i32::from_le_bytes(self.bytes(what)?) as i64)
    }

    pub(super) fn bin_f64(&mut self, what: &str) -> Result<f64> {
        let at = self.pos;
        let x = f64::from_le_bytes(self.bytes(what)?);
        self.finite(at, x, what)
    }

    pub(super) fn finite(&self, at: usize, x: f64, what: &str) -> Result<f64> {
        if x.is_finite() {
            Ok(x)
        } else {
            Err(self.err(at, format!("{what} is {x}")))
        }
    }

    // Mode-independent readers for MSH 4.1, whose binary layout mirrors its text layout.

    pub(super) fn int(&mut self, what: &str) -> Result<i64> {
        if self.binary {
            self.bin_i32(what)
        } else {
            self.ascii(what)
        }
    }

    pub(super) fn size(&mut self, what: &str) -> Result<u64> {
        if !self.binary {
            return self.ascii(what);
        }
        Ok(if self.size_t == 4 {
            u32::from_le_bytes(self.bytes(what)?) as u64
        } else {
            u64::from_le_bytes(self.bytes(what)?)
        })
    }

    pub(super) fn real(&mut self, what: &str) -> Result<f64> {
        if self.binary {
            return self.bin_f64(what);
        }
        let at = self.pos;
        let x = self.ascii(what)?;
        self.finite(at, x, what)
    }
}
