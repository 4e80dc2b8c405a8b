//! Orderings that gather the structural non-zeros of a sparse square matrix
//! into a narrow band, by reverse Cuthill-McKee: nodes that are neighbours in
//! the matrix's graph get neighbouring numbers. A chain of loops then has a
//! band as wide as one loop, whatever its length.
//!
//! Two graphs are tried and the narrower band is kept: the bipartite graph
//! of rows and columns (rows and columns numbered in the order they are
//! reached), and the symmetric graph of the columns after a matching of rows
//! to columns has put a structural non-zero on every diagonal position.
//!
//! Before that, [`block_order`] splits a matrix into the blocks that can be
//! factorised one after the other; only a large block needs a band.

mod blocks;

pub(crate) use blocks::{block_order, BlockOrder};

/// Marker for "not matched".
const NONE: usize = usize::MAX;

/// New numbers of rows and columns and the band they give.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct BandOrder {
    /// New index of every original row.
    pub row_new: Vec<usize>,
    /// New index of every original column.
    pub col_new: Vec<usize>,
    /// Sub-diagonals of the reordered matrix.
    pub kl: usize,
    /// Super-diagonals of the reordered matrix.
    pub ku: usize,
}

/// The ordering for the pattern `rows` (the columns of the structural
/// non-zeros of every row), or `None` when the pattern is structurally
/// singular (no matching of every row to a column of its own).
pub(crate) fn band_order(n: usize, rows: &[Vec<usize>]) -> Option<BandOrder> {
    let matched = match_rows(n, rows)?;
    let a = matched_order(n, rows, &matched);
    let b = bipartite_order(n, rows);
    let cost = |o: &BandOrder| o.kl * (o.kl + o.ku + 1);
    Some(if cost(&b) < cost(&a) { b } else { a })
}

/// Reverse Cuthill-McKee on the bipartite graph of rows (nodes `0..n`) and
/// columns (nodes `n..2n`).
fn bipartite_order(n: usize, rows: &[Vec<usize>]) -> BandOrder {
    let mut adj: Vec<Vec<usize>> = vec![Vec::new(); 2 * n];
    for (i, cols) in rows.iter().enumerate() {
        for &c in cols {
            adj[i].push(n + c);
            adj[n + c].push(i);
        }
    }
    for a in &mut adj {
        a.sort_unstable();
        a.dedup();
    }
    let order = reverse_cuthill_mckee(&adj);
    let (mut row_new, mut col_new) = (vec![0; n], vec![0; n]);
    let (mut r, mut c) = (0, 0);
    for &v in &order {
        if v < n {
            row_new[v] = r;
            r += 1;
        } else {
            col_new[v - n] = c;
            c += 1;
        }
    }
    with_band(rows, row_new, col_new)
}

/// Reverse Cuthill-McKee on the columns, each row placed at its matched column.
fn matched_order(n: usize, rows: &[Vec<usize>], matched: &[usize]) -> BandOrder {
    // The graph of the matrix with row i moved to the position of its
    // matched column, made symmetric.
    let mut adj: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (i, cols) in rows.iter().enumerate() {
        let c0 = matched[i];
        for &c in cols {
            if c != c0 {
                adj[c0].push(c);
                adj[c].push(c0);
            }
        }
    }
    for a in &mut adj {
        a.sort_unstable();
        a.dedup();
    }
    let order = reverse_cuthill_mckee(&adj);
    let mut col_new = vec![0; n];
    for (new, &old) in order.iter().enumerate() {
        col_new[old] = new;
    }
    let row_new: Vec<usize> = matched.iter().map(|&c| col_new[c]).collect();
    with_band(rows, row_new, col_new)
}

/// The order with the band it gives to `rows`.
fn with_band(rows: &[Vec<usize>], row_new: Vec<usize>, col_new: Vec<usize>) -> BandOrder {
    let (mut kl, mut ku) = (0, 0);
    for (i, cols) in rows.iter().enumerate() {
        for &c in cols {
            let (r, c) = (row_new[i], col_new[c]);
            if r > c {
                kl = kl.max(r - c);
            } else {
                ku = ku.max(c - r);
            }
        }
    }
    BandOrder { row_new, col_new, kl, ku }
}

