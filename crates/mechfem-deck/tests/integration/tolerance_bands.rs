//! The bands of a TOLERANCE block against central differences of whole
//! runs: each toleranced dimension moved by +-h in the deck, the motion run
//! again, and sum_k |dy/dp_k| t_k compared with the worst-case band at
//! every position (the RSS band likewise).

use std::path::Path;

use mechfem_core::design::evaluate;
use mechfem_core::run::Extent;
use mechfem_core::{DesignVar, Quantity};
use mechfem_deck::{parse_str, Change, Compiled, EvaluatedBands};

const DECK: &str = "tests/decks/valid/tolerance_fourbar.mec";

fn compile(text: &str) -> Compiled {
    let deck = parse_str(text, "tolerance.mec").unwrap_or_else(|e| panic!("{e}"));
    mechfem_deck::compile(&deck, Path::new(".")).unwrap_or_else(|e| panic!("{e}"))
}

/// The values of `quantities` at every position of a whole run of `c` with
/// `changes` made, in the deck's units.
fn run(c: &Compiled, changes: &[Change], quantities: &[Quantity]) -> Vec<f64> {
    let mut state = c.numbers(changes).unwrap_or_else(|e| panic!("{e}")).state;
    let motion = c.motion_for(&mut state, Extent::Motion).expect("a motion");
    let run =
        evaluate(&c.mechanism, &mut state, &motion, &c.params, &[], quantities, &[]).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(run.positions, motion.steps + 1);
    let nq = quantities.len();
    (0..run.values.len()).map(|k| run.values[k] * c.out_scale(quantities[k % nq])).collect()
}

/// Checks every band of `c`'s TOLERANCE block against central differences
/// with steps `h` (deck units) of its dimensions; returns the bands.
fn check_against_central_differences(c: &Compiled, h: f64) -> EvaluatedBands {
    let tol = c.tolerance.as_ref().expect("a TOLERANCE block");
    let got = tol.evaluate(c).unwrap_or_else(|e| panic!("{e}"));
    let b = &got.bands;
    let quantities: Vec<Quantity> =
        tol.bands.iter().map(|d| c.buffers.iter().find(|x| x.number == d.source).expect("source").quantity).collect();
    let (nb, nv) = (quantities.len(), tol.dims.len());
    let [prescribed, _] = c.rows_as_written();
    let x = c.coords_as_written();
    let mut slopes = vec![0.0; b.positions * nb * nv];
    for (k, d) in tol.dims.iter().enumerate() {
        let change = |s: f64| match d.var {
            DesignVar::Row(r) => Change::Row(r + 1, prescribed[r].para.expect("PARA") + s * h),
            DesignVar::Fixed(i) => Change::Coord(i + 1, x[i] + s * h),
        };
        let (up, down) = (run(c, &[change(1.0)], &quantities), run(c, &[change(-1.0)], &quantities));
        for p in 0..b.positions {
            for q in 0..nb {
                slopes[(p * nb + q) * nv + k] = (up[p * nb + q] - down[p * nb + q]) / (2.0 * h);
            }
        }
    }
    let mut worst_err: f64 = 0.0;
    for p in 0..b.positions {
        for q in 0..nb {
            let s = &slopes[(p * nb + q) * nv..(p * nb + q + 1) * nv];
            let worst: f64 = s.iter().zip(&b.tolerances).map(|(s, t)| s.abs() * t).sum();
            let rss = s.iter().zip(&b.tolerances).map(|(s, t)| (s * t).powi(2)).sum::<f64>().sqrt();
            let (w, r) = (b.worst[p * nb + q], b.rss[p * nb + q]);
            let scale = worst.abs().max(1e-6);
            worst_err = worst_err.max((w - worst).abs() / scale);
            assert!((w - worst).abs() <= 1e-5 * scale, "band {q} at position {p}: worst case {w} vs {worst}");
            assert!((r - rss).abs() <= 1e-5 * scale, "band {q} at position {p}: RSS {r} vs {rss}");
        }
    }
    eprintln!("largest relative difference of a worst-case band from central differences: {worst_err:.2e}");
    got
}

#[test]
fn bands_equal_central_differences_of_whole_runs() {
    let c = compile(&std::fs::read_to_string(DECK).expect("read the deck"));
    let got = check_against_central_differences(&c, 1e-5);
    // The widest position is where the worst case is largest, and its
    // shares add up to 1, largest first.
    let b = &got.bands;
    let nb = got.labels.len();
    for q in 0..nb {
        let w = b.widest[q].as_ref().expect("a widest position");
        let max = (0..b.positions).map(|p| b.worst[p * nb + q]).fold(f64::MIN, f64::max);
        assert_eq!(b.worst[w.position * nb + q], max);
        let total: f64 = w.shares.iter().map(|s| s.of_worst).sum();
        assert!((total - 1.0).abs() < 1e-12);
        assert!(w.shares.windows(2).all(|p| p[0].deviation >= p[1].deviation));
    }
}

#[test]
fn the_band_of_a_transmission_angle_equals_central_differences() {
    let text = std::fs::read_to_string(DECK).expect("read the deck");
    let text = text.replacen("BUFDET 103", "BUFDET 103\nBUFTRA 2 3 105", 1).replacen(
        "BUFTOL 102 204",
        "BUFTOL 102 204\nBUFTOL 105 206",
        1,
    );
    let c = compile(&text);
    let got = check_against_central_differences(&c, 1e-5);
    assert_eq!(got.labels.len(), 4);
    assert_eq!(got.labels[3].1, "deg");
    assert!(got.bands.worst.iter().skip(3).step_by(4).all(|w| w.is_finite() && *w > 0.0));
}
