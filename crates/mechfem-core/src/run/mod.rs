//! The run modes, a file each, over the stepping core of [`crate::motion`]:
//!
//! * `kinematic.rs`, [`run`]: the kinematic run (mode `KIN ANA`), which the
//!   other modes move the mechanism with.
//! * `inverse.rs`, [`InverseDynamics`]: inverse dynamics (mode `DYN ANA`)
//!   at each position of a kinematic run.
//! * `simulate.rs`, [`simulate`]: forward dynamics (mode `DYN SIM`), its
//!   outputs taken from the integrator's solution.
//! * [`design`]: one design of an optimiser (mode `KIN OPT`), a kinematic
//!   run with the design sensitivities and the extrema of chosen quantities,
//!   on the assembly branch of the start design (`branch.rs`).
//!
//! [`move_through`] (`dispatch.rs`) runs or simulates as a [`RunMode`] says
//! (over the motion [`motion_of`] gives for an [`Extent`]),
//! and [`MemoryRefusal`] refuses a run whose results would not fit in memory.
//!
//! Every mode hands its positions to an [`Observer`] and ends with a
//! [`RunReport`] (`observe.rs`); a [`Recorder`] (`record.rs`) keeps the
//! [`Quantity`]s of the deck's buffer table, a [`Layout`] (`layout.rs`)
//! names the columns of a recording of all of them, and a [`Selection`]
//! (`selection.rs`) those of a deck's own recording, in blocks the same way.
//! [`tolerance`] gives the tolerance bands of quantities from their design
//! sensitivities.

mod branch;
pub mod design;
mod dispatch;
pub mod dynamic_design;
mod fault;
mod inverse;
mod kinematic;
mod layout;
mod observe;
mod pins;
mod record;
mod selection;
mod simulate;
pub mod tolerance;
mod transfer_record;
mod transmission;

pub use dispatch::{motion_of, move_through, transfer_order_of, Extent, MemoryRefusal, OrderError, RunMode};
pub use inverse::{DynamicSensitivity, InverseDynamics};
pub use kinematic::run;
pub use layout::{Block, Columns, Layout};
pub use observe::{Observer, PositionView, RunReport, Stop};
pub use record::{record, record_evaluated, recorded_value, Quantity, Recorder};
pub use selection::Selection;
pub use simulate::{simulate, simulate_within, Event, Segment, SimReport};
pub use transfer_record::TransferRecord;
pub use transmission::transmission_angle;
