//! Hostile input, as property tests: the repository's decks mangled
//! (lines dropped, repeated and swapped, numbers replaced by extreme values,
//! bytes inserted) never make the reader panic, and generated decks that
//! compile run without a panic and without a NaN or infinity passed on as a
//! result. The fuzz targets in `fuzz/` do the same at length (`make fuzz`);
//! what they found is kept in `tests/decks/hostile` and replayed here.
//!
//! Replay a fuzz input with
//! `HOSTILE_INPUT=path cargo test -p mechfem-deck --test integration hostile::replay -- --ignored --nocapture`
//! (`HOSTILE_GRAMMAR=1` for an input of the `deck_grammar` target).

#[path = "../support/mod.rs"]
mod support;

use std::path::{Path, PathBuf};
use std::sync::mpsc::{self, RecvTimeoutError};
use std::time::Duration;

use mechfem_core::{Quantity, Recorder, RunReport, SolveError};
use mechfem_deck::DiagnosticKind;
use proptest::prelude::*;
use proptest::sample::Index;
use support::{check_deck, compile_text, deck, every_quantity, Bytes, Outcome, FUZZ_MAX_STEPS};

/// Where MOV_FUNC files of the generated and mangled decks are read from.
const DIR: &str = "tests/decks/hostile";
/// Longest motion a test deck runs; longer ones are cut to this.
const MAX_STEPS: usize = 50;

/// Every deck of the repository: examples, run-failure decks, golden decks.
fn repository_decks() -> Vec<(PathBuf, String)> {
    let mut paths = Vec::new();
    for dir in ["../../examples", "../../tests/decks", "tests/decks/valid", "tests/decks/invalid", DIR] {
        let mut stack = vec![PathBuf::from(dir)];
        while let Some(d) = stack.pop() {
            for entry in std::fs::read_dir(&d).unwrap_or_else(|e| panic!("{}: {e}", d.display())).flatten() {
                let p = entry.path();
                if p.is_dir() {
                    stack.push(p);
                } else if p.extension().is_some_and(|x| x == "mec") {
                    paths.push(p);
                }
            }
        }
    }
    paths.sort();
    paths.into_iter().map(|p| (p.clone(), std::fs::read_to_string(&p).expect("deck"))).collect()
}

/// Words that replace a number of a deck: the edges of what a number can be.
const REPLACEMENTS: &[&str] = &[
    "0",
    "-1",
    "-0",
    "1e308",
    "-1e308",
    "1e-308",
    "5e-324",
    "1e999",
    "nan",
    "NaN",
    "inf",
    "-inf",
    "1.#INF",
    "9223372036854775807",
    "9223372036854775808",
    "-9223372036854775808",
    "4294967296",
    "99999999999999999999999",
    "10000000",
    ".",
    "1D",
];

/// One change to a deck.
#[derive(Debug, Clone)]
enum Mutation {
    Delete(Index),
    Duplicate(Index, Index),
    Swap(Index, Index),
    /// Replaces a word of a line that reads as a number.
    Number(Index, Index, &'static str),
    /// Inserts bytes (read as lossy UTF-8) into a line.
    Bytes(Index, Index, Vec<u8>),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        1 => any::<Index>().prop_map(Mutation::Delete),
        1 => (any::<Index>(), any::<Index>()).prop_map(|(a, b)| Mutation::Duplicate(a, b)),
        1 => (any::<Index>(), any::<Index>()).prop_map(|(a, b)| Mutation::Swap(a, b)),
        3 => (any::<Index>(), any::<Index>(), proptest::sample::select(REPLACEMENTS))
            .prop_map(|(l, w, r)| Mutation::Number(l, w, r)),
        1 => (any::<Index>(), any::<Index>(), proptest::collection::vec(any::<u8>(), 1..6))
            .prop_map(|(l, at, b)| Mutation::Bytes(l, at, b)),
    ]
}

