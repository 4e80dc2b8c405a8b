//! The block triangular form of a sparse square matrix (as in KLU's BTF):
//! after a matching of rows to columns, the strongly connected components
//! of the columns' graph (Tarjan) are the diagonal blocks, found in an order
//! in which every row touches only its own block and earlier ones. For
//! D^c a block is a group of co-ordinates that can only be found together:
//! the crank of a four-bar, then its dyad, then the coupler point.

use super::{match_rows, NONE};

/// New numbers of rows and columns, and the blocks they form.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct BlockOrder {
    /// New index of every original row.
    pub row_new: Vec<usize>,
    /// New index of every original column.
    pub col_new: Vec<usize>,
    /// The first new index of every block, then n: block b is
    /// `starts[b]..starts[b + 1]`, rows and columns alike.
    pub starts: Vec<usize>,
}

/// The block lower triangular ordering of the pattern `rows` (the columns
/// of the structural non-zeros of every row), or `None` when the pattern is
/// structurally singular.
pub(crate) fn block_order(n: usize, rows: &[Vec<usize>]) -> Option<BlockOrder> {
    let matched = match_rows(n, rows)?;
    let mut row_of_col = vec![NONE; n];
    for (i, &c) in matched.iter().enumerate() {
        row_of_col[c] = i;
    }
    // Tarjan's algorithm without recursion; column c leads to the columns
    // of the row matched to it. A component is complete only after every
    // component it leads to, so components come out in the order wanted.
    let mut index = vec![NONE; n];
    let mut low = vec![0; n];
    let mut on_stack = vec![false; n];
    let mut stack: Vec<usize> = Vec::new();
    let mut path: Vec<(usize, usize)> = Vec::new();
    let mut order: Vec<usize> = Vec::with_capacity(n);
    let mut starts = vec![0];
    let mut counter = 0;
    for root in 0..n {
        if index[root] != NONE {
            continue;
        }
        macro_rules! visit {
            ($v:expr) => {{
                let v = $v;
                index[v] = counter;
                low[v] = counter;
                counter += 1;
                stack.push(v);
                on_stack[v] = true;
                path.push((v, 0));
            }};
        }
        visit!(root);
        while let Some(&(v, e)) = path.last() {
            let out = &rows[row_of_col[v]];
            if e < out.len() {
                path.last_mut().expect("the path is not empty").1 += 1;
                let w = out[e];
                if index[w] == NONE {
                    visit!(w);
                } else if on_stack[w] {
                    low[v] = low[v].min(index[w]);
                }
                continue;
            }
            path.pop();
            if let Some(&(u, _)) = path.last() {
                low[u] = low[u].min(low[v]);
            }
            if low[v] == index[v] {
                while let Some(w) = stack.pop() {
                    on_stack[w] = false;
                    order.push(w);
                    if w == v {
                        break;
                    }
                }
                starts.push(order.len());
            }
        }
    }
    let mut col_new = vec![0; n];
    for (new, &old) in order.iter().enumerate() {
        col_new[old] = new;
    }
    let row_new = matched.iter().map(|&c| col_new[c]).collect();
    Some(BlockOrder { row_new, col_new, starts })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every row's columns lie in its own block or an earlier one, and
    /// every block is as small as the pattern allows (checked by sizes).
    fn check(rows: &[Vec<usize>], sizes: &[usize]) {
        let n = rows.len();
        let o = block_order(n, rows).unwrap();
        let got: Vec<usize> = o.starts.windows(2).map(|w| w[1] - w[0]).collect();
        assert_eq!(got, sizes);
        let block = |k: usize| o.starts.iter().rposition(|&s| s <= k).unwrap();
        for (i, cols) in rows.iter().enumerate() {
            for &c in cols {
                assert!(block(o.col_new[c]) <= block(o.row_new[i]), "row {i} column {c}");
            }
        }
    }

    #[test]
    fn a_four_bar_splits_into_crank_dyad_and_coupler_point() {
        // Columns xA yA xB yB xC yC; rows: crank length, coupler length,
        // rocker length, u and v of C, crank angle (the input).
        let rows =
            vec![vec![0, 1], vec![0, 1, 2, 3], vec![2, 3], vec![0, 1, 2, 3, 4, 5], vec![0, 1, 2, 3, 4, 5], vec![0, 1]];
        check(&rows, &[2, 2, 2]);
    }

    #[test]
    fn a_closed_loop_is_one_block_and_a_diagonal_is_n() {
        let cycle: Vec<Vec<usize>> = (0..5).map(|i| vec![i, (i + 1) % 5]).collect();
        check(&cycle, &[5]);
        let diagonal: Vec<Vec<usize>> = (0..4).map(|i| vec![i]).collect();
        check(&diagonal, &[1, 1, 1, 1]);
    }

    #[test]
    fn a_long_chain_needs_no_recursion() {
        // Row i touches columns i and i-1: 100 000 blocks of one.
        let n = 100_000;
        let rows: Vec<Vec<usize>> = (0..n).map(|i| if i == 0 { vec![0] } else { vec![i, i - 1] }).collect();
        let o = block_order(n, &rows).unwrap();
        assert_eq!(o.starts.len(), n + 1);
        assert_eq!(o.col_new[0], 0);
    }
}
