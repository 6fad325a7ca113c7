//! One line of a Wavefront OBJ file read into a mesh (`Mesh::read_obj`
//! reads the file line by line).

use super::Mesh;
use glam::DVec3;

/// One OBJ line into `mesh` (`face` a buffer for a face's indices), its
/// words split at Unicode whitespace: on an ASCII line without a vertical
/// tab (every line of a usual file) the same words as ASCII whitespace
/// gives, which is found byte by byte rather than character by character.
pub(super) fn statement(mesh: &mut Mesh, text: &str, face: &mut Vec<u32>) -> Result<(), String> {
    if text.is_ascii() && !text.as_bytes().contains(&0x0b) {
        words(mesh, text.split_ascii_whitespace(), face)
    } else {
        words(mesh, text.split_whitespace(), face)
    }
}

/// One OBJ line's `words` into `mesh`.
fn words<'a>(
    mesh: &mut Mesh,
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
            mesh.vertices.push(DVec3::from_array(c));
        }
        Some("f") => {
            let count = mesh.vertices.len() as i64;
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
                mesh.triangles.push([face[0], face[k], face[k + 1]]);
            }
        }
        _ => {}
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

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
        let base = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
        for line in lines {
            let run = |fast: bool| {
                let mut m = Mesh::from_obj(base).unwrap();
                let mut face = Vec::new();
                let r = match fast {
                    true => statement(&mut m, line, &mut face),
                    false => words(&mut m, line.split_whitespace(), &mut face),
                };
                (r, m)
            };
            assert_eq!(run(true), run(false), "{line:?}");
        }
        let mut m = Mesh::from_obj(base).unwrap();
        let vt = "v 1\x0b2 3\n";
        assert!(words(&mut m, vt.split_ascii_whitespace(), &mut Vec::new()).is_err());
        assert!(statement(&mut m, vt, &mut Vec::new()).is_ok());
    }
}
