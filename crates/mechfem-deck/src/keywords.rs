//! The keyword table: every keyword, the block it belongs to, its arguments.

use std::fmt;

/// A block of the deck, opened by its header line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Block {
    /// Elements, form parameters, degrees of freedom.
    Topology,
    /// Initial co-ordinates and prescribed values.
    Geometry,
    /// Names of points, co-ordinates, elements, rows and labels of buffers.
    Names,
    /// Masses, loads and springs (modes `DYN ANA` and `DYN SIM`).
    Dynamics,
    /// Input motion and solver settings.
    Movement,
    /// Design variables, targets, bounds and the objective (mode `KIN OPT`).
    Optimise,
    /// Output buffers and what to do with them.
    Storage,
    /// Tolerances of dimensions and the bands of buffers they give (modes
    /// `KIN ANA` and `DYN ANA`).
    Tolerance,
}

impl Block {
    /// Every block, in the order of a deck.
    pub const ALL: [Block; 8] = [
        Block::Topology,
        Block::Geometry,
        Block::Names,
        Block::Dynamics,
        Block::Movement,
        Block::Optimise,
        Block::Storage,
        Block::Tolerance,
    ];

    /// The header word.
    pub fn name(self) -> &'static str {
        match self {
            Block::Topology => "TOPOLOGY",
            Block::Geometry => "GEOMETRY",
            Block::Names => "NAMES",
            Block::Dynamics => "DYNAMICS",
            Block::Movement => "MOVEMENT",
            Block::Optimise => "OPTIMISE",
            Block::Storage => "STORAGE",
            Block::Tolerance => "TOLERANCE",
        }
    }

    /// The block whose header is `word` (case-insensitive).
    pub fn from_name(word: &str) -> Option<Block> {
        Block::ALL.into_iter().find(|b| b.name().eq_ignore_ascii_case(word))
    }
}

impl fmt::Display for Block {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

macro_rules! keywords {
    ($($variant:ident $name:literal $block:ident $min:literal $max:expr, $usage:literal;)*) => {
        /// A keyword of a block.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum Keyword {
            $(#[doc = concat!("`", $name, " ", $usage, "`")] $variant,)*
        }

        impl Keyword {
            /// Every keyword, in the order of the deck reference.
            pub const ALL: &'static [Keyword] = &[$(Keyword::$variant,)*];

            /// The keyword as written in decks.
            pub fn name(self) -> &'static str {
                match self { $(Keyword::$variant => $name,)* }
            }

            /// The block the keyword belongs to.
            pub fn block(self) -> Block {
                match self { $(Keyword::$variant => Block::$block,)* }
            }

            /// Its arguments, as in the deck reference (`s NAME k dest [f]`).
            pub fn usage(self) -> &'static str {
                match self { $(Keyword::$variant => $usage,)* }
            }

            /// Least and largest number of arguments (`None`: no limit).
            /// ELEM's count depends on the element type.
            pub(crate) fn arity(self) -> (usize, Option<usize>) {
                match self { $(Keyword::$variant => ($min, $max),)* }
            }
        }
    };
}

