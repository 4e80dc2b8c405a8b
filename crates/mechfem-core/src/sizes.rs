//! Code with a path for each small size, known to the compiler: a loop over
//! a count the compiler knows is unrolled and what it carries stays in
//! registers.

/// Calls `$f::<N>` for a size `$n` of 1 to 16, the sizes that have a
/// fixed-size path, `$general` for the others.
macro_rules! by_size {
    ($n:expr, $f:ident, ($($arg:expr),*), $general:expr) => {
        match $n {
            1 => $f::<1>($($arg),*),
            2 => $f::<2>($($arg),*),
            3 => $f::<3>($($arg),*),
            4 => $f::<4>($($arg),*),
            5 => $f::<5>($($arg),*),
            6 => $f::<6>($($arg),*),
            7 => $f::<7>($($arg),*),
            8 => $f::<8>($($arg),*),
            9 => $f::<9>($($arg),*),
            10 => $f::<10>($($arg),*),
            11 => $f::<11>($($arg),*),
            12 => $f::<12>($($arg),*),
            13 => $f::<13>($($arg),*),
            14 => $f::<14>($($arg),*),
            15 => $f::<15>($($arg),*),
            16 => $f::<16>($($arg),*),
            _ => $general,
        }
    };
}
pub(crate) use by_size;
