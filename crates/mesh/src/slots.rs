//! Arrays of slots that keep their numbers: removing entries by moving the
//! last entries into the gaps, so that every other entry keeps its index.
//! The sculpt remesher numbers its vertices and triangles this way, and
//! the modeler's stroke frames rely on it: an edit renumbers only the few
//! entries that moved, which a patch can name.

/// Removes the slots `holes` (ascending, distinct, all `< items.len()`)
/// from `items` by moving the last remaining items into them, in order:
/// the lowest hole gets the last item that is not itself a hole.
/// `moved(from, to)` is told of every move. Entries not moved keep their
/// index; the length drops by `holes.len()`.
pub fn fill_holes<T: Copy>(items: &mut Vec<T>, holes: &[u32], mut moved: impl FnMut(usize, usize)) {
    let mut len = items.len();
    let (mut i, mut j) = (0, holes.len());
    while i < j {
        let last = len - 1;
        if holes[j - 1] as usize == last {
            j -= 1;
            len -= 1;
            continue;
        }
        let h = holes[i] as usize;
        items[h] = items[last];
        moved(last, h);
        len -= 1;
        i += 1;
    }
    items.truncate(len);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Against removing by hand: what remains is the set of kept entries,
    /// the untouched ones at their old index, and every reported move
    /// says where an entry went.
    #[test]
    fn holes_are_filled_from_the_end() {
        let mut items: Vec<u32> = (0..10).collect();
        let holes = [1, 4, 8, 9];
        let mut moves = Vec::new();
        fill_holes(&mut items, &holes, |from, to| moves.push((from, to)));
        assert_eq!(items.len(), 6);
        let mut kept = items.clone();
        kept.sort_unstable();
        assert_eq!(kept, vec![0, 2, 3, 5, 6, 7]);
        for (i, &v) in items.iter().enumerate() {
            if !moves.iter().any(|&(_, to)| to == i) {
                assert_eq!(v as usize, i, "an unmoved entry changed its index");
            }
        }
        assert_eq!(moves, vec![(7, 1), (6, 4)]);
        let mut none: Vec<u32> = vec![5, 6];
        fill_holes(&mut none, &[0, 1], |_, _| panic!("nothing moves"));
        assert!(none.is_empty());
    }
}