keywords! {
    Elem "ELEM" Topology 2 None, "k TYPE c1 c2 ...";
    Form "FORM" Topology 4 Some(5), "s NAME k dest [f]";
    Nrdof "NRDOF" Topology 1 Some(1), "n";
    Xfix "XFIX" Geometry 2 Some(2), "i value";
    Xmov "XMOV" Geometry 2 Some(2), "i value";
    Para "PARA" Geometry 2 Some(2), "row value";
    Mass "MASS" Dynamics 4 Some(5), "k m u v [J]";
    Pmass "PMASS" Dynamics 3 Some(3), "i j m";
    Inertia "INERTIA" Dynamics 2 Some(2), "i J";
    Gravity "GRAVITY" Dynamics 2 Some(2), "gx gy";
    Force "FORCE" Dynamics 4 Some(4), "i j fx fy";
    Load "LOAD" Dynamics 2 Some(2), "r value";
    LoadFunc "LOADFUNC" Dynamics 2 Some(2), "r file";
    Spring "SPRING" Dynamics 3 Some(4), "r k e0 [c]";
    Motor "MOTOR" Dynamics 3 Some(3), "r T0 w0";
    Tstepe "TSTEPE" Movement 1 Some(2), "n [dt]";
    MovRele "MOV_RELE" Movement 2 Some(2), "j delta";
    MovAbse "MOV_ABSE" Movement 2 Some(2), "j end";
    MovFunc "MOV_FUNC" Movement 2 Some(2), "j file";
    MovFree "MOV_FREE" Movement 2 Some(2), "j ds";
    MovDyn "MOV_DYN" Movement 2 Some(2), "j v0";
    Accuracy "ACCURACY" Movement 1 Some(1), "tol";
    Maxiter "MAXITER" Movement 1 Some(1), "m";
    Inttol "INTTOL" Movement 2 Some(2), "rtol atol";
    Integrator "INTEGRATOR" Movement 1 Some(1), "auto|explicit|implicit";
    StopWhen "STOPWHEN" Movement 2 Some(2), "b value";
    Vary "VARY" Optimise 3 Some(3), "r lo hi";
    VaryX "VARYX" Optimise 3 Some(3), "i lo hi";
    Target "TARGET" Optimise 2 Some(3), "b file [w]";
    TargetAt "TARGETAT" Optimise 3 Some(4), "b k value [w]";
    TargetExt "TARGETEXT" Optimise 3 Some(4), "b bref value [w]";
    Bound "BOUND" Optimise 3 Some(3), "b lo hi";
    Minimise "MINIMISE" Optimise 2 Some(3), "kind b [b2]";
    Maximise "MAXIMISE" Optimise 2 Some(3), "kind b [b2]";
    OptSteps "OPTSTEPS" Optimise 1 Some(1), "n";
    OptTol "OPTTOL" Optimise 1 Some(1), "tol";
    OptFTol "OPTFTOL" Optimise 2 Some(2), "rtol atol";
    FreeTime "FREETIME" Optimise 1 Some(4), "r [ORDERED [WITHIN w]]";
    FullRot "FULLROT" Optimise 1 Some(1), "r";
    VaryFrame "VARYFRAME" Optimise 3 Some(3), "i lo hi";
    VaryM "VARYM" Optimise 4 Some(4), "what n lo hi";
    BufInp "BUFINP" Storage 2 Some(2), "j b";
    BufTime "BUFTIME" Storage 1 Some(1), "b";
    BufX0 "BUFX0" Storage 2 Some(2), "i b";
    BufKx1 "BUFKX1" Storage 3 Some(3), "i j b";
    BufKx2 "BUFKX2" Storage 3 Some(4), "i j [m] b";
    BufVx "BUFVX" Storage 2 Some(2), "i b";
    BufAx "BUFAX" Storage 2 Some(2), "i b";
    BufE0 "BUFE0" Storage 2 Some(2), "r b";
    BufKe1 "BUFKE1" Storage 3 Some(3), "r j b";
    BufKe2 "BUFKE2" Storage 3 Some(4), "r j [m] b";
    BufVe "BUFVE" Storage 2 Some(2), "r b";
    BufAe "BUFAE" Storage 2 Some(2), "r b";
    BufDet "BUFDET" Storage 1 Some(1), "b";
    BufSig "BUFSIG" Storage 2 Some(2), "r b";
    BufDrv "BUFDRV" Storage 2 Some(2), "j b";
    BufRea "BUFREA" Storage 2 Some(2), "i b";
    BufEkin "BUFEKIN" Storage 1 Some(1), "b";
    BufEpot "BUFEPOT" Storage 1 Some(1), "b";
    BufPow "BUFPOW" Storage 1 Some(1), "b";
    BufMred "BUFMRED" Storage 3 Some(3), "j m b";
    BufTra "BUFTRA" Storage 3 Some(3), "e1 e2 b";
    BufPin "BUFPIN" Storage 4 Some(4), "e i j b";
    BufShake "BUFSHAKE" Storage 1 Some(1), "b";
    PrintBuf "PRINTBUF" Storage 0 None, "[b ...]";
    SaveData "SAVEDATA" Storage 1 None, "b ...";
    Animate "ANIMATE" Storage 1 Some(1), "name";
    BeginPic "BEGINPIC" Storage 0 None, "[title]";
    EndPic "ENDPIC" Storage 0 Some(0), "";
    PlotFunc "PLOTFUNC" Storage 2 Some(2), "bx by";
    PlotCurv "PLOTCURV" Storage 2 Some(2), "bx by";
    PlotHodo "PLOTHODO" Storage 2 Some(2), "ix iy";
    Tol "TOL" Tolerance 2 Some(2), "r t";
    TolX "TOLX" Tolerance 2 Some(2), "i t";
    BufTol "BUFTOL" Tolerance 2 Some(2), "bsrc b";
}

impl Keyword {
    /// The keyword spelled `word` (case-insensitive).
    pub fn from_name(word: &str) -> Option<Keyword> {
        Keyword::ALL.iter().copied().find(|k| k.name().eq_ignore_ascii_case(word))
    }

    /// The keywords of one block, in reference order.
    pub fn of_block(block: Block) -> impl Iterator<Item = Keyword> {
        Keyword::ALL.iter().copied().filter(move |k| k.block() == block)
    }

    /// Whether the keyword defines a buffer (`BUF...`).
    pub fn is_buffer(self) -> bool {
        matches!(
            self,
            Keyword::BufInp
                | Keyword::BufTime
                | Keyword::BufX0
                | Keyword::BufKx1
                | Keyword::BufKx2
                | Keyword::BufVx
                | Keyword::BufAx
                | Keyword::BufE0
                | Keyword::BufKe1
                | Keyword::BufKe2
                | Keyword::BufVe
                | Keyword::BufAe
                | Keyword::BufDet
                | Keyword::BufTra
        ) || self.is_dynamic_buffer()
    }

