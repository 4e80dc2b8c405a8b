//! The full recording layout ([`Layout`]): its blocks tile the table, and a
//! position recorded block by block holds, bit for bit, what the quantity of
//! each column gives on its own ([`record`]), over example decks of every
//! kind: one and several inputs, dependent rows, limit positions, free
//! motion, masses and loads, a simulation, and first-order runs. A deck's
//! own recording ([`Selection`]) names its blocks as the full layout does.
//! The table made afterwards from a run's [`TransferRecord`] holds, bit for
//! bit, what the layout records position by position.

use mechfem_core::run::{Columns, Layout, Selection, TransferRecord};
use mechfem_core::{record, run, simulate, InverseDynamics, Observer, PositionView, Quantity, TransferOrder};
use std::path::Path;

/// Records every position twice: through the layout and quantity by quantity.
struct Both {
    layout: Layout,
    quantities: Vec<Quantity>,
    dynamics: Option<InverseDynamics>,
    order: TransferOrder,
    by_layout: Vec<f64>,
    by_quantity: Vec<f64>,
    /// The same positions as the motion computed them, for the table made afterwards.
    record: TransferRecord,
    positions: usize,
    limits: usize,
}

impl Observer for Both {
    fn position(&mut self, view: &PositionView<'_>) {
        let at = self.by_quantity.len();
        record(&self.quantities, view, self.dynamics.as_mut(), &mut self.by_quantity);
        if let Some(d) = self.dynamics.as_mut() {
            d.evaluate(view);
        }
        // `record` reads some quantities by a shorter way: each is what the quantity gives on its own.
        for (q, &x) in self.quantities.iter().zip(&self.by_quantity[at..]) {
            let own = match self.dynamics.as_ref() {
                Some(d) if q.is_dynamic() => q.dynamic_value(view.mech, d),
                _ => q.value(view),
            };
            assert_eq!(x.to_bits(), own.to_bits(), "{q:?} at position {}", view.index + 1);
        }
        self.layout.record(view, self.dynamics.as_ref(), &mut self.by_layout);
        self.record.push(&self.layout, view, self.dynamics.as_ref());
        self.positions += 1;
        self.limits += usize::from(view.kin.order().is_none());
    }

    fn transfer_order(&self) -> Option<TransferOrder> {
        Some(self.order)
    }
}

/// The example deck `deck`, or, for `DEAD_CENTRE`, the free slider-crank
/// started exactly at its stretched dead centre, where D^c is singular.
fn load(deck: &str) -> mechfem_deck::Compiled {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples").join(deck);
    if deck != DEAD_CENTRE {
        return mechfem_deck::load(&path).unwrap_or_else(|e| panic!("{deck}: {e:?}"));
    }
    let path = path.with_file_name("slider_dead_centre_free.mec");
    let mut text = std::fs::read_to_string(&path).unwrap();
    for (old, new) in [
        ("XMOV 3 0.5", "XMOV 3 1.0"),
        ("     4 0.866", "     4 0.0"),
        ("     5 3.372", "     5 4.0"),
        ("     3 3.3722813232690143", "     3 4.0"),
    ] {
        assert!(text.contains(old));
        text = text.replace(old, new);
    }
    let parsed = mechfem_deck::parse_str(&text, &path).unwrap();
    mechfem_deck::compile(&parsed, path.parent().unwrap()).unwrap()
}

fn both(deck: &str, order: TransferOrder) -> Both {
    let mut c = load(deck);
    let layout = Layout::full(&c.mechanism, c.dynamics.is_some());
    let mut out = Both {
        quantities: layout.quantities(),
        // Room for no position: the record grows as a run that goes on past its motion's steps makes it.
        record: TransferRecord::new(&layout, &c.mechanism, 0),
        layout,
        dynamics: c.dynamics.clone().map(|d| InverseDynamics::new(&c.mechanism, d)),
        order,
        by_layout: Vec::new(),
        by_quantity: Vec::new(),
        positions: 0,
        limits: 0,
    };
    let motion = c.motion.as_ref().expect("the deck has a motion");
    match (&c.dynamics, c.mode.name()) {
        (Some(d), "DYN SIM") => {
            simulate(&c.mechanism, &mut c.state, motion, &c.params, &c.integration, d, &mut out).map(drop)
        }
        _ => run(&c.mechanism, &mut c.state, Some(motion), &c.params, &mut out).map(drop),
    }
    .unwrap_or_else(|e| panic!("{deck}: {e}"));
    out
}

const DEAD_CENTRE: &str = "limits/dead_centre.mec";

const DECKS: [&str; 8] = [
    "fourbar/fourbar.mec",
    "supply/supply.mec",
    "supply/supply_dyn.mec",
    "supply/supply_sim.mec",
    "manipulator/manipulator.mec",
    "limits/slider_dead_centre_free.mec",
    "limits/stephenson_limits.mec",
    DEAD_CENTRE,
];

