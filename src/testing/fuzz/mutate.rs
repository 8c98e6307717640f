//! Byte-level mutations of model files: bit flips, inserted, deleted, duplicated and repeated
//! ranges, splices of two inputs, numbers replaced by extreme numerals, truncation, line
//! edits, duplicated bracketed groups (JSON) and IGES fields replaced in their columns.

use super::Rng;
use std::sync::OnceLock;

/// The longest input made (a mutation that would make it longer is cut).
pub(crate) const MAX_LEN: usize = 1 << 21;

/// Numerals that break readers: huge and tiny exponents, thousands of digits, signed zeros,
/// not-numbers, counts at and past every limit, Fortran exponents, fractions, non-ASCII digits.
pub(crate) fn extreme_numerals() -> &'static [String] {
    static LIST: OnceLock<Vec<String>> = OnceLock::new();
    LIST.get_or_init(|| {
        let mut v: Vec<String> = [
            "0",
            "-0",
            "-0.0",
            "+0",
            "0e0",
            "-0e-0",
            "1",
            "-1",
            "2",
            "3",
            "16",
            "17",
            "64",
            "65",
            "0.5",
            "1.5",
            "2.5",
            "1/3",
            "-1/-3",
            "1/0",
            "0/0",
            "1/2/3",
            "1e-400",
            "1e400",
            "-1e400",
            "1e308",
            "1e309",
            "5e-324",
            "1e10000",
            "1e-10000",
            "1e10001",
            "-1e-10001",
            "1e99999",
            "1e-99999",
            "1e999999999999",
            "1e0000000001",
            "1D300",
            "1.0D-400",
            "1E+",
            "1e",
            "e5",
            ".",
            "-",
            "+",
            "--1",
            "nan",
            "NaN",
            "-nan",
            "inf",
            "-inf",
            "Infinity",
            "-Infinity",
            "0x10",
            "1_000",
            "1,5",
            "99999",
            "100000",
            "100001",
            "999999",
            "1000000",
            "1000001",
            "99999999",
            "100000000",
            "2147483648",
            "4294967296",
            "9223372036854775807",
            "-9223372036854775808",
            "18446744073709551615",
            "18446744073709551616",
            "123456789012345678901234567890",
            "1e9999/1e-9999",
            "\u{661}\u{662}",
            "\u{ff11}",
            "\u{b2}",
            "",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        v.push("9".repeat(2000));
        v.push("9".repeat(2001));
        v.push("1".repeat(5000));
        v.push(format!("0.{}1", "0".repeat(1998)));
        v.push(format!("1{}e8000", "0".repeat(1999)));
        v.push(format!("-{}.{}", "7".repeat(1000), "3".repeat(1000)));
        v.push(format!("{}/{}", "9".repeat(2000), "7".repeat(2000)));
        v
    })
}

/// Bytes worth writing over others.
const INTERESTING: &[u8] = b"\0\x7f\xff\n\r\t ,;./-+eEdDH0123456789[]{}\":#vfx";

/// The byte ranges of number-like tokens: runs of `0-9 . + - e E d D` holding a digit.
pub fn number_tokens(bytes: &[u8]) -> Vec<(usize, usize)> {
    let numeric = |b: u8| b.is_ascii_digit() || b"+-.eEdD".contains(&b);
    let mut spans = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        if numeric(bytes[i]) {
            let start = i;
            while i < bytes.len() && numeric(bytes[i]) {
                i += 1;
            }
            if bytes[start..i].iter().any(u8::is_ascii_digit) {
                spans.push((start, i));
            }
        } else {
            i += 1;
        }
    }
    spans
}

/// Line ranges, each with its line break.
pub fn line_spans(bytes: &[u8]) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut start = 0;
    for (i, &b) in bytes.iter().enumerate() {
        if b == b'\n' {
            spans.push((start, i + 1));
            start = i + 1;
        }
    }
    if start < bytes.len() {
        spans.push((start, bytes.len()));
    }
    spans
}

/// A random range of `bytes` of at most `max` bytes (empty input: `0..0`).
fn range(rng: &mut Rng, len: usize, max: usize) -> (usize, usize) {
    if len == 0 {
        return (0, 0);
    }
    let a = rng.below(len);
    let n = 1 + rng.below(max.min(len - a));
    (a, a + n)
}

/// A short length, mostly small: 1..=8 three times in four, up to `max` otherwise.
fn short(rng: &mut Rng, max: usize) -> usize {
    if rng.chance(3, 4) {
        1 + rng.below(8)
    } else {
        1 + rng.below(max.max(1))
    }
}

