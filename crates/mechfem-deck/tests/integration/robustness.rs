//! No input makes the deck crate panic: decks mangled at random (seeded)
//! must give either a model or diagnostics.

use std::path::Path;

use mechfem_deck::{compile, parse_str};

/// A small seeded generator (xorshift), so failures can be replayed.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

const WORDS: &[&str] = &[
    "0",
    "-1",
    "1",
    "2",
    "3",
    "9",
    "20",
    "99",
    "1e999",
    "nan",
    ".",
    "-",
    "+.5",
    "1.5D0",
    "\t",
    ";",
    "ELEM",
    "FORM",
    "NRDOF",
    "XFIX",
    "XMOV",
    "PARA",
    "TSTEPE",
    "MOV_FREE",
    "MOV_FUNC",
    "BUFKX2",
    "BUFKE2",
    "PRINTBUF",
    "BEGINPIC",
    "ENDPIC",
    "PLOTHODO",
    "TOPOLOGY",
    "GEOMETRY",
    "MOVEMENT",
    "STORAGE",
    "END",
    "BIN",
    "TR2",
    "GR1",
    "LENL",
    "ANGB",
    "COOR",
    "KIN",
    "ANA",
    "DYN",
    "DYNAMICS",
    "MASS",
    "PMASS",
    "INERTIA",
    "GRAVITY",
    "FORCE",
    "LOAD",
    "LOADFUNC",
    "SPRING",
    "MOTOR",
    "BUFSIG",
    "BUFREA",
    "BUFMRED",
    "SIM",
    "MOV_DYN",
    "INTTOL",
    "OPT",
    "OPTIMISE",
    "VARY",
    "VARYX",
    "TARGET",
    "TARGETAT",
    "TARGETEXT",
    "BOUND",
    "MINIMISE",
    "MAXIMISE",
    "MAXABS",
    "OPTSTEPS",
    "OPTTOL",
    "*",
    "torque.dat",
    "rocker.dat",
    "Ä",
    "9007199254740993",
    "-9007199254740992",
];

fn mangle(text: &str, rng: &mut Rng) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    for _ in 0..1 + rng.below(4) {
        let k = rng.below(lines.len());
        match rng.below(5) {
            0 => {
                lines.remove(k);
            }
            1 => {
                let copy = lines[k].clone();
                lines.insert(rng.below(lines.len()), copy);
            }
            2 => {
                let mut words: Vec<String> = lines[k].split_whitespace().map(str::to_string).collect();
                let w = WORDS[rng.below(WORDS.len())].to_string();
                if words.is_empty() || rng.below(2) == 0 {
                    words.insert(rng.below(words.len() + 1), w);
                } else {
                    let at = rng.below(words.len());
                    words[at] = w;
                }
                lines[k] = words.join(" ");
            }
            3 => {
                let mut words: Vec<String> = lines[k].split_whitespace().map(str::to_string).collect();
                if !words.is_empty() {
                    words.remove(rng.below(words.len()));
                }
                lines[k] = words.join("\t");
            }
            _ => lines.truncate(k),
        }
        if lines.is_empty() {
            break;
        }
    }
    lines.join("\n")
}

#[test]
fn mangled_decks_never_panic() {
    let dir = Path::new("tests/decks/valid");
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let mut outcomes = [0usize; 2];
    for entry in std::fs::read_dir(dir).expect("valid decks").flatten() {
        let path = entry.path();
        if path.extension().and_then(|x| x.to_str()) != Some("mec") {
            continue;
        }
        let text = std::fs::read_to_string(&path).expect("deck");
        for _ in 0..400 {
            let mangled = mangle(&text, &mut rng);
            let result = parse_str(&mangled, &path)
                .map_err(|e| e.to_string())
                .and_then(|deck| compile(&deck, dir).map(|_| ()).map_err(|e| e.to_string()));
            match result {
                Ok(()) => outcomes[0] += 1,
                Err(message) => {
                    assert!(message.starts_with("error: "), "{message}");
                    outcomes[1] += 1;
                }
            }
        }
    }
    assert!(outcomes[0] > 0 && outcomes[1] > 0, "{outcomes:?}");
}
