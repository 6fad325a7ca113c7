//! Wavefront OBJ text read into a mesh (`Mesh::read_obj`): a block of a
//! few MiB at a time, cut at line ends into pieces that are parsed on all
//! threads and joined in file order. A piece's faces need the count of
//! vertices before them (for negative indices and the range check), so
//! each piece's `v` statements are counted first; the mesh, and the first
//! error in file order, are those of reading the lines one by one.

use super::{Mesh, MeshError};
use glam::DVec3;
use rayon::prelude::*;
use std::io::{self, BufRead};

/// How the file is cut: read `block` bytes at a time (then to the end of
/// a line), parsed in pieces of about `piece` bytes.
#[derive(Clone, Copy, Debug)]
pub(super) struct Cuts {
    block: usize,
    piece: usize,
}

impl Cuts {
    /// A block holds enough pieces to keep every thread busy, and is small
    /// beside the mesh it becomes (a file's bytes are never held whole).
    /// On one thread a block is one piece, whose vertices need not be
    /// counted ahead.
    pub(super) fn file() -> Cuts {
        let block = 1 << 22;
        let piece = match rayon::current_num_threads() {
            1 => block,
            _ => 1 << 18,
        };
        Cuts { block, piece }
    }
}

/// The byte-order mark a file may begin with.
const BOM: &[u8] = "\u{feff}".as_bytes();

/// The mesh of the OBJ text from `reader`, cut as `cuts` says. A leading
/// byte-order mark is skipped; a line that is not UTF-8, or a read that
/// fails, is an error at its line.
pub(super) fn read(mut reader: impl BufRead, cuts: Cuts) -> Result<Mesh, MeshError> {
    let mut mesh = Mesh::default();
    let (mut block, mut line) = (Vec::new(), 1);
    loop {
        block.clear();
        let filled = fill(&mut reader, &mut block, cuts.block);
        // After a failed read, the lines read whole come before its error.
        let whole = match filled {
            Ok(()) if block.is_empty() => return Ok(mesh),
            Ok(()) => block.len(),
            Err(_) => block
                .iter()
                .rposition(|&b| b == b'\n')
                .map_or(0, |end| end + 1),
        };
        let text = &block[..whole];
        let text = match line {
            1 => text.strip_prefix(BOM).unwrap_or(text),
            _ => text,
        };
        line = read_block(&mut mesh, text, line, cuts.piece)?;
        if let Err(e) = filled {
            let message = format!("cannot be read: {e}");
            return Err(MeshError::Obj { line, message });
        }
    }
}

/// Appends about `size` bytes from `reader` to `block`, then the rest of
/// the line they end in.
fn fill(reader: &mut impl BufRead, block: &mut Vec<u8>, size: usize) -> io::Result<()> {
    while block.len() < size {
        let available = match reader.fill_buf() {
            Ok(bytes) => bytes,
            Err(e) if e.kind() == io::ErrorKind::Interrupted => continue,
            Err(e) => return Err(e),
        };
        if available.is_empty() {
            return Ok(());
        }
        let n = available.len().min(size - block.len());
        block.extend_from_slice(&available[..n]);
        reader.consume(n);
    }
    reader.read_until(b'\n', block).map(|_| ())
}

/// The vertices and triangles of one piece of the file, whose first
/// vertex is the mesh's `base`-th.
#[derive(Debug, Default, PartialEq)]
struct Piece {
    base: usize,
    vertices: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
    /// Its lines.
    lines: usize,
}

/// Reads the whole lines `text`, the first of them line `line` of the
/// file, into `mesh` in pieces of about `piece` bytes; the line after
/// them.
fn read_block(mesh: &mut Mesh, text: &[u8], line: usize, piece: usize) -> Result<usize, MeshError> {
    let pieces = cut(text, piece);
    let mut base = mesh.vertices.len();
    let counts = match pieces.len() {
        1 => vec![0],
        _ => each(&pieces, |_, p| vertex_statements(p)),
    };
    let bases: Vec<usize> = (counts.into_iter())
        .map(|count| {
            base += count;
            base - count
        })
        .collect();
    let parsed = each(&pieces, |k, p| parse_piece(p, bases[k]));
    let mut line = line;
    for piece in parsed {
        match piece {
            Ok(p) => {
                mesh.vertices.extend(p.vertices);
                mesh.triangles.extend(p.triangles);
                line += p.lines;
            }
            Err((at, message)) => {
                return Err(MeshError::Obj {
                    line: line + at,
                    message,
                })
            }
        }
    }
    Ok(line)
}

/// `f(k, piece)` of each of `pieces`, on all threads where there are
/// several.
fn each<T: Send>(pieces: &[&[u8]], f: impl Fn(usize, &[u8]) -> T + Sync) -> Vec<T> {
    match pieces {
        [one] => vec![f(0, one)],
        _ => pieces
            .par_iter()
            .enumerate()
            .map(|(k, p)| f(k, p))
            .collect(),
    }
}

