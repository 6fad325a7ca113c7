//! Names a user may have misspelt: the nearest known one, for "did you
//! mean" hints on fixture names, fields, objects and views.

/// The known name nearest to `name` by edit distance, if it is near (at
/// most a third of its length away, rounded up).
pub(crate) fn closest<'k, K: AsRef<str>>(name: &str, known: &'k [K]) -> Option<&'k K> {
    known
        .iter()
        .map(|k| (edit_distance(name, k.as_ref()), k))
        .filter(|(d, _)| *d > 0 && *d <= name.chars().count().div_ceil(3))
        .min_by_key(|(d, _)| *d)
        .map(|(_, k)| k)
}

/// `; did you mean "K"?` for the known name `K` nearest to `name`, or
/// nothing when none is near.
pub(crate) fn did_you_mean<K: AsRef<str>>(name: &str, known: &[K]) -> String {
    closest(name, known).map_or_else(String::new, |k| format!("; did you mean {:?}?", k.as_ref()))
}

/// The Levenshtein distance between two strings, in characters.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let above = row[j + 1];
            row[j + 1] = (above + 1)
                .min(row[j] + 1)
                .min(diagonal + usize::from(ca != *cb));
            diagonal = above;
        }
    }
    row[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_near_miss_is_suggested_and_a_far_one_is_not() {
        let known = ["flange", "stage", "teaser"];
        assert_eq!(closest("flang", &known), Some(&"flange"));
        assert_eq!(closest("stgae", &known), Some(&"stage"));
        assert_eq!(closest("sphere", &known), None);
        assert_eq!(
            did_you_mean("velocty", &["start", "velocity"]),
            "; did you mean \"velocity\"?"
        );
        assert_eq!(did_you_mean("velocity", &["start", "velocity"]), "");
        assert_eq!(edit_distance("kitten", "sitting"), 3);
    }
}