/// Applies one random mutation to `bytes`; `other` is another input to splice from, `dict`
/// the target's tokens, `iges` whether to keep IGES records 80 columns wide (sometimes).
pub(crate) fn mutate(rng: &mut Rng, bytes: &mut Vec<u8>, other: &[u8], dict: &[&str], iges: bool) {
    let len = bytes.len();
    match rng.below(if iges { 20 } else { 17 }) {
        0 if len > 0 => {
            let p = rng.below(len);
            bytes[p] ^= 1 << rng.below(8);
        }
        1 if len > 0 => {
            let p = rng.below(len);
            bytes[p] = *rng.pick(INTERESTING);
        }
        2 => {
            let p = rng.below(len + 1);
            let n = short(rng, 64);
            let ins: Vec<u8> = (0..n).map(|_| rng.next_u64() as u8).collect();
            bytes.splice(p..p, ins);
        }
        3 | 4 => {
            let p = rng.below(len + 1);
            let t = rng.pick(dict).as_bytes().to_vec();
            bytes.splice(p..p, t);
        }
        5 if len > 0 => {
            let max = short(rng, 256);
            let (a, b) = range(rng, len, max);
            bytes.drain(a..b);
        }
        6 if len > 0 => {
            // Duplicate a range somewhere else.
            let max = short(rng, 512);
            let (a, b) = range(rng, len, max);
            let copy = bytes[a..b].to_vec();
            let p = rng.below(len + 1);
            bytes.splice(p..p, copy);
        }
        7 if len > 0 => {
            // Repeat a range in place: repeated structure.
            let max = short(rng, 128);
            let (a, b) = range(rng, len, max);
            let times = *rng.pick(&[2, 3, 10, 100, 1000, 10_000]);
            let copy = bytes[a..b].repeat(times.min(MAX_LEN / (b - a).max(1)));
            bytes.splice(b..b, copy);
        }
        8 if !other.is_empty() => {
            // Splice: a prefix of this input and a suffix of the other, or a piece of the
            // other inserted.
            let cut = rng.below(len + 1);
            let from = rng.below(other.len());
            if rng.chance(1, 2) {
                bytes.truncate(cut);
                bytes.extend_from_slice(&other[from..]);
            } else {
                let n = short(rng, 2048).min(other.len() - from);
                bytes.splice(cut..cut, other[from..from + n].iter().copied());
            }
        }
        9..=11 => {
            let spans = number_tokens(bytes);
            if !spans.is_empty() {
                let (a, b) = spans[rng.below(spans.len())];
                let g = rng.pick(extreme_numerals()).clone();
                bytes.splice(a..b, g.into_bytes());
            }
        }
        12 => {
            let keep = if rng.chance(1, 2) {
                rng.below(len + 1)
            } else {
                len.saturating_sub(short(rng, 64))
            };
            bytes.truncate(keep);
        }
        13 | 14 => line_edit(rng, bytes),
        15 => duplicate_group(rng, bytes),
        16 if len > 0 => {
            // Swap two bytes.
            let (x, y) = (rng.below(len), rng.below(len));
            bytes.swap(x, y);
        }
        17..=19 => iges_field(rng, bytes),
        _ => {}
    }
    if bytes.len() > MAX_LEN {
        bytes.truncate(MAX_LEN);
    }
}

/// Duplicates, deletes, swaps or repeats lines.
fn line_edit(rng: &mut Rng, bytes: &mut Vec<u8>) {
    let lines = line_spans(bytes);
    if lines.is_empty() {
        return;
    }
    let (a, b) = lines[rng.below(lines.len())];
    match rng.below(4) {
        0 => {
            let mut copy = bytes[a..b].to_vec();
            if copy.last() != Some(&b'\n') {
                copy.insert(0, b'\n');
            }
            bytes.splice(b..b, copy);
        }
        1 => {
            bytes.drain(a..b);
        }
        2 => {
            let (c, d) = lines[rng.below(lines.len())];
            let (first, second) = if a <= c {
                ((a, b), (c, d))
            } else {
                ((c, d), (a, b))
            };
            if first != second {
                let mut out = bytes[..first.0].to_vec();
                out.extend_from_slice(&bytes[second.0..second.1]);
                out.extend_from_slice(&bytes[first.1..second.0]);
                out.extend_from_slice(&bytes[first.0..first.1]);
                out.extend_from_slice(&bytes[second.1..]);
                *bytes = out;
            }
        }
        _ => {
            // A run of consecutive lines, repeated.
            let k = 1 + rng.below(4);
            let end = lines
                [(lines.iter().position(|l| l.0 == a).unwrap_or(0) + k - 1).min(lines.len() - 1)]
            .1;
            let mut block = bytes[a..end].to_vec();
            if block.last() != Some(&b'\n') {
                block.push(b'\n');
            }
            let times = *rng.pick(&[2, 10, 100, 1000]);
            let copy = block.repeat(times.min(MAX_LEN / block.len().max(1)));
            bytes.splice(end..end, copy);
        }
    }
}