/// `text` cut after line ends into pieces of at least `size` bytes (but
/// the last); one piece for text of under two.
fn cut(text: &[u8], size: usize) -> Vec<&[u8]> {
    let mut pieces = Vec::new();
    let mut rest = text;
    while rest.len() >= 2 * size {
        let end =
            (rest[size..].iter().position(|&b| b == b'\n')).map_or(rest.len(), |at| size + at + 1);
        let (piece, after) = rest.split_at(end);
        pieces.push(piece);
        rest = after;
    }
    if !rest.is_empty() || pieces.is_empty() {
        pieces.push(rest);
    }
    pieces
}

/// The lines of `text`, each with its line end.
fn lines(text: &[u8]) -> impl Iterator<Item = &[u8]> {
    text.split_inclusive(|&b| b == b'\n')
}

/// How many vertices (`v` statements) the lines of `text` give, up to the
/// first line that is not UTF-8 (where reading stops).
fn vertex_statements(text: &[u8]) -> usize {
    match std::str::from_utf8(text) {
        Ok(text) if ascii_words(text) => text
            .split_inclusive('\n')
            .filter(|l| ascii_vertex(l))
            .count(),
        Ok(text) => text
            .split_inclusive('\n')
            .filter(|l| first_word(l) == Some("v"))
            .count(),
        Err(_) => lines(text)
            .map_while(|line| std::str::from_utf8(line).ok())
            .filter(|line| first_word(line) == Some("v"))
            .count(),
    }
}

/// Whether the first word of `line`, split at ASCII whitespace, is `v`.
fn ascii_vertex(line: &str) -> bool {
    let mut rest = line
        .trim_start_matches(|c: char| c.is_ascii_whitespace())
        .bytes();
    rest.next() == Some(b'v') && rest.next().is_none_or(|b| b.is_ascii_whitespace())
}

/// The piece of the file `text`, its first vertex the mesh's `base`-th;
/// else the first error in it, at its line counted from 0. (Text found
/// UTF-8, or [`ascii_words`], as a whole is so line by line.)
fn parse_piece(text: &[u8], base: usize) -> Result<Piece, (usize, String)> {
    let mut piece = Piece {
        base,
        ..Piece::default()
    };
    let mut face = Vec::new();
    let Ok(whole) = std::str::from_utf8(text) else {
        for (at, raw) in lines(text).enumerate() {
            let line = std::str::from_utf8(raw).map_err(|_| (at, "is not UTF-8".to_string()))?;
            statement(&mut piece, line, &mut face).map_err(|m| (at, m))?;
            piece.lines += 1;
        }
        return Ok(piece);
    };
    let ascii = ascii_words(whole);
    for (at, line) in whole.split_inclusive('\n').enumerate() {
        match ascii {
            true => words(&mut piece, line.split_ascii_whitespace(), &mut face),
            false => statement(&mut piece, line, &mut face),
        }
        .map_err(|m| (at, m))?;
        piece.lines += 1;
    }
    Ok(piece)
}

/// Whether `text` is split into words byte by byte: an ASCII line without
/// a vertical tab (every line of a usual file), where ASCII whitespace
/// gives the words Unicode whitespace gives.
fn ascii_words(text: &str) -> bool {
    text.is_ascii() && !text.as_bytes().contains(&0x0b)
}

/// The first word of a line.
fn first_word(text: &str) -> Option<&str> {
    match ascii_words(text) {
        true => text.split_ascii_whitespace().next(),
        false => text.split_whitespace().next(),
    }
}

/// One OBJ line into `piece` (`face` a buffer for a face's indices), its
/// words split at Unicode whitespace (found byte by byte where
/// [`ascii_words`]).
fn statement(piece: &mut Piece, text: &str, face: &mut Vec<u32>) -> Result<(), String> {
    match ascii_words(text) {
        true => words(piece, text.split_ascii_whitespace(), face),
        false => words(piece, text.split_whitespace(), face),
    }
}