/// A perfect matching of rows to columns (`matched[row] = column`) by
/// augmenting paths, or `None` when there is none.
fn match_rows(n: usize, rows: &[Vec<usize>]) -> Option<Vec<usize>> {
    let mut row_col = vec![NONE; n];
    let mut col_row = vec![NONE; n];
    for (i, cols) in rows.iter().enumerate() {
        if let Some(&c) = cols.iter().find(|&&c| col_row[c] == NONE) {
            row_col[i] = c;
            col_row[c] = i;
        }
    }
    let mut stamp = vec![NONE; n];
    let mut stack: Vec<(usize, usize)> = Vec::new();
    let mut via: Vec<usize> = Vec::new();
    for i in 0..n {
        if row_col[i] != NONE {
            continue;
        }
        // Depth-first search for an alternating path from row i to a free column.
        stack.clear();
        via.clear();
        stack.push((i, 0));
        let mut found = false;
        while let Some(top) = stack.last_mut() {
            let (r, next) = *top;
            if next == rows[r].len() {
                stack.pop();
                via.pop();
                continue;
            }
            top.1 += 1;
            let c = rows[r][next];
            if stamp[c] == i {
                continue;
            }
            stamp[c] = i;
            if col_row[c] == NONE {
                // Flip the path: every row on it takes the column it went through.
                let mut col = c;
                for k in (0..stack.len()).rev() {
                    let row = stack[k].0;
                    row_col[row] = col;
                    col_row[col] = row;
                    if k > 0 {
                        col = via[k - 1];
                    }
                }
                found = true;
                break;
            }
            via.push(c);
            stack.push((col_row[c], 0));
        }
        if !found {
            return None;
        }
    }
    Some(row_col)
}

/// Reverse Cuthill-McKee numbering of a symmetric graph: `order[new] = old`.
/// Each connected component starts from a pseudo-peripheral node.
fn reverse_cuthill_mckee(adj: &[Vec<usize>]) -> Vec<usize> {
    let n = adj.len();
    let mut order = Vec::with_capacity(n);
    let mut placed = vec![false; n];
    let mut level = vec![NONE; n];
    let mut by_degree: Vec<usize> = (0..n).collect();
    by_degree.sort_by_key(|&v| adj[v].len());
    let mut next: Vec<usize> = Vec::new();
    for &seed in &by_degree {
        if placed[seed] {
            continue;
        }
        let start = pseudo_peripheral(adj, seed, &mut level);
        let first = order.len();
        order.push(start);
        placed[start] = true;
        let mut head = first;
        while head < order.len() {
            let v = order[head];
            head += 1;
            next.clear();
            next.extend(adj[v].iter().copied().filter(|&w| !placed[w]));
            next.sort_by_key(|&w| adj[w].len());
            for &w in &next {
                placed[w] = true;
                order.push(w);
            }
        }
    }
    order.reverse();
    order
}

/// A node of `seed`'s component far from the others: repeated breadth-first
/// searches from the last level's node of least degree, while the depth grows.
fn pseudo_peripheral(adj: &[Vec<usize>], seed: usize, level: &mut [usize]) -> usize {
    let mut start = seed;
    let mut depth = 0;
    let mut queue: Vec<usize> = Vec::new();
    for _ in 0..8 {
        queue.clear();
        queue.push(start);
        level[start] = 0;
        let mut head = 0;
        while head < queue.len() {
            let v = queue[head];
            head += 1;
            for &w in &adj[v] {
                if level[w] == NONE {
                    level[w] = level[v] + 1;
                    queue.push(w);
                }
            }
        }
        let last = level[*queue.last().expect("the start is in the queue")];
        let far = queue.iter().copied().filter(|&v| level[v] == last).min_by_key(|&v| adj[v].len()).unwrap_or(start);
        for &v in &queue {
            level[v] = NONE;
        }
        if last <= depth {
            break;
        }
        depth = last;
        start = far;
    }
    start
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_shuffled_tridiagonal_pattern_gets_its_band_back() {
        // Tridiagonal, with rows and columns numbered in a scrambled order.
        let n = 40;
        let scramble = |i: usize| (i * 17 + 5) % n;
        let mut rows = vec![Vec::new(); n];
        for i in 0..n {
            for j in i.saturating_sub(1)..(i + 2).min(n) {
                rows[scramble(i)].push(scramble(j));
            }
        }
        let o = band_order(n, &rows).unwrap();
        assert!(o.kl + o.ku <= 3, "band {} {}", o.kl, o.ku);
        let mut seen = vec![false; n];
        for &r in &o.row_new {
            assert!(!seen[r]);
            seen[r] = true;
        }
    }

    #[test]
    fn a_structurally_singular_pattern_has_no_order() {
        // Rows 0 and 1 both touch column 0 only.
        let rows = vec![vec![0], vec![0], vec![1, 2]];
        assert!(band_order(3, &rows).is_none());
    }

    #[test]
    fn matching_needs_augmenting_paths() {
        // Greedy takes column 0 for row 0; row 1 only has column 0.
        let rows = vec![vec![0, 1], vec![0], vec![1, 2]];
        let m = match_rows(3, &rows).unwrap();
        assert_eq!(m, vec![1, 0, 2]);
    }
}