#[test]
fn blocks_tile_the_table_once() {
    for deck in DECKS {
        let c = load(deck);
        for dynamic in [false, true] {
            let layout = Layout::full(&c.mechanism, dynamic);
            let mut next = 0;
            for b in layout.blocks() {
                assert_eq!(b.start, next, "{deck}: block {} starts where the one before it ends", b.name);
                next = b.columns().end;
            }
            assert_eq!(next, layout.width(), "{deck}");
            assert_eq!(layout.quantities().len(), layout.width(), "{deck}");
            assert_eq!(layout.is_dynamic(), dynamic);
            assert_eq!(layout.block("sigma").is_some(), dynamic);
            let (n, nd) = (c.mechanism.n_coords(), c.mechanism.n_dof());
            assert_eq!(layout.block("kx2").unwrap().shape, vec![n, nd, nd]);
            assert_eq!(layout.block("det").unwrap().columns(), layout.width() - 1..layout.width());
            for (k, q) in layout.quantities().into_iter().enumerate() {
                assert_eq!(layout.column(q), Some(k), "{deck}: {q:?}");
            }
            assert_eq!(layout.column(Quantity::X0(0)), None);
            assert_eq!(layout.column(Quantity::Vx(n)), None);
            assert_eq!(layout.column(Quantity::Ekin).is_some(), dynamic);
        }
    }
}

#[test]
fn a_decks_selection_names_its_blocks_as_the_full_layout_does() {
    for deck in DECKS {
        let c = load(deck);
        let (mech, dynamic) = (&c.mechanism, c.dynamics.is_some());
        let buffers: Vec<Quantity> = c.buffers.iter().map(|b| b.quantity).collect();
        let hodograph: Vec<usize> = (0..mech.n_coords()).rev().collect();
        let s = Selection::deck(mech, &buffers, &hodograph, dynamic);
        let mut next = 0;
        for b in s.blocks() {
            assert_eq!(b.start, next, "{deck}: block {} starts where the one before it ends", b.name);
            next = b.columns().end;
        }
        assert_eq!((next, s.quantities().len()), (s.width(), s.width()), "{deck}");
        let names: Vec<&str> = s.blocks().iter().map(|b| b.name).collect();
        let mut expected = vec!["buffers", "hodograph"];
        if dynamic {
            expected.extend(["inputs", "drive", "ekin", "epot", "power", "loadpow", "vin"]);
        }
        expected.extend(["time", "det"]);
        assert_eq!(names, expected, "{deck}");
        assert_eq!(s.quantities()[s.block("buffers").unwrap().columns()], buffers[..], "{deck}");
        let at = s.block("hodograph").unwrap().start;
        for (k, &coord) in hodograph.iter().enumerate() {
            assert_eq!(s.quantities()[at + k], Quantity::Kx1 { coord, j: 0 }, "{deck}");
        }
        // Every block but the deck's own has the shape and quantities of the full layout's block of that name;
        // the inputs' speeds (`vin`) are in the full layout's `ve`.
        let full = Layout::full(mech, dynamic);
        let quantities = full.quantities();
        if let Some(vin) = s.block("vin") {
            for q in &s.quantities()[vin.columns()] {
                let column = full.column(*q).unwrap_or_else(|| panic!("{deck}: the full layout has {q:?}"));
                assert!(full.block("ve").unwrap().columns().contains(&column), "{deck}: {q:?}");
            }
        }
        for b in s.blocks().iter().filter(|b| !["buffers", "hodograph", "vin"].contains(&b.name)) {
            let f = full.block(b.name).unwrap_or_else(|| panic!("{deck}: the full layout has {}", b.name));
            assert_eq!(b.shape, f.shape, "{deck}: {}", b.name);
            assert_eq!(s.quantities()[b.columns()], quantities[f.columns()], "{deck}: {}", b.name);
        }
        // det(D^c) is asked for by a reader, not by its block.
        let plain = Selection::deck(mech, &[Quantity::X0(0)], &[], false);
        assert_eq!(plain.transfer_order(), None, "{deck}");
        assert_eq!(Selection::deck(mech, &[Quantity::Det], &[], false).transfer_order(), Some(TransferOrder::First));
    }
}

/// Records every position of a deck's selection twice: by
/// [`Selection::record`] and quantity by quantity ([`record`]).
struct Selected {
    selection: Selection,
    dynamics: Option<InverseDynamics>,
    order: TransferOrder,
    by_selection: Vec<f64>,
    by_quantity: Vec<f64>,
}

impl Observer for Selected {
    fn position(&mut self, view: &PositionView<'_>) {
        record(self.selection.quantities(), view, self.dynamics.as_mut(), &mut self.by_quantity);
        self.selection.record(view, self.dynamics.as_mut(), &mut self.by_selection);
    }

