//! The outputs of a built deck (its STORAGE block): buffers, lists and pictures.

use crate::ast::{BufDef, BufList, PictureDef, PlotDef, Storage};
use crate::diagnostic::DiagnosticKind;
use crate::keywords::Keyword;

use super::{at, checks, DeckBuilder, Refused};

impl DeckBuilder {
    /// Begins the storage: buffers, lists and pictures.
    pub fn storage(&mut self) -> Result<(), Refused> {
        if matches!(self.block, Some(Keyword::Elem | Keyword::BufX0)) {
            return Err(self.refuse(
                DiagnosticKind::WrongBlock,
                self.line + 1,
                "the storage comes before the geometry or twice",
            ));
        }
        let line = self.next_line("STORAGE");
        self.deck.storage = Some(Storage { line, ..Storage::default() });
        self.block = Some(Keyword::BufX0);
        Ok(())
    }

    /// Buffer `number`: `keyword` (`BUFX0`, ...) of the deck numbers `args`.
    pub fn buffer(&mut self, keyword: &str, args: &[i64], number: i64) -> Result<(), Refused> {
        self.in_block(Keyword::BufX0, Keyword::BufX0, "a buffer")?;
        let line = self.next_line(format!("buffer {number}"));
        let what = format!("buffer {number}");
        let kw = Keyword::from_name(keyword).filter(|k| k.is_buffer());
        let Some(kw) = kw else {
            return Err(self.refuse(
                DiagnosticKind::UnknownKeyword,
                line,
                format!("{what} records `{keyword}`, no quantity"),
            ));
        };
        if kw.is_dynamic_buffer() && !self.deck.mode.value.has_dynamics() {
            let message = format!("{what} records a result of the dynamics ({kw}), which a model without masses or loads does not compute");
            return Err(self.refuse(DiagnosticKind::WrongMode, line, message));
        }
        let (min, max) = kw.arity();
        let n = args.len() + 1;
        if n < min || max.is_some_and(|m| n > m) {
            return Err(self.refuse(
                DiagnosticKind::ArgumentCount,
                line,
                format!("{what} ({kw}) has {} arguments", args.len()),
            ));
        }
        let args = args.iter().map(|&a| checks::whole(self, line, a, &what).map(|v| at(v, line)));
        let args = args.collect::<Result<Vec<_>, _>>()?;
        let number = checks::buffer_number(self, line, number)?;
        if let Some(s) = self.deck.storage.as_mut() {
            s.buffers.push(BufDef { line, keyword: at(kw, line), args, number });
        }
        Ok(())
    }

    /// The buffers the print file tabulates (all of them when empty).
    pub fn printbuf(&mut self, buffers: &[i64]) -> Result<(), Refused> {
        self.buffer_list(buffers, "PRINTBUF", true)
    }

    /// The buffers the data set holds, in order.
    pub fn savedata(&mut self, buffers: &[i64]) -> Result<(), Refused> {
        self.buffer_list(buffers, "SAVEDATA", false)
    }

    fn buffer_list(&mut self, buffers: &[i64], what: &str, print: bool) -> Result<(), Refused> {
        self.in_block(Keyword::PrintBuf, Keyword::BufX0, what)?;
        let line = self.next_line(what);
        let buffers = buffers.iter().map(|&b| checks::buffer_number(self, line, b)).collect::<Result<Vec<_>, _>>()?;
        let list = BufList { line, buffers };
        if let Some(s) = self.deck.storage.as_mut() {
            if print {
                s.printbuf.push(list)
            } else {
                s.savedata.push(list)
            }
        }
        Ok(())
    }

    /// The name of the animation file (without extension).
    pub fn animate(&mut self, name: &str) -> Result<(), Refused> {
        self.in_block(Keyword::Animate, Keyword::BufX0, "the animation")?;
        let line = self.next_line("ANIMATE");
        if self.deck.storage.as_ref().is_some_and(|s| s.animate.is_some()) {
            return Err(self.refuse(DiagnosticKind::DuplicateKeyword, line, "the animation is given twice"));
        }
        let name = checks::file_name(self, line, name, "the animation")?;
        if let Some(s) = self.deck.storage.as_mut() {
            s.animate = Some(at(name, line));
        }
        Ok(())
    }

    /// A picture titled `title` of `plots`: (`PLOTFUNC`, `PLOTCURV` or
    /// `PLOTHODO`, first, second), buffer numbers or, for PLOTHODO, a point's
    /// co-ordinate numbers.
    pub fn picture(&mut self, title: &str, plots: &[(String, i64, i64)]) -> Result<(), Refused> {
        self.in_block(Keyword::BeginPic, Keyword::BufX0, "a picture")?;
        let line = self.next_line(title);
        let title = checks::title(self, line, title)?;
        if plots.is_empty() {
            let message = format!("the picture {title:?} has nothing in it: give it at least one plot");
            return Err(self.refuse(DiagnosticKind::PictureStructure, line, message));
        }
        let mut items = Vec::with_capacity(plots.len());
        for (kw, a, b) in plots {
            let l = self.next_line(format!("a plot of {title:?}"));
            let keyword = Keyword::from_name(kw)
                .filter(|k| matches!(k, Keyword::PlotFunc | Keyword::PlotCurv | Keyword::PlotHodo));
            let Some(keyword) = keyword else {
                return Err(self.refuse(
                    DiagnosticKind::UnknownKeyword,
                    l,
                    format!("the picture {title:?} has a plot of kind `{kw}`"),
                ));
            };
            let (a, b) = if keyword == Keyword::PlotHodo {
                (checks::whole(self, l, *a, "a co-ordinate")?, checks::whole(self, l, *b, "a co-ordinate")?)
            } else {
                (checks::buffer_number(self, l, *a)?.value, checks::buffer_number(self, l, *b)?.value)
            };
            items.push(PlotDef { line: l, keyword: at(keyword, l), a: at(a, l), b: at(b, l) });
        }
        self.next_line("ENDPIC");
        if let Some(s) = self.deck.storage.as_mut() {
            s.pictures.push(PictureDef { line, title, items });
        }
        Ok(())
    }
}
