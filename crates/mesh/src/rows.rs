//! Items filed into numbered rows by a counting sort: the sides of a
//! triangle mesh under their smaller end, triangles under their smallest
//! corner. Two passes over the items and none over pairs of them, where
//! sorting all of them would cost a factor of their logarithm; the rows
//! are then short, and each is sorted or scanned on its own, in parallel.

use rayon::prelude::*;

/// Items in rows: row `r` is `items[start[r]..start[r + 1]]`, in the
/// order the items were given.
#[derive(Clone, Debug, Default)]
pub struct Rows<T> {
    /// Where each row starts, and one past the last row's end.
    pub start: Vec<u32>,
    /// Every item, row after row.
    pub items: Vec<T>,
}

impl<T: Copy + Default + Send> Rows<T> {
    /// Files the items `each()` gives (`(row, item)`, every row below
    /// `rows`; `each` is called twice and must give the same items both
    /// times) into `rows` rows.
    ///
    /// ```
    /// use holey_mesh::rows::Rows;
    /// let words = [(2, 'c'), (0, 'a'), (2, 'd'), (0, 'b')];
    /// let rows = Rows::file(3, || words.iter().copied());
    /// assert_eq!(rows.start, vec![0, 2, 2, 4]);
    /// assert_eq!(rows.items, vec!['a', 'b', 'c', 'd']);
    /// ```
    pub fn file<I: Iterator<Item = (u32, T)>>(rows: usize, each: impl Fn() -> I) -> Rows<T> {
        let mut start = vec![0u32; rows + 1];
        for (r, _) in each() {
            start[r as usize + 1] += 1;
        }
        for r in 0..rows {
            start[r + 1] += start[r];
        }
        let mut cursor = start.clone();
        let mut items = vec![T::default(); start[rows] as usize];
        for (r, item) in each() {
            let slot = &mut cursor[r as usize];
            items[*slot as usize] = item;
            *slot += 1;
        }
        Rows { start, items }
    }

    /// Whether `f` holds for every row, each row passed as a mutable
    /// slice (to be sorted in place, say), rows in parallel.
    pub fn all_rows_mut(&mut self, f: impl Fn(&mut [T]) -> bool + Sync + Send) -> bool
    where
        T: Sync,
    {
        self.rows_mut().into_par_iter().all(f)
    }

    /// Every row as a mutable slice, in order.
    pub fn rows_mut(&mut self) -> Vec<&mut [T]> {
        let mut rows = Vec::with_capacity(self.start.len().saturating_sub(1));
        let mut rest = self.items.as_mut_slice();
        for w in self.start.windows(2) {
            let (head, tail) = rest.split_at_mut((w[1] - w[0]) as usize);
            rows.push(head);
            rest = tail;
        }
        rows
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Filing agrees with a stable sort by row, empty rows included.
    #[test]
    fn filing_is_a_stable_sort_by_row() {
        let items: Vec<(u32, u32)> = (0..500u32).map(|i| ((i * 7919) % 37, i)).collect();
        let mut rows = Rows::file(40, || items.iter().copied());
        let mut sorted = items.clone();
        sorted.sort_by_key(|&(r, _)| r);
        assert_eq!(
            rows.items,
            sorted.iter().map(|&(_, i)| i).collect::<Vec<_>>()
        );
        for r in 0..40u32 {
            let count = items.iter().filter(|&&(q, _)| q == r).count() as u32;
            assert_eq!(rows.start[r as usize + 1] - rows.start[r as usize], count);
        }
        assert_eq!(rows.rows_mut().len(), 40);
        assert!(rows.all_rows_mut(|row| row.windows(2).all(|w| w[0] < w[1])));
        assert!(!rows.all_rows_mut(|row| row.len() < 10));
    }
}