/// One OBJ line's `words` into `piece`.
fn words<'a>(
    piece: &mut Piece,
    mut words: impl Iterator<Item = &'a str>,
    face: &mut Vec<u32>,
) -> Result<(), String> {
    match words.next() {
        Some("v") => {
            let mut c = [0.0; 3];
            for x in &mut c {
                let w = words.next().ok_or("a vertex needs 3 coordinates")?;
                *x = w.parse().map_err(|_| format!("bad coordinate {w:?}"))?;
            }
            piece.vertices.push(DVec3::from_array(c));
        }
        Some("f") => {
            let count = (piece.base + piece.vertices.len()) as i64;
            face.clear();
            for w in words {
                let first = w.split('/').next().unwrap_or("");
                let i: i64 = first.parse().map_err(|_| format!("bad face index {w:?}"))?;
                let resolved = if i < 0 { count + i } else { i - 1 };
                if i == 0 || resolved < 0 || resolved >= count {
                    return Err(format!("face index {i} is out of range (1..={count})"));
                }
                face.push(resolved as u32);
            }
            if face.len() < 3 {
                return Err("a face needs at least 3 vertices".into());
            }
            for k in 1..face.len() - 1 {
                piece.triangles.push([face[0], face[k], face[k + 1]]);
            }
        }
        _ => {}
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One piece: the file read a line at a time.
    const WHOLE: Cuts = Cuts {
        block: usize::MAX / 4,
        piece: usize::MAX / 4,
    };

    /// Small blocks of many pieces.
    const SMALL: Cuts = Cuts {
        block: 97,
        piece: 13,
    };

    /// A line's words are those of Unicode whitespace whichever way they
    /// are found: tabs, form feeds, carriage returns, a vertical tab, a
    /// no-break space, in vertices and faces. The control: ASCII
    /// whitespace alone does not split at a vertical tab.
    #[test]
    fn obj_words_are_split_at_unicode_whitespace() {
        let lines = [
            "v 1 2 3\n",
            "v\t1.5  -2\x0c3\r\n",
            "v 1\x0b2 3\n",
            "v 1\u{a0}2 3\n",
            "f 1\t2 3\r\n",
            "f 1 2\x0b3\n",
            "f 1\u{2003}2 3\n",
            "vt 0.5 0.5\n",
        ];
        let three = || Piece {
            base: 3,
            ..Piece::default()
        };
        for line in lines {
            let run = |fast: bool| {
                let (mut p, mut face) = (three(), Vec::new());
                let r = match fast {
                    true => statement(&mut p, line, &mut face),
                    false => words(&mut p, line.split_whitespace(), &mut face),
                };
                (r, p)
            };
            assert_eq!(run(true), run(false), "{line:?}");
        }
        let vt = "v 1\x0b2 3\n";
        assert!(words(&mut three(), vt.split_ascii_whitespace(), &mut Vec::new()).is_err());
        assert!(statement(&mut three(), vt, &mut Vec::new()).is_ok());
    }

    /// An OBJ text whose faces reach back over many lines, by positive and
    /// negative indices, with polygons, comments, other statements and a
    /// line of Unicode whitespace.
    fn text() -> String {
        let mut text = String::from("\u{feff}# rings\nmtllib a.mtl\n");
        for i in 0..40 {
            text += &format!("v {i} {} 0.5\nv\u{a0}{i} 1 -{i}.25\n", i * i);
            if i >= 2 {
                text += &format!("f -1 -2 -3\nf {} {}/1 {}//2 -4\n", 2 * i, 2 * i - 1, i);
            }
            text += "vt 0 1\n\n";
        }
        text
    }

    /// Cut into pieces parsed apart, a file reads as it does a line at a
    /// time. The control: its later pieces' faces name vertices of
    /// earlier pieces, so that a piece parsed without them fails.
    #[test]
    fn a_file_read_in_pieces_is_read_as_a_whole() {
        let text = text();
        let whole = read(text.as_bytes(), WHOLE).unwrap();
        let cut_up = read(text.as_bytes(), SMALL).unwrap();
        assert_eq!(cut_up, whole);
        assert_eq!(whole.triangles.len(), 38 * 3);
        let pieces = cut(text.as_bytes(), SMALL.piece);
        assert!(pieces.len() > 50, "{}", pieces.len());
        assert_eq!(pieces.concat(), text.as_bytes());
        let later = pieces.iter().filter(|p| parse_piece(p, 0).is_err()).count();
        assert!(later > 10, "{later} pieces need the vertices before them");
    }

    /// The first error in the file is the one reported, at its line,
    /// whichever piece and block it falls in and whatever follows it.
    #[test]
    fn the_first_bad_line_is_reported_wherever_the_file_is_cut() {
        let text = text();
        let lines: Vec<&[u8]> = text.as_bytes().split_inclusive(|&b| b == b'\n').collect();
        let bad: [&[u8]; 5] = [
            b"f 1 2 999\n",
            b"v 0 x 0\n",
            b"f -1\n",
            b"\xff\n",
            b"f 0 1 2\n",
        ];
        for (k, b) in bad.into_iter().enumerate() {
            for at in [3, 40, 77, lines.len() - 1] {
                let mut spoiled = lines.clone();
                spoiled[at] = b;
                // A later error, in the same piece or another.
                if let Some(later) = spoiled.get_mut(at + 1 + 7 * (k % 2)) {
                    *later = b"f 1 2 1000\n";
                }
                let bytes = spoiled.concat();
                let expected = read(&bytes[..], WHOLE).unwrap_err();
                assert!(
                    matches!(expected, MeshError::Obj { line, .. } if line == at + 1),
                    "{expected:?} for {b:?} at {at}"
                );
                assert_eq!(read(&bytes[..], SMALL).unwrap_err(), expected);
            }
        }
    }
}