    /// Whether the keyword may stand in `block`: its own block, and for a
    /// buffer definition also OPTIMISE, whose targets and objective name
    /// buffers.
    pub fn allowed_in(self, block: Block) -> bool {
        self.block() == block || (block == Block::Optimise && self.is_buffer())
    }

    /// Whether the keyword records a result of the dynamics (BUFSIG,
    /// BUFDRV, ...), which only a dynamics mode computes.
    pub fn is_dynamic_buffer(self) -> bool {
        matches!(
            self,
            Keyword::BufSig
                | Keyword::BufDrv
                | Keyword::BufRea
                | Keyword::BufEkin
                | Keyword::BufEpot
                | Keyword::BufPow
                | Keyword::BufMred
                | Keyword::BufPin
                | Keyword::BufShake
        )
    }

    /// The full usage line, `FORM s NAME k dest [f]`.
    pub fn synopsis(self) -> String {
        if self.usage().is_empty() {
            self.name().to_string()
        } else {
            format!("{} {}", self.name(), self.usage())
        }
    }

    /// How many arguments it takes, in words: "2", "3 or 4", "at least 1".
    pub(crate) fn arity_text(self) -> String {
        match self.arity() {
            (0, Some(0)) => "no".to_string(),
            (a, Some(b)) if a == b => a.to_string(),
            (a, Some(b)) if b == a + 1 => format!("{a} or {b}"),
            (a, Some(b)) => format!("{a} to {b}"),
            (a, None) => format!("at least {a}"),
        }
    }
}

impl fmt::Display for Keyword {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Edit distance between two words (case-insensitive).
fn distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.to_ascii_uppercase().chars().collect();
    let b: Vec<char> = b.to_ascii_uppercase().chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.iter().enumerate() {
        let mut cur = vec![i + 1; b.len() + 1];
        for (j, cb) in b.iter().enumerate() {
            let substitute = prev[j] + usize::from(ca != cb);
            cur[j + 1] = substitute.min(prev[j + 1] + 1).min(cur[j] + 1);
        }
        prev = cur;
    }
    prev[b.len()]
}

/// The known word closest to `word`, if it is close enough to be a typo.
pub(crate) fn closest<'a>(word: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    let limit = (word.chars().count() / 2).clamp(1, 3);
    candidates
        .into_iter()
        .map(|c| (distance(word, c), c))
        .filter(|(d, _)| *d <= limit)
        .min_by_key(|(d, _)| *d)
        .map(|(_, c)| c)
}

/// Every word that may start a line after the mode line.
pub(crate) fn all_words() -> impl Iterator<Item = &'static str> {
    Block::ALL.iter().map(|b| b.name()).chain(Keyword::ALL.iter().map(|k| k.name())).chain(["UNITS", "END"])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn typos_find_their_keyword() {
        assert_eq!(closest("ELME", all_words()), Some("ELEM"));
        assert_eq!(closest("xfx", all_words()), Some("XFIX"));
        assert_eq!(closest("MOV_REL", all_words()), Some("MOV_RELE"));
        assert_eq!(closest("PRINTBUFF", all_words()), Some("PRINTBUF"));
        assert_eq!(closest("DYNAMIC", all_words()), Some("DYNAMICS"));
        assert_eq!(closest("GRAVTY", all_words()), Some("GRAVITY"));
        assert_eq!(closest("LOADFUNK", all_words()), Some("LOADFUNC"));
        assert_eq!(closest("BUFMRD", all_words()), Some("BUFMRED"));
        assert_eq!(closest("MOV_DIN", all_words()), Some("MOV_DYN"));
        assert_eq!(closest("INTOL", all_words()), Some("INTTOL"));
        assert_eq!(closest("MINIMIZE", all_words()), Some("MINIMISE"));
        assert_eq!(closest("OPTIMIZE", all_words()), Some("OPTIMISE"));
        assert_eq!(closest("TARGETEXTR", all_words()), Some("TARGETEXT"));
        assert_eq!(closest("BANANA", all_words()), None);
    }

    #[test]
    fn buffers_may_also_stand_in_optimise() {
        let buffers: Vec<&str> = Keyword::ALL.iter().filter(|k| k.is_buffer()).map(|k| k.name()).collect();
        assert_eq!(buffers.len(), 23);
        assert!(buffers.iter().all(|n| n.starts_with("BUF")));
        assert!(Keyword::BufKe2.allowed_in(Block::Optimise) && Keyword::BufKe2.allowed_in(Block::Storage));
        assert!(!Keyword::PrintBuf.allowed_in(Block::Optimise));
        assert!(!Keyword::Vary.allowed_in(Block::Storage));
    }

    #[test]
    fn every_keyword_is_found_by_its_name() {
        for &k in Keyword::ALL {
            assert_eq!(Keyword::from_name(&k.name().to_lowercase()), Some(k));
        }
    }
}