    fn transfer_order(&self) -> Option<TransferOrder> {
        Some(self.order)
    }
}

#[test]
fn a_selection_records_what_each_quantity_gives_to_the_last_bit() {
    for deck in DECKS {
        for (order, own) in
            [TransferOrder::First, TransferOrder::Second].into_iter().flat_map(|o| [(o, true), (o, false)])
        {
            let mut c = load(deck);
            let mech = &c.mechanism;
            let (n, nd) = (mech.n_coords(), mech.n_dof());
            // The deck's buffers (or none: then a one-input mechanism's are
            // all read directly) and every co-ordinate's position, velocity
            // and acceleration.
            let mut buffers: Vec<Quantity> = c.buffers.iter().map(|b| b.quantity).filter(|_| own).collect();
            buffers.extend((0..n).flat_map(|i| [Quantity::X0(i), Quantity::Vx(i), Quantity::Ax(i)]));
            buffers.extend((0..n).flat_map(|coord| (0..nd).map(move |j| Quantity::Kx1 { coord, j })));
            let selection = Selection::deck(mech, &buffers, &(0..n).collect::<Vec<_>>(), c.dynamics.is_some());
            let mut out = Selected {
                selection,
                dynamics: c.dynamics.clone().map(|d| InverseDynamics::new(mech, d)),
                order,
                by_selection: Vec::new(),
                by_quantity: Vec::new(),
            };
            let motion = c.motion.as_ref().expect("the deck has a motion");
            match (&c.dynamics, c.mode.name()) {
                (Some(d), "DYN SIM") => {
                    simulate(mech, &mut c.state, motion, &c.params, &c.integration, d, &mut out).map(drop)
                }
                _ => run(mech, &mut c.state, Some(motion), &c.params, &mut out).map(drop),
            }
            .unwrap_or_else(|e| panic!("{deck}: {e}"));
            let width = out.selection.width();
            assert!(out.by_quantity.len() > width, "{deck}");
            assert_eq!(out.by_selection.len(), out.by_quantity.len(), "{deck}");
            for (k, (x, y)) in out.by_selection.iter().zip(&out.by_quantity).enumerate() {
                let q = out.selection.quantities()[k % width];
                assert_eq!(x.to_bits(), y.to_bits(), "{deck}, {order:?}: position {}, {q:?}", k / width);
            }
        }
    }
}

#[test]
fn every_column_is_its_quantity_to_the_last_bit() {
    let mut limits = 0;
    for deck in DECKS {
        for order in [TransferOrder::First, TransferOrder::Second] {
            let b = both(deck, order);
            assert!(b.positions > 1, "{deck}");
            assert_eq!(b.by_layout.len(), b.positions * b.layout.width(), "{deck}");
            for (k, (x, y)) in b.by_layout.iter().zip(&b.by_quantity).enumerate() {
                let q = b.quantities[k % b.layout.width()];
                assert_eq!(x.to_bits(), y.to_bits(), "{deck}, {order:?}: position {}, {q:?}", k / b.layout.width());
            }
            limits += b.limits;
            // The table made from the record, column after column, is the one recorded position by position.
            let (width, positions) = (b.layout.width(), b.positions);
            assert_eq!(b.record.positions(), positions, "{deck}");
            let table = b.layout.table(&b.record);
            assert_eq!(table.len(), b.by_layout.len(), "{deck}");
            for (k, x) in table.iter().enumerate() {
                let (column, position) = (k / positions, k % positions);
                let y = b.by_layout[position * width + column];
                let q = b.quantities[column];
                assert_eq!(x.to_bits(), y.to_bits(), "{deck}, {order:?}: position {position}, {q:?} from the record");
            }
            // The record keeps fewer numbers a position than the table has columns.
            assert!(b.record.stride() < width, "{deck}: {} numbers a position", b.record.stride());
        }
    }
    // The decks include positions without transfer functions, where the layout writes NaN.
    assert!(limits > 0);
}

#[test]
fn columns_hold_each_quantity_contiguously_however_many_positions_come() {
    for room in [0, 1, 3, 4, 10] {
        let mut t = Columns::new(3, room);
        for k in 0..4 {
            let k = f64::from(k);
            t.push(&[k, 10.0 + k, 20.0 + k]);
        }
        assert_eq!(t.positions(), 4);
        assert_eq!(t.get(2, 1), 12.0);
        let expected = [0.0, 1.0, 2.0, 3.0, 10.0, 11.0, 12.0, 13.0, 20.0, 21.0, 22.0, 23.0];
        assert_eq!(t.into_vec(), expected, "room for {room}");
    }
    assert!(Columns::new(5, 10).into_vec().is_empty());
}