fn apply(text: &str, mutations: &[Mutation]) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    for m in mutations {
        if lines.is_empty() {
            break;
        }
        let n = lines.len();
        match m {
            Mutation::Delete(k) => {
                lines.remove(k.index(n));
            }
            Mutation::Duplicate(k, to) => {
                let copy = lines[k.index(n)].clone();
                lines.insert(to.index(n + 1), copy);
            }
            Mutation::Swap(a, b) => lines.swap(a.index(n), b.index(n)),
            Mutation::Number(k, w, r) => {
                let line = &mut lines[k.index(n)];
                let mut words: Vec<String> = line.split_whitespace().map(str::to_string).collect();
                let numbers: Vec<usize> = (0..words.len())
                    .filter(|&i| words[i].starts_with(|c: char| c.is_ascii_digit() || "+-.".contains(c)))
                    .collect();
                if !numbers.is_empty() {
                    words[numbers[w.index(numbers.len())]] = r.to_string();
                    *line = words.join(" ");
                }
            }
            Mutation::Bytes(k, at, bytes) => {
                let line = &mut lines[k.index(n)];
                let chars: Vec<char> = line.chars().collect();
                let at = at.index(chars.len() + 1);
                let inserted = String::from_utf8_lossy(bytes);
                *line = chars[..at].iter().collect::<String>() + &inserted + &chars[at..].iter().collect::<String>();
            }
        }
    }
    lines.join("\n")
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1000, failure_persistence: None, ..ProptestConfig::default() })]

    /// Mangled decks of the repository: never a panic, diagnostics render,
    /// and a mangled deck that still compiles runs cleanly.
    #[test]
    fn mangled_repository_decks_are_read_and_run_cleanly(
        which in any::<Index>(),
        mutations in proptest::collection::vec(mutation(), 1..5),
    ) {
        let decks = repository_decks();
        let (_, text) = &decks[which.index(decks.len())];
        check_deck(&apply(text, &mutations), Path::new(DIR), MAX_STEPS);
    }

    /// Generated decks, plausible line by line: those that compile run
    /// without a panic and without a silent NaN or infinity.
    #[test]
    fn generated_decks_are_read_and_run_cleanly(choices in proptest::collection::vec(any::<u8>(), 0..400)) {
        check_deck(&deck(&mut Bytes::new(&choices)), Path::new(DIR), MAX_STEPS);
    }
}

/// The generator is worth its time: a fair share of its decks compile and
/// run, some to the end, and some are refused; decks of every mode get
/// through the reader.
#[test]
fn generated_decks_reach_the_solver() {
    let mut counts = std::collections::HashMap::new();
    let mut modes = std::collections::BTreeMap::<String, usize>::new();
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    for _ in 0..300 {
        let choices: Vec<u8> = (0..300)
            .map(|_| {
                seed ^= seed << 13;
                seed ^= seed >> 7;
                seed ^= seed << 17;
                (seed >> 24) as u8
            })
            .collect();
        let text = deck(&mut Bytes::new(&choices));
        let outcome = check_deck(&text, Path::new(DIR), MAX_STEPS);
        *counts.entry(outcome).or_insert(0) += 1;
        if outcome != Outcome::Rejected {
            *modes.entry(text.lines().next().unwrap_or("").to_string()).or_insert(0) += 1;
        }
    }
    // The new modes are reached too: designs evaluated, simulations run.
    for mode in ["KIN ANA", "DYN ANA", "DYN SIM", "KIN OPT"] {
        assert!(modes.get(mode).copied().unwrap_or(0) >= 3, "{modes:?}");
    }
    let count = |o| counts.get(&o).copied().unwrap_or(0);
    assert!(count(Outcome::Rejected) > 0, "{counts:?}");
    assert!(count(Outcome::Completed) + count(Outcome::Stopped) >= 30, "{counts:?}");
    assert!(count(Outcome::Completed) > 0, "{counts:?}");
}

/// Every repository deck as it is passes the checks.
#[test]
fn repository_decks_are_read_and_run_cleanly() {
    for (path, text) in repository_decks() {
        // Shown with the failure, if there is one.
        println!("{}", path.display());
        check_deck(&text, Path::new(DIR), MAX_STEPS);
    }
}

fn hostile_deck(name: &str) -> String {
    std::fs::read_to_string(Path::new(DIR).join(name)).expect("hostile deck")
}

/// Checks a deck of `tests/decks/hostile` as the fuzz targets do, in a
/// thread that must be done within a minute (some of them used to hang).
fn hostile(name: &str) -> Outcome {
    let text = hostile_deck(name);
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || tx.send(check_deck(&text, Path::new(DIR), FUZZ_MAX_STEPS)));
    match rx.recv_timeout(Duration::from_secs(60)) {
        Ok(outcome) => outcome,
        Err(RecvTimeoutError::Timeout) => panic!("{name} takes more than a minute"),
        Err(RecvTimeoutError::Disconnected) => panic!("{name} failed a check (see above)"),
    }
}

