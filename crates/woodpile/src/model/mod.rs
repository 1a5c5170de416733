//! What is solved: materials, Hertz contacts, unit cells, chains and lattices.

pub mod beam;
pub mod cell;
pub mod chain;
pub mod contact;
pub mod fe_beam;
pub mod free_rod;
pub mod lab;
pub mod lattice;
pub mod lattice_load;
pub mod law;
pub mod material;

pub use beam::{BeamTheory, Reduction, Rod};
pub use cell::{CellModel, Resonator, UnitCell, PAPER_OPTIMIZED_CHAIN_MM, TABLE1_LENGTHS_MM};
pub use chain::{Body, Chain, ChainBuilder, Element, Wall, PAPER_ROD_DIAMETER_M};
pub use contact::{
    complete_elliptic_integrals, hertz_beta, hertz_contact, EllipseSolution, HertzContact, Surface,
};
pub use fe_beam::FreeRodModes;
pub use free_rod::TimoshenkoMode;
pub use lab::{ContactDamping, Damping, Preload, ResonatorDamping};
pub use lattice::{
    Lattice, LatticeBuilder, LatticeContact, LatticeRod, LayerSpec, RodOverrides, RodPoint,
    Supports,
};
pub use lattice_load::{LatticeExcitation, LatticeLab, LoadPoints};
pub use law::ContactLaw;
pub use material::Material;