/// Duplicates a bracketed group (`[...]` or `{...}`) after itself, with a comma: repeated
/// JSON structure (more patches, more points, more coordinates).
fn duplicate_group(rng: &mut Rng, bytes: &mut Vec<u8>) {
    let opens: Vec<usize> = (0..bytes.len())
        .filter(|&i| bytes[i] == b'[' || bytes[i] == b'{')
        .collect();
    if opens.is_empty() {
        return;
    }
    let start = opens[rng.below(opens.len())];
    let (open, close) = if bytes[start] == b'[' {
        (b'[', b']')
    } else {
        (b'{', b'}')
    };
    let mut depth = 0usize;
    let mut end = None;
    for (i, &b) in bytes.iter().enumerate().skip(start) {
        if b == open {
            depth += 1;
        } else if b == close {
            depth -= 1;
            if depth == 0 {
                end = Some(i + 1);
                break;
            }
        }
    }
    let Some(end) = end else { return };
    let times = *rng.pick(&[1, 1, 2, 10, 100]);
    let mut copy = Vec::new();
    for _ in 0..times {
        copy.push(b',');
        copy.extend_from_slice(&bytes[start..end]);
        if copy.len() > MAX_LEN / 2 {
            break;
        }
    }
    bytes.splice(end..end, copy);
}

/// The fields of the IGES records in `bytes`: (line start, field start, field end, width of
/// the data region that must be kept). D records give their nine 8-column fields; G and P
/// records the number tokens of their data columns (1-72 and 1-64).
pub fn iges_fields(bytes: &[u8]) -> Vec<(usize, usize, usize, usize)> {
    let mut fields = Vec::new();
    for (a, b) in line_spans(bytes) {
        let line = &bytes[a..b];
        if line.len() < 80 || !line[..80].is_ascii() {
            continue;
        }
        match line[72] {
            b'D' => fields.extend((0..9).map(|f| (a, a + 8 * f, a + 8 * f + 8, 72))),
            section @ (b'G' | b'P') => {
                let width = if section == b'P' { 64 } else { 72 };
                fields.extend(
                    number_tokens(&line[..width])
                        .into_iter()
                        .map(|(x, y)| (a, a + x, a + y, width)),
                );
            }
            _ => {}
        }
    }
    fields
}

/// Replaces one IGES field by an extreme numeral, keeping the record 80 columns wide (so the
/// reader gets past the record checks into the entities).
fn iges_field(rng: &mut Rng, bytes: &mut Vec<u8>) {
    let fields = iges_fields(bytes);
    if fields.is_empty() {
        return;
    }
    let g = rng.pick(extreme_numerals()).clone();
    replace_iges_field(bytes, fields[rng.below(fields.len())], &g);
}

/// Writes `g` (its ASCII characters) over one field of [`iges_fields`], right-aligned in a D
/// field's 8 columns, and keeps the record 80 columns wide (the data region cut or padded).
pub fn replace_iges_field(bytes: &mut Vec<u8>, field: (usize, usize, usize, usize), g: &str) {
    let (line, x, y, width) = field;
    let g: String = g.chars().filter(char::is_ascii).collect();
    let text: Vec<u8> = if bytes[line + 72] == b'D' {
        let t = format!("{g:>8}").into_bytes();
        t[t.len().saturating_sub(8)..].to_vec()
    } else {
        g.into_bytes()
    };
    let mut data = bytes[line..line + width].to_vec();
    data.splice(x - line..y - line, text);
    data.resize(width, b' ');
    bytes.splice(line..line + width, data);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mutations_are_deterministic_and_bounded() {
        let base = b"1\n1 1\n0 0 0\n0 1 0\n1 0 0\n1 1 0\n".to_vec();
        let run = |seed: u64| {
            let mut rng = Rng::new(seed);
            let mut b = base.clone();
            for _ in 0..50 {
                mutate(&mut rng, &mut b, b"{\"patches\": []}", &["v ", "f "], true);
            }
            b
        };
        assert_eq!(run(3), run(3));
        assert!(run(4).len() <= MAX_LEN);
    }
}