/// Runs a deck of `tests/decks/hostile`, recording every quantity.
fn run_hostile(name: &str) -> (Result<RunReport, SolveError>, Recorder) {
    let c = compile_text(&hostile_deck(name), Path::new(DIR)).expect("the deck compiles");
    let mut state = c.state.clone();
    let mut rec = Recorder::new(every_quantity(&c), false);
    (mechfem_core::run(&c.mechanism, &mut state, c.motion.as_ref(), &c.params, &mut rec), rec)
}

#[test]
fn a_limit_search_with_an_infinite_step_ends() {
    assert_eq!(hostile("limit_search_infinite_step.mec"), Outcome::Stopped);
    let (report, _) = run_hostile("limit_search_infinite_step.mec");
    let stop = report.expect("position 1").stop.expect("a stop");
    assert_eq!(stop.limit, None);
}

#[test]
fn an_overflowing_dependent_transfer_function_is_an_error() {
    assert_eq!(hostile("dependent_transfer_overflow.mec"), Outcome::Failed);
    assert_eq!(run_hostile("dependent_transfer_overflow.mec").0.unwrap_err(), SolveError::NonFinite);
}

#[test]
fn an_overflowing_determinant_is_an_error() {
    assert_eq!(hostile("determinant_overflow.mec"), Outcome::Failed);
    assert_eq!(run_hostile("determinant_overflow.mec").0.unwrap_err(), SolveError::NonFinite);
}

#[test]
fn adjusting_between_opposite_extremes_reaches_the_target() {
    assert_eq!(hostile("adjust_between_extremes.mec"), Outcome::Completed);
    let (report, rec) = run_hostile("adjust_between_extremes.mec");
    assert_eq!(report.expect("position 1").stop, None);
    let input = rec.quantities().iter().position(|q| *q == Quantity::Input(0)).expect("input recorded");
    assert_eq!(rec.column(input)[0], 1e308);
}

#[test]
fn a_motion_longer_than_a_number_can_hold_is_a_deck_error() {
    assert_eq!(hostile("free_motion_endless_time.mec"), Outcome::Rejected);
    let e = compile_text(&hostile_deck("free_motion_endless_time.mec"), Path::new(DIR)).unwrap_err();
    assert_eq!(e.0[0].kind, DiagnosticKind::BadValue);
}

#[test]
fn newton_that_neither_converges_nor_diverges_ends() {
    assert_eq!(hostile("newton_oscillates.mec"), Outcome::Failed);
    let text = hostile_deck("newton_oscillates.mec").replace("MAXITER 1000", "MAXITER 1001");
    assert_eq!(compile_text(&text, Path::new(DIR)).unwrap_err().0[0].kind, DiagnosticKind::BadValue);
}

#[test]
fn whole_numbers_from_2_pow_53_on_are_refused_not_rounded() {
    let text = hostile_deck("newton_oscillates.mec").replace("MAXITER 1000", "MAXITER 9007199254740993");
    let e = compile_text(&text, Path::new(DIR)).unwrap_err();
    assert_eq!(e.0[0].kind, DiagnosticKind::NumberOutOfRange);
    assert!(e.0[0].message.contains("`9007199254740993`"), "{}", e.0[0].message);
}

/// Finite transfer functions times a huge input velocity overflow: the run
/// stops there with the reason instead of recording an infinity.
#[test]
fn an_overflowing_velocity_stops_the_run() {
    let (report, rec) = run_hostile("velocity_overflow.mec");
    assert!(rec.data().iter().all(|v| v.is_finite()), "{:?} with {report:?}", rec.data());
    match report {
        Ok(report) => {
            assert!(matches!(report.stop.as_ref().map(|s| &s.error), Some(SolveError::NonFinite)), "{:?}", report.stop)
        }
        Err(e) => assert!(matches!(e, SolveError::NonFinite), "{e:?}"),
    }
}

/// A simulation's motion is not the kinematic run's: `run` refuses it as
/// unsupported, and the deck's position 1 is checked instead.
#[test]
fn a_simulation_deck_is_checked_at_position_one() {
    let text = std::fs::read_to_string("tests/decks/valid/pendulum_released.mec").expect("deck");
    assert_eq!(check_deck(&text, Path::new(DIR), MAX_STEPS), Outcome::Simulation);
    let c = compile_text(&text, Path::new(DIR)).expect("the deck compiles");
    let mut state = c.state.clone();
    let mut rec = Recorder::new(Vec::new(), false);
    let refused = mechfem_core::run(&c.mechanism, &mut state, c.motion.as_ref(), &c.params, &mut rec);
    assert!(matches!(refused, Err(SolveError::Unsupported(_))), "{refused:?}");
}

/// Replays one fuzz input given by `HOSTILE_INPUT`, printing the deck.
#[test]
#[ignore = "replays the fuzz input named by HOSTILE_INPUT"]
fn replay() {
    let path = std::env::var_os("HOSTILE_INPUT").expect("HOSTILE_INPUT names a fuzz input");
    let bytes = std::fs::read(path).expect("fuzz input");
    let text = match std::env::var_os("HOSTILE_GRAMMAR") {
        Some(_) => deck(&mut Bytes::new(&bytes)),
        None => String::from_utf8_lossy(&bytes).into_owned(),
    };
    println!("{text}");
    if let Err(e) = compile_text(&text, Path::new(DIR)) {
        println!("{e}");
    }
    println!("{:?}", check_deck(&text, Path::new(DIR), FUZZ_MAX_STEPS));
}

/// The edges of what a number of the dynamics or of an optimisation can be.
const OVERFLOWS: [&str; 5] = ["1e308", "-1e308", "1e-320", "nan", "inf"];

/// Every deck with `(line, word)` of its numbers replaced by each value of
/// [`OVERFLOWS`], for every number of every line of its DYNAMICS and
/// OPTIMISE blocks and of its MOV_DYN and INTTOL lines.
fn overflowing_variants(text: &str) -> Vec<(usize, String)> {
    let lines: Vec<&str> = text.lines().collect();
    let mut block = "";
    let mut out = Vec::new();
    for (k, line) in lines.iter().enumerate() {
        let words: Vec<&str> = line.split(';').next().unwrap_or("").split_whitespace().collect();
        let Some(first) = words.first() else { continue };
        if ["TOPOLOGY", "GEOMETRY", "DYNAMICS", "MOVEMENT", "OPTIMISE", "STORAGE"].contains(first) {
            block = first;
            continue;
        }
        if !(matches!(block, "DYNAMICS" | "OPTIMISE") || ["MOV_DYN", "INTTOL"].contains(first)) {
            continue;
        }
        for (w, word) in words.iter().enumerate() {
            if !word.starts_with(|c: char| c.is_ascii_digit() || "+-.".contains(c)) {
                continue;
            }
            for value in OVERFLOWS {
                let mut changed = words.clone();
                changed[w] = value;
                let mut variant: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
                variant[k] = changed.join(" ");
                out.push((k + 1, variant.join("\n")));
            }
        }
    }
    out
}

/// Every number of every DYNAMICS and OPTIMISE line (and of MOV_DYN and
/// INTTOL) of decks that use every keyword of those blocks, replaced by
/// 1e308, -1e308, 1e-320, NaN and infinity: each variant is refused with a
/// diagnostic, or it runs (inverse dynamics recorded, a simulation, a design
/// evaluated) with finite results, stopping with its reason where they
/// would not be.
#[test]
fn overflowing_numbers_of_the_dynamics_and_optimisation_are_refused_or_run_finite() {
    let dir = Path::new("tests/decks/valid");
    let mut counts = std::collections::BTreeMap::<String, usize>::new();
    for name in ["slider_crank.mec", "load_function.mec", "motor_run_up.mec", "fourbar_optimise.mec"] {
        let text = std::fs::read_to_string(dir.join(name)).expect("deck");
        let variants = overflowing_variants(&text);
        assert!(variants.len() >= 20, "{name}: only {} variants", variants.len());
        for (line, variant) in variants {
            // Shown with the failure, if there is one.
            println!("{name}, line {line}: {}", variant.lines().nth(line - 1).unwrap_or(""));
            let outcome = check_deck(&variant, dir, MAX_STEPS);
            *counts.entry(format!("{outcome:?}")).or_insert(0) += 1;
        }
    }
    // Most are refused by the deck reader; the rest ran to a finite end.
    println!("{counts:?}");
    assert!(counts.get("Rejected").copied().unwrap_or(0) > 100, "{counts:?}");
}
